"""Bulk sound speeds and full-zone stability from phonopy force constants.

Phonopy builds the supercell, chooses the symmetry-reduced finite displacements and
assembles (and symmetrises) the force constants; the forces come from our own
nearest-neighbour pair-force calculator (:func:`pair_forces`), never from external code.
This is the independent check of the prestress terms of Eq. (A11): the analytic route
(:mod:`surfwave.elastic`) sums bond formulas, this one differentiates forces.

Units are the reduced units of PHYSICS.md (d0 = K = m = 1): force constants in K / d0^2,
omega^2 in K / m, speeds squared in K d0^2 / m, wave vectors k in rad / d0. Phonopy's
``unit_conversion_factor`` is set to 1, so its "frequencies" are angular frequencies in
(K/m)^(1/2). Phonopy's reduced wave vector q (reciprocal-lattice units, phase
exp(2 pi i q.n)) and the lab-frame Cartesian k (phase exp(i k.r)) are related by
``q = cell @ k / (2 pi)`` with the primitive vectors as rows of ``cell``.

Long-wave limit. For a Bravais lattice with unit mass D(k) = sum_R Phi(R) exp(i k.R), so
the acoustic tensor per unit density is A_ik(n) = -1/2 sum_R Phi_ik(R) (n.R)^2 =
W_ikjl n_j n_l with W = (C_ijkl + sigma_jl delta_ik) / rho. ``long_wave="curvature"``
(default) evaluates W from phonopy's force constants and phonopy's own image vectors
(the exact second derivative at Gamma); ``"secant"`` uses phonopy's dynamical matrix at
k = eps n, A = [D(eps n) - D(0)] / eps^2 (error O(eps^2)). Branches are assigned by the
polarisation of the eigenvectors of A(x) and A(y), not by their order.

Triangular lattice: the 2D cell is padded with vacuum along z (``Crystal.cell3d``), the
supercell is N x N x 1 and only the in-plane (x, y) block of the dynamical matrix is used
(the out-of-plane modes of a prestressed 2D sheet are not part of the model).
"""
from __future__ import annotations

import itertools
from typing import Literal

import numpy as np

from .errors import SurfwaveError
from .lattices import build, check_combination
from .potentials import PairPotential, get_potential

#: Default accuracy knobs (see benchmarks/bench_phonons.py for the measured trade).
DEFAULT_SUPERCELL = 2
DEFAULT_DISPLACEMENT = 1e-4
DEFAULT_ZONE_MESH = 8
DEFAULT_LONG_WAVE = "curvature"
DEFAULT_SECANT_EPS = 1e-3
#: omega^2 (K/m) or c^2 (K d0^2/m) below -TOLERANCE counts as unstable.
TOLERANCE = 1e-7

_SPEED_AXES = {  # name -> (propagation axis, polarisation axis) in the lab frame
    "c2_L_par": (0, 0), "c2_T_par": (0, 1), "c2_SH": (0, 2),
    "c2_L_perp": (1, 1), "c2_T_perp": (1, 0),
}

_C2 = "K d0^2 / m"
VARIABLES: dict[str, dict] = {
    "c2_L_par_phonopy": {"long_name": "squared longitudinal sound speed along x from phonopy force constants", "units": _C2, "dims": ("strain",)},
    "c2_T_par_phonopy": {"long_name": "squared transverse sound speed along x polarised along y, phonopy", "units": _C2, "dims": ("strain",)},
    "c2_L_perp_phonopy": {"long_name": "squared longitudinal sound speed along y (surface normal), phonopy", "units": _C2, "dims": ("strain",)},
    "c2_T_perp_phonopy": {"long_name": "squared transverse sound speed along y polarised along x, phonopy", "units": _C2, "dims": ("strain",)},
    "c2_SH_phonopy": {"long_name": "squared shear-horizontal sound speed along x polarised along z, phonopy (NaN in 2D)", "units": _C2, "dims": ("strain",)},
    "stable_phonon": {"long_name": "no imaginary phonon frequency on the zone mesh nor at long waves in any direction", "units": "1", "dims": ("strain",)},
    "min_omega2": {"long_name": "lowest omega^2 on the zone mesh (Gamma excluded; refined locally when negative)", "units": "K / m", "dims": ("strain",)},
    "min_omega2_q": {"long_name": "Cartesian lab-frame wave vector k of min_omega2 (phase exp(i k.r))", "units": "rad / d0", "dims": ("strain", "xyz")},
    "min_c2_phonopy": {"long_name": "lowest acoustic-tensor eigenvalue over all directions, phonopy long-wave limit", "units": _C2, "dims": ("strain",)},
    "min_c2_direction": {"long_name": "unit propagation direction of min_c2_phonopy, lab frame", "units": "1", "dims": ("strain", "xyz")},
    "reason": {"long_name": "why a point has NaN phonopy values (empty if computed)", "units": "1", "dims": ("strain",)},
}


class PhonopyPointError(SurfwaveError):
    """Phonopy could not produce trustworthy force constants at one strain point."""


# --------------------------------------------------------------------------- forces
def neighbour_table(frac: np.ndarray, lattice: np.ndarray, bonds: np.ndarray) -> np.ndarray:
    """Index of the atom at r_i + b for every supercell atom i and half-bond b.

    The table is built once from the undisplaced supercell by matching fractional
    coordinates modulo the supercell lattice, so it stays right at any strain (a
    distance cutoff would not: compressed crystals bring second neighbours within d0).

    Parameters
    ----------
    frac : ndarray, shape (N, 3)
        Fractional coordinates of the supercell atoms.
    lattice : ndarray, shape (3, 3)
        Supercell vectors (rows), d0.
    bonds : ndarray, shape (nb, 3)
        Half of the nearest-neighbour bond vectors, d0.

    Returns
    -------
    ndarray of int, shape (N, nb)
    """
    target = frac[:, None, :] + bonds @ np.linalg.inv(lattice)
    diff = target[:, :, None, :] - frac[None, None, :, :]
    diff -= np.round(diff)
    hit = np.all(np.abs(diff) < 1e-6, axis=-1)
    if not np.all(hit.sum(-1) == 1):
        raise PhonopyPointError("bond end points do not map onto supercell atoms")
    return hit.argmax(-1)


def pair_forces(
    displacements: np.ndarray, bonds: np.ndarray, table: np.ndarray, potential: PairPotential
) -> np.ndarray:
    """Forces on all supercell atoms from nearest-neighbour pair forces.

    Each bond (i, table[i, b]) is counted once; its vector is b + u_j - u_i, so periodic
    images never need a minimum-image search.

    Parameters
    ----------
    displacements : ndarray, shape (N, 3)
        Atomic displacements from the reference supercell, d0.
    bonds : ndarray, shape (nb, 3)
        Half bond vectors of the undisplaced crystal, d0.
    table : ndarray of int, shape (N, nb)
        From :func:`neighbour_table`.
    potential : PairPotential

    Returns
    -------
    ndarray, shape (N, 3)
        Forces in K d0.
    """
    r = bonds[None, :, :] + displacements[table] - displacements[:, None, :]
    length = np.linalg.norm(r, axis=-1)
    f = (potential.dphi(length) / length)[..., None] * r  # force on i from bond i -> j
    forces = f.sum(axis=1)
    np.add.at(forces, table.ravel(), -f.reshape(-1, 3))
    return forces


# --------------------------------------------------------------------------- phonopy
def make_phonopy(crystal, index: int, potential: PairPotential, supercell: int, displacement: float):
    """Phonopy object with force constants for strain point ``index`` of ``crystal``.

    Returns
    -------
    phonon : phonopy.Phonopy
        ``unit_conversion_factor`` = 1, ``primitive_matrix`` = identity (our cell is
        primitive), unit masses; force constants produced.
    bonds : ndarray, shape (nb, 3)
        Half bond vectors (3D, lab frame), d0.
    """
    from phonopy import Phonopy
    from phonopy.structure.atoms import PhonopyAtoms

    cell = crystal.cell3d()[index]
    bonds = crystal.bonds[index]
    if bonds.shape[1] == 2:
        bonds = np.column_stack([bonds, np.zeros(len(bonds))])
    unit = PhonopyAtoms(symbols=["H"], cell=cell, scaled_positions=[[0.0, 0.0, 0.0]], masses=[1.0])
    nz = supercell if crystal.dim == 3 else 1
    phonon = Phonopy(unit, supercell_matrix=np.diag([supercell, supercell, nz]), primitive_matrix=np.eye(3))
    phonon.unit_conversion_factor = 1.0
    phonon.generate_displacements(distance=displacement, is_plusminus="auto")
    sc = phonon.supercell
    table = neighbour_table(sc.scaled_positions, sc.cell, bonds)
    ref = sc.positions
    forces = []
    for disp_cell in phonon.supercells_with_displacements:
        u = disp_cell.positions - ref
        u -= np.round(u @ np.linalg.inv(sc.cell)) @ sc.cell  # undo wrapping into the cell
        forces.append(pair_forces(u, bonds, table, potential))
    phonon.forces = np.array(forces)
    phonon.produce_force_constants()
    return phonon, bonds


def _image_terms(phonon) -> tuple[np.ndarray, np.ndarray]:
    """Force-constant terms Phi_t (T, 3, 3) and their Cartesian image vectors R_t (T, 3).

    D(k) = sum_t Phi_t exp(i k.R_t) with phonopy's shortest images, each shared equally
    among equivalent images (phonopy's convention).
    """
    svecs, multi = phonon.primitive.get_smallest_vectors()
    pcell = phonon.primitive.cell
    fc = phonon.force_constants
    p = phonon.primitive.p2s_map[0]
    p_row = 0 if fc.shape[0] == 1 else p
    phis, vecs = [], []
    for j in range(fc.shape[1]):
        count, offset = multi[j, 0]
        for v in svecs[offset : offset + count]:
            phis.append(fc[p_row, j] / count)
            vecs.append(v @ pcell)
    return np.array(phis), np.array(vecs)


def check_images(phonon, bonds: np.ndarray, tol: float = 1e-8) -> None:
    """Raise :class:`PhonopyPointError` unless phonopy's images are exactly the bonds.

    Phonopy pairs each supercell atom with its shortest image(s); under strong strain a
    non-bonded image can become shorter than a bond in a small supercell, which would
    silently corrupt D(k). Every interacting image must be +b or -b of a real bond.
    """
    phis, vecs = _image_terms(phonon)
    allowed = np.vstack([bonds, -bonds])
    scale = np.abs(phis).max()
    for phi, v in zip(phis, vecs):
        if np.linalg.norm(v) < tol or np.abs(phi).max() < 1e-9 * scale:
            continue
        if not np.any(np.linalg.norm(allowed - v, axis=1) < 1e-6):
            raise PhonopyPointError(
                f"supercell too small: phonopy's image {np.round(v, 4)} of an interacting atom "
                "is not a bond vector (a non-bonded image is shorter); increase supercell"
            )


def long_wave_tensor(phonon) -> np.ndarray:
    """W_ikjl = -1/2 sum_t Phi_t,ik R_t,j R_t,l, the exact curvature of D(k) at Gamma.

    Returns
    -------
    ndarray, shape (3, 3, 3, 3)
        A_ik(n) = W_ikjl n_j n_l in K d0^2 / m; equals (C_ijkl + sigma_jl delta_ik) / rho
        symmetrised over (j, l).
    """
    phis, vecs = _image_terms(phonon)
    return -0.5 * np.einsum("tik,tj,tl->ikjl", phis, vecs, vecs)


def dynamical_matrix(phonon, k: np.ndarray, cell: np.ndarray) -> np.ndarray:
    """Phonopy's dynamical matrix at Cartesian wave vector k (rad / d0), shape (3, 3), K/m."""
    phonon.dynamical_matrix.run(cell @ np.asarray(k, float) / (2 * np.pi))
    return np.array(phonon.dynamical_matrix.dynamical_matrix)


def secant_tensor(phonon, cell: np.ndarray, n: np.ndarray, eps: float) -> np.ndarray:
    """A(n) = [D(eps n) - D(0)] / eps^2 from phonopy's dynamical matrix, shape (3, 3), K d0^2/m."""
    d0 = dynamical_matrix(phonon, np.zeros(3), cell)
    return (dynamical_matrix(phonon, eps * np.asarray(n, float), cell) - d0).real / eps**2


def assign_polarisation(a: np.ndarray) -> np.ndarray:
    """Eigenvalues of a symmetric (d, d) tensor ordered by polarisation along the lab axes.

    The permutation maximising sum_a |e_a|^2 of the assigned eigenvectors is chosen, so
    branches are identified by polarisation, not by order (degenerate pairs give the same
    value either way).

    Returns
    -------
    ndarray, shape (d,)
        Element a is the eigenvalue whose eigenvector points (mostly) along lab axis a.
    """
    val, vec = np.linalg.eigh(0.5 * (a + a.T))
    w = vec**2  # w[axis, mode]
    best = max(itertools.permutations(range(len(val))), key=lambda p: sum(w[i, p[i]] for i in range(len(p))))
    return val[list(best)]


def _directions(dim: int, n: int = 600) -> np.ndarray:
    """Unit vectors over half the circle/sphere, high-symmetry ones included, shape (k, 3)."""
    if dim == 2:
        a = np.linspace(0.0, np.pi, n, endpoint=False)
        return np.column_stack([np.cos(a), np.sin(a), 0 * a])
    i = np.arange(n) + 0.5
    z = i / n
    ph = np.pi * (1 + 5**0.5) * i
    fib = np.column_stack([np.sqrt(1 - z**2) * np.cos(ph), np.sqrt(1 - z**2) * np.sin(ph), z])
    sym = np.array([p for p in itertools.product((-1, 0, 1), repeat=3) if any(p)], float)
    return np.vstack([sym / np.linalg.norm(sym, axis=1, keepdims=True), fib])


def min_acoustic(w: np.ndarray, dim: int, rounds: int = 14) -> tuple[float, np.ndarray]:
    """Lowest eigenvalue of A(n) = W_ikjl n_j n_l over all directions n, and its n.

    A direction grid, then a shrinking local pattern search from the best direction.
    In 2D only the in-plane block and in-plane directions count.

    Returns
    -------
    min_c2 : float
        K d0^2 / m.
    n : ndarray, shape (3,)
    """
    w = w[:dim, :dim, :dim, :dim]

    def lowest(ns):
        return np.linalg.eigvalsh(np.einsum("ikjl,nj,nl->nik", w, ns[:, :dim], ns[:, :dim]))[:, 0]

    grid = _directions(dim)
    e = lowest(grid)
    best = grid[np.argmin(e)]
    e_best = e.min()
    step = 0.1
    for _ in range(rounds):
        if dim == 2:
            ang = np.arctan2(best[1], best[0]) + step * np.array([-1.0, 1.0])
            cand = np.column_stack([np.cos(ang), np.sin(ang), 0 * ang])
        else:
            t1 = np.cross(best, [1.0, 0, 0] if abs(best[0]) < 0.9 else [0, 1.0, 0])
            t1 /= np.linalg.norm(t1)
            t2 = np.cross(best, t1)
            off = np.array([(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1) if a or b], float)
            cand = best + step * (off[:, :1] * t1 + off[:, 1:] * t2)
            cand /= np.linalg.norm(cand, axis=1, keepdims=True)
        ec = lowest(cand)
        if ec.min() < e_best:
            e_best, best = ec.min(), cand[np.argmin(ec)]
        else:
            step *= 0.5
    return float(e_best), best


def zone_scan(phonon, cell: np.ndarray, dim: int, mesh: int) -> tuple[float, np.ndarray]:
    """Lowest omega^2 (K/m) on a Gamma-centred mesh x mesh (x mesh) grid, Gamma excluded.

    Uses phonopy's mesh sampler. In 2D, modes polarised mostly along z are dropped. A
    negative minimum is refined by a local Nelder-Mead search in k, so the reported value
    and wave vector do not depend on where the mesh points fall.

    Returns
    -------
    min_omega2 : float
    k : ndarray, shape (3,)
        Cartesian lab-frame wave vector, rad / d0.
    """
    from scipy.optimize import minimize

    nz = mesh if dim == 3 else 1
    phonon.run_mesh([mesh, mesh, nz], is_gamma_center=True, is_mesh_symmetry=False,
                    with_eigenvectors=(dim == 2))
    res = phonon.mesh
    q = np.asarray(res.qpoints)
    f = np.asarray(res.frequencies)
    w2 = np.sign(f) * f**2
    if dim == 2:
        inplane = (np.abs(np.asarray(res.eigenvectors)[:, :2, :]) ** 2).sum(axis=1) > 0.5
        w2 = np.where(inplane, w2, np.inf)
    w2 = np.where(np.all(np.abs(q) < 1e-12, axis=1)[:, None], np.inf, w2)
    i_q, _ = np.unravel_index(np.argmin(w2), w2.shape)
    best = float(w2[i_q].min())
    k_best = 2 * np.pi * np.linalg.solve(cell, q[i_q])
    if best < 0:
        def lowest(kv):
            k3 = np.zeros(3)
            k3[:dim] = kv
            return np.linalg.eigvalsh(dynamical_matrix(phonon, k3, cell)[:dim, :dim])[0]

        opt = minimize(lowest, k_best[:dim], method="Nelder-Mead",
                       options={"xatol": 1e-6, "fatol": 1e-12, "maxiter": 400})
        if opt.fun < best:
            best = float(opt.fun)
            k_best = np.zeros(3)
            k_best[:dim] = opt.x
    return best, k_best


# --------------------------------------------------------------------------- public API
def _point(crystal, index, pot, supercell, displacement, zone_mesh, long_wave, secant_eps):
    phonon, bonds = make_phonopy(crystal, index, pot, supercell, displacement)
    check_images(phonon, bonds)
    dim = crystal.dim
    cell = crystal.cell3d()[index]
    w = long_wave_tensor(phonon)
    if long_wave == "curvature":
        a_par, a_perp = w[:, :, 0, 0], w[:, :, 1, 1]
    else:
        a_par = secant_tensor(phonon, cell, [1.0, 0, 0], secant_eps)
        a_perp = secant_tensor(phonon, cell, [0, 1.0, 0], secant_eps)
    par = assign_polarisation(a_par[:dim, :dim])
    perp = assign_polarisation(a_perp[:dim, :dim])
    out = {"c2_L_par": par[0], "c2_T_par": par[1], "c2_L_perp": perp[1], "c2_T_perp": perp[0],
           "c2_SH": par[2] if dim == 3 else np.nan}
    out["min_c2_phonopy"], out["min_c2_direction"] = min_acoustic(w, dim)
    out["min_omega2"], out["min_omega2_q"] = zone_scan(phonon, cell, dim, zone_mesh)
    out["stable_phonon"] = bool(out["min_omega2"] > -TOLERANCE and out["min_c2_phonopy"] > -TOLERANCE)
    return out


def bulk_speeds(
    lattice: str,
    loading: str,
    potential: str | PairPotential,
    direction: str,
    d_over_d0,
    supercell: int = DEFAULT_SUPERCELL,
    displacement: float = DEFAULT_DISPLACEMENT,
    zone_mesh: int = DEFAULT_ZONE_MESH,
    long_wave: Literal["curvature", "secant"] = DEFAULT_LONG_WAVE,
    secant_eps: float = DEFAULT_SECANT_EPS,
) -> dict[str, np.ndarray]:
    """Bulk sound speeds and full-zone stability from phonopy finite displacements.

    Each strain point is computed on its own (its own crystal build and phonopy object),
    so calling on [a, b] equals calling on [a] and [b]. A point that fails (impossible
    geometry, a supercell too small for the strain, ...) gets NaN and a ``reason``.

    Parameters
    ----------
    lattice, loading, direction : str
        As in :func:`surfwave.lattices.build`.
    potential : str or PairPotential
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the propagation direction x.
    supercell : int
        N of the N x N x N (2D: N x N x 1) supercell of the primitive cell. N = 2 is
        already exact for nearest-neighbour forces.
    displacement : float
        Finite-displacement amplitude, d0 (error ~ amplitude^2).
    zone_mesh : int
        Points per reciprocal axis of the Gamma-centred stability mesh.
    long_wave : {"curvature", "secant"}
        Exact second derivative of D(k) at Gamma, or the secant at k = secant_eps.
    secant_eps : float
        |k| of the secant, rad / d0.

    Returns
    -------
    dict of ndarray
        Keys and units in :data:`VARIABLES`: ``c2_*_phonopy`` (n,) K d0^2/m
        (``c2_SH_phonopy`` NaN in 2D), ``stable_phonon`` (n,) bool, ``min_omega2`` (n,)
        K/m, ``min_omega2_q`` (n, 3) rad/d0 (Cartesian lab frame), ``min_c2_phonopy`` (n,),
        ``min_c2_direction`` (n, 3), ``reason`` (n,) str.
    """
    check_combination(lattice, loading, direction)
    pot = get_potential(potential)
    s = np.atleast_1d(np.asarray(d_over_d0, dtype=float))
    n = s.size
    out = {f"{k}_phonopy": np.full(n, np.nan) for k in _SPEED_AXES}
    out.update(stable_phonon=np.zeros(n, bool), min_omega2=np.full(n, np.nan),
               min_omega2_q=np.full((n, 3), np.nan), min_c2_phonopy=np.full(n, np.nan),
               min_c2_direction=np.full((n, 3), np.nan), reason=np.full(n, "", dtype=object))
    for i, si in enumerate(s):
        try:
            crystal = build(lattice, loading, direction, [si], potential=pot)
            res = _point(crystal, 0, pot, supercell, displacement, zone_mesh, long_wave, secant_eps)
        except Exception as exc:  # noqa: BLE001 - recorded per point, never raised mid-array
            out["reason"][i] = f"{type(exc).__name__}: {exc}"
            continue
        for k in _SPEED_AXES:
            out[f"{k}_phonopy"][i] = res[k]
        for k in ("stable_phonon", "min_omega2", "min_omega2_q", "min_c2_phonopy", "min_c2_direction"):
            out[k][i] = res[k]
    out["reason"] = out["reason"].astype(str)
    return out


# --------------------------------------------------------------------------- stability
def _long_wave_flags(lattice, loading, potential, direction, s: np.ndarray) -> np.ndarray:
    """Analytic long-wave stability per point (``surfwave.point(...)["stable"]``).

    Computed point by point so the result is separable; a point whose geometry cannot be
    built is reported unstable-unknown as False.
    """
    from .api import point

    flags = np.zeros(s.size, bool)
    for i, si in enumerate(s):
        try:
            flags[i] = bool(np.asarray(point(lattice, loading, potential, direction, [si])["stable"])[0])
        except Exception:  # noqa: BLE001 - geometry failures end the stable range
            flags[i] = False
    return flags


def stability_scan(
    lattice: str,
    loading: str,
    potential: str | PairPotential,
    direction: str,
    d_over_d0,
    supercell: int = DEFAULT_SUPERCELL,
    displacement: float = DEFAULT_DISPLACEMENT,
    zone_mesh: int = DEFAULT_ZONE_MESH,
) -> dict[str, np.ndarray]:
    """Long-wave and full-zone stability flags at each strain.

    Parameters
    ----------
    lattice, loading, potential, direction : str
    d_over_d0 : array_like, shape (n,)
    supercell, displacement, zone_mesh
        Phonopy knobs, as in :func:`bulk_speeds`.

    Returns
    -------
    dict
        ``stable_long_wave`` (n,) bool: analytic acoustic tensor Q(n) positive for every
        direction (:func:`surfwave.point`); ``stable_full_zone`` (n,) bool: phonopy's
        ``stable_phonon`` (zone mesh and long-wave limit of the force constants);
        ``min_omega2`` (n,) K/m, ``min_omega2_q`` (n, 3) rad/d0, ``min_c2_phonopy`` (n,)
        K d0^2/m, ``reason`` (n,) str. Points that cannot be built are False in both flags.
    """
    s = np.atleast_1d(np.asarray(d_over_d0, dtype=float))
    bulk = bulk_speeds(lattice, loading, potential, direction, s, supercell=supercell,
                       displacement=displacement, zone_mesh=zone_mesh)
    return {
        "d_over_d0": s,
        "stable_long_wave": _long_wave_flags(lattice, loading, potential, direction, s),
        "stable_full_zone": bulk["stable_phonon"] & (bulk["reason"] == ""),
        "min_omega2": bulk["min_omega2"],
        "min_omega2_q": bulk["min_omega2_q"],
        "min_c2_phonopy": bulk["min_c2_phonopy"],
        "reason": bulk["reason"],
    }


def _flag(lattice, loading, potential, direction, kind, d, knobs) -> bool:
    if kind == "long_wave":
        return bool(_long_wave_flags(lattice, loading, potential, direction, np.array([d]))[0])
    r = bulk_speeds(lattice, loading, potential, direction, [d], **knobs)
    return bool(r["stable_phonon"][0] and r["reason"][0] == "")


def instability_limits(
    lattice: str,
    loading: str,
    potential: str | PairPotential,
    direction: str,
    kind: Literal["long_wave", "full_zone"] = "long_wave",
    step: float = 0.01,
    tol: float = 1e-4,
    search: tuple[float, float] = (0.3, 2.0),
    **knobs,
) -> tuple[float, float]:
    """First unstable d/d0 in compression and in tension, walking out from d/d0 = 1.

    Steps of ``step`` from 1 until the flag turns False, then bisection of the last
    stable / first unstable bracket down to ``tol``; the unstable end is returned. A
    geometry that cannot be built counts as unstable (e.g. in-plane hydrostatic FCC at
    d/d0 -> sqrt 2). NaN if the crystal stays stable up to the ``search`` bound.

    Parameters
    ----------
    kind : {"long_wave", "full_zone"}
        Analytic acoustic-tensor criterion, or phonopy's full-zone criterion.
    step, tol : float
        Walk step and bisection tolerance in d/d0.
    search : (float, float)
        Lowest and highest d/d0 examined.
    **knobs
        Phonopy knobs for ``kind="full_zone"`` (supercell, displacement, zone_mesh).

    Returns
    -------
    (d_compress, d_tension) : tuple of float
        d/d0 of the first instability below and above 1 (accurate to ``tol``).
    """
    if kind not in ("long_wave", "full_zone"):
        raise ValueError(f"kind must be 'long_wave' or 'full_zone', got {kind!r}")
    limits = []
    for sign, bound in ((-1.0, search[0]), (1.0, search[1])):
        stable, unstable = 1.0, None
        n_steps = int(np.floor(abs(bound - 1.0) / step + 1e-9))
        for j in range(1, n_steps + 1):
            d = 1.0 + sign * j * step
            if not _flag(lattice, loading, potential, direction, kind, d, knobs):
                unstable = d
                break
            stable = d
        if unstable is None:
            limits.append(np.nan)
            continue
        while abs(unstable - stable) > tol:
            mid = 0.5 * (stable + unstable)
            if _flag(lattice, loading, potential, direction, kind, mid, knobs):
                stable = mid
            else:
                unstable = mid
        limits.append(float(unstable))
    return limits[0], limits[1]
