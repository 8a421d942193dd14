"""Real roots of cubic polynomials, vectorised, in closed form (real arithmetic only).

Used by Eq. (17) (:mod:`surfwave.solvers.rayleigh`), which needs the real roots of one
cubic per point for 10^4-10^6 points at a time: the trigonometric form where there are three
real roots, Cardano's where there is one, then Newton steps on the roots that matter.
Cubics whose leading coefficient is small against the others go through numpy.roots.
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

_HALF_SQRT3 = 0.5 * np.sqrt(3.0)
#: |c3| / max|c| at or below which a cubic goes through numpy.roots (:func:`real_roots_closed_form`).
_SMALL_LEAD = 1e-4


def real_roots_closed_form(c3: np.ndarray, c2: np.ndarray, c1: np.ndarray, c0: np.ndarray,
                           coef_bound: float | None = None) -> tuple[np.ndarray, ...]:
    """Real roots of c3 x^3 + c2 x^2 + c1 x + c0 before polishing, and the monic coefficients.

    Parameters
    ----------
    c3, c2, c1, c0 : ndarray, shape (n,)
        Coefficients, float, any units.
    coef_bound : float, optional
        A bound on |c2|, |c1|, |c0| that lets the small-leading-coefficient test look at c3 only.

    Returns
    -------
    x : ndarray, shape (3, n)
        The real roots, in descending order where there are three, NaN-padded.
    B, C, D : ndarray, shape (n,)
        x^3 + B x^2 + C x + D, the monic cubic (for :func:`newton_polish`); NaN at the points
        solved by numpy.roots (accurate already).

    Notes
    -----
    With x = y - B/3 the monic cubic becomes y^3 + p y + q = 0;
    h = q/2, t = p/3, Delta = h^2 + t^3. Delta > 0: one real root, Cardano's form with the
    cube root taken of -h - sign(h) sqrt(Delta) (no cancellation), y = u - t/u. Delta <= 0:
    three real roots y_k = 2 sqrt(-t) cos(phi - 2 pi k/3), cos(3 phi) = -h / (-t)^(3/2),
    k = 0, 1, 2 in descending order; cos(phi -+ 2 pi/3) from cos phi and sin phi >= 0
    (phi in [0, pi/3]), so one arccos and one cos per point. Real arithmetic only. Points
    with a small leading coefficient (|c3| <= 1e-4 max|c|: a root beyond ~1e4 times the
    others, whose depressed form would lose the small ones) go through numpy.roots.
    """
    x = np.empty((3,) + c3.shape)
    if not c3.size:
        return x, np.empty(0), np.empty(0), np.empty(0)
    if coef_bound is None:
        scale = np.maximum(np.maximum(np.abs(c3), np.abs(c2)), np.maximum(np.abs(c1), np.abs(c0)))
        degenerate = np.abs(c3) <= _SMALL_LEAD * scale
    else:  # |c2|, |c1|, |c0| <= coef_bound: only |c3| <= _SMALL_LEAD coef_bound can be degenerate
        degenerate = np.abs(c3) <= _SMALL_LEAD * coef_bound
        if degenerate.any():
            m = np.flatnonzero(degenerate)
            degenerate[m] = np.abs(c3[m]) <= _SMALL_LEAD * np.max(np.abs([c3[m], c2[m], c1[m], c0[m]]), axis=0)
    with np.errstate(all="ignore"):
        inv = 1.0 / (np.where(degenerate, 1.0, c3) if degenerate.any() else c3)
        B, C, D = c2 * inv, c1 * inv, c0 * inv
        shift = B * (1.0 / 3.0)
        s2 = shift * shift
        mt = s2 - C * (1.0 / 3.0)                          # -p / 3
        hn = shift * (0.5 * C - s2) - 0.5 * D              # -q / 2
        delta = hn * hn - mt * mt * mt
        one = delta > 0
        n_one = np.count_nonzero(one)
        if n_one:                                          # one real root: Cardano
            u = np.cbrt(hn + np.copysign(np.sqrt(delta if n_one == one.size else np.where(one, delta, 0.0)), hn))
            y1 = u + mt / u
        if n_one < one.size:                               # three real roots: trigonometric
            r = np.sqrt(mt)
            # 0/0 at a triple root (r = 0, h = 0): fmin/fmax turn the NaN into 1, any angle will do
            cos3 = np.fmax(np.fmin(hn / (mt * r), 1.0), -1.0)
            cphi = np.cos(np.arccos(cos3) * (1.0 / 3.0))
            sphi = np.sqrt((1.0 - cphi) * (1.0 + cphi))     # cos returns |cphi| <= 1
            m = r + r
            y0 = m * cphi
            base = -0.5 * y0 - shift
            ms = _HALF_SQRT3 * m * sphi
            y1_3, y2_3 = base + ms, base - ms               # already shifted
        if n_one == 0:
            np.subtract(y0, shift, out=x[0])
            x[1], x[2] = y1_3, y2_3
        elif n_one == one.size:
            np.subtract(y1, shift, out=x[0])
            x[1:] = np.nan
        else:
            np.subtract(np.where(one, y1, y0), shift, out=x[0])
            x[1], x[2] = np.where(one, np.nan, y1_3), np.where(one, np.nan, y2_3)
    if degenerate.any():
        for i in np.flatnonzero(degenerate):
            z = np.roots([c3[i], c2[i], c1[i], c0[i]])
            z = z[np.abs(z.imag) <= 1e-12 * np.maximum(1.0, np.abs(z))].real
            x[:, i] = np.concatenate([z, np.full(3 - z.size, np.nan)])
        B[degenerate] = C[degenerate] = D[degenerate] = np.nan
    return x, B, C, D


def newton_polish(x: np.ndarray, B: np.ndarray, C: np.ndarray, D: np.ndarray, steps: int = 2,
                  lim: float | None = None) -> np.ndarray:
    """Newton steps on x^3 + B x^2 + C x + D = 0, elementwise; 1-D arrays of one length (n,).

    A correction larger than ``lim`` (default 1e-6 (|x| + |B|)) is refused: the closed forms
    are far closer than that; such a step only comes from a derivative vanishing at a double root
    (where rounding noise in f would throw x away). After the first step, the others only
    where the last correction exceeded 1e-12 |x| (elsewhere a further step would change x
    by ~1e-24 relative). NaN coefficients (degenerate points) leave x as it is.
    """
    idx = None                                       # the entries still being polished
    with np.errstate(all="ignore"):
        for step in range(steps):
            xs, Bs, Cs, Ds = (x, B, C, D) if idx is None else (x[idx], B[idx], C[idx], D[idx])
            f = ((xs + Bs) * xs + Cs) * xs + Ds
            df = (3.0 * xs + (Bs + Bs)) * xs + Cs
            dx = f / df
            dx = np.where(np.abs(dx) <= (1e-6 * (np.abs(xs) + np.abs(Bs)) if lim is None else lim), dx, 0.0)
            xs = xs - dx
            if idx is None:
                x = xs
            else:
                x[idx] = xs
            if step + 1 < steps:
                more = np.flatnonzero(np.abs(dx) > 1e-12 * np.abs(xs))
                if not more.size:
                    break
                idx = more if idx is None else idx[more]
    return x


def real_cubic_roots(c3: ArrayLike, c2: ArrayLike, c1: ArrayLike, c0: ArrayLike) -> np.ndarray:
    """Real roots of c3 x^3 + c2 x^2 + c1 x + c0, vectorised; shape (..., 3), NaN-padded.

    The closed forms of :func:`real_roots_closed_form`, then :func:`newton_polish` on every
    root (Eq. 17 polishes only the roots it may select, surfwave.solvers.rayleigh).

    Examples
    --------
    >>> real_cubic_roots(1.0, -6.0, 11.0, -6.0)   # (x - 1)(x - 2)(x - 3)
    array([3., 2., 1.])
    """
    c3, c2, c1, c0 = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (c3, c2, c1, c0)))
    shape = c3.shape
    cs = [np.ravel(v) for v in (c3, c2, c1, c0)]
    x, B, C, D = real_roots_closed_form(cs[0], cs[1], cs[2], cs[3])
    x = newton_polish(x.ravel().copy(), np.tile(B, 3), np.tile(C, 3), np.tile(D, 3)).reshape(x.shape)
    return np.moveaxis(x, 0, -1).reshape(shape + (3,))
