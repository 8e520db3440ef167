"""Verification suite: the worked examples of the sources as checked cases.

Each case module builds its model, runs it and returns rows of (quantity, reference, computed,
tolerance); :func:`moorline.verification.core.run_cases` runs them, ``moorline verify`` prints
them.
"""

from .core import CASES, Row, register, run_cases

register("tuah-ex1", "tuah_ex1:run")
register("tuah-ex2", "tuah_ex2:run")
register("tcheou-t1", "tcheou_t1:run")
register("oc3-line", "oc3_line:run")
register("tuah-ex3", "tuah_ex3:run")
register("tuah-ex4", "tuah_ex4:run")
register("steady-current", "steady_current:run")
register("wang-w1", "wang_w1:run")
register("wang-w2", "wang_dynamics:run_w2")
register("wang-w3", "wang_dynamics:run_w3")
register("tuah-ex5", "tuah_ex5:run")
register("tuah-ex7", "tuah_ex7:run")
register("tuah-ex6", "tuah_ex6:run")
register("modes-string", "modes_string:run")
register("modes-irvine", "modes_irvine:run")
register("tuah-ex7-lift", "tuah_ex7_lift:run")
register("stochastic-riser", "stochastic_riser:run")
register("tuah-ex5-random", "tuah_ex5_random:run")
register("tcheou-t2", "tcheou_t2:run")
register("bending", "bending:run")
register("bem-rao", "bem_rao:run")  # capytaine ([bem] extra)
register("cummins", "cummins:run")  # the spar rows need the [bem] extra
register("harmonic-body", "harmonic_body:run")
register("moorpy-statics", "moorpy_statics:run")  # other codes ([compare] extra)
register("moordyn-dynamics", "moordyn_dynamics:run")  # other codes ([compare] extra)
register("moordyn-body", "moordyn_body:run")  # other codes ([compare] extra)
register("moordyn-body-deck", "moordyn_body_deck:run")  # other codes ([compare] extra)
register("bending-moordyn", "bending:run_moordyn")  # other codes ([compare] extra)

__all__ = ["CASES", "Row", "register", "run_cases"]
