"""The compiled time loop: many steps of the compiled Newmark step
(:func:`moorline.solvers.fast_newmark.newmark_step`) in one numba call.

:func:`advance_block` advances a block of full steps, each of ``per_step`` sub-steps (the
sub-stepping level of :func:`moorline.solvers.dynamics.simulate`), with everything that
depends on time alone computed before the call, vectorized, and passed as arrays (the
prescribed nodes' kinematics, the point force histories, the ramps and phases of the waves
and current at every sub-step; the fluid kinematics at the element midpoints, which depend
on the positions, are evaluated with every residual,
:func:`moorline.solvers.fast_fluid.fluid_at_midpoints`). It keeps the modified-Newton
bookkeeping of :class:`~moorline.solvers.fast_newmark.FastStepper` (refresh when the
factorization is missing, was made for another step size or is ``stiffness_update`` steps
old) and writes the output records of the steps flagged in ``record`` into preallocated
buffers. A sub-step that does not converge (or ends with a non-finite residual) stops the
loop with the state after the last converged sub-step: Python cuts that sub-step
(:func:`moorline.solvers.dynamics._advance`) and resumes. A single step of
:class:`FastStepper` is a block of one sub-step, so the Python path and the compiled loop
run the same code.

numba checks a cached function against its own file only, and this loop compiles in kernels
of other files (:mod:`~moorline.solvers.fast_newmark`, :mod:`~moorline.physics.fused`): the
cache directory is therefore named by a hash of all kernel sources
(:mod:`moorline.numba_cache`), so a change to any of them compiles the loop again.
"""

from __future__ import annotations

import math

import numpy as np

from ..jit import numba
from ..physics.fused import maxwell_forces
from . import fast_bodies as fb
from .fast_newmark import _JIT, newmark_step


@numba.njit(**_JIT)
def _sub_step(j, x0, v0, a0, x1, v1, a1, hs, xc, vc, ac, fixed, fnodes, fvals, fluid, model,
              newton, tan, counters, work, other0, strain0, maxwell0, bodies):
    """Sub-step ``j`` of the block from (x0, v0, a0) and the material state (strain0,
    maxwell0) (and the bodies' state in ``bodies``) into (x1, v1, a1); returns (converged,
    residual max-norm)."""
    (free, band, bw, elements, props, laws, with_drag, with_added_mass, node_mass, external,
     seabed_on, seabed_z, k_sb, c_sb, ramp, mu, v_slip, sag_on, sag_active, sag_load, beta,
     gamma, alpha) = model
    (tol, max_iter, refresh_ratio, stall_ratio, stall_limit, max_halvings,
     stiffness_update, local) = newton
    lu, buf, rvec, trial, pforce, uf, af = work
    for q in range(fixed.shape[0]):
        n = fixed[q]
        for c in range(3):
            x1[n, c] = xc[j, q, c]
            v1[n, c] = vc[j, q, c]
            a1[n, c] = ac[j, q, c]
    pforce[:, :] = 0.0
    for q in range(fnodes.shape[0]):
        for c in range(3):
            pforce[fnodes[q], c] += fvals[j, q, c]
    h = hs[j]
    refresh = tan[0] == 0.0 or tan[1] != h or tan[2] >= stiffness_update
    ok, norm, refactored = newmark_step(
        x0, v0, a0, x1, v1, a1, free, band, bw, elements, props, laws, with_drag,
        with_added_mass, node_mass, external, pforce, uf, af, seabed_on, seabed_z, k_sb, c_sb,
        ramp, mu, v_slip, sag_on, sag_active, sag_load, h, beta, gamma, alpha, other0, strain0,
        maxwell0, tol,
        max_iter, refresh, lu, buf, rvec,
        trial, counters, refresh_ratio, stall_ratio, stall_limit, max_halvings, fluid, j,
        bodies, local)
    if refactored:
        tan[0], tan[1], tan[2] = 1.0, h, 0.0
    if not ok:
        tan[0] = 0.0
        return False, norm
    tan[2] += 1.0
    return True, norm


@numba.njit(**_JIT)
def advance_block(x0, v0, a0, x1, v1, a1, hs, per_step, record, xc, vc, ac, fixed, fnodes,
                  fvals, fluid, model, newton, tan, counters, work, other0, saved, out,
                  bodies):
    """Advance ``len(hs) // per_step`` full steps of ``per_step`` sub-steps of sizes ``hs``.

    On entry ``(x0, v0, a0)`` is the state and ``saved``'s strains and Maxwell-branch forces
    its material state; on return the state after the last converged sub-step, with its
    element forces, tensions, strains, added-mass forces, residual and Maxwell-branch forces
    (the viscoelastic elements' updated after every converged sub-step, a sub-step that does
    not converge leaves them) in ``saved``. Per sub-step ``j``: the fixed and prescribed
    nodes ``fixed`` take ``xc[j], vc[j], ac[j]`` (n_fixed, 3), the nodes ``fnodes`` the point
    forces ``fvals[j]`` and the elements the waves and current of ``fluid``
    (:func:`moorline.solvers.fast_fluid.fluid_at_midpoints`). After full step ``k`` with
    ``record[k]``, the state goes into the next record of ``out = (positions, velocities,
    tensions, end_forces, end_elements, end_sides)``: the end forces are the element forces
    ``[end_elements[i], end_sides[i]]``. ``bodies``: the free rigid bodies
    (:mod:`moorline.solvers.fast_bodies`), their state carried from sub-step to sub-step like
    the nodes', their origins, rotations and velocities recorded into ``out[6:9]``.
    ``tan`` = (factorization valid, its step size, its age in steps). ``other0``: the nodal
    forces without inertia at the state (HHT weights them into the next step's residual),
    kept up to date.

    Returns
    -------
    (full steps done, sub-step index in the next step where it stopped, residual max-norm
    there (of the last sub-step when complete), records written): the loop stops at the
    first sub-step that does not converge (index -1 when the block is complete).
    """
    el_forces, tension, strain, f_am, resid, maxwell = saved
    props = model[4]
    pos, vel, ten, ends, end_el, end_side = out[:6]
    body_out = out[6:]
    buf = work[1]
    n_steps = hs.shape[0] // per_step
    j = np.int64(0)  # not the literal 0: its callees would be compiled twice (numba)
    r = np.int64(0)
    norm = 0.0
    for k in range(n_steps):
        for i in range(per_step):
            ok, norm = _sub_step(j, x0, v0, a0, x1, v1, a1, hs, xc, vc, ac, fixed, fnodes,
                                 fvals, fluid, model, newton, tan, counters, work, other0,
                                 strain, maxwell, bodies)
            if not (ok and math.isfinite(norm)):
                return k, i, norm, r
            maxwell_forces(buf[4], props, maxwell)  # with the rows of this sub-step
            fb.commit(bodies)
            x0[:, :] = x1
            v0[:, :] = v1
            a0[:, :] = a1
            el_forces[:, :, :] = buf[0]
            tension[:] = buf[3]
            strain[:] = buf[4]
            f_am[:, :] = buf[10]
            resid[:, :] = buf[11]
            node_mass = model[8]
            for n in range(x0.shape[0]):
                for c in range(3):
                    other0[n, c] = resid[n, c] + node_mass[n] * a0[n, c] - f_am[n, c]
            j += 1
        if record[k]:
            pos[r] = x0
            vel[r] = v0
            ten[r] = tension
            for q in range(end_el.shape[0]):
                for c in range(3):
                    ends[r, q, c] = el_forces[end_el[q], end_side[q], c]
            fb.record(bodies, r, body_out)
            r += 1
    return n_steps, -1, norm, r
