"""`moorline compile` (moorline.precompile): the kernels it compiles are the ones other cases of
the same kind use, so a later run of a different case loads its compiled step from the cache."""

import json
import os
import subprocess
import sys
import textwrap

from click.testing import CliRunner

from moorline.cli import cli

#: A run in a fresh interpreter of the OC3 three lines (20 segments: another model than the
#: precompile's 10) in a current, printing how many times the compiled step and time loop
#: were compiled instead of loaded from the cache.
_OTHER_LINES_RUN = textwrap.dedent("""
    import json
    from dataclasses import replace
    from moorline.model import Current, DynamicsSettings
    from moorline.solvers import fast_loop, fast_newmark
    from moorline.solvers.dynamics import simulate
    from moorline.solvers.statics import solve_statics
    from moorline.verification.oc3_system import oc3_three_lines
    system = oc3_three_lines(20)
    system = replace(system, environment=replace(system.environment,
                                                 current=Current(speed=0.5)))
    run = simulate(system, DynamicsSettings(duration=0.2, dt=0.05),
                   initial=solve_statics(system), output_every=0.05)
    assert run.success, run.message
    print(json.dumps({name: sum(f.stats.cache_misses.values()) for name, f in
                      (("step", fast_newmark.newmark_step),
                       ("loop", fast_loop.advance_block))}))
""")


def test_compile_rejects_an_unknown_kind_with_exit_2():
    result = CliRunner().invoke(cli, ["compile", "boats"])
    assert result.exit_code == 2
    assert "unknown kind 'boats'" in result.output


def test_a_compiled_kind_serves_another_case_of_that_kind(tmp_path):
    """After `moorline compile lines`, a different line-only case (another mesh, a current)
    compiles neither the step nor the time loop: the kernels are specialized on the model's
    kind only."""
    env = dict(os.environ)
    done = subprocess.run([sys.executable, "-m", "moorline", "compile", "lines", "--json"],
                          env=env, capture_output=True, text=True, check=True)
    (result,) = json.loads(done.stdout)
    assert result["kind"] == "lines" and os.path.isdir(result["cache"])
    other = subprocess.run([sys.executable, "-c", _OTHER_LINES_RUN], env=env,
                           capture_output=True, text=True, check=True, cwd=tmp_path)
    assert json.loads(other.stdout.strip().splitlines()[-1]) == {"step": 0, "loop": 0}
