"""Diagnostics of a least-squares fit: the covariance from the Jacobian, the warnings when
parameters are not separable, and the profile check of the linear uncertainties.

Used by :func:`surfwave.metrology.fit.fit`; see docs/physics/metrology.md for what each test
means and why its threshold is where it is.
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np

__all__ = ["CONDITION_LIMIT", "CORRELATION_LIMIT", "LOOSE", "NAN_PENALTY", "PREDICTION_MARGIN", "PROFILE_RANGE",
           "RANK_TOL", "covariance", "profile_rises", "profile_warning", "separability_warnings"]

#: |correlation| above which two parameters are reported as not separable.
CORRELATION_LIMIT = 0.99
#: Condition number of the column-normalised Jacobian above which the weakest combination of
#: parameters is reported (two parameters at |r| = 0.99 give about 14; 1e3 means some
#: combination is determined 1000 x worse than the best one).
CONDITION_LIMIT = 1.0e3
#: Relative 1-sigma uncertainty above which a strongly correlated pair is called not separable
#: (below it the pair is reported as correlated: determined, but mainly as a combination).
LOOSE = 0.1
#: Singular values below this fraction of the largest count as zero (no information at all).
RANK_TOL = 1.0e-9
#: Residual (in units of sigma) that stands in for a point where the model has no answer
#: (a mode cut off) during the iterations: the trust region rejects such a step.
NAN_PENALTY = 1.0e8
#: Range of the profile chi^2 rise one sigma from the fitted value (1 for a model linear over the
#: 1-sigma region) outside which the fit warns that the linear uncertainty is off: 0.6 and 1.6
#: correspond to a profile 1-sigma about 30 % wider or 20 % narrower than the linear one.
PROFILE_RANGE = (0.6, 1.6)
#: How far above the lower end of the range the rise predicted for the next chord step must be for
#: a refit to stop early (:func:`profile_rises` with ``accept``): the prediction is first order; in
#: seeded layered fits it was up to 0.032 above the three-step rise (docs/physics/metrology.md).
PREDICTION_MARGIN = 0.05


def profile_rises(residual: Callable[[np.ndarray], np.ndarray], u: np.ndarray, cov: np.ndarray,
                  J: np.ndarray, unit: float, lb: np.ndarray, ub: np.ndarray, *,
                  accept: tuple[float, float] | None = None) -> np.ndarray:
    """chi^2 rise when each parameter is held one sigma away and the others are refitted.

    Returns shape (m, 2) (+ sigma, - sigma), in units of ``unit`` (the variance of one weighted
    residual: 1 with given sigma, chi2/dof otherwise); NaN where the step crosses a bound, inf
    where the model has no answer. A model linear over the 1-sigma region gives exactly 1
    everywhere. The others are refitted by three chord (fixed-Jacobian Gauss-Newton) steps from
    the linear prediction (the conditional optimum of the linearised model, where chi^2 rises by
    exactly 1), so the check costs 8 m model calls and no new Jacobian.

    With ``accept = (lo, hi)`` the refit of one side stops early, after the model call at the
    linear prediction or after any chord step, once the result is known to lie in [lo, hi]:
    the rise evaluated there (the others not yet optimal: an upper bound of the refitted rise)
    is at most ``hi``, and the rise the next chord step predicts (that bound minus the squared
    projection of the residuals onto the others' Jacobian columns) is at least ``lo`` +
    :data:`PREDICTION_MARGIN`. The value returned for that side is then the bound (inside
    [lo, hi]); sides that do not pass get the full three steps and the same number as without
    ``accept``; where a parameter is then out of range, its other side is refitted in full too
    (the warning quotes both; the points it already evaluated are not evaluated again). Cost:
    2 m model calls where the model is linear over one sigma, about 4 m along a curved valley of
    chi^2, 8 m where it bends (as without ``accept``).
    """
    seen: dict[bytes, np.ndarray] = {}

    def memo(v: np.ndarray) -> np.ndarray:  # a side refitted in full after an early stop retraces its points
        key = v.tobytes()
        if key not in seen:
            seen[key] = residual(v)
        return seen[key]

    r0 = residual(u)
    chi0 = float(r0 @ r0)
    m = u.size
    out = np.full((m, 2), np.nan)
    for j in range(m):
        if not cov[j, j] > 0:
            continue
        early = [False, False]
        for col, sgn in enumerate((1.0, -1.0)):
            out[j, col], early[col] = _profile_side(memo, u, cov, J, j, sgn, chi0, unit, lb, ub, accept)
        if any(not e and not _inside(v, accept) for e, v in zip(early, out[j])):
            # flagged: the warning quotes both sides, so the side that stopped early gets the full refit
            for col, sgn in enumerate((1.0, -1.0)):
                if early[col]:
                    out[j, col] = _profile_side(memo, u, cov, J, j, sgn, chi0, unit, lb, ub, None)[0]
    return out


def _inside(v: float, band: tuple[float, float] | None) -> bool:
    """Whether a rise raises no warning: inside ``band`` (default :data:`PROFILE_RANGE`), or NaN (a bound)."""
    band = PROFILE_RANGE if band is None else band
    return bool(np.isfinite(v) and band[0] <= v <= band[1]) or bool(np.isnan(v))


def _profile_side(residual: Callable[[np.ndarray], np.ndarray], u: np.ndarray, cov: np.ndarray, J: np.ndarray,
                  j: int, sgn: float, chi0: float, unit: float, lb: np.ndarray, ub: np.ndarray,
                  accept: tuple[float, float] | None) -> tuple[float, bool]:
    """One side of :func:`profile_rises`: (the rise, whether it stopped early by ``accept``)."""
    m = u.size
    others = [k for k in range(m) if k != j]
    Jo = J[:, others]
    v = u + sgn * cov[:, j] / math.sqrt(cov[j, j])  # held one sigma off, others at the linear optimum
    for _ in range(3 if others else 0):
        r = residual(v)
        if np.any(r == NAN_PENALTY):
            break
        delta = np.linalg.lstsq(Jo, r, rcond=None)[0]
        if accept is not None and not (np.any(v < lb) or np.any(v > ub)):
            bound = (float(r @ r) - chi0) / unit       # the others not yet optimal: above the profile
            gain = Jo @ delta                          # what the next chord step is predicted to remove
            if bound <= accept[1] and bound - float(gain @ gain) / unit >= accept[0] + PREDICTION_MARGIN:
                return bound, True
        v[others] -= delta
    if np.any(v < lb) or np.any(v > ub):
        return math.nan, False
    r = residual(v)
    return (math.inf if np.any(r == NAN_PENALTY) else (float(r @ r) - chi0) / unit), False


def covariance(J: np.ndarray) -> tuple[np.ndarray, np.ndarray, float, np.ndarray]:
    """(J^T J)^-1 through the SVD of the column-normalised J; infinite along null directions.

    Returns the covariance (scaled parameters), the singular values of the normalised J
    (descending), its condition number, and its right singular vectors (columns, the last one
    the weakest combination).
    """
    norms = np.linalg.norm(J, axis=0)
    safe = np.where(norms > 0, norms, 1.0)
    _, sv, Vt = np.linalg.svd(J / safe, full_matrices=False)
    zero = (sv <= RANK_TOL * sv[0]) if sv[0] > 0 else np.ones(sv.shape, bool)
    zero_cols = norms <= RANK_TOL * max(float(norms.max()), 1e-300)
    V = Vt.T
    inv = np.where(zero, 0.0, 1.0 / np.where(zero, 1.0, sv) ** 2)
    cov_n = (V * inv) @ V.T
    cov = cov_n / np.outer(safe, safe)
    # parameters touched by a null direction (or with no effect at all) are not determined
    undetermined = zero_cols | np.any(np.abs(V[:, zero]) > 1e-6, axis=1)
    cov[undetermined, :] = np.nan
    cov[:, undetermined] = np.nan
    cov[undetermined, undetermined] = np.inf
    cond = float(sv[0] / sv[-1]) if sv[-1] > RANK_TOL * sv[0] else math.inf
    return cov, sv, cond, V


def separability_warnings(names: list[str], J: np.ndarray, corr: np.ndarray, cond: float, V: np.ndarray,
                          context: str, sol: Any, p: dict[str, float], bnds: np.ndarray, sd: np.ndarray,
                          red: float, p_value: float) -> list[str]:
    """Plain-language warnings about a fit, in the order a reader needs them.

    Parameters without effect (a zero column of ``J``); pairs with |correlation| above
    :data:`CORRELATION_LIMIT` (not separable, or only correlated when both are known to better
    than :data:`LOOSE`); the parameters of the weakest direction when the condition number of
    the column-normalised Jacobian exceeds :data:`CONDITION_LIMIT` (or it is singular);
    parameters at a bound or with an uncertainty above their value; a chi^2 improbable for the
    given sigma; a solver that did not converge.

    Parameters
    ----------
    names : list of str, length m
    J : ndarray, shape (n, m)
        Weighted Jacobian in the fitter's scaled parameters.
    corr : ndarray, shape (m, m)
    cond : float
        Condition number of the column-normalised J.
    V : ndarray, shape (m, m)
        Its right singular vectors (columns; the last is the weakest direction).
    context : str
        The data in words ("from one mode (Love mode 0) at kh 0.05-0.3").
    sol : scipy.optimize.OptimizeResult
        The solver's result (``success``, ``message``).
    p : dict
        The fitted values; ``bnds`` (2, m) their bounds; ``sd`` (m,) their 1-sigma.
    red, p_value : float
        chi^2/dof and its probability (NaN without sigma).
    """
    out: list[str] = []
    norms = np.linalg.norm(J, axis=0)
    dead = [nm for j, nm in enumerate(names) if norms[j] <= RANK_TOL * max(float(norms.max()), 1e-300)]
    for nm in dead:
        out.append(f"{nm} has no effect on the data {context} (dc/d{nm} = 0 at every point): it cannot be "
                   "fitted; fix it" if context != "from these data" else
                   f"{nm} has no effect on these data (dc/d{nm} = 0 at every point): it cannot be fitted; fix it")
    named_pairs: list[set[str]] = []
    m = len(names)
    for i in range(m):
        for j in range(i + 1, m):
            r = corr[i, j]
            if np.isfinite(r) and abs(r) > CORRELATION_LIMIT:
                named_pairs.append({names[i], names[j]})
                rel = [sd[k] / abs(p[names[k]]) if p[names[k]] else math.inf for k in (i, j)]
                if max(rel) > LOOSE:
                    out.append(f"{names[i]} and {names[j]} are not separable {context} (correlation {r:+.4f}): "
                               "fix one, or add data that tell them apart (another mode, a wider kh range)")
                else:
                    out.append(f"{names[i]} and {names[j]} are strongly correlated {context} (correlation "
                               f"{r:+.4f}): the data determine mainly a combination of them; their uncertainties "
                               f"({100 * rel[0]:.2g} %, {100 * rel[1]:.2g} %) include this, and fixing one would "
                               "sharpen the other")
    if m > 1 and (not math.isfinite(cond) or cond > CONDITION_LIMIT):
        v = V[:, -1]  # the weakest direction (normalised columns)
        live = [j for j in range(m) if names[j] not in dead]
        share = np.abs(v) / max(float(np.abs(v).max()), 1e-300)
        involved = [names[j] for j in live if share[j] > 0.1]
        if len(involved) >= 2 and set(involved) not in named_pairs:
            how = ("the data depend on them only through a combination of them" if not math.isfinite(cond)
                   else f"one combination of them is determined {cond:.3g} times worse than the best one")
            out.append(f"{', '.join(involved[:-1])} and {involved[-1]} are not separable {context}: {how}; "
                       "fix one of them")
    for j, nm in enumerate(names):
        at_lo = np.isfinite(bnds[0, j]) and math.isclose(p[nm], bnds[0, j], rel_tol=1e-6, abs_tol=1e-300)
        at_hi = np.isfinite(bnds[1, j]) and math.isclose(p[nm], bnds[1, j], rel_tol=1e-6, abs_tol=1e-300)
        if at_lo or at_hi:
            out.append(f"{nm} stopped at its {'lower' if at_lo else 'upper'} bound {p[nm]:.6g}: the fit wants it "
                       "beyond; its uncertainty there means little")
        elif np.isfinite(sd[j]) and nm not in dead and abs(p[nm]) > 0 and sd[j] > abs(p[nm]):
            out.append(f"{nm} is not determined {context}: its 1-sigma uncertainty ({sd[j]:.3g}) exceeds its "
                       f"value ({p[nm]:.3g})")
    if math.isfinite(p_value) and p_value < 1e-3:
        out.append(f"chi2/dof = {red:.3g} with the given sigma (p = {p_value:.2g}): the model does not fit the "
                   "data within their uncertainties, or sigma is underestimated")
    if not sol.success:
        out.append(f"the least-squares solver did not converge: {sol.message}")
    return out


def profile_warning(names: list[str], rises: np.ndarray, sd: np.ndarray) -> str:
    """The warning text for the parameters whose profile contradicts their linear 1-sigma ("" if none).

    ``rises`` (m, 2) from :func:`profile_rises`, ``sd`` the linear 1-sigma of each parameter.
    """
    off = []
    for j, nm in enumerate(names):
        up, down = rises[j]
        if any(v == math.inf or (np.isfinite(v) and not PROFILE_RANGE[0] <= v <= PROFILE_RANGE[1])
               for v in (up, down)):
            plus = sd[j] / math.sqrt(up) if np.isfinite(up) and up > 0 else math.nan
            minus = sd[j] / math.sqrt(down) if np.isfinite(down) and down > 0 else math.nan
            off.append(f"{nm}: chi2 rises by {up:.2g} and {down:.2g}, profile +{plus:.2g} / -{minus:.2g}")
    if not off:
        return ""
    which = [o.split(":")[0] for o in off]
    return (f"the 1-sigma uncertaint{'y' if len(off) == 1 else 'ies'} of {', '.join(which)} "
            f"{'is only a linear estimate' if len(off) == 1 else 'are only linear estimates'}: held one sigma above "
            "and below with the others refitted, chi2 should rise by 1 but the model bends within that range ("
            + "; ".join(off) + "); confirm by refitting perturbed data")

