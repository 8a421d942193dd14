"""Surface waves of real crystals under in-plane stress, and their acoustoelastic coefficients.

Surface and direction by name in, the one path out: :func:`surface_wave_speed` is
:func:`surfwave.real_crystals.stressed_wave.surface_wave` (the function ``surfwave.material``
and the cube solver call too) and :func:`loading_stress` is
:func:`surfwave.real_crystals.loads.stress_tensor`. The stressed crystal comes from
:func:`surfwave.real_crystals.toec.stressed_state` (natural-state C2, Brugger C3, Cauchy
stress sigma in crystal axes); its surface wave from the general solver
(:func:`surfwave.solvers.stroh.surface_wave`, which uses Eq. (17) at mirror directions) with
the wave-propagation coefficients A_ijkl = C*_ijkl + sigma_jl delta_ik in the laboratory
frame of the *deformed* crystal: x1 along F m0 (the image of the given crystal direction m0),
x2 along F^-T n0 (the normal of the deformed surface, into the crystal), x3 = x1 x x2
(:func:`deformed_axes`). Speeds are true phase speeds in the stressed state, m/s.

The acoustoelastic coefficient is (1/v) dv/dsigma at zero stress, 1/GPa, by a central
difference of step :data:`DEFAULT_STEP` = 1e-4 GPa. The step is chosen from a measured scan
(``benchmarks/bench_toec.py``: the 8 database crystals with TOEC, (001)[100] and [110], three
loadings, with and without TOEC, against a Richardson-extrapolated reference): the largest
relative error falls as h^2 from 1e-2 at h = 0.1 GPa to 2e-6 at 1e-3 GPa and 8e-9 at
1e-4 GPa, then grows again as 1/h (round-off of the deformation solve and of the speed:
1e-7 at 1e-6 GPa). 1e-4 GPa is the bottom of that valley.
"""
from __future__ import annotations

from typing import Any, Sequence

import numpy as np
from numpy.typing import ArrayLike

from surfwave.case import check_stress
from surfwave.errors import InputError
from surfwave.real_crystals import toec
from surfwave.real_crystals.loads import TRACTION_TOL, stress_tensor
from surfwave.real_crystals.stressed_wave import REASON_TRACTION, Constants, surface_wave
from surfwave.real_crystals.toec import DEFAULT_TOL
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.tensors import rotate2
from surfwave.vocab import STRESS_LOADINGS

#: A surface ("(hkl)" or its Miller indices) and a propagation direction in it ("[uvw]", an
#: angle in degrees from the reference direction, or a crystal vector).
_Surface = str | Sequence[float] | np.ndarray
_Direction = str | float | Sequence[float] | np.ndarray

__all__ = ["DEFAULT_STEP", "LOADINGS", "REASON_TRACTION", "TRACTION_TOL", "acoustoelastic_coefficients",
           "check_in_plane", "deformed_axes", "loading_stress", "surface_wave_speed"]

#: Loading kinds: uniaxial along / across the propagation direction (in the surface),
#: equi-biaxial in the surface plane, uniaxial along a given crystal axis in the surface.
LOADINGS = STRESS_LOADINGS
#: Central-difference step of the acoustoelastic coefficient, GPa.
DEFAULT_STEP = 1e-4


def _axes(surface, direction) -> np.ndarray:
    R = lab_axes(surface, direction)
    if R.ndim != 2:
        raise InputError(f"one propagation direction per call, got {np.shape(direction)} angles")
    return R


def loading_stress(kind: str, magnitude: ArrayLike, surface: _Surface = "(001)", direction: _Direction = "[100]",
                   axis: str | Sequence[float] | np.ndarray | None = None) -> np.ndarray:
    """Cauchy stress tensors of a loading, crystal axes, GPa.

    Parameters
    ----------
    kind : {"along", "across", "biaxial", "axis"}
        ``along``: sigma = s m m (uniaxial along the propagation direction m);
        ``across``: sigma = s t t, t = the in-plane direction normal to m;
        ``biaxial``: sigma = s (m m + t t) (equal in-plane stress, sigma . n = 0);
        ``axis``: sigma = s a a along the crystal direction ``axis`` (must lie in the surface).
    magnitude : float or array_like, shape (k,)
        s in GPa (negative = compression).

    Returns
    -------
    ndarray, shape (k, 3, 3) (or (3, 3) for a scalar magnitude)
    """
    if kind not in LOADINGS:
        raise InputError(f"unknown loading {kind!r}; choose one of {list(LOADINGS)}")
    return stress_tensor(kind, magnitude, _axes(surface, direction), axis=axis)


def check_in_plane(sigma: ArrayLike, surface: _Surface = "(001)", direction: _Direction = "[100]",
                   tol: float | None = None) -> None:
    """Raise :class:`InputError` naming the first out-of-plane component of sigma.

    The free surface is in equilibrium only if sigma . n = 0; in the natural laboratory
    frame (x propagation, y normal, z in-plane) that is sigma_yy = sigma_xy = sigma_yz = 0,
    to ``tol`` GPa (default: :data:`TRACTION_TOL` times max |sigma| of each tensor, the one
    tolerance of :mod:`surfwave.real_crystals.stressed_wave`).
    """
    sigma = np.asarray(sigma, dtype=float)
    lab = rotate2(sigma, _axes(surface, direction))
    limit = TRACTION_TOL * np.abs(sigma).max(axis=(-2, -1)) if tol is None else tol
    for name, (i, j) in (("sigma_yy", (1, 1)), ("sigma_xy", (0, 1)), ("sigma_yz", (1, 2))):
        v = lab[..., i, j]
        if np.any(np.abs(v) > limit):
            bad = float(np.ravel(v)[np.argmax(np.abs(np.ravel(v)))])
            raise InputError(f"out-of-plane stress component {name} = {bad:.6g} GPa (lab frame: x along "
                             f"{direction}, y normal to {surface}); only in-plane stress is allowed")


def deformed_axes(F: ArrayLike, surface: _Surface = "(001)", direction: _Direction = "[100]") -> np.ndarray:
    """Laboratory axes of the deformed crystal for a surface and direction given by name
    (:func:`surfwave.real_crystals.toec.deformed_axes`): rows x = F m0, y = F^-T n0, z = x cross y.

    Parameters
    ----------
    F : ndarray, shape (..., 3, 3)

    Returns
    -------
    ndarray, shape (..., 3, 3), orthonormal rows (F m0 . F^-T n0 = m0 . n0 = 0).
    """
    return toec.deformed_axes(F, _axes(surface, direction))


def surface_wave_speed(C2: np.ndarray, C3: np.ndarray | None, rho0: float, sigma: ArrayLike,
                       surface: _Surface = "(001)", direction: _Direction = "[100]", *,
                       tol: float = DEFAULT_TOL) -> dict:
    """Surface-wave speed of a real crystal under in-plane stress (general solver).

    Parameters
    ----------
    C2 : array_like, shape (6, 6) or (3, 3, 3, 3)
        Natural-state constants, GPa, crystal axes.
    C3 : array_like, shape (6, 6, 6), or None
        Brugger third-order constants, GPa; None: fixed-C model (C* = C2, rho = rho0).
    rho0 : float
        Natural-state density, kg/m^3.
    sigma : array_like, shape (..., 3, 3)
        Cauchy stress, crystal axes, GPa: numbers, symmetric, in GPa and in-plane, checked by
        :func:`surfwave.case.check_stress` (InputError in the words of every door, e.g. the
        traction sigma . n it finds).
    surface : str or 3-vector
        "(hkl)" of the natural crystal.
    direction : str or float
        A Miller direction in the surface or an angle in degrees from the surface's reference
        direction (:func:`surfwave.solvers.orientation.lab_axes`).

    Returns
    -------
    dict
        Shapes sigma.shape[:-2]: ``c_R`` (m/s, NaN where none; real part for a pseudo wave),
        ``c_limit`` (m/s), ``wave_type``, ``reason`` (str, "" if fine), ``ok`` (the stressed
        state exists and its surface is traction-free), ``rho`` (kg/m^3); ``F`` (..., 3, 3)
        and ``axes`` (..., 3, 3), the deformed lab axes (rows, crystal axes).
    """
    sigma = np.asarray(sigma, dtype=float)
    if sigma.shape[-2:] != (3, 3):
        raise InputError(f"sigma must have shape (..., 3, 3), got {sigma.shape}")
    R = _axes(surface, direction)
    flat = sigma.reshape(-1, 3, 3)                  # the one check of a case, in its words
    check_stress(flat, np.broadcast_to(R, flat.shape), surface if isinstance(surface, str) else str(list(surface)))
    r = surface_wave(Constants(C2, rho0, C3), R, sigma, toec=C3 is not None, state_tol=tol, bulk=False, leaky=False)
    return {"c_R": r["c_R"], "c_limit": r["c_limit"], "wave_type": r["wave_type"].astype(str),
            "reason": r["reason"].astype(str), "ok": r["ok"], "rho": r["rho"], "F": r["F"], "axes": r["axes"]}


def acoustoelastic_coefficients(C2: np.ndarray, C3: np.ndarray | None, rho0: float, surface: _Surface = "(001)",
                                direction: _Direction = "[100]", *, step: float = DEFAULT_STEP,
                                tol: float = DEFAULT_TOL) -> dict:
    """(1/v) dv/dsigma of the surface wave at zero stress, with and without third-order constants.

    Central difference (v(+h) - v(-h)) / (2 h v(0)) for uniaxial stress along and across the
    propagation direction and for equi-biaxial in-plane stress; error O(h^2) (see the module
    docstring for the choice of h).

    Parameters
    ----------
    C2, C3, rho0 : as for :func:`surface_wave_speed`
        With C3 None only the fixed-C model is available (the ``toec`` entries are NaN).
    surface, direction : str or 3-vector
    step : float
        Stress step h, GPa.

    Returns
    -------
    dict
        ``toec`` and ``fixed_C``: dicts loading -> coefficient (1/GPa) for ``along``,
        ``across``, ``biaxial``; ``c_R0`` (m/s, unstressed); ``step`` (GPa).
    """
    if not (np.isfinite(step) and step > 0):
        raise InputError(f"step must be a positive stress in GPa, got {step!r}")
    kinds = ("along", "across", "biaxial")
    h = np.array([-step, step])
    sig = np.stack([loading_stress(k, h, surface, direction) for k in kinds])  # (3, 2, 3, 3)
    sig0 = np.zeros((1, 3, 3))
    out: dict[str, Any] = {"step": float(step)}
    for model, c3 in (("toec", C3), ("fixed_C", None)):
        if model == "toec" and C3 is None:
            out[model] = {k: float("nan") for k in kinds}
            continue
        v = surface_wave_speed(C2, c3, rho0, np.concatenate([sig.reshape(-1, 3, 3), sig0]),
                               surface, direction, tol=tol)["c_R"]
        v0 = v[-1]
        pm = v[:-1].reshape(3, 2)
        out[model] = {k: float((pm[i, 1] - pm[i, 0]) / (2 * step * v0)) for i, k in enumerate(kinds)}
        out["c_R0"] = float(v0)
    return out
