"""Stress, elastic constants, stress derivatives, bulk sound speeds; the elastic half of point.

Long-wave stability (the acoustic tensor over all directions) lives in
:mod:`surfwave.solvers.long_wave`.

All tensors are *per atom times the volume*, i.e. V sigma and V C in K d0^2 (reduced units,
docs/physics/paper.md), in the lab frame (x = propagation, y = surface normal, z = in-plane normal).
With m = 1 the squared sound speeds are then simply components of V S:
rho c^2 = S  <=>  c^2 = (V S) / m.

Pair sums over each bond once (Appendix, Eq. A12):

    V sigma_ab  = sum r_a r_b / r^2 (r phi')
    V C_abcd    = sum r_a r_b r_c r_d / r^4 (r^2 phi'' - r phi')
    S_abcd      = sigma_ad delta_bc + sigma_bd delta_ac - sigma_ab delta_cd + C_abcd   (A11)
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers.long_wave import STABILITY_DIRECTIONS, long_wave_stability, long_wave_stable


def _bond_terms(bonds: np.ndarray, potential: str | PairPotential):
    pot = get_potential(potential)
    r = np.sqrt(np.einsum("...i,...i->...", bonds, bonds))
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
    dim = bonds.shape[-1]
    dyad = (rhat[..., :, None] * rhat[..., None, :]).reshape(rhat.shape[:-1] + (dim * dim,))
    C = np.swapaxes(dyad * w[..., None], -1, -2) @ dyad  # sum over bonds as one product
    return C.reshape(C.shape[:-2] + (dim,) * 4)


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
    dim = sigma.shape[-1]
    S = np.empty(np.broadcast_shapes(C.shape[:-4], sigma.shape[:-2]) + (dim,) * 4, np.result_type(C, sigma))
    S[...] = C
    for k in range(dim):  # the Kronecker deltas as in-place adds on the diagonals they select
        S[..., :, k, k, :] += sigma  # sigma_ad delta_bc
        S[..., k, :, k, :] += sigma  # sigma_bd delta_ac
        S[..., :, :, k, k] -= sigma  # sigma_ab delta_cd
    return S


def sound_speeds(S: np.ndarray, rho: ArrayLike = 1.0) -> dict[str, np.ndarray]:
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


def properties_and_stress(lattice, loading, potential, direction, d_over_d0,
                          min_eig: bool) -> tuple[dict, np.ndarray]:
    """:func:`properties` and the stress tensor V sigma, shape (n, d, d) (the front door's
    :func:`surfwave.point` needs both)."""
    crystal = build(lattice, loading, potential, direction, d_over_d0)
    sigma = stress(crystal.bonds, potential)
    C = elastic_constants(crystal.bonds, potential)
    S = stress_derivatives(sigma, C)
    out: dict = {"d_over_d0": crystal.d_over_d0, "volume": crystal.volume, "stress": sigma[:, 0, 0]}
    out.update(sound_speeds(S))
    if min_eig:
        out["stable"], out["min_acoustic_eig"], _ = long_wave_stability(C, sigma, STABILITY_DIRECTIONS)
    else:
        out["stable"] = long_wave_stable(C, sigma, STABILITY_DIRECTIONS)
    out["C"] = C
    out["S"] = S
    return out, sigma


#: The former private name, kept.
_properties = properties_and_stress


def properties(lattice: str, loading: str, potential: str | PairPotential, direction: str, d_over_d0: ArrayLike,
               *, min_eig: bool = True) -> dict:
    """Stress, C, S, bulk sound speeds and long-wave stability of a prestressed crystal.

    The elastic half of :func:`surfwave.point` (which adds the Rayleigh speed); the workflow's
    ``elastic`` stage calls this so that Rayleigh-solver changes do not rerun it.

    Parameters
    ----------
    lattice, loading, potential, direction
        As for :func:`surfwave.model_crystals.lattices.build`.
    d_over_d0 : float or array_like, shape (n,)

    Returns
    -------
    dict
        ``d_over_d0``, ``volume``, ``stress``, ``c2_L_par``, ``c2_T_par``, ``c2_L_perp``,
        ``c2_T_perp``, ``c2_SH`` (shape (n,)), ``stable``, ``min_acoustic_eig`` (shape (n,),
        only with ``min_eig``), ``C`` and ``S`` (shape (n, d, d, d, d), times V, lab frame).

    Other Parameters
    ----------------
    min_eig : bool
        Also report ``min_acoustic_eig``, the lowest eigenvalue of V Q(n) over all
        directions, which needs the direction scan at every point (the elastic cube holds
        it). Without it ``stable`` alone is computed, by :func:`long_wave_stable` (a
        sufficient test, a certificate of instability, the scan only where neither
        decides: same flags, several times faster).
    """
    return properties_and_stress(lattice, loading, potential, direction, d_over_d0, min_eig)[0]
