"""Bulk sound speeds and full-zone stability from phonopy force constants.

Phonopy builds the supercell, chooses the symmetry-reduced finite displacements and
assembles (and symmetrises) the force constants; the forces come from our own
nearest-neighbour pair-force calculator (:func:`pair_forces`), never from external code.
This is the independent check of the prestress terms of Eq. (A11): the analytic route
(:mod:`surfwave.model_crystals.elastic`) sums bond formulas, this one differentiates forces.

Units are the reduced units of docs/physics/paper.md (d0 = K = m = 1): force constants in K / d0^2,
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

Stability scans and instability limits built on this module: :mod:`surfwave.model_crystals.stability`.
"""

from __future__ import annotations

import itertools
from typing import TYPE_CHECKING, Final, Literal, cast

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError, PhonopyPointError, SurfwaveError
from surfwave.model_crystals.lattices import Crystal, build_checked, check_combination
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers.long_wave import STABILITY_DIRECTIONS, long_wave_stability
from surfwave.validate import as_1d
from surfwave.vocab import Direction, Lattice, Loading

if TYPE_CHECKING:
    from phonopy import Phonopy
    from phonopy.phonon.mesh import Mesh

#: Default accuracy knobs (see benchmarks/bench_phonons.py for the measured trade).
DEFAULT_SUPERCELL = 2
DEFAULT_DISPLACEMENT = 3e-5
DEFAULT_ZONE_MESH = 8
DEFAULT_LONG_WAVE: Final = "curvature"
DEFAULT_SECANT_EPS = 1e-3
#: omega^2 (K/m) or c^2 (K d0^2/m) below -TOLERANCE counts as unstable.
TOLERANCE = 1e-7

_SPEEDS = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH")



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
def make_phonopy(crystal: Crystal, index: int, potential: PairPotential, supercell: int,
                 displacement: float) -> tuple[Phonopy, np.ndarray]:
    """Phonopy object with force constants for strain point ``index`` of ``crystal``.

    Parameters
    ----------
    crystal : surfwave.model_crystals.lattices.Crystal
        Built by :func:`surfwave.model_crystals.lattices.build`; its ``cell3d()`` (d0) is the unit cell.
    index : int
        Strain point of ``crystal`` to use.
    potential : PairPotential
        Supplies the forces (:func:`pair_forces`).
    supercell : int
        N of the N x N x N supercell (N x N x 1 in 2D).
    displacement : float
        Finite-displacement amplitude, d0.

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
    displaced = phonon.supercells_with_displacements
    assert displaced is not None  # set by generate_displacements
    for disp_cell in displaced:
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


def check_images(phonon: Phonopy, bonds: np.ndarray, tol: float = 1e-8) -> None:
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


def long_wave_tensor(phonon: Phonopy) -> np.ndarray:
    """W_ikjl = -1/2 sum_t Phi_t,ik R_t,j R_t,l, the exact curvature of D(k) at Gamma.

    Returns
    -------
    ndarray, shape (3, 3, 3, 3)
        A_ik(n) = W_ikjl n_j n_l in K d0^2 / m; equals (C_ijkl + sigma_jl delta_ik) / rho
        symmetrised over (j, l).
    """
    phis, vecs = _image_terms(phonon)
    return -0.5 * np.einsum("tik,tj,tl->ikjl", phis, vecs, vecs)


def dynamical_matrix(phonon: Phonopy, k: np.ndarray, cell: np.ndarray) -> np.ndarray:
    """Phonopy's dynamical matrix at Cartesian wave vector k (rad / d0), shape (3, 3), K/m."""
    dm = phonon.dynamical_matrix
    assert dm is not None  # set with the force constants (make_phonopy)
    dm.run(cell @ np.asarray(k, float) / (2 * np.pi))
    return np.array(dm.dynamical_matrix)


def secant_tensor(phonon: Phonopy, cell: np.ndarray, n: ArrayLike, eps: float) -> np.ndarray:
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


def min_acoustic(w: np.ndarray, dim: int) -> tuple[float, np.ndarray]:
    """Lowest eigenvalue of A(n) = W_ikjl n_j n_l over all directions n, and its n.

    The direction search (grid of directions, then a shrinking local pattern search) is
    :func:`surfwave.solvers.long_wave.long_wave_stability`, fed with C'_ijkl = W_ikjl and zero stress
    (W already holds the prestress term). In 2D only the in-plane block and in-plane
    directions count.

    Parameters
    ----------
    w : ndarray, shape (3, 3, 3, 3)
        From :func:`long_wave_tensor`, K d0^2 / m.
    dim : int
        2 or 3.

    Returns
    -------
    min_c2 : float
        K d0^2 / m.
    n : ndarray, shape (3,)
        Unit direction (lab frame; z = 0 in 2D).
    """
    c = np.swapaxes(w[:dim, :dim, :dim, :dim], 1, 2)[None]  # C'_ijkl = W_ikjl
    _, e_min, n_min = long_wave_stability(c, np.zeros((1, dim, dim)), STABILITY_DIRECTIONS)
    n = np.zeros(3)
    n[:dim] = n_min[0]
    return float(e_min[0]), n


def zone_scan(phonon: Phonopy, cell: np.ndarray, dim: int, mesh: int) -> tuple[float, np.ndarray]:
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
    phonon.run_mesh(
        [mesh, mesh, nz], is_gamma_center=True, is_mesh_symmetry=False, with_eigenvectors=(dim == 2)
    )
    res = cast("Mesh", phonon.mesh)  # run_mesh above, without an iterator mesh
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

        opt = minimize(
            lowest,
            k_best[:dim],
            method="Nelder-Mead",
            options={"xatol": 1e-6, "fatol": 1e-12, "maxiter": 400},
        )
        if opt.fun < best:
            best = float(opt.fun)
            k_best = np.zeros(3)
            k_best[:dim] = opt.x
    return best, k_best


# --------------------------------------------------------------------------- public API
#: Larger supercells tried when phonopy's shortest images are not the bonds (strong strain).
MAX_EXTRA_SUPERCELL = 2


def _point(crystal, index, pot, supercell, displacement, zone_mesh, long_wave, secant_eps):
    for sc in range(supercell, supercell + MAX_EXTRA_SUPERCELL + 1):
        phonon, bonds = make_phonopy(crystal, index, pot, sc, displacement)
        try:
            check_images(phonon, bonds)
            break
        except PhonopyPointError:
            if sc == supercell + MAX_EXTRA_SUPERCELL:
                raise
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
    out = {
        "c2_L_par": par[0],
        "c2_T_par": par[1],
        "c2_L_perp": perp[1],
        "c2_T_perp": perp[0],
        "c2_SH": par[2] if dim == 3 else np.nan,
    }
    out["min_c2_phonopy"], out["min_c2_direction"] = min_acoustic(w, dim)
    out["min_omega2"], out["min_omega2_q"] = zone_scan(phonon, cell, dim, zone_mesh)
    out["stable_phonon"] = bool(out["min_omega2"] > -TOLERANCE and out["min_c2_phonopy"] > -TOLERANCE)
    out["supercell_used"] = sc
    return out


def bulk_speeds(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential,
    direction: Direction,
    d_over_d0: ArrayLike,
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
        As in :func:`surfwave.model_crystals.lattices.build`.
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
        Keys and units in ``surfwave.data.variables.CUBES["bulk"]``: ``c2_*_phonopy`` (n,) K d0^2/m
        (``c2_SH_phonopy`` NaN in 2D), ``stable_phonon`` (n,) bool, ``min_omega2`` (n,)
        K/m, ``min_omega2_q`` (n, 3) rad/d0 (Cartesian lab frame), ``min_c2_phonopy`` (n,),
        ``min_c2_direction`` (n, 3), ``reason`` (n,) str.
    """
    check_combination(lattice, loading, direction)
    pot = get_potential(potential)
    if long_wave not in ("curvature", "secant"):
        raise InputError(f"long_wave must be 'curvature' or 'secant', got {long_wave!r}")
    if int(supercell) != supercell or supercell < 2 or not displacement > 0 or int(zone_mesh) < 2:
        raise InputError(
            f"need an integer supercell >= 2, displacement > 0 and zone_mesh >= 2; got "
            f"supercell={supercell!r}, displacement={displacement!r}, zone_mesh={zone_mesh!r}"
        )
    s = as_1d(d_over_d0, finite=False)  # a non-finite point is NaN with its reason
    n = s.size
    out = {f"{k}_phonopy": np.full(n, np.nan) for k in _SPEEDS}
    out.update(
        stable_phonon=np.zeros(n, bool),
        min_omega2=np.full(n, np.nan),
        min_omega2_q=np.full((n, 3), np.nan),
        min_c2_phonopy=np.full(n, np.nan),
        min_c2_direction=np.full((n, 3), np.nan),
        supercell_used=np.zeros(n, int),
        reason=np.full(n, "", dtype=object),
    )
    for i, si in enumerate(s):
        try:
            crystal = build_checked(lattice, loading, pot, direction, [si])
            res = _point(crystal, 0, pot, supercell, displacement, zone_mesh, long_wave, secant_eps)
        except (SurfwaveError, np.linalg.LinAlgError) as exc:
            # a point the physics cannot take (impossible geometry, singular dynamical matrix)
            # is NaN with its reason; anything else is a bug and is raised
            out["reason"][i] = f"{type(exc).__name__}: {exc}"
            continue
        for k in _SPEEDS:
            out[f"{k}_phonopy"][i] = res[k]
        for k in (
            "stable_phonon",
            "min_omega2",
            "min_omega2_q",
            "min_c2_phonopy",
            "min_c2_direction",
            "supercell_used",
        ):
            out[k][i] = res[k]
    out["reason"] = out["reason"].astype(str)
    return out
