"""Natural frequencies and mode shapes of a cable system about its static equilibrium.

The equations of motion linearized about the static equilibrium ``x0`` are
``M u'' + K u = 0`` with

- ``K`` the exact tangent stiffness ``-dR/dx`` at ``x0`` over the free dofs
  (:meth:`moorline.solvers.equilibrium.StaticModel.tangent`): material (axial) part, the
  geometric (initial-stress) part ``T/l (I - n n^T)`` that gives a cable its transverse
  stiffness, and the seabed contact springs of the nodes in contact;
- ``M`` the structural mass (lumped: half of each element to each node; or consistent, Tuah
  1982 eq. 3.1.12), the point masses, and when asked the added mass: per element
  ``rho A L0 [Ca (I - t t^T) + Cat t t^T] / 2`` to each node, ``t`` the element direction at
  ``x0`` (Tuah eq. 3.2.a.2, :func:`moorline.physics.hydro.added_mass_blocks`), and
  ``rho Ca V`` on the three translations of each point.

Fixed and prescribed points are held. The generalized eigenproblem
``K phi = omega^2 M phi`` is solved densely (:func:`scipy.linalg.eigh`) for small systems and
otherwise with ARPACK in shift-invert mode (:func:`scipy.sparse.linalg.eigsh`), followed by a
Rayleigh-Ritz step on the subspace found (M-orthonormal modes, refined eigenvalues). These
are the frequencies and modes the mode-superposition analyses of Tuah (1982) use (sec. 3.2.b
step 4: strumming; sec. 5.3: stochastic response).

Repeated frequencies (the two transverse polarizations of a straight string) have no unique
modes; within each cluster of (numerically) equal eigenvalues the basis is rotated so that the
modes separate by direction where they can, which makes the ``dominant`` labels
reproducible.
"""

from __future__ import annotations

import logging
from dataclasses import asdict

import numpy as np
import scipy.linalg as sla
import scipy.sparse as sp
import scipy.sparse.linalg as spla
from numpy.typing import NDArray

from ..errors import ConvergenceError, MoorlineError
from ..mesh import Mesh, dynamic_mesh, with_loads_of
from ..model import ModalSettings, System
from ..physics import element, hydro
from ..results import BODY_DOFS, ModalResult, StaticResult
from .assembly import scatter_free
from .linearized_laws import refuse_unlinearized
from .statics import equilibrium_for

FloatArray = NDArray[np.float64]
logger = logging.getLogger(__name__)

#: Up to this many free dofs the eigenproblem is solved densely (all eigenvalues, LAPACK).
DENSE_LIMIT = 300
#: Eigenvalues closer than this (relative) form a cluster of repeated frequencies.
CLUSTER_RTOL = 1.0e-7
AXES = ("x", "y", "z")


def solve_modes(
    system: System,
    settings: ModalSettings | None = None,
    statics: StaticResult | None = None,
) -> ModalResult:
    """Natural frequencies and mass-normalized mode shapes about the static equilibrium.

    Parameters
    ----------
    system
        The problem (lines, points and rigid bodies).
    settings
        Number of modes or frequency band, mass model, added mass; default: the first modal
        analysis of the system, else :class:`~moorline.model.ModalSettings` defaults.
    statics
        The equilibrium to linearize about; solved with the system's statics settings when
        not given.

    Returns
    -------
    ModalResult
        Modes in increasing frequency; ``phi^T M phi = I`` over the free dofs.

    ``success`` is False (no modes, the message says why) when the eigensolver does not
    converge.

    Raises
    ------
    ConvergenceError
        When the statics did not converge (there is no equilibrium to linearize about).
    MoorlineError
        When the model has no free dof or a free dof without mass.

    Notes
    -----
    ``K`` is symmetrized, ``K = (K + K^T) / 2``: all static loads are conservative (weights,
    buoyancy, constant point forces, elastic elements and seabed springs derive from a
    potential), so the exact tangent is the Hessian of the potential energy and symmetric;
    the symmetrization only removes round-off, and lets the symmetric solvers (``eigh``,
    ``eigsh``) be used. Sag-corrected elements (:mod:`moorline.physics.sag`) have no
    potential: for them it takes the symmetric part of a tangent whose asymmetry is of the
    order of their discretization error (3.4e-5 of the fairlead stiffness of the OC3 line at
        20 elements), and their sag follows the modes quasi-statically. The shift-invert shift
    is slightly below zero (or just below the
    band's lower end), so that ``K - sigma M`` is positive definite even for a (near-)
    mechanism and ARPACK converges to the eigenvalues nearest the shift: the lowest ones.
    """
    refuse_unlinearized(system, "modal")
    settings = settings or _default_settings(system)
    statics = equilibrium_for(system, statics, "modal analysis")
    mesh = dynamic_mesh(statics.mesh, statics.positions)
    if mesh.n_dofs == 0 and not mesh.body_names:
        raise MoorlineError(f"modal analysis of {system.name}: the model has no free node")
    K, M, P, problem = system_matrices(mesh, statics.positions, statics.body_pose, settings)
    try:
        if problem.n_unknowns > problem.n_free:  # modes with body dofs: labelled by body dof
            return _body_modes(system, statics, settings, K, M, P, problem)
        lam, phi, solver = _eigen(K, M, settings)
    except ConvergenceError as exc:
        return _failed(system, statics, settings, str(exc), problem.n_unknowns)
    phi = _rotate_clusters(lam, phi, M, mesh)
    phi = _fix_signs(phi)
    return _result(system, statics, settings, lam, phi, M, solver)


def _failed(system: System, statics: StaticResult, settings: ModalSettings, message: str,
            n_dofs: int) -> ModalResult:
    """A modal analysis that found no modes (the eigensolver did not converge)."""
    mesh = statics.mesh
    none = np.zeros((0, 3))
    return ModalResult(
        success=False, status="failed", message=message, omega=np.zeros(0),
        mode_shapes=np.zeros((0, mesh.n_nodes, 3)), participation=none, effective_mass=none,
        dominant=(), positions=statics.positions, tension=statics.tension, mesh=mesh,
        case=system.name, units=system.units, solver="shift-invert", n_dofs=n_dofs,
        settings={k: v for k, v in asdict(settings).items() if k != "kind"})


def _default_settings(system: System) -> ModalSettings:
    return system.first(ModalSettings)


def modal_matrices(mesh: Mesh, x: FloatArray, settings: ModalSettings,
                   taut_axial: bool = False) -> tuple[sp.csr_matrix, sp.csr_matrix]:
    """Stiffness and mass matrices over the free dofs at positions ``x`` of a system without
    bodies (:func:`system_matrices`).

    Parameters
    ----------
    mesh
        The discretized system.
    x
        Node positions of the equilibrium (n_nodes, 3).
    settings
        Mass model (``lumped``/``consistent``) and whether to add the added mass.
    taut_axial
        Taut axial stiffness in slack elements too
        (:meth:`~moorline.solvers.equilibrium.StaticModel.tangent`).

    Returns
    -------
    K, M
        Symmetric CSR matrices (n_dofs, n_dofs).
    """
    if mesh.body_names:
        raise ValueError("modal_matrices: a system with bodies needs their poses "
                         "(system_matrices)")
    K, M, _, _ = system_matrices(mesh, x, np.zeros((0, 6)), settings, taut_axial=taut_axial)
    return K, M


def _eigen(K: sp.csr_matrix, M: sp.csr_matrix,
           settings: ModalSettings) -> tuple[FloatArray, FloatArray, str]:
    """Eigenvalues ``omega^2`` (ascending) and M-orthonormal vectors (n_dofs, n_modes)."""
    n = K.shape[0]
    diag_m = M.diagonal()
    if np.any(diag_m <= 0):
        dof = int(np.flatnonzero(diag_m <= 0)[0])
        raise MoorlineError(f"modal analysis: free dof {dof} has no mass (a massless free "
                            "point or line); give it mass")
    if n <= DENSE_LIMIT or (settings.band is None and settings.n_modes >= n - 1):
        return (*_dense(K, M, settings), "dense")
    lam, phi = _shift_invert(K, M, settings)
    return lam, phi, "shift-invert"


def _dense(K: sp.csr_matrix, M: sp.csr_matrix,
           settings: ModalSettings) -> tuple[FloatArray, FloatArray]:
    n = K.shape[0]
    kwargs: dict = {"subset_by_index": [0, min(settings.n_modes, n) - 1]}
    if settings.band is not None:
        low, high = settings.band
        lower = low * low * (1 - 1e-12) if low > 0 else -np.inf
        kwargs = {"subset_by_value": [lower, high * high * (1 + 1e-12)]}
    try:
        return sla.eigh(K.toarray(), M.toarray(), **kwargs)
    except np.linalg.LinAlgError as exc:
        raise MoorlineError(f"modal analysis: mass matrix not positive definite ({exc})") \
            from None


def _default_shift(K: sp.csr_matrix, M: sp.csr_matrix) -> float:
    """A shift slightly below zero on the scale of the system: a millionth of the median
    diagonal ratio ``K_ii / M_ii`` (for a cable of N elements the lowest eigenvalue is about
    ``pi^2 T / (2 EA N^2)`` times that ratio)."""
    ratio = K.diagonal() / M.diagonal()
    ratio = ratio[ratio > 0]
    return -1e-6 * float(np.median(ratio)) if ratio.size else -1.0


def _shift_invert(K: sp.csr_matrix, M: sp.csr_matrix,
                  settings: ModalSettings) -> tuple[FloatArray, FloatArray]:
    """ARPACK shift-invert: the lowest ``n_modes``, or every mode in the band (the number
    asked for grows until the farthest eigenvalue found lies beyond the band's width)."""
    n = K.shape[0]
    sigma = _default_shift(K, M)
    if settings.band is None:
        return _rayleigh_ritz(K, M, _arpack(K, M, settings.n_modes, sigma))
    low, high = settings.band
    if low > 0:
        sigma = low * low * (1 - 1e-6) + min(sigma, 0.0) * 1e-6
    width = high * high - sigma
    k = max(settings.n_modes, 6)
    while True:
        if k >= n - 1:
            return _dense(K, M, settings)
        lam, phi = _rayleigh_ritz(K, M, _arpack(K, M, k, sigma))
        if np.max(np.abs(lam - sigma)) > width:
            keep = (lam >= low * low * (1 - 1e-12)) & (lam <= high * high * (1 + 1e-12))
            return lam[keep], phi[:, keep]
        k *= 2


def _arpack(K: sp.csr_matrix, M: sp.csr_matrix, k: int, sigma: float) -> FloatArray:
    try:
        _, vectors = spla.eigsh(K.tocsc(), k=k, M=M.tocsc(), sigma=sigma, which="LM",
                                mode="normal")
    except spla.ArpackNoConvergence as exc:
        raise ConvergenceError(f"modal analysis: ARPACK did not converge ({exc})") from None
    return vectors


def _rayleigh_ritz(K: sp.csr_matrix, M: sp.csr_matrix,
                   basis: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Project onto the subspace found: refined eigenvalues and exactly M-orthonormal modes."""
    lam, y = sla.eigh(basis.T @ (K @ basis), basis.T @ (M @ basis))
    return lam, basis @ y


def _dof_axis(mesh: Mesh) -> NDArray[np.int64]:
    """Axis (0, 1, 2) of every free dof."""
    axis = np.empty(mesh.n_dofs, dtype=np.int64)
    free = mesh.dof_of_node >= 0
    axis[mesh.dof_of_node[free]] = np.nonzero(free)[1]
    return axis


def _rotate_clusters(lam: FloatArray, phi: FloatArray, M: sp.csr_matrix,
                     mesh: Mesh) -> FloatArray:
    """Within each cluster of repeated eigenvalues, rotate the (M-orthonormal) basis to
    diagonalize ``sum_d w_d phi^T D_d phi`` with weights 1, 2, 3 for x, y, z (``D_d`` the
    mass diagonal on the dofs of axis ``d``): modes then separate by direction."""
    phi = phi.copy()
    weight = M.diagonal() * (1.0 + _dof_axis(mesh))
    scale = max(float(np.max(np.abs(lam), initial=0.0)), np.finfo(float).tiny)
    start = 0
    for i in range(1, len(lam) + 1):
        if i < len(lam) and abs(lam[i] - lam[i - 1]) <= CLUSTER_RTOL * max(abs(lam[i]),
                                                                           1e-12 * scale):
            continue
        if i - start > 1:
            block = phi[:, start:i]
            _, rotation = np.linalg.eigh(block.T @ (weight[:, None] * block))
            phi[:, start:i] = block @ rotation
        start = i
    return phi


def _fix_signs(phi: FloatArray) -> FloatArray:
    """Make the largest component of every mode positive (reproducible signs)."""
    idx = np.argmax(np.abs(phi), axis=0)
    signs = np.sign(phi[idx, np.arange(phi.shape[1])])
    return phi * np.where(signs == 0, 1.0, signs)


def participation(phi: FloatArray, M: sp.csr_matrix, mesh: Mesh) -> tuple[FloatArray,
                                                                          FloatArray]:
    """Direction shares and effective modal masses of mass-normalized modes.

    Returns
    -------
    share
        (n_modes, 3): the share of ``sum_i m_i phi_i^2`` (``m_i`` the diagonal of ``M``) on the
        dofs of each axis; rows sum to 1. The dominant direction of a mode is its largest.
    effective_mass
        (n_modes, 3): ``(phi^T M r_d)^2`` with ``r_d`` the unit translation of all free dofs
        along axis ``d`` (the modal mass excited by a uniform acceleration along ``d``).
    """
    axis = _dof_axis(mesh)
    energy = M.diagonal()[:, None] * phi**2
    share = np.stack([energy[axis == d].sum(axis=0) for d in range(3)], axis=1)
    share /= np.maximum(share.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    Mphi = M @ phi
    gamma = np.stack([Mphi[axis == d].sum(axis=0) for d in range(3)], axis=1)
    return share, gamma**2


def _result(system: System, statics: StaticResult, settings: ModalSettings, lam: FloatArray,
            phi: FloatArray, M: sp.csr_matrix, solver: str) -> ModalResult:
    mesh = statics.mesh
    negative = lam < 0
    if np.any(negative):
        logger.warning("%s: %d negative eigenvalue(s): the equilibrium is unstable (reported "
                       "as negative omega)", system.name, int(negative.sum()))
    omega = np.sign(lam) * np.sqrt(np.abs(lam))
    share, effective = participation(phi, M, mesh)
    shapes = np.stack([scatter_free(phi[:, j], mesh.dof_of_node) for j in range(phi.shape[1])])
    shapes = shapes.reshape(phi.shape[1], mesh.n_nodes, 3)
    dominant = tuple(AXES[int(k)] for k in np.argmax(share, axis=1)) if len(lam) else ()
    found = f"{len(lam)} modes" + (f" in band {settings.band} rad/s" if settings.band else "")
    return ModalResult(
        success=True, message=f"{found} ({solver}, {mesh.n_dofs} dofs)", omega=omega,
        mode_shapes=shapes, participation=share, effective_mass=effective, dominant=dominant,
        positions=statics.positions, tension=statics.tension, mesh=mesh, case=system.name,
        units=system.units, solver=solver, n_dofs=mesh.n_dofs,
        settings={k: v for k, v in asdict(settings).items() if k != "kind"})




def body_modal_matrices(system: System, mesh: Mesh, positions: FloatArray,
                        body_pose: FloatArray, settings: ModalSettings, problem=None,
                        taut_axial: bool = False):
    """Stiffness and mass of lines and rigid bodies together at a state.

    The coupled tangent (lines and bodies, with the master-slave transformation of Tuah
    (1982) eq. 3.3.6-3.3.10; :mod:`moorline.solvers.coupled_statics`) and the mass of the
    lines transformed the same way plus each body's rigid-body mass and added mass.

    Parameters
    ----------
    system, mesh
        The problem and its discretization (with bodies).
    positions
        Node positions (n_nodes, 3).
    body_pose
        Body poses (n_bodies, 6): position and rotation vector.
    settings
        Mass model and added mass.
    problem
        A :class:`~moorline.solvers.coupled_statics.CoupledStatics` of ``system`` and
        ``mesh`` to reuse (built when not given).
    taut_axial
        Taut axial stiffness in slack elements too
        (:meth:`~moorline.solvers.equilibrium.StaticModel.tangent`).

    Returns
    -------
    K, M : scipy.sparse.csr_matrix
        Symmetric matrices over the unknowns (free line dofs, then 6 per free body).
    P : scipy.sparse matrix
        Map from the unknowns to the extended dofs (free line dofs, then the slave nodes).
    problem : CoupledStatics
        Its dof numbering (``n_free``, ``body_dof``, ``bodies``).
    """
    return system_matrices(with_loads_of(mesh, system), positions, body_pose, settings,
                           problem, taut_axial)


def system_matrices(mesh: Mesh, positions: FloatArray, body_pose: FloatArray,
                    settings: ModalSettings, problem=None, taut_axial: bool = False,
                    tabulated_added_mass: bool = True):
    """Stiffness ``K``, mass ``M`` over the unknowns (free node dofs, then six per free body;
    none without bodies), the master-slave map ``P`` and the coupled statics ``problem``
    (see :func:`body_modal_matrices` for the arguments): the one place modal, strumming and
    stochastic analyses get their matrices. ``tabulated_added_mass=False`` leaves out the
    added mass of bodies with a radiation table (a frequency-domain caller adds ``A(w)``)."""
    from .bodies import (
        BodyState,
        body_mass_matrix,
        refuse_pinned,
        rotation_matrix,
        transformation,
        world_arms,
    )
    from .coupled_statics import CoupledStatics

    refuse_pinned(mesh, "modal, strumming and stochastic")
    problem = problem or CoupledStatics(mesh)
    poses = BodyState(body_pose[:, :3].copy(), rotation_matrix(body_pose[:, 3:]))
    _, state = problem.residual(positions, poses)
    K = problem.tangent(positions, poses, state, taut_axial)
    K = ((K + K.T) * 0.5).tocsr()
    P = transformation(mesh, problem.ext_dofs, problem.n_free, problem.body_dof,
                       world_arms(mesh, poses))
    M_ext = _line_mass(mesh, positions, settings, problem.pattern)
    M = (P.T @ M_ext @ P).tolil()
    for b, body in enumerate(problem.bodies):
        d = problem.body_dof[b]
        if d >= 0:
            added = (_body_added_mass(body) if tabulated_added_mass
                     or getattr(body, "radiation", None) is None else np.zeros((6, 6)))
            if not settings.added_mass:
                added = 0.0 * added
            M[d:d + 6, d:d + 6] = (M[d:d + 6, d:d + 6].toarray()
                                   + body_mass_matrix(body, poses.R[b]) + added)
    return K, M.tocsr(), P, problem


def _body_added_mass(body) -> FloatArray:
    """A body's constant added mass; with a radiation table its infinite-frequency added
    mass (the instantaneous inertia of the Cummins equation: the modes leave out the
    frequency dependence, A(w_n) - A_inf, and the radiation damping)."""
    if getattr(body, "radiation", None) is not None:
        from .body_model import memory_model

        return np.asarray(memory_model(body).added_mass_infinite, dtype=float)
    return np.asarray(body.added_mass if body.added_mass is not None else np.zeros((6, 6)),
                      dtype=float)


def body_mode_shapes(phi: FloatArray, P, problem, mesh: Mesh) -> FloatArray:
    """Node displacements (n_modes, n_nodes, 3) of coupled modes ``phi`` (n_unknowns,
    n_modes): the free nodes' own dofs, the slave nodes' from the bodies' rigid motion."""
    ext = P @ phi
    shapes = np.zeros((phi.shape[1], mesh.n_nodes, 3))
    free = mesh.dof_of_node >= 0
    shapes[:, free] = ext[: problem.n_free][mesh.dof_of_node[free]].T
    shapes[:, mesh.slave_node] = ext[problem.n_free:].T.reshape(phi.shape[1], -1, 3)
    return shapes


def _body_modes(system: System, statics: StaticResult, settings: ModalSettings, K, M, P,
                problem) -> ModalResult:
    """Modes of lines and rigid bodies together (:func:`system_matrices`). A mode whose
    kinetic energy is mostly in a body is labelled by the body's dominant dof."""
    mesh = statics.mesh
    lam, phi, solver = _eigen(K, M, settings)
    phi = _fix_signs(phi)
    shapes = body_mode_shapes(phi, P, problem, mesh)
    energy = M.diagonal()[:, None] * phi**2
    energy /= np.maximum(energy.sum(axis=0, keepdims=True), np.finfo(float).tiny)
    share, effective = _shares(shapes, mesh, statics)
    dominant = []
    for j in range(phi.shape[1]):
        label = AXES[int(np.argmax(share[j]))]
        for b, name in enumerate(mesh.body_names):
            d = problem.body_dof[b]
            if d >= 0 and energy[d:d + 6, j].sum() > 0.5:
                label = f"{name} {BODY_DOFS[int(np.argmax(energy[d:d + 6, j]))]}"
        dominant.append(label)
    omega = np.sign(lam) * np.sqrt(np.abs(lam))
    return ModalResult(
        success=True, message=f"{len(lam)} modes ({solver}, {problem.n_unknowns} dofs incl. "
        f"{6 * int(np.sum(problem.body_dof >= 0))} body dofs)", omega=omega,
        mode_shapes=shapes, participation=share, effective_mass=effective,
        dominant=tuple(dominant), positions=statics.positions, tension=statics.tension,
        mesh=mesh, case=system.name, units=system.units, solver=solver,
        n_dofs=problem.n_unknowns,
        settings={k: v for k, v in asdict(settings).items() if k != "kind"})


def _line_mass(mesh: Mesh, x: FloatArray, settings: ModalSettings, pattern) -> sp.csr_matrix:
    """The lines' mass (and added mass) assembled over ``pattern``'s dofs."""
    point_mass = mesh.node_mass.copy()
    el_blocks = None
    if settings.mass == "consistent":
        el_blocks = element.consistent_mass_blocks(mesh.length0, mesh.mass_per_length)
    else:
        point_mass += element.lumped_mass(mesh.elements, mesh.length0, mesh.mass_per_length,
                                          mesh.n_nodes)
    if settings.added_mass and mesh.water_density > 0:
        added = hydro.added_mass_blocks(x, mesh.elements, mesh.length0, mesh.diameter, mesh.Ca,
                                        mesh.Cat, mesh.water_density)
        el_blocks = added if el_blocks is None else el_blocks + added
        point_mass += mesh.water_density * mesh.node_Ca * mesh.node_volume
    return pattern.assemble(el_blocks, point_mass[:, None, None] * np.eye(3))


def _shares(shapes: FloatArray, mesh: Mesh, statics: StaticResult):
    """Direction shares of the node motion (lumped line mass weights) for body systems."""
    weight = element.lumped_mass(mesh.elements, mesh.length0, mesh.mass_per_length,
                                 mesh.n_nodes) + mesh.node_mass
    energy = np.einsum("n,jnc->jc", weight, shapes**2)
    share = energy / np.maximum(energy.sum(axis=1, keepdims=True), np.finfo(float).tiny)
    return share, energy
