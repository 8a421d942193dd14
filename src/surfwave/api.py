"""The library's front door: one call per question.

:func:`point` answers "what are the bulk speeds and the Rayleigh speed of this prestressed
model crystal at these strains?"; :func:`material` answers the same for a real cubic
crystal from measured elastic constants.
"""
from __future__ import annotations

import numpy as np

from surfwave.continuum import elastic, rayleigh
from surfwave.errors import InputError
from surfwave.continuum.lattices import _FCC_LAB_AXES
from surfwave.continuum.tensors import cubic_voigt, voigt_to_tensor


def point(lattice: str, loading: str, potential: str, direction: str, d_over_d0) -> dict:
    """Stress, bulk sound speeds, stability and Rayleigh speed of a prestressed crystal.

    Parameters
    ----------
    lattice : {"fcc", "triangular"}
    loading : {"uniaxial", "in_plane_hydrostatic"}
    potential : str
        A registered potential (``"harmonic"``, ``"lj"``, ...).
    direction : {"[100]", "[110]", "[10]"}
        Propagation direction (``"[10]"``: the close-packed rows of the triangular lattice).
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the propagation direction (1 = unstressed).

    Returns
    -------
    dict
        Arrays with leading axis n (a scalar input still gives shape (1,)):
        ``stress`` (sigma_xx V / K d0^2), ``c2_L_par``, ``c2_T_par``, ``c2_L_perp``,
        ``c2_T_perp``, ``c2_SH`` (NaN in 2D), ``c2_R`` (all in K d0^2 / m), ``wave_type``,
        ``reason``, ``stable`` (long-wave stability in every direction),
        ``min_acoustic_eig``, ``C`` and ``S`` (shape (n, d, d, d, d), times V, lab frame),
        ``volume`` and ``d_over_d0``.

    Raises
    ------
    InputError, GeometryError
        Unknown names or an impossible geometry (the message names the value).

    Examples
    --------
    >>> import surfwave
    >>> r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.0)
    >>> round(float(r["c2_R"][0]), 4)   # Table I: 0.3596
    0.3596
    """
    out = elastic.properties(lattice, loading, potential, direction, d_over_d0)
    ray = rayleigh.solve(out["S"], 1.0, out["c2_SH"])
    out.update(c2_R=ray["c2_R"], wave_type=ray["wave_type"], reason=ray["reason"])
    return out


def material(C11: float, C12: float, C44: float, rho: float, direction: str, stress: float = 0.0) -> dict:
    """Rayleigh and bulk speeds of a real cubic crystal on its (001) surface.

    Parameters
    ----------
    C11, C12, C44 : float
        Measured elastic constants in GPa (taken as the stressed crystal's C).
    rho : float
        Density in kg/m^3.
    direction : {"[100]", "[110]"}
        Propagation direction in the (001) surface.
    stress : float
        In-plane uniaxial stress sigma_xx along the propagation direction, GPa (negative
        = compression). Enters through Eq. (A11).

    Returns
    -------
    dict of float
        ``c_R``, ``c_L_par``, ``c_T_par``, ``c_L_perp``, ``c_T_perp``, ``c_SH`` (m/s; NaN
        where imaginary), ``wave_type``, ``reason``, ``stable``.

    Examples
    --------
    >>> r = material(2.0, 1.0, 1.0, 1e9, "[100]")   # nearest-neighbour FCC ratios
    >>> round(r["c_R"] ** 2 / 1.0, 6)               # (3 - sqrt 3)/2 C44/rho, m^2/s^2
    0.633975
    """
    if direction not in _FCC_LAB_AXES:
        raise InputError(f"direction {direction!r} not supported; choose '[100]' or '[110]'")
    for name, value in (("C11", C11), ("C12", C12), ("C44", C44), ("rho", rho), ("stress", stress)):
        if not np.isfinite(value):
            raise InputError(f"{name} must be finite, got {value!r}")
    if rho <= 0:
        raise InputError(f"density rho must be positive, got {rho!r} kg/m^3")
    R = _FCC_LAB_AXES[direction]
    C = np.einsum("ai,bj,ck,dl,ijkl->abcd", R, R, R, R, voigt_to_tensor(cubic_voigt(C11, C12, C44)))
    sigma = np.diag([stress, 0.0, 0.0])
    S = elastic.stress_derivatives(sigma, C) * 1e9  # Pa
    speeds = elastic.sound_speeds(S[None], rho)
    ray = rayleigh.solve(S[None], rho)
    stable, _, _ = elastic.long_wave_stability(C[None], sigma[None])
    out = {}
    for key, value in speeds.items():
        v = float(value[0])
        out["c" + key[2:]] = float(np.sqrt(v)) if v > 0 else float("nan")
    c2 = float(ray["c2_R"][0])
    out["c_R"] = float(np.sqrt(c2)) if c2 > 0 else float("nan")
    out["wave_type"] = str(ray["wave_type"][0])
    out["reason"] = str(ray["reason"][0])
    out["stable"] = bool(stable[0])
    return out
