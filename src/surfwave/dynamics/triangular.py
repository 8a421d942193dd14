"""Row-by-row lattice dynamics of the prestressed triangular lattice (nearest neighbours).

Atoms of row I, column J sit at x = (I + 2J) d_x, y = I d_y (row 0 is the surface, y points
into the crystal). For a wave exp(i k x) along the rows with theta = k d_x, the equations of
motion (m = 1, reduced units) of row amplitudes U_I (shape (2,): u along x, v along y) read

    omega^2 U_I = A0 U_I + A1 U_{I+1} + A1^H U_{I-1}          (bulk rows, I >= 1)
    omega^2 U_0 = A0_surface U_0 + A1 U_1                      (free surface row)

with the bond force constant Phi_b = phi''(r) r^r^ + (phi'(r)/r)(1 - r^r^) (docs/physics/paper.md):

    A0 = 2 Phi_row (1 - cos 2 theta) + 2 Phi_up + 2 Phi_um,
    A0_surface = 2 Phi_row (1 - cos 2 theta) + Phi_up + Phi_um,
    A1 = -(Phi_up e^{+i theta} + Phi_um e^{-i theta}),

where "row" is the in-row bond (2 d_x, 0), "up" the bond (d_x, d_y) and "um" (-d_x, d_y).
All functions are vectorised: strain axis first, theta axis second.

:func:`long_wave` is the one place where the modules of the triangular lattice
(:mod:`surfwave.dynamics.dispersion`, :mod:`surfwave.dynamics.triangular_surface`,
:mod:`surfwave.dynamics.entropy`) get the
long-wave sound speeds, stability and the Cauchy-case Rayleigh speed, Eq. (20): from the bond
sums of :mod:`surfwave.model_crystals.elastic` (Eqs. A11, A12).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers import rayleigh
from surfwave.validate import as_1d


def bond_force_constants(potential: str | PairPotential, d_over_d0: ArrayLike) -> np.ndarray:
    """Force-constant matrices of the three bond types.

    Parameters
    ----------
    potential : str or PairPotential
    d_over_d0 : float or array_like, shape (n,)
        2 d_x / d0.

    Returns
    -------
    ndarray, shape (n, 3, 2, 2)
        Phi for the bonds (2 d_x, 0), (d_x, d_y), (-d_x, d_y), in K (units of phi'').
    """
    pot = get_potential(potential)
    crystal = build("triangular", "uniaxial", None, "[10]", d_over_d0)
    r = crystal.bonds  # (n, 3, 2)
    length = np.linalg.norm(r, axis=-1)  # (n, 3)
    rhat = r / length[..., None]
    outer = rhat[..., :, None] * rhat[..., None, :]
    eye = np.eye(2)
    k_par = pot.d2phi(length)[..., None, None]
    k_perp = (pot.dphi(length) / length)[..., None, None]
    return k_par * outer + k_perp * (eye - outer)


def row_matrices(
    potential: str | PairPotential, d_over_d0: ArrayLike, theta: ArrayLike
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Row matrices A0 (bulk), A0_surface and A1 of the row equations (module docstring).

    Parameters
    ----------
    potential : str or PairPotential
    d_over_d0 : float or array_like, shape (n,)
    theta : float or array_like, shape (m,)
        k d_x in radians.

    Returns
    -------
    A0, A0_surface, A1 : ndarray, shape (n, m, 2, 2), complex
        In units of K/m (omega^2 units). A0 and A0_surface are real symmetric.
    """
    phi = bond_force_constants(potential, d_over_d0)[:, None]  # (n, 1, 3, 2, 2)
    th = as_1d(theta, "theta")[None, :, None, None]  # (1, m, 1, 1)
    row, up, um = phi[:, :, 0], phi[:, :, 1], phi[:, :, 2]
    in_row = 4.0 * row * np.sin(th) ** 2  # 2 Phi_row (1 - cos 2 theta), no cancellation at 0, pi
    a0 = (in_row + 2.0 * up + 2.0 * um).astype(complex)
    a0_surface = (in_row + up + um).astype(complex)
    a1 = -(up * np.exp(1j * th) + um * np.exp(-1j * th))
    return a0, a0_surface, a1


def long_wave(potential: str | PairPotential, d_over_d0: ArrayLike) -> dict[str, np.ndarray]:
    """Long-wave bulk speeds, stability and the Eq. (20) Rayleigh root of the triangular lattice.

    Parameters
    ----------
    potential : str or PairPotential
    d_over_d0 : float or array_like, shape (n,)
        2 d_x / d0, in (0, 2) (else GeometryError).

    Returns
    -------
    dict of ndarray, each shape (n,)
        ``c2_L_par``, ``c2_T_par``, ``c2_L_perp``, ``c2_T_perp`` (Eq. A7 with S of Eq. A11
        from the bond sums, K d0^2/m); ``min_acoustic_eig`` (lowest eigenvalue of V Q(n) over
        all directions, K d0^2) and ``stable`` (bool), from
        :func:`surfwave.solvers.long_wave.long_wave_stability`; ``c2_R_cauchy``: the raw root of
        Eq. (20) (:func:`surfwave.solvers.rayleigh.cauchy_c2`; NaN where the square root is
        imaginary), K d0^2/m, not checked to lie in (0, c2_T_par).
    """
    props = elastic.properties("triangular", "uniaxial", potential, "[10]", d_over_d0)
    keys = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp")
    out = {k: np.asarray(props[k], dtype=float) for k in keys}
    out["min_acoustic_eig"] = np.asarray(props["min_acoustic_eig"], dtype=float)
    out["stable"] = np.asarray(props["stable"], dtype=bool)
    out["c2_R_cauchy"] = rayleigh.cauchy_c2(*(out[k] for k in keys))
    return out
