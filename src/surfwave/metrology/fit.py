"""Least-squares fit of a forward model's parameters to measured dispersion points, with the
covariance from the Jacobian and plain warnings when parameters are not separable.

The forward model is any callable ``model(params, x) -> c``: ``params`` a dict of named floats,
``x`` the measured abscissae (kh or frequency), ``c`` the predicted phase speed (m/s) of the
chosen mode, shape (n,). When it also has a ``jacobian(params, x, names) -> (n, m)`` method (or
one is passed as ``jacobian=``) the sensitivities dc/dp come from it; otherwise from central
differences with a step set by each parameter's scale.

The fit runs in scaled parameters u_j = p_j / s_j (s_j = |initial value|, or the bound width
when the initial value is 0), so that parameters of very different size (GPa, kg/m^3, metres)
are treated alike by the trust-region solver (:func:`scipy.optimize.least_squares`, ``trf``).
See docs/physics/metrology.md.

Examples
--------
>>> import numpy as np
>>> line = lambda p, x: p["a"] + p["b"] * x
>>> x = np.linspace(0.0, 1.0, 5)
>>> r = fit(line, x, 1.0 + 2.0 * x + np.array([0.01, -0.01, 0.0, 0.01, -0.01]),
...         {"a": 0.5, "b": 1.0}, noise="absolute")
>>> round(r["values"]["b"], 4), r["uncertainty_basis"]
(1.992, 'reduced_chi2')
"""
from __future__ import annotations

import math
from collections.abc import Callable, Mapping, Sequence
from typing import Any, Literal, TypedDict

import numpy as np
from scipy.optimize import least_squares
from scipy.special import chdtrc

from surfwave.errors import InputError
from surfwave.metrology.diagnostics import (
    NAN_PENALTY,
    PROFILE_RANGE,
    covariance,
    profile_rises,
    profile_warning,
    separability_warnings,
)

__all__ = ["FitResult", "ForwardModel", "JacobianFunction", "fit", "finite_difference_jacobian"]

ForwardModel = Callable[[dict[str, float], np.ndarray], np.ndarray]
JacobianFunction = Callable[[dict[str, float], np.ndarray, Sequence[str]], np.ndarray]

#: With jacobian_updates="broyden": rank-1 updates per free parameter between two exact Jacobians.
BROYDEN_REFRESH = 2


class FitResult(TypedDict):
    """Result of :func:`fit` (and :func:`surfwave.fit_film`).

    Attributes
    ----------
    names : list of str
        The free parameters, in the order of ``covariance`` and ``correlation``.
    values : dict of str to float
        Every parameter (free ones at their fitted value, fixed ones as given).
    uncertainties : dict of str to float
        1-sigma uncertainty of each free parameter (same unit as the value); ``inf`` for a
        parameter the data do not determine at all.
    covariance : ndarray, shape (m, m)
        Covariance of the free parameters (units: products of theirs).
    correlation : ndarray, shape (m, m)
        Correlation matrix (1); NaN where an uncertainty is infinite.
    uncertainty_basis : {"sigma", "reduced_chi2"}
        ``sigma``: propagated from the given measurement uncertainties alone;
        ``reduced_chi2``: no sigma given, the covariance is scaled by chi2/dof (the scatter of
        the residuals estimates the measurement noise).
    chi2 : float
        sum(((c_model - c) / sigma)^2). With no sigma: sigma = c (``noise="relative"``, chi2
        dimensionless) or 1 m/s (``noise="absolute"``, chi2 in (m/s)^2).
    dof : int
        Degrees of freedom, n points - m free parameters.
    reduced_chi2 : float
        chi2 / dof (NaN when dof = 0).
    p_value : float
        Probability of a chi2 at least this large (NaN without sigma).
    residuals : ndarray, shape (n,)
        c_model - c at the fitted values, m/s.
    x, c : ndarray, shape (n,)
        The data.
    sigma : ndarray, shape (n,)
        The given 1-sigma uncertainties of c (m/s); with none given, their estimate from the
        scatter, sqrt(chi2/dof) x c (relative noise) or x 1 m/s (absolute noise).
    c_model : ndarray, shape (n,)
        The model at the fitted values, m/s.
    curve_x, curve_c : ndarray, shape (k,)
        The model on a fine grid over the data's range (for figures).
    singular_values : ndarray, shape (m,)
        Of the column-normalised Jacobian, descending (1).
    condition_number : float
        Their ratio, largest / smallest (inf when rank-deficient).
    jacobian_method : {"analytic", "finite differences"}
    warnings : list of str
        Plain-language problems: parameters not separable, without effect, at a bound, a poor
        fit for the given sigma, no convergence.
    success : bool
        The least-squares solver converged.
    message : str
        The solver's message.
    nfev : int
        Model evaluations by the solver (not counting finite-difference Jacobians).
    model : str
        The forward model in words.
    x_name : str
        What x is ("kh", "frequency_Hz", ...).
    noise : {"sigma", "relative", "absolute"}
        How the points were weighted: by the given sigma, or (none given) as equally uncertain
        in relative terms or in m/s; then sqrt(reduced_chi2) is the noise estimated from the
        scatter (a fraction of c, or m/s).
    """

    names: list[str]
    values: dict[str, float]
    uncertainties: dict[str, float]
    covariance: np.ndarray
    correlation: np.ndarray
    uncertainty_basis: Literal["sigma", "reduced_chi2"]
    chi2: float
    dof: int
    reduced_chi2: float
    p_value: float
    residuals: np.ndarray
    x: np.ndarray
    c: np.ndarray
    sigma: np.ndarray
    c_model: np.ndarray
    curve_x: np.ndarray
    curve_c: np.ndarray
    singular_values: np.ndarray
    condition_number: float
    jacobian_method: Literal["analytic", "finite differences"]
    warnings: list[str]
    success: bool
    message: str
    nfev: int
    model: str
    x_name: str
    noise: Literal["sigma", "relative", "absolute"]


def _data(x, c, sigma) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    arrays = []
    for name, v in (("x", x), ("c", c)):
        a = np.atleast_1d(np.asarray(v, dtype=float))
        if a.ndim != 1:
            raise InputError(f"{name} must be 1-D, got shape {a.shape}")
        if not np.all(np.isfinite(a)):
            raise InputError(f"{name} must be finite, got {a[~np.isfinite(a)][:3].tolist()}")
        arrays.append(a)
    xa, ca = arrays
    if xa.shape != ca.shape:
        raise InputError(f"x and c must have the same length, got {xa.size} and {ca.size}")
    if sigma is None:
        return xa, ca, None
    s = np.broadcast_to(np.asarray(sigma, dtype=float), ca.shape).copy()
    if not np.all(np.isfinite(s) & (s > 0)):
        raise InputError(f"sigma must be finite and > 0, got {s[~(np.isfinite(s) & (s > 0))][:3].tolist()}")
    return xa, ca, s


def _parameters(initial: Mapping[str, float], free: Sequence[str] | None,
                bounds: Mapping[str, tuple[float, float]] | None) -> tuple[list[str], np.ndarray, np.ndarray]:
    """Free names, their (lo, hi) bounds, their scales; every problem named."""
    init = {}
    for k, v in initial.items():
        try:
            init[k] = float(v)
        except (TypeError, ValueError):
            raise InputError(f"initial value of {k!r} must be a number, got {v!r}") from None
        if not math.isfinite(init[k]):
            raise InputError(f"initial value of {k!r} must be finite, got {v!r}")
    names = list(init) if free is None else list(free)
    if not names:
        raise InputError("no free parameter: name at least one in 'free'")
    unknown = [n for n in names if n not in init]
    if unknown:
        raise InputError(f"free parameter(s) {unknown} have no initial value; given: {sorted(init)}")
    if len(set(names)) != len(names):
        raise InputError(f"free parameters named twice: {names}")
    bounds = dict(bounds or {})
    stray = [b for b in bounds if b not in names]
    if stray:
        raise InputError(f"bounds given for {stray}, which are not free parameters {names}")
    lo = np.full(len(names), -np.inf)
    hi = np.full(len(names), np.inf)
    for j, n in enumerate(names):
        if n in bounds:
            try:
                lo[j], hi[j] = (float(b) for b in bounds[n])
            except (TypeError, ValueError):
                raise InputError(f"bounds of {n!r} must be a pair (low, high), got {bounds[n]!r}") from None
            if not lo[j] < hi[j]:
                raise InputError(f"bounds of {n!r} must have low < high, got {bounds[n]!r}")
            if not lo[j] <= init[n] <= hi[j]:
                raise InputError(f"initial value {init[n]!r} of {n!r} is outside its bounds {bounds[n]!r}")
    scale = np.array([abs(init[n]) for n in names])
    for jz in np.flatnonzero(scale == 0):
        width = hi[jz] - lo[jz]
        scale[jz] = width if np.isfinite(width) else 1.0
    return names, np.stack([lo, hi]), scale


def finite_difference_jacobian(model: ForwardModel, params: Mapping[str, float], x: np.ndarray,
                               names: Sequence[str], scale: np.ndarray | None = None,
                               bounds: np.ndarray | None = None) -> np.ndarray:
    """Central differences dc/dp, shape (n, m), with steps eps^(1/3) x each parameter's scale.

    Parameters
    ----------
    model : callable
        ``model(params, x) -> c``.
    params : mapping
        Where to differentiate.
    x : ndarray, shape (n,)
    names : sequence of str, length m
    scale : ndarray, shape (m,), optional
        Typical size of each parameter (default: |value|, or 1 at 0). The step is
        eps^(1/3) * scale, which balances truncation (step^2) and rounding (eps / step) errors.
    bounds : ndarray, shape (2, m), optional
        Where a central step would leave the bounds, a one-sided second-order formula is used.
    """
    p = {k: float(v) for k, v in params.items()}
    if scale is None:
        scale = np.array([abs(p[n]) or 1.0 for n in names])
    step = np.finfo(float).eps ** (1.0 / 3.0) * np.asarray(scale, dtype=float)
    cols = []
    for j, n in enumerate(names):
        h = float(step[j])
        lo, hi = (-np.inf, np.inf) if bounds is None else (bounds[0, j], bounds[1, j])

        def at(delta: float, n: str = n) -> np.ndarray:
            q = dict(p)
            q[n] = p[n] + delta
            return np.asarray(model(q, x), dtype=float)

        if p[n] - h >= lo and p[n] + h <= hi:
            cols.append((at(h) - at(-h)) / (2.0 * h))
        else:
            sgn = 1.0 if p[n] + 2.0 * h <= hi else -1.0
            cols.append(sgn * (-3.0 * at(0.0) + 4.0 * at(sgn * h) - at(2.0 * sgn * h)) / (2.0 * h))
    return np.stack(cols, axis=1)


def fit(model: ForwardModel, x, c, initial: Mapping[str, float], *, free: Sequence[str] | None = None,
        bounds: Mapping[str, tuple[float, float]] | None = None, sigma=None,
        jacobian: JacobianFunction | None = None, noise: Literal["relative", "absolute"] = "relative",
        jacobian_updates: Literal["exact", "broyden"] = "exact",
        context: str = "from these data", x_name: str = "x", description: str | None = None,
        check_linearity: bool | Literal["fast", "profile"] = True,
        max_nfev: int = 200, curve_points: int = 200) -> FitResult:
    """Fit the free parameters of ``model`` to measured points (x, c) by least squares.

    Parameters
    ----------
    model : callable
        ``model(params: dict[str, float], x: ndarray) -> ndarray``, the predicted phase speed
        (m/s), shape (n,), NaN where the model has no answer. If it has a ``jacobian`` method
        it is used for dc/dp (see ``jacobian``).
    x : array_like, shape (n,)
        Measured abscissae (kh, or frequency in Hz: whatever ``model`` takes).
    c : array_like, shape (n,)
        Measured phase speeds, m/s.
    initial : mapping of str to float
        Every parameter the model needs: the free ones' starting values, the fixed ones'
        values.
    free : sequence of str, optional
        The parameters to fit (default: all of ``initial``).
    bounds : mapping of str to (float, float), optional
        (low, high) of some free parameters (default unbounded).
    sigma : float or array_like, shape (n,), optional
        1-sigma uncertainty of each c, m/s. Given: weighted fit, uncertainties from sigma
        alone (``uncertainty_basis = "sigma"``). Not given: see ``noise``; the covariance is
        scaled by the reduced chi^2 (``"reduced_chi2"``).
    jacobian : callable, optional
        ``jacobian(params, x, names) -> ndarray (n, len(names))``, dc/dp. Default: the
        model's ``jacobian`` attribute if it has one, else central differences
        (:func:`finite_difference_jacobian`).
    jacobian_updates : {"exact", "broyden"}
        ``exact``: a fresh Jacobian at every iteration. ``broyden``: between fresh ones (every
        max(3, m) iterations) the Jacobian is updated from the steps already taken (Broyden's
        rank-1 update), which saves the 2 m model calls of a finite-difference Jacobian per
        iteration; the solution is then checked with an exact Jacobian (and finished with
        exact ones if the Gauss-Newton step left exceeds 1 % of a 1-sigma), and the
        covariance always comes from an exact Jacobian at the solution. For expensive models
        without a Jacobian.
    noise : {"relative", "absolute"}
        Without ``sigma``: every point equally uncertain in relative terms (sigma_i
        proportional to c_i, the default: timing and frequency errors scale with c) or in m/s;
        the common factor is estimated from the scatter. Ignored when ``sigma`` is given.
    context : str
        Words describing the data for the warnings ("from one mode at kh 0.05-0.3").
    x_name : str
        What x is ("kh", "frequency_Hz"), recorded in the result.
    check_linearity : bool or {"fast", "profile"}
        Hold each free parameter one sigma above and below its fitted value, refit the others
        (up to three fixed-Jacobian steps) and warn when chi^2 rises by less than 0.6 or more
        than 1.6 instead of 1: the model is then not linear over the 1-sigma range and the
        linear uncertainty is off by more than about 25 % on that side. ``True`` (= ``"fast"``,
        the default): each side's refit stops as soon as its rise is known to lie inside that
        range (:func:`surfwave.metrology.diagnostics.profile_rises` with ``accept``; 2 model
        calls per free parameter where the model is linear over one sigma, up to 8 where it
        bends); ``"profile"``: the three steps everywhere (8 m model calls); the same warnings
        either way. ``False``: no check.
    description : str, optional
        The model in words, recorded in the result (default: ``repr(model)``).
    max_nfev : int
        Most model evaluations of the solver.
    curve_points : int
        Points of ``curve_x``/``curve_c`` (the fitted model over the data's range; 0: none).

    Returns
    -------
    FitResult
        Values, 1-sigma uncertainties, covariance and correlation, chi^2, dof, residuals and
        warnings (:class:`FitResult`).

    Raises
    ------
    InputError
        Bad data, parameters or bounds, fewer points than free parameters, or a model with no
        answer at the initial values; before any fit.
    """
    xa, ca, sa = _data(x, c, sigma)
    names, bnds, scale = _parameters(initial, free, bounds)
    m, n = len(names), xa.size
    if n < m or (sa is None and n == m):
        raise InputError(f"{n} points cannot determine {m} free parameters {names}"
                         + ("" if sa is not None else " and the noise level (give sigma or more points)"))
    base = {k: float(v) for k, v in initial.items()}
    jac_fn = jacobian if jacobian is not None else getattr(model, "jacobian", None)
    if noise not in ("relative", "absolute"):
        raise InputError(f"noise must be 'relative' or 'absolute', got {noise!r}")
    if jacobian_updates not in ("exact", "broyden"):
        raise InputError(f"jacobian_updates must be 'exact' or 'broyden', got {jacobian_updates!r}")
    if check_linearity not in (True, False, "fast", "profile"):
        raise InputError(f"check_linearity must be True, False, 'fast' or 'profile', got {check_linearity!r}")
    if sa is not None:
        w = sa
    else:
        w = np.abs(ca) if noise == "relative" else np.ones(n)
        if np.any(w == 0):
            raise InputError("noise='relative' needs c != 0 at every point; give sigma or noise='absolute'")

    def params_of(u: np.ndarray) -> dict[str, float]:
        p = dict(base)
        p.update({nm: float(u[j] * scale[j]) for j, nm in enumerate(names)})
        return p

    def dcdp(p: dict[str, float]) -> np.ndarray:
        if jac_fn is not None:
            J = np.asarray(jac_fn(p, xa, names), dtype=float).reshape(n, m)
        else:
            J = finite_difference_jacobian(model, p, xa, names, scale, bnds)
        return J

    c0 = np.asarray(model(dict(base), xa), dtype=float)
    if c0.shape != (n,):
        raise InputError(f"the model returned shape {c0.shape} for {n} points")
    if not np.all(np.isfinite(c0)):
        bad = xa[~np.isfinite(c0)]
        raise InputError(f"the model has no answer at x = {bad[:5].tolist()} with the initial values "
                         f"{ {k: base[k] for k in names} } (a mode below its cut-off?); change them or the data")

    tried: dict[bytes, np.ndarray] = {}  # residuals at the points the solver evaluated (the last few)
    exact: dict[bytes, np.ndarray] = {}  # the last exact (model's or finite-difference) scaled Jacobian
    last: dict[str, Any] = {"u": None, "r": None, "J": None, "updates": 0}
    refresh = BROYDEN_REFRESH * m  # Broyden updates between two exact Jacobians

    def residual(u: np.ndarray) -> np.ndarray:
        key = u.tobytes()
        if key not in tried:  # the solver asks again for the start and the solution: one model call each
            r = (np.asarray(model(params_of(u), xa), dtype=float) - ca) / w
            if len(tried) > 64:
                tried.clear()
            tried[key] = np.where(np.isfinite(r), r, NAN_PENALTY)
        return tried[key]

    def exact_jac(u: np.ndarray) -> np.ndarray:
        key = u.tobytes()
        if key not in exact:
            J = dcdp(params_of(u)) * scale[None, :] / w[:, None]
            exact.clear()
            exact[key] = np.where(np.isfinite(J), J, 0.0)
        return exact[key]

    def jac_u(u: np.ndarray) -> np.ndarray:
        r = tried.get(u.tobytes())
        if (jacobian_updates == "broyden" and last["J"] is not None and r is not None
                and last["r"] is not None and last["updates"] < refresh):
            du, dr = u - last["u"], r - last["r"]
            dd = float(du @ du)
            J = last["J"] + np.outer(dr - last["J"] @ du, du) / dd if dd > 0 else last["J"]
            last["updates"] += 1
        else:
            J = exact_jac(u)
            last["updates"] = 0
        last.update(u=u.copy(), r=r, J=J)
        return J

    u0 = np.array([base[nm] / scale[j] for j, nm in enumerate(names)])
    tried[u0.tobytes()] = (c0 - ca) / w
    lb, ub = bnds[0] / scale, bnds[1] / scale
    opts = dict(bounds=(lb, ub), method="trf", x_scale=1.0, xtol=1e-12, ftol=1e-12, gtol=1e-12)
    sol = least_squares(residual, u0, jac=jac_u, max_nfev=max_nfev, **opts)
    if jacobian_updates == "broyden" and not _converged(exact_jac(sol.x), sol.fun, sa is None):
        # the updated Jacobian can stop the solver short: finish with exact Jacobians
        nfev = sol.nfev
        jacobian_updates = "exact"
        sol = least_squares(residual, sol.x, jac=jac_u, max_nfev=max_nfev, **opts)
        sol.nfev += nfev
    p_fit = params_of(sol.x)
    r_fit = tried.get(sol.x.tobytes())
    if r_fit is not None and np.all(r_fit != NAN_PENALTY):
        c_fit = ca + r_fit * w
    else:
        c_fit = np.asarray(model(p_fit, xa), dtype=float)
    resid = c_fit - ca
    J_u = exact_jac(sol.x)
    chi2 = float(np.sum((resid / w) ** 2))
    dof = n - m
    red = chi2 / dof if dof > 0 else math.nan
    cov_u, sv, cond, null = covariance(J_u)
    if sa is None:
        cov_u = cov_u * red
    cov = cov_u * scale[:, None] * scale[None, :]
    sd = np.sqrt(np.diag(cov))
    with np.errstate(invalid="ignore", divide="ignore"):
        corr = cov / np.outer(sd, sd)
    corr[~np.isfinite(corr)] = np.nan
    np.fill_diagonal(corr, np.where(np.isfinite(sd), 1.0, np.nan))
    p_value = float(chdtrc(dof, chi2)) if (sa is not None and dof > 0) else math.nan
    warns = separability_warnings(names, J_u, corr, cond, null, context, sol, p_fit, bnds, sd, red, p_value)
    if check_linearity and np.all(np.isfinite(cov_u)) and (sa is not None or red > 0):
        rises = profile_rises(residual, sol.x, cov_u, J_u, red if sa is None else 1.0, lb, ub,
                              accept=None if check_linearity == "profile" else PROFILE_RANGE)
        text = profile_warning(names, rises, sd)
        if text:
            warns.append(text)
    if curve_points > 0:
        curve_x = np.linspace(float(xa.min()), float(xa.max()), curve_points)
        curve_c = np.asarray(model(p_fit, curve_x), dtype=float)
    else:
        curve_x = curve_c = np.empty(0)
    return FitResult(
        names=names, values=p_fit, uncertainties={nm: float(sd[j]) for j, nm in enumerate(names)},
        covariance=cov, correlation=corr, uncertainty_basis="sigma" if sa is not None else "reduced_chi2",
        chi2=chi2, dof=dof, reduced_chi2=red, p_value=p_value, residuals=resid, x=xa, c=ca,
        sigma=sa if sa is not None else math.sqrt(red) * w, c_model=c_fit, curve_x=curve_x, curve_c=curve_c,
        singular_values=sv, condition_number=cond,
        jacobian_method="analytic" if jac_fn is not None else "finite differences",
        warnings=warns, success=bool(sol.success), message=str(sol.message), nfev=int(sol.nfev),
        model=description if description is not None else repr(model), x_name=x_name,
        noise="sigma" if sa is not None else noise)


def _converged(J: np.ndarray, r: np.ndarray, scaled: bool) -> bool:
    """Whether the Gauss-Newton step from the exact Jacobian is below 1 % of every 1-sigma."""
    step = np.linalg.lstsq(J, -r, rcond=None)[0]
    dof = max(J.shape[0] - J.shape[1], 1)
    var = np.diag(np.linalg.pinv(J.T @ J)) * (float(r @ r) / dof if scaled else 1.0)
    return bool(np.all(np.abs(step) <= 0.01 * np.sqrt(var) + 1e-12 * np.abs(step).max(initial=0.0)))
