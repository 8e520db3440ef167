"""A small stand-alone MoorPy driver: the statics process benchmark P2 times (bench_all.py).

It imports only MoorPy (not moorline), builds the system from a MoorDyn-format input file (the
fairleads on one coupled body), solves the equilibrium (``solveEquilibrium``) and the 6x6
stiffness of the body (``getCoupledStiffnessA``, analytic) and prints ``{"K11": ..., "T1": ...}``
(surge stiffness [N/m], fairlead tension of line 1 [N]) as JSON on stdout.

Usage: ``python moorpy_drive.py DECK``.
"""

from __future__ import annotations

import contextlib
import io
import json
import sys


def main(deck: str) -> None:
    """Build, solve and print."""
    import moorpy

    with contextlib.redirect_stdout(io.StringIO()):  # MoorPy reports its reading on stdout
        ms = moorpy.System(file=deck)
        ms.initialize()
        ms.solveEquilibrium()
        K = ms.getCoupledStiffnessA()
    print(json.dumps({"K11": float(K[0, 0]), "T1": float(ms.lineList[0].TB)}))


if __name__ == "__main__":
    main(sys.argv[1])
