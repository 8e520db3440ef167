"""A small stand-alone MoorDyn driver: the process benchmark P1 times (bench_all.py).

It imports only numpy and ``moordyn`` (not moorline, whose import would be charged to MoorDyn),
reads the deck and a table of the coupled points' positions and velocities at every coupling
interval, finds MoorDyn's initial condition (``Init``), steps through the table (``Step`` once
per interval; MoorDyn sub-steps with the deck's ``dtM``) and writes the fairlead tension of
every line (``|GetLineNodeForce(line, N)|``, the force of the line on its fairlead node, as
moorline's ``fairlead_tension``) at every interval to a text file; it prints the CPU time
of the stepping loop on stderr (``loop SECONDS``).

Usage: ``python moordyn_drive.py DECK MOTION.npz OUT.txt [segment]`` where ``MOTION.npz`` holds
``t`` (n,), ``x`` and ``v`` (n, 3 * coupled points). Exit code 1 when a value is not finite.
With ``segment`` the tension written is that of the line's last segment instead
(``|GetLineNodeTen(line, N)|``, the segment's ``T + Td``: moorline's last ``tension``).
"""

from __future__ import annotations

import sys
import time

import numpy as np


def main(deck: str, motion: str, out: str, quantity: str = "force") -> int:
    """Run the deck along the motion table; write ``time T1 T2 ...`` rows to ``out``
    (``quantity``: ``force``, the end node's force, or ``segment``, the last segment's
    tension)."""
    import moordyn

    table = np.load(motion)
    t, x, v = table["t"], table["x"], table["v"]
    md = moordyn.Create(deck)
    moordyn.SetVerbosity(md, moordyn.LEVEL_ERR)
    if moordyn.Init(md, x[0].tolist(), [0.0] * x.shape[1]):
        return 1
    lines = [moordyn.GetLine(md, i) for i in range(1, moordyn.GetNumberLines(md) + 1)]
    ends = [moordyn.GetLineN(line) for line in lines]
    tension = np.empty((len(t), len(lines)))

    get = moordyn.GetLineNodeTen if quantity == "segment" else moordyn.GetLineNodeForce

    def record(k: int) -> None:
        for j, (line, n) in enumerate(zip(lines, ends, strict=True)):
            tension[k, j] = np.linalg.norm(get(line, n))

    record(0)
    ok = True
    start = time.process_time()
    for k in range(1, len(t)):
        moordyn.Step(md, x[k - 1].tolist(), v[k - 1].tolist(), float(t[k - 1]),
                     float(t[k] - t[k - 1]))
        record(k)
        if not np.isfinite(tension[k]).all():
            ok = False
            tension = tension[:k + 1]
            break
    loop = time.process_time() - start
    moordyn.Close(md)
    print(f"loop {loop:.6f}", file=sys.stderr)
    np.savetxt(out, np.column_stack([t[:len(tension)], tension]), fmt="%.10g")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
