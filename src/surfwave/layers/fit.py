"""Thin-film metrology: fit film parameters to a measured dispersion curve by least squares.

:func:`fit_film` adjusts named parameters of the films (Young's modulus ``E``, Poisson's ratio
``nu``, density ``rho``, ``thickness``, equibiaxial ``stress`` or a Voigt constant ``C11``,
``C13``, ...) so that the speeds of one mode (label, e.g. "R") match measured points given at kh
or at frequencies, weighted by their uncertainties.

Sensitivities by implicit differentiation. At a mode, lam(c, p) = 0, where lam is the eigenvalue
of the boundary matrix that vanishes there (:mod:`surfwave.layers.recursion`; with frequency data
kh = 2 pi f H / c also depends on c and on the thickness). Hence

    dc/dp = -(d lam / dp) / (d lam / dc),

both partial derivatives of the secular eigenvalue at the solved c (central differences of lam,
which cost no root search). The tests compare dc/dp with finite differences of solved speeds.
The covariance of the parameters is (J^T W J)^-1 (scaled by the reduced chi^2 when no
uncertainties are given); 1-sigma uncertainties and correlations follow, and a plain message
says when parameters are not separable (|correlation| > 0.99 or an ill-conditioned J^T W J).
"""
from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.recursion import boundary_matrix, top_impedance
from surfwave.layers.stack import resolve_stack

__all__ = ["fit_film", "sensitivities"]

_SCALAR = ("E", "nu", "rho", "thickness", "stress")
#: Relative step of the central differences of lam in a parameter, and in c.
STEP_P = 1e-6
STEP_C = 1e-7
#: Smallest absolute step per parameter kind (stress in GPa may start at 0).
MIN_STEP = {"stress": 1e-4, "nu": 1e-7}


def _parse(name: str) -> tuple[int, str]:
    """'E' -> (0, 'E'); '1.thickness' -> (1, 'thickness'); 'C13' -> (0, 'C13')."""
    idx, key = (name.split(".", 1) if "." in name else ("0", name))
    try:
        i = int(idx)
    except ValueError:
        raise InputError(f"parameter {name!r}: use KEY or FILM.KEY (film index from the top)") from None
    if key not in _SCALAR and not (len(key) == 3 and key[0] == "C" and key[1] in "123456" and key[2] in "123456"):
        raise InputError(f"parameter {name!r}: fit one of {list(_SCALAR)} or a Voigt constant Cij")
    return i, key


def _get(films: list, i: int, key: str) -> float:
    f = films[i]
    if key.startswith("C"):
        if "voigt" not in f:
            raise InputError(f"parameter {key} of film {i}: give that film as a voigt mapping to fit its constants")
        return float(np.asarray(f["voigt"], dtype=float)[int(key[1]) - 1, int(key[2]) - 1])
    if key not in f:
        if key == "stress":
            return 0.0
        raise InputError(f"parameter {key!r} of film {i}: the film has no {key!r} to start from")
    return float(f[key])


def _set(films: list, i: int, key: str, value: float) -> None:
    f = films[i]
    if key.startswith("C"):
        C = np.array(f["voigt"], dtype=float)
        a, b = int(key[1]) - 1, int(key[2]) - 1
        C[a, b] = C[b, a] = value
        f["voigt"] = C
    else:
        f[key] = value


def _explicit(film: Mapping) -> dict:
    """A film given by name as explicit constants: {E, nu, rho} if isotropic, else {voigt, rho} (+ the rest)."""
    from surfwave.layers.films import lookup

    f = dict(film)
    name = f.pop("name", None) or f.pop("material", None)
    if name is None:
        return f
    rec = lookup(str(name))
    if rec.get("e") is not None:
        raise InputError(f"fitting a piezoelectric film ({name}) is not supported; give it by constants")
    C = np.asarray(rec["voigt"], dtype=float)
    lam, mu = C[0, 1], C[3, 3]
    iso = np.allclose(C, _iso(lam, mu), rtol=1e-9, atol=1e-9 * np.abs(C).max())
    if iso:
        f.update(E=float(mu * (3 * lam + 2 * mu) / (lam + mu)), nu=float(lam / (2 * (lam + mu))))
    else:
        f["voigt"] = C
    f.setdefault("rho", rec["rho"])
    if rec.get("eps_r") is not None:
        f.setdefault("permittivity", np.asarray(rec["eps_r"]))
    return f


def _iso(lam: float, mu: float) -> np.ndarray:
    C = np.zeros((6, 6))
    C[:3, :3] = lam
    C[[0, 1, 2], [0, 1, 2]] = lam + 2 * mu
    C[[3, 4, 5], [3, 4, 5]] = mu
    return C


class _Model:
    """Speeds of one mode at the data points as a function of the parameter vector."""

    def __init__(self, substrate, films, names, mode, kw, kh=None, frequency=None) -> None:
        self.keys = [_parse(n) for n in names]
        fitted = {i for i, _ in self.keys}
        films = [_explicit(f) if k in fitted else f for k, f in enumerate(films)]
        self.substrate, self.films0, self.mode, self.kw = substrate, films, mode, kw
        for i, _ in self.keys:
            if not 0 <= i < len(films):
                raise InputError(f"film index {i} out of range (there are {len(films)} films)")
        self.kh, self.frequency = kh, frequency
        self.p0 = np.array([_get(films, i, k) for i, k in self.keys])

    def films(self, p) -> list:
        films = copy.deepcopy(list(self.films0))
        for (i, k), v in zip(self.keys, p):
            _set(films, i, k, float(v))
        return films

    def speeds(self, p) -> np.ndarray:
        import surfwave

        films = self.films(p)
        arg = {"kh": self.kh} if self.kh is not None else {"frequency": self.frequency}
        r = surfwave.layered(self.substrate, films, **self.kw, **arg)
        hit = r["mode"] == self.mode
        c = np.full(hit.shape[0], np.nan)
        rows, cols = np.nonzero(hit)
        c[rows] = r["c"][rows, cols]
        self.last_kh = np.full(hit.shape[0], np.nan)
        self.last_kh[rows] = r["kh"][rows, cols]
        return c

    def lam(self, p, c, kh_of_c) -> np.ndarray:
        """The boundary eigenvalue nearest zero at speeds c (m,) with kh = kh_of_c(c, films)."""
        films = self.films(p)
        st = resolve_stack(self.substrate, films, euler=self.kw.get("euler"), surface=self.kw.get("surface", "(001)"),
                           direction=self.kw.get("direction", "[100]"), stress=self.kw.get("stress"))
        b = scaled_blocks(st)
        fam = next(f for f in families(b) if self.mode.rstrip("~").startswith(
            {"R": "R", "S": "R", "L": "L", "M": "M"}[self.mode[0]]) and f.prefix == {"R": "R", "S": "R", "L": "L",
                                                                                    "M": "M"}[self.mode[0]])
        kh = kh_of_c(c, st.total_thickness)
        M = top_impedance(b, fam, c, kh[:, None])["M"][:, 0]
        Z, _ = boundary_matrix(b, fam, M, self.kw.get("electrical", "free"))
        w = np.linalg.eigvalsh(Z)
        return np.take_along_axis(w, np.argmin(np.abs(w), axis=-1)[:, None], axis=-1)[:, 0]


def sensitivities(model: _Model, p, c) -> np.ndarray:
    """dc/dp (n, m) at the solved speeds c (n,) by implicit differentiation of the secular eigenvalue."""
    if model.kh is not None:
        kh = np.asarray(model.kh, dtype=float)

        def kh_of_c(cc, H):
            return kh
    else:
        f = np.asarray(model.frequency, dtype=float)

        def kh_of_c(cc, H):
            return 2 * np.pi * f * H / cc
    hc = STEP_C * c
    dl_dc = (model.lam(p, c + hc, kh_of_c) - model.lam(p, c - hc, kh_of_c)) / (2 * hc)
    J = np.zeros((c.size, p.size))
    for j in range(p.size):
        h = max(STEP_P * abs(p[j]), MIN_STEP.get(model.keys[j][1], 0.0), 1e-300)
        pp, pm = p.copy(), p.copy()
        pp[j] += h
        pm[j] -= h
        dl_dp = (model.lam(pp, c, kh_of_c) - model.lam(pm, c, kh_of_c)) / (2 * h)
        J[:, j] = -dl_dp / dl_dc
    return J


def fit_film(substrate, films, data: Mapping, params: Sequence[str], *, mode: str = "R", euler=None,
             surface: str = "(001)", direction="[100]", electrical: str = "free", stress=None,
             max_iterations: int = 50) -> dict:
    """Least-squares fit of film parameters to measured speeds of one mode.

    Parameters
    ----------
    substrate, films
        As for :func:`surfwave.layered`; the films hold the starting values.
    data : mapping
        ``kh`` (n,) or ``frequency`` (n,) Hz; ``c`` (n,) measured phase speeds, m/s; optional
        ``sigma`` (n,) their 1-sigma uncertainties, m/s.
    params : sequence of str
        Names ``KEY`` (top film) or ``FILM.KEY``: E (GPa), nu, rho (kg/m^3), thickness (m),
        stress (GPa, equibiaxial), or a Voigt constant Cij (GPa, film given by ``voigt``).
    mode : str
        Label of the measured mode ("R", "S1", "L0", "M0", ...).
    max_iterations : int
        Gauss-Newton (Levenberg-Marquardt) iterations at most.

    Returns
    -------
    dict
        ``values`` (m,), ``uncertainty`` (m,) 1 sigma, ``correlation`` (m, m), ``covariance`` (m, m),
        ``names``, ``residuals`` (n,) m/s, ``chi2`` (weighted sum of squares), ``dof``,
        ``jacobian`` (n, m) dc/dp, ``converged`` (bool), ``message`` (str: "" or why parameters are
        not separable / the fit did not converge).

    Raises
    ------
    InputError
        Bad data or parameter names, a mode missing at a data point for the starting values.
    """
    from scipy.optimize import least_squares

    c_obs = validate.real_array(data.get("c"), "data c").reshape(-1)
    if ("kh" in data) == ("frequency" in data):
        raise InputError("data needs exactly one of 'kh' or 'frequency'")
    x = validate.real_array(data["kh"] if "kh" in data else data["frequency"], "data kh/frequency").reshape(-1)
    if x.size != c_obs.size or c_obs.size == 0 or not (np.all(np.isfinite(x)) and np.all(np.isfinite(c_obs))):
        raise InputError(f"data: kh/frequency and c must be finite arrays of one length, got {x.size} and "
                         f"{c_obs.size}")
    sigma = np.ones(c_obs.size) if data.get("sigma") is None else \
        validate.real_array(data["sigma"], "data sigma").reshape(-1)
    if sigma.size != c_obs.size or np.any(~(sigma > 0)):
        raise InputError("data sigma must be positive, one per point")
    if len(params) == 0 or len(set(params)) != len(params):
        raise InputError(f"params must name distinct parameters, got {list(params)}")
    if len(params) >= c_obs.size:
        raise InputError(f"{len(params)} parameters cannot be fitted to {c_obs.size} points")
    kw = {"euler": euler, "surface": surface, "direction": direction, "electrical": electrical, "stress": stress}
    model = _Model(substrate, list(films), list(params), mode, kw,
                   kh=x if "kh" in data else None, frequency=x if "frequency" in data else None)
    p0 = model.p0
    scale = np.where(np.abs(p0) > 0, np.abs(p0), 1.0)
    c0 = model.speeds(p0)
    if not np.all(np.isfinite(c0)):
        raise InputError(f"mode {mode!r} is missing at {int(np.sum(~np.isfinite(c0)))} data points for the "
                         "starting values")
    cache: dict = {}

    def speeds(z):
        key = z.tobytes()
        if key not in cache:
            cache.clear()
            cache[key] = model.speeds(z * scale)
        return cache[key]

    def resid(z):
        c = speeds(z)
        return np.where(np.isfinite(c), (c - c_obs) / sigma, 1e6)

    def jac(z):
        c = speeds(z)
        J = sensitivities(model, z * scale, np.where(np.isfinite(c), c, c_obs))
        return J * scale[None, :] / sigma[:, None]

    sol = least_squares(resid, p0 / scale, jac=jac, method="lm", max_nfev=max_iterations * (p0.size + 1),
                        xtol=1e-12, ftol=1e-12)
    p = sol.x * scale
    c = model.speeds(p)
    J = sensitivities(model, p, c)
    Jw = J * scale[None, :] / sigma[:, None]                       # per relative change of each parameter
    A = Jw.T @ Jw
    dof = c_obs.size - p.size
    chi2 = float(np.sum(((c - c_obs) / sigma) ** 2))
    message = "" if sol.success else f"the fit did not converge: {sol.message}"
    with np.errstate(all="ignore"):
        cond = np.linalg.cond(A)
        try:
            cov = np.linalg.inv(A) * np.outer(scale, scale)
        except np.linalg.LinAlgError:
            cov = np.full(A.shape, np.inf)
    if data.get("sigma") is None:
        cov = cov * chi2 / max(dof, 1)
    unc = np.sqrt(np.clip(np.diag(cov), 0, None))
    with np.errstate(all="ignore"):
        corr = cov / np.outer(unc, unc)
    pairs = [(params[i], params[j], corr[i, j]) for i in range(p.size) for j in range(i + 1, p.size)
             if abs(corr[i, j]) > 0.99]
    if pairs or cond > 1e12:
        what = ", ".join(f"{a} and {b} (correlation {r:+.4f})" for a, b, r in pairs) or \
            f"(condition number of J^T W J {cond:.3g})"
        message = (message + "; " if message else "") + f"not separable from these data: {what}"
    return {"values": p, "uncertainty": unc, "correlation": corr, "covariance": cov, "names": list(params),
            "residuals": c - c_obs, "chi2": chi2, "dof": dof, "jacobian": J, "converged": bool(sol.success),
            "message": message}
