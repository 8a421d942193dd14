"""Stress, elastic constants, stress derivatives, bulk sound speeds and long-wave stability.

All tensors are *per atom times the volume*, i.e. V sigma and V C in K d0^2 (reduced units,
PHYSICS.md), in the lab frame (x = propagation, y = surface normal, z = in-plane normal).
With m = 1 the squared sound speeds are then simply components of V S:
rho c^2 = S  <=>  c^2 = (V S) / m.

Pair sums over each bond once (Appendix, Eq. A12):

    V sigma_ab  = sum r_a r_b / r^2 (r phi')
    V C_abcd    = sum r_a r_b r_c r_d / r^4 (r^2 phi'' - r phi')
    S_abcd      = sigma_ad delta_bc + sigma_bd delta_ac - sigma_ab delta_cd + C_abcd   (A11)
"""
from __future__ import annotations

import numpy as np

from surfwave.continuum.lattices import build
from surfwave.continuum.potentials import PairPotential, get_potential
from surfwave.errors import InputError

#: Accuracy of the long-wave stability search (directions on the half sphere).
STABILITY_DIRECTIONS = 400

#: Metadata of the arrays this module produces (used to build the netCDF cubes).
VARIABLES: dict[str, dict] = {
    "stress": {"long_name": "in-plane stress sigma0_xx times volume per atom, sigma0 V / (K d0^2)",
               "units": "1", "dims": ()},
    "c2_L_par": {"long_name": "squared longitudinal sound speed along x (propagation), rho c^2 = S_xxxx",
                 "units": "K d0^2 / m", "dims": ()},
    "c2_T_par": {"long_name": "squared transverse sound speed along x polarised along y, rho c^2 = S_xyyx",
                 "units": "K d0^2 / m", "dims": ()},
    "c2_L_perp": {"long_name": "squared longitudinal sound speed along y (surface normal), rho c^2 = S_yyyy",
                  "units": "K d0^2 / m", "dims": ()},
    "c2_T_perp": {"long_name": "squared transverse sound speed along y polarised along x, rho c^2 = S_xyxy",
                  "units": "K d0^2 / m", "dims": ()},
    "c2_SH": {"long_name": "squared shear-horizontal sound speed along x polarised along z, rho c^2 = S_xzzx",
              "units": "K d0^2 / m", "dims": ()},
    "stable": {"long_name": "long-wave (acoustic tensor) stability over all propagation directions",
               "units": "1", "dims": ()},
    "min_acoustic_eig": {"long_name": "lowest eigenvalue of the acoustic tensor V Q(n) over all directions n",
                         "units": "K d0^2", "dims": ()},
    "C": {"long_name": "elastic constants times volume per atom, V C_ijkl, lab frame",
          "units": "K d0^2", "dims": ("i", "j", "k", "l")},
    "S": {"long_name": "stress derivatives (Eq. A11) times volume per atom, V S_ijkl, lab frame",
          "units": "K d0^2", "dims": ("i", "j", "k", "l")},
    "volume": {"long_name": "volume (area in 2D) per atom", "units": "d0^3 (d0^2 for the 2D triangular lattice)", "dims": ()},
}


def _bond_terms(bonds: np.ndarray, potential: str | PairPotential):
    pot = get_potential(potential)
    r = np.linalg.norm(bonds, axis=-1)
    rhat = bonds / r[..., None]
    return pot, r, rhat


def stress(bonds: np.ndarray, potential: str | PairPotential) -> np.ndarray:
    """V sigma_ab from the bond sum.

    Parameters
    ----------
    bonds : ndarray, shape (..., nb, dim)
        Each bond once (half of the neighbours), units of d0.
    potential : str or PairPotential

    Returns
    -------
    ndarray, shape (..., dim, dim)
        V sigma in K d0^2.
    """
    pot, r, rhat = _bond_terms(bonds, potential)
    w = r * pot.dphi(r)
    return np.einsum("...b,...bi,...bj->...ij", w, rhat, rhat)


def elastic_constants(bonds: np.ndarray, potential: str | PairPotential) -> np.ndarray:
    """V C_abcd from the bond sum (Eq. A12).

    Parameters
    ----------
    bonds : ndarray, shape (..., nb, dim)
    potential : str or PairPotential

    Returns
    -------
    ndarray, shape (..., dim, dim, dim, dim)
        V C in K d0^2.
    """
    pot, r, rhat = _bond_terms(bonds, potential)
    w = r**2 * pot.d2phi(r) - r * pot.dphi(r)
    return np.einsum("...b,...bi,...bj,...bk,...bl->...ijkl", w, rhat, rhat, rhat, rhat)


def third_order_constants(bonds: np.ndarray, potential: str | PairPotential) -> np.ndarray:
    """V C3_abcdef, the third Lagrangian-strain derivatives of the bond energy (Brugger).

    With r^2 = R . (I + 2 eta) . R for each bond, the third eta-derivative of sum phi(r) is

        V C3_abcdef = sum r_a r_b r_c r_d r_e r_f / r^6 (r^3 phi3 - 3 r^2 phi'' + 3 r phi'),

    (phi3 the third derivative of phi), the third-order analogue of Eq. (A12), about the
    geometry of ``bonds``.

    Parameters
    ----------
    bonds : ndarray, shape (..., nb, dim)
    potential : str or PairPotential
        Must provide ``d3phi``.

    Returns
    -------
    ndarray, shape (..., dim, dim, dim, dim, dim, dim)
        V C3 in K d0^2.
    """
    pot, r, rhat = _bond_terms(bonds, potential)
    if pot.d3phi is None:
        raise InputError(f"potential {pot.name!r} has no third derivative d3phi")
    w = r**3 * pot.d3phi(r) - 3.0 * r**2 * pot.d2phi(r) + 3.0 * r * pot.dphi(r)
    return np.einsum("...b,...bi,...bj,...bk,...bl,...bm,...bn->...ijklmn", w, *([rhat] * 6))


def stress_derivatives(sigma: np.ndarray, C: np.ndarray) -> np.ndarray:
    """S_abcd = sigma_ad delta_bc + sigma_bd delta_ac - sigma_ab delta_cd + C_abcd (Eq. A11).

    Parameters
    ----------
    sigma : ndarray, shape (..., d, d)
    C : ndarray, shape (..., d, d, d, d)

    Returns
    -------
    ndarray, shape (..., d, d, d, d)
        In the units of the inputs (times V if they are).
    """
    eye = np.eye(sigma.shape[-1])
    return (
        np.einsum("...ad,bc->...abcd", sigma, eye)
        + np.einsum("...bd,ac->...abcd", sigma, eye)
        - np.einsum("...ab,cd->...abcd", sigma, eye)
        + C
    )


def sound_speeds(S: np.ndarray, rho=1.0) -> dict[str, np.ndarray]:
    """Long-wave bulk sound speeds squared along and normal to the surface (Eq. A7).

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d)
        Stress derivatives, lab frame (times V if ``rho`` is the mass per atom).
    rho : float or ndarray broadcastable to S.shape[:-4]
        Density (or m = 1 when S is V S).

    Returns
    -------
    dict of ndarray, shape S.shape[:-4]
        ``c2_L_par`` (S_xxxx), ``c2_T_par`` (S_xyyx), ``c2_L_perp`` (S_yyyy),
        ``c2_T_perp`` (S_xyxy), ``c2_SH`` (S_xzzx; NaN in 2D), each divided by rho.
    """
    rho = np.asarray(rho, dtype=float)
    x, y, z = 0, 1, 2
    out = {
        "c2_L_par": S[..., x, x, x, x] / rho,
        "c2_T_par": S[..., x, y, y, x] / rho,
        "c2_L_perp": S[..., y, y, y, y] / rho,
        "c2_T_perp": S[..., x, y, x, y] / rho,
    }
    if S.shape[-1] == 3:
        out["c2_SH"] = S[..., x, z, z, x] / rho
    else:
        out["c2_SH"] = np.full(S.shape[:-4], np.nan)
    return out


def _sphere_directions(dim: int, n: int) -> np.ndarray:
    """Unit vectors covering half the circle/sphere (n and -n are equivalent), shape (k, dim)."""
    if dim == 2:
        phi = np.linspace(0.0, np.pi, n, endpoint=False)
        return np.column_stack([np.cos(phi), np.sin(phi)])
    i = np.arange(n) + 0.5
    zc = i / n  # upper hemisphere z in (0, 1)
    phi = np.pi * (1 + 5**0.5) * i
    rxy = np.sqrt(1 - zc**2)
    fib = np.column_stack([rxy * np.cos(phi), rxy * np.sin(phi), zc])
    sym = np.array(
        [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1],
         [0, 1, 1], [0, 1, -1], [1, 1, 1], [1, 1, -1], [1, -1, 1], [-1, 1, 1]], dtype=float
    )
    sym /= np.linalg.norm(sym, axis=1, keepdims=True)
    return np.vstack([sym, fib])


def acoustic_tensor(C: np.ndarray, sigma: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Q_ik(n) = (C_ijkl + sigma_jl delta_ik) n_j n_l.

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
    sigma : ndarray, shape (s, d, d)
    n : ndarray, shape (s, k, d) or (k, d)
        Unit propagation directions.

    Returns
    -------
    ndarray, shape (s, k, d, d)
    """
    if n.ndim == 2:
        n = np.broadcast_to(n, (C.shape[0],) + n.shape)
    q = np.einsum("sijkl,snj,snl->snik", C, n, n)
    q += np.einsum("sjl,snj,snl->sn", sigma, n, n)[..., None, None] * np.eye(C.shape[-1])
    return q


def long_wave_stability(
    C: np.ndarray, sigma: np.ndarray, n_directions: int = 400, refine: int = 12
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lowest eigenvalue of the acoustic tensor over all propagation directions.

    Every bulk acoustic wave must have rho c^2 > 0 in every direction (PHYSICS.md); the
    paper checks only c_T,par. A grid of directions (high-symmetry ones included) is
    searched, then the best direction of each strain is refined by a shrinking local
    pattern search, vectorised over strain.

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
        V C.
    sigma : ndarray, shape (s, d, d)
        V sigma.
    n_directions : int
        Size of the initial direction grid (half sphere/circle).
    refine : int
        Number of refinement rounds (each halves the step).

    Returns
    -------
    stable : ndarray of bool, shape (s,)
        True if the lowest eigenvalue is positive.
    min_eig : ndarray, shape (s,)
        Lowest eigenvalue of V Q, K d0^2.
    direction : ndarray, shape (s, d)
        Unit vector where it occurs.
    """
    dim = C.shape[-1]
    grid = _sphere_directions(dim, n_directions)
    eig = np.linalg.eigvalsh(acoustic_tensor(C, sigma, grid))[..., 0]  # (s, k)
    best = np.argmin(eig, axis=1)
    n_best = grid[best]
    e_best = eig[np.arange(len(best)), best]
    # Local refinement: perturb along the tangent plane with a shrinking step.
    step = 0.5 * np.sqrt(4.0 * np.pi / n_directions) if dim == 3 else np.pi / n_directions
    if dim == 3:
        offsets = np.array([[a, b] for a in (-1, 0, 1) for b in (-1, 0, 1) if (a, b) != (0, 0)], float)
    else:
        offsets = np.array([[-1.0], [1.0]])
    for _ in range(refine):
        if dim == 3:
            helper = np.where(np.abs(n_best[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
            t1 = np.cross(n_best, helper)
            t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
            t2 = np.cross(n_best, t1)
            cand = n_best[:, None, :] + step * (offsets[None, :, :1] * t1[:, None] + offsets[None, :, 1:] * t2[:, None])
        else:
            t1 = np.column_stack([-n_best[:, 1], n_best[:, 0]])
            cand = n_best[:, None, :] + step * offsets[None, :, :1] * t1[:, None]
        cand /= np.linalg.norm(cand, axis=-1, keepdims=True)
        e_c = np.linalg.eigvalsh(acoustic_tensor(C, sigma, cand))[..., 0]
        j = np.argmin(e_c, axis=1)
        e_j = e_c[np.arange(len(j)), j]
        better = e_j < e_best
        n_best = np.where(better[:, None], cand[np.arange(len(j)), j], n_best)
        e_best = np.where(better, e_j, e_best)
        step *= 0.5
    return e_best > 0.0, e_best, n_best


def properties(lattice: str, loading: str, potential: str | PairPotential, direction: str, d_over_d0) -> dict:
    """Stress, C, S, bulk sound speeds and long-wave stability of a prestressed crystal.

    The elastic half of :func:`surfwave.point` (which adds the Rayleigh speed); the workflow's
    ``elastic`` stage calls this so that Rayleigh-solver changes do not rerun it.

    Parameters
    ----------
    lattice, loading, potential, direction
        As for :func:`surfwave.continuum.lattices.build`.
    d_over_d0 : float or array_like, shape (n,)

    Returns
    -------
    dict
        ``d_over_d0``, ``volume``, ``stress``, ``c2_L_par``, ``c2_T_par``, ``c2_L_perp``,
        ``c2_T_perp``, ``c2_SH`` (shape (n,)), ``stable``, ``min_acoustic_eig`` (shape (n,)),
        ``C`` and ``S`` (shape (n, d, d, d, d), times V, lab frame).
    """
    crystal = build(lattice, loading, direction, d_over_d0, potential)
    sigma = stress(crystal.bonds, potential)
    C = elastic_constants(crystal.bonds, potential)
    S = stress_derivatives(sigma, C)
    out: dict = {"d_over_d0": crystal.d_over_d0, "volume": crystal.volume, "stress": sigma[:, 0, 0]}
    out.update(sound_speeds(S))
    out["stable"], out["min_acoustic_eig"], _ = long_wave_stability(C, sigma, STABILITY_DIRECTIONS)
    out["C"] = C
    out["S"] = S
    return out
