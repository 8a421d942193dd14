"""Love waves in an isotropic film on an isotropic half-space: closed-form dispersion and its
exact parameter sensitivities.

A shear-horizontal (SH) wave guided by a film (shear modulus mu, density rho, thickness h,
shear speed b1 = sqrt(mu/rho)) on a faster substrate (mu_s, rho_s, b2 = sqrt(mu_s/rho_s) > b1)
travels at b1 < c < b2 where

    tan(k h q1) = mu_s q2 / (mu q1),   q1 = sqrt(c^2/b1^2 - 1),   q2 = sqrt(1 - c^2/b2^2)

(the film's field is a standing wave across its thickness, the substrate's decays as
exp(-k q2 depth)). Mode n lives on the branch n pi <= k h q1 < n pi + pi/2 and exists above its
cut-off k h = n pi / sqrt(b2^2/b1^2 - 1). The root is found per point by Brent's method in the
variable t of q1 = Q sin t, q2 = (b1/b2) Q cos t (Q = sqrt(b2^2/b1^2 - 1)), which keeps both q1
and q2 accurate from the cut-off to kh -> infinity, on the bracket of the mode's branch.

Sensitivities dc/dp follow from implicit differentiation of G(c, p) = mu q1 sin(theta) -
mu_s q2 cos(theta) = 0 (theta = k h q1): dc/dp = -G_p / G_c, exact to rounding.

Parameters (the ``params`` mapping of :class:`LoveModel`; moduli in GPa, densities in kg/m^3,
thickness in m): ``mu`` or (``E``, ``nu``) of the film, ``rho``, ``thickness``, and of the
substrate ``substrate_mu``, ``substrate_rho``. The abscissa ``x`` is ``kh`` (wavenumber times
film thickness) or ``frequency`` (Hz, then k h = 2 pi f h / c and the thickness matters).

Examples
--------
>>> import numpy as np
>>> m = LoveModel(variable="kh")
>>> p = {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0}
>>> c = m(p, np.array([0.0, 1.0, 50.0]))
>>> np.round(c, 2)   # kh = 0: the substrate's shear speed; large kh: the film's
array([5000.  , 4715.01, 3767.68])
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Literal

import numpy as np
from scipy.optimize import brentq

from surfwave.errors import InputError

__all__ = ["LOVE_PARAMETERS", "LoveModel", "love_cutoff", "love_speed"]

#: Names a :class:`LoveModel` understands (``E`` and ``nu`` replace ``mu`` when given).
LOVE_PARAMETERS = ("mu", "E", "nu", "rho", "thickness", "substrate_mu", "substrate_rho")
GPA = 1.0e9
Variable = Literal["kh", "frequency"]


def _moduli(params: Mapping[str, float]) -> tuple[float, float, float, float]:
    """(mu, rho, mu_s, rho_s) in Pa and kg/m^3 from a parameter mapping."""
    if "mu" in params:
        mu = float(params["mu"])
    elif "E" in params and "nu" in params:
        mu = float(params["E"]) / (2.0 * (1.0 + float(params["nu"])))
    else:
        raise InputError(f"the Love model needs the film's 'mu' or 'E' and 'nu' (GPa), got keys {sorted(params)}")
    missing = [k for k in ("rho", "substrate_mu", "substrate_rho") if k not in params]
    if missing:
        raise InputError(f"the Love model needs {missing} (substrate_mu in GPa, densities in kg/m^3)")
    return mu * GPA, float(params["rho"]), float(params["substrate_mu"]) * GPA, float(params["substrate_rho"])


def love_cutoff(mode: int, mu: float, rho: float, substrate_mu: float, substrate_rho: float) -> float:
    """Cut-off kh of Love mode ``mode`` (0 has none: returns 0): n pi / sqrt(b2^2/b1^2 - 1).

    Moduli in any common unit, densities in kg/m^3; NaN when the film is not slower than the
    substrate (no guided SH wave).
    """
    Q2 = (substrate_mu / substrate_rho) / (mu / rho) - 1.0
    return mode * math.pi / math.sqrt(Q2) if Q2 > 0 else math.nan


def _solve_t(K: float, s: float | None, a: float, r: float, Q: float, mode: int) -> float:
    """Root t of sin t sin theta - a r cos t cos theta = 0 on branch ``mode``; NaN if cut off.

    theta = K q1 (K = kh) or, at fixed frequency, theta = s q1 / sqrt(1 + q1^2) (s = omega h / b1);
    q1 = Q sin t. a = mu_s / mu, r = b1 / b2.
    """
    n = mode

    def q1_of_theta(theta: float) -> float:
        if s is None:
            return theta / K
        return theta / math.sqrt(s * s - theta * theta) if theta < s else math.inf

    def t_of_q1(q1: float) -> float:
        return math.asin(min(1.0, q1 / Q))

    lo = t_of_q1(q1_of_theta(n * math.pi)) if n > 0 else 0.0
    if n > 0 and q1_of_theta(n * math.pi) >= Q:
        return math.nan  # below the cut-off
    hi = t_of_q1(q1_of_theta(n * math.pi + 0.5 * math.pi))
    sign = -1.0 if n % 2 else 1.0

    def h(t: float) -> float:
        q1 = Q * math.sin(t)
        theta = K * q1 if s is None else s * q1 / math.sqrt(1.0 + q1 * q1)
        return sign * (math.sin(t) * math.sin(theta) - a * r * math.cos(t) * math.cos(theta))

    f_lo, f_hi = h(lo), h(hi)
    if f_lo == 0.0:
        return lo
    if f_hi == 0.0:
        return hi
    if not (f_lo < 0.0 < f_hi):  # the branch's bracket is exact; this is rounding at a cut-off
        return math.nan
    return float(brentq(h, lo, hi, xtol=1e-300, rtol=4.0 * np.finfo(float).eps, maxiter=200))


def love_speed(x, params: Mapping[str, float], *, mode: int = 0, variable: Variable = "kh") -> np.ndarray:
    """Phase speed (m/s) of Love mode ``mode`` at each ``x``; NaN below its cut-off.

    Parameters
    ----------
    x : array_like, shape (n,)
        kh (wavenumber times film thickness, >= 0) or frequency (Hz, >= 0), per ``variable``.
    params : mapping
        ``mu`` (GPa) or ``E`` (GPa) and ``nu``; ``rho`` (kg/m^3); ``substrate_mu`` (GPa),
        ``substrate_rho``; ``thickness`` (m; needed with ``variable="frequency"``).
    mode : int
        0 = fundamental (no cut-off), 1, 2, ... higher modes.
    variable : {"kh", "frequency"}

    Returns
    -------
    ndarray, shape (n,)
        c in m/s: b2 at x = 0 for mode 0; NaN below a mode's cut-off, at negative or non-finite
        x, and everywhere when the film is not slower than the substrate (no Love wave exists
        then) or a modulus or density is not positive.
    """
    return _speed_and_t(x, params, mode, variable)[0]


def _speed_and_t(x, params: Mapping[str, float], mode: int, variable: Variable) -> tuple[np.ndarray, np.ndarray]:
    mu, rho, mu_s, rho_s = _moduli(params)
    xs = np.atleast_1d(np.asarray(x, dtype=float))
    if variable not in ("kh", "frequency"):
        raise InputError(f"variable must be 'kh' or 'frequency', got {variable!r}")
    if not (isinstance(mode, (int, np.integer)) and mode >= 0):
        raise InputError(f"mode must be an integer >= 0, got {mode!r}")
    c = np.full(xs.shape, np.nan)
    t = np.full(xs.shape, np.nan)
    if not all(math.isfinite(v) and v > 0 for v in (mu, rho, mu_s, rho_s)):
        return c, t  # a trial point of a fit outside physics: no wave
    b1, b2 = math.sqrt(mu / rho), math.sqrt(mu_s / rho_s)
    if not b1 < b2:
        return c, t
    Q = math.sqrt(b2 * b2 / (b1 * b1) - 1.0)
    a, r = mu_s / mu, b1 / b2
    h = float(params.get("thickness", math.nan))
    for i, xi in enumerate(xs):
        if not np.isfinite(xi) or xi < 0:
            continue
        if xi == 0.0:
            if mode == 0:
                c[i], t[i] = b2, 0.5 * math.pi
            continue
        if variable == "kh":
            ti = _solve_t(float(xi), None, a, r, Q, mode)
        else:
            ti = _solve_t(0.0, 2.0 * math.pi * float(xi) * h / b1, a, r, Q, mode)
        if np.isfinite(ti):
            q1 = Q * math.sin(ti)
            t[i], c[i] = ti, b1 * math.sqrt(1.0 + q1 * q1)
    return c, t


def love_jacobian(x, params: Mapping[str, float], names: Sequence[str], *, mode: int = 0,
                  variable: Variable = "kh") -> np.ndarray:
    """Exact sensitivities dc/dp (implicit differentiation), shape (n, len(names)).

    Units: m/s per GPa for ``mu``, ``E``, ``substrate_mu``; m/s per kg/m^3 for the densities;
    m/s per m for ``thickness``; m/s for ``nu``. NaN where c is NaN; at x = 0 (c = b2) the
    limit (only the substrate's parameters matter).
    """
    mu, rho, mu_s, rho_s = _moduli(params)
    xs = np.atleast_1d(np.asarray(x, dtype=float))
    c, t = _speed_and_t(xs, params, mode, variable)
    out = np.full((xs.size, len(names)), np.nan)
    unknown = [n for n in names if n not in LOVE_PARAMETERS]
    if unknown:
        raise InputError(f"unknown Love-model parameter(s) {unknown}; known: {list(LOVE_PARAMETERS)}")
    if not all(math.isfinite(v) and v > 0 for v in (mu, rho, mu_s, rho_s)):
        return out
    b1sq, b2sq = mu / rho, mu_s / rho_s
    if not b1sq < b2sq:
        return out
    Q = math.sqrt(b2sq / b1sq - 1.0)
    h = float(params.get("thickness", math.nan))
    for i in range(xs.size):
        if not np.isfinite(c[i]):
            continue
        ci = c[i]
        if xs[i] == 0.0:  # c = b2 exactly
            d = {"substrate_mu": ci / (2.0 * mu_s), "substrate_rho": -ci / (2.0 * rho_s)}
        else:
            q1, q2 = Q * math.sin(t[i]), math.sqrt(b1sq / b2sq) * Q * math.cos(t[i])
            if variable == "kh":
                K, dK_dc, dK_dh = xs[i], 0.0, 0.0
            else:
                w = 2.0 * math.pi * xs[i]
                K, dK_dc, dK_dh = w * h / ci, -w * h / ci**2, w / ci
            th = K * q1
            sn, cs = math.sin(th), math.cos(th)
            D = mu * q1 * cs + mu_s * q2 * sn  # dG/dtheta
            # partials of q1, q2 (c, mu, rho, mu_s, rho_s)
            q1_c, q1_mu, q1_rho = ci / (b1sq * q1), -ci * ci / (2.0 * mu * b1sq * q1), ci * ci / (2.0 * mu * q1)
            q2_c, q2_mus, q2_rhos = -ci / (b2sq * q2), ci * ci / (2.0 * mu_s * b2sq * q2), -ci * ci / (2.0 * mu_s * q2)
            G_c = mu * sn * q1_c - mu_s * cs * q2_c + D * (K * q1_c + q1 * dK_dc)
            G = {"mu": q1 * sn + (mu * sn + D * K) * q1_mu,
                 "rho": (mu * sn + D * K) * q1_rho,
                 "substrate_mu": -q2 * cs - mu_s * cs * q2_mus,
                 "substrate_rho": -mu_s * cs * q2_rhos,
                 "thickness": D * q1 * dK_dh}
            d = {k: -v / G_c for k, v in G.items()}
        d_mu = d.get("mu", 0.0)
        for j, name in enumerate(names):
            if name == "E":
                out[i, j] = d_mu * GPA / (2.0 * (1.0 + float(params["nu"])))
            elif name == "nu":
                out[i, j] = -d_mu * float(params["E"]) * GPA / (2.0 * (1.0 + float(params["nu"])) ** 2)
            elif name in ("mu", "substrate_mu"):
                out[i, j] = d.get(name, 0.0) * GPA
            else:
                out[i, j] = d.get(name, 0.0)
    return out


class LoveModel:
    """The forward model ``model(params, x) -> c`` of one Love mode, with its exact Jacobian.

    Parameters
    ----------
    mode : int
        Love mode (0 = fundamental).
    variable : {"kh", "frequency"}
        What ``x`` is: kh, or frequency in Hz.

    Notes
    -----
    Calling it returns :func:`love_speed`; :meth:`jacobian` returns :func:`love_jacobian`. The
    fitter (:func:`surfwave.metrology.fit.fit`) uses the ``jacobian`` attribute when present.
    """

    def __init__(self, mode: int = 0, variable: Variable = "kh") -> None:
        if variable not in ("kh", "frequency"):
            raise InputError(f"variable must be 'kh' or 'frequency', got {variable!r}")
        self.mode, self.variable = int(mode), variable

    def __call__(self, params: Mapping[str, float], x: np.ndarray) -> np.ndarray:
        """Phase speed (m/s), shape (n,)."""
        return love_speed(x, params, mode=self.mode, variable=self.variable)

    def jacobian(self, params: Mapping[str, float], x: np.ndarray, names: Sequence[str]) -> np.ndarray:
        """dc/dp of the named parameters, shape (n, len(names))."""
        return love_jacobian(x, params, names, mode=self.mode, variable=self.variable)

    def __repr__(self) -> str:  # noqa: D105
        return f"LoveModel(mode={self.mode}, variable={self.variable!r})"
