"""Rayleigh (surface) wave velocity of a prestressed crystal, long-wave limit.

The sagittal problem along x on a surface normal to y, with mirror symmetry so that the
shear-horizontal motion decouples, depends on five stress derivatives (Eq. 17):

    a = S_xxxx, b = S_xyxy, c = S_xyyx, d = S_yyyy, f = S_yyxx,   X = rho c_R^2.

Partial waves u ~ exp(i k x - k kappa y) (y into the crystal) have

    b d kappa^4 - [b (c - X) + d (a - X) - (f + b)^2] kappa^2 + (a - X)(c - X) = 0,

and the free-surface condition, after dividing out the trivial factor (kappa_1 - kappa_2), is

    G(X) = A M + A N (s + p) - f M p + f N p^2 = 0,
    A = a - X, M = f (f + b) - d A, N = d b, s = kappa_1^2 + kappa_2^2, p = kappa_1 kappa_2.

Squaring away the sign of p gives the cubic Eq. (17), whose extra roots belong to p < 0
(partial waves that grow into the crystal). We find the roots of Eq. (17) in closed form,
keep those in 0 < X < min(a, c) whose two kappa have positive real part (complex allowed),
and accept one only if it satisfies the *unsquared* G(X) = 0 with p > 0.

Numerics (:func:`rayleigh_c2`, :func:`solve`): S is read in blocks of :data:`BLOCK` points;
one pass bounds the components that must vanish (:func:`check_orthotropic`), a..f are
gathered into (5, n) rows, the real roots of Eq. (17) come from the trigonometric or
Cardano closed form (:mod:`surfwave.solvers.cubic`), and only roots near (0, min(a, c)) are gathered,
polished (Newton) and tested (:func:`_select_flat`). About 7-9x the time of Eq. (20) from
the same S at 1e4-1e5 points per call (benchmarks/bench_rayleigh.py).

The initial stress enters through S (Eq. A11); the traction condition uses C_iykl, which
equals S_iykl when sigma_yy = sigma_xy = 0 (free surface in equilibrium, docs/physics/paper.md).
"""
from __future__ import annotations

import itertools
from typing import Literal, overload

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError, SymmetryError
from surfwave.solvers.cubic import newton_polish as _polish
from surfwave.solvers.cubic import real_roots_closed_form as _cubic_rows
from surfwave.validate import real_array
from surfwave.vocab import SAGITTAL_WAVE_TYPES

#: Wave types this solver reports (it never reports ``pseudo``).
WAVE_TYPES = SAGITTAL_WAVE_TYPES

REASON_SHEAR = "no surface wave: c_T,par^2 <= 0 (shear instability along the surface)"
REASON_PERP = "no surface wave: S_yyyy <= 0 or S_xyxy <= 0 (unstable normal to the surface)"
#: Relative size (of max |S|) above which a component breaking sagittal orthotropy is refused.
ORTHOTROPY_TOL = 1e-9

REASON_NOROOT = ("no root of Eq. (17) in 0 < rho c^2 < min(S_xxxx, S_xyyx) satisfies the "
                 "unsquared boundary condition with decaying partial waves")

#: Flat positions, in S.reshape(-1, d**4), of (a, b, c, d, f) = (S_xxxx, S_xyxy, S_xyyx, S_yyyy, S_yyxx).
_SAGITTAL_FLAT = {d: np.ravel_multi_index(([0, 0, 0, 1, 1], [0, 1, 1, 1, 1], [0, 0, 1, 1, 0], [0, 1, 0, 1, 0]),
                                          (d,) * 4) for d in (2, 3)}
#: Candidate roots may lie this far (relative to max |a..f|) outside (0, min(a, c)) before the Newton
#: polish; far above the polish's corrections (~1e-8 even at a double root).
_POLISH_MARGIN = 1e-6
#: Newton steps on each candidate root after the closed form.
POLISH_STEPS = 2
#: Points per vectorised block: the temporaries of a block (~100 arrays of BLOCK floats) stay
#: in the CPU cache; smaller blocks pay numpy's per-call overhead (benchmarks/bench_rayleigh.py).
BLOCK = 8192


def secular_coefficients(a: np.ndarray, b: np.ndarray, c: np.ndarray, d: np.ndarray,
                         f: np.ndarray) -> tuple[np.ndarray, ...]:
    """Coefficients (c3, c2, c1, c0) of Eq. (17) as a cubic polynomial in X = rho c_R^2.

    (X - c)[d (X - a) + f^2]^2 - b d (X - a)[(X - c) + b]^2.
    """
    g = f * f - d * a
    h = b - c
    bd = b * d
    cd = c * d
    # the products of the formula above, shared (doubling is exact: the same floats)
    c3 = d * d - bd
    c2 = (d + d) * g - cd * d - bd * (h + h - a)
    c1 = g * g - (cd + cd) * g - bd * (h * h - (a + a) * h)
    c0 = -c * g * g + bd * a * h * h
    return c3, c2, c1, c0


def decay_constants(X: ArrayLike, a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike,
                    f: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """The two decay constants kappa (principal square roots, Re >= 0) at X = rho c^2.

    Returns
    -------
    kappa1, kappa2 : complex ndarray, broadcast shape of the inputs
        Ordered so that |kappa1| >= |kappa2|.
    """
    X, a, b, c, d, f = (np.asarray(v, dtype=float) for v in (X, a, b, c, d, f))
    e = f + b
    bd = b * d
    with np.errstate(all="ignore"):
        s = (b * (c - X) + d * (a - X) - e * e) / bd
        p2 = (a - X) * (c - X) / bd
        root = np.sqrt((s * s - 4 * p2).astype(complex))
        k2a = (s + root) / 2
        k2b = np.where(np.abs(k2a) > 0, p2 / k2a, (s - root) / 2)  # Vieta: stable small root
    return np.sqrt(k2a.astype(complex)), np.sqrt(k2b.astype(complex))


def boundary_function(X: ArrayLike, a: ArrayLike, b: ArrayLike, c: ArrayLike, d: ArrayLike,
                      f: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Unsquared free-surface condition G(X) with p = +sqrt(p^2), and its magnitude scale.

    The four-term form of the module docstring, elementwise (G also equals
    e [A (c - b - X) + p (d A - f^2)], e = f + b; the sum of the four |terms| is its scale).
    """
    X, a, b, c, d, f = (np.asarray(v, dtype=float) for v in (X, a, b, c, d, f))
    e = f + b
    A = a - X
    M = f * e - d * A
    N = d * b
    with np.errstate(all="ignore"):
        s = (b * (c - X) + d * A - e * e) / N
        pp = np.maximum(A * (c - X) / N, 0.0)
        p = np.sqrt(pp)                            # the real part of the principal root
        terms = (A * M, A * N * (s + p), -f * M * p, f * N * pp)
    G = sum(terms)
    scale = sum(np.abs(t) for t in terms)
    return G, scale


def _sagittal_components(S: np.ndarray) -> tuple[np.ndarray, ...]:
    """(a, b, c, d, f) = (S_xxxx, S_xyxy, S_xyyx, S_yyyy, S_yyxx), each shape S.shape[:-4]."""
    return S[..., 0, 0, 0, 0], S[..., 0, 1, 0, 1], S[..., 0, 1, 1, 0], S[..., 1, 1, 1, 1], S[..., 1, 1, 0, 0]


def _odd_index_components(d: int) -> tuple[list[tuple[int, ...]], tuple[np.ndarray, ...]]:
    """Components of S that vanish when the sagittal plane is orthotropic and a mirror.

    Orthotropy in the sagittal plane (x -> -x) removes those with an odd number of x
    indices among the sagittal ones; the mirror z -> -z (3D) those with an odd number of z.
    """
    comps = [c for c in itertools.product(range(d), repeat=4)
             if sum(i == 0 for i in c) % 2 == 1 or sum(i == 2 for i in c) % 2 == 1]
    return comps, tuple(np.array(col) for col in zip(*comps))


_ODD = {d: _odd_index_components(d) for d in (2, 3)}
_ODD_MASK = {d: np.isin(np.arange(d**4), np.ravel_multi_index(_ODD[d][1], (d,) * 4)) for d in (2, 3)}


def _flat_tensor(S: np.ndarray) -> np.ndarray:
    """S (..., d, d, d, d), d = 2 or 3, as a float array of shape (n, d**4) (a view when possible)."""
    S = np.asarray(S, dtype=float)
    d = S.shape[-1] if S.ndim >= 4 else 0
    if d not in _ODD or S.shape[-4:] != (d,) * 4:
        raise SymmetryError(f"S must have shape (..., d, d, d, d) with d = 2 or 3, got {S.shape}")
    return S.reshape(-1, d**4)


def _gather(flat: np.ndarray) -> np.ndarray:
    """The rows (a, b, c, d, f) of Eq. (17) from ``flat`` (n, d**4); shape (5, n), contiguous."""
    d = 3 if flat.shape[1] == 81 else 2
    return flat.T[_SAGITTAL_FLAT[d]]


def _surely_orthotropic(flat: np.ndarray, unit: np.ndarray, rtol: float) -> bool:
    """One pass over S proving every point orthotropic, or False (then check point by point).

    sqrt(sum of the squared must-vanish components over all points) bounds each of them, and
    ``unit`` = max |a..f| of a point is at most its max |S|: a sum below (rtol min unit)^2
    passes the exact test of :func:`check_orthotropic` at every point. Overflow or NaN
    give False.
    """
    if not flat.size:
        return True
    n, w = flat.shape
    m = n - n % 8
    with np.errstate(all="ignore"):
        # column sums of squares; eight points per row of the einsum (longer inner loops)
        sq = np.einsum("ij,ij->j", *(flat[:m].reshape(m // 8, 8 * w),) * 2).reshape(8, w).sum(axis=0)
        if m < n:
            sq += np.einsum("ij,ij->j", flat[m:], flat[m:])
        odd = sq[_ODD_MASK[3 if w == 81 else 2]].sum()
        thr = rtol * unit.min()
        return bool(thr > 1e-150 and odd <= thr * thr)  # thr^2 must not underflow



def check_orthotropic(S: np.ndarray, rtol: float = ORTHOTROPY_TOL) -> None:
    """Raise :class:`SymmetryError` unless S is orthotropic in the sagittal plane (Eq. 17 applies).

    Eq. (17) needs x -> -x and (3D) z -> -z symmetry: every component with an odd number of
    x or of z indices must vanish (relative to max |S| of the point). General tensors belong to
    :func:`surfwave.solvers.stroh.surface_wave`.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d), d = 2 or 3
    rtol : float

    Raises
    ------
    SymmetryError
        Naming the largest offending components and their size relative to max |S|.

    Notes
    -----
    One pass over S (the sum of squares of the must-vanish components against the smallest
    max |a..f|, :func:`_surely_orthotropic`) proves the usual case; only when that bound fails
    are the points compared one by one, which decides.
    """
    S = np.asarray(S, dtype=float)
    flat = _flat_tensor(S)
    if not _surely_orthotropic(flat, np.abs(_gather(flat)).max(axis=0), rtol):
        _orthotropy_error(S, flat, rtol)


def _orthotropy_error(S: np.ndarray, flat: np.ndarray, rtol: float) -> None:
    """The exact test of :func:`check_orthotropic`, point by point; ``flat`` is S as (n, d**4).

    Each point's largest must-vanish component against its max |S| (a point with NaN in S
    is never the culprit, and does not hide one). Raises the SymmetryError or returns.
    """
    d = S.shape[-1]
    comps = _ODD[d][0]
    absf = np.abs(flat)
    scale = absf.max(axis=1)
    with np.errstate(all="ignore"):
        rel = absf[:, _ODD_MASK[d]] / np.where(scale == 0, 1.0, scale)[:, None]   # NaN stays NaN
        worst = np.fmax.reduce(rel, axis=1)
        bad = worst > rtol
    if not bad.any():
        return
    k = int(np.argmax(np.where(bad, worst, -np.inf)))
    order = np.argsort(rel[k])[::-1][:4]
    names = ", ".join(f"S_{''.join('xyz'[i] for i in comps[j])} = {rel[k, j]:.2g}"
                      for j in order if rel[k, j] > rtol)
    raise SymmetryError(
        "Eq. (17) needs a sagittal plane that is a mirror and orthotropic; at point "
        f"{np.unravel_index(k, S.shape[:-4]) if S.ndim > 4 else ()} these components do not vanish "
        f"(relative to max|S|): {names}. Use surfwave.solvers.stroh.surface_wave for general tensors."
    )


def _select_flat(comp: np.ndarray, unit: np.ndarray, rtol: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """The admissible root X = rho c_R^2 of Eq. (17) per point and whether one exists.

    Parameters
    ----------
    comp : ndarray, shape (5, n)
        Rows a, b, c, d, f (:func:`_gather`), any units.
    unit : ndarray, shape (n,)
        max |a..f| per point; the problem is solved in units of it (scale invariance: S in
        Pa, GPa or reduced units takes the same path; the degenerate-cubic test compares
        coefficients of different degree in S).
    rtol : float
        Relative tolerance on the unsquared boundary condition G(X) = 0.

    Returns
    -------
    X : ndarray, shape (n,)
        In the units of ``comp``; meaningful only where ``has``.
    has : ndarray of bool, shape (n,)

    Notes
    -----
    The rule of the module docstring: among the real roots of Eq. (17) in 0 < X < min(a, c),
    with b, d > 0 and both kappa of positive real part, those with |G| <= rtol (scale of G)
    are admissible; the one with the smallest |G| / scale wins (normally the only one; ties
    go to the larger root). Only roots near that interval are polished and tested, gathered
    into 1-D arrays.
    """
    n = comp.shape[1]
    unit = np.where(unit > 0, unit, 1.0)
    an = comp / unit                                          # (5, n), max |a..f| = 1
    margin = _POLISH_MARGIN
    a, b, c, d, f = an
    # |c2|, |c1|, |c0| <= 16 when max |a..f| = 1 (secular_coefficients term by term); 17 for rounding
    c3, c2, c1, c0 = secular_coefficients(a, b, c, d, f)
    X, B, C, D = _cubic_rows(c3, c2, c1, c0, coef_bound=17.0)   # (3, n)
    with np.errstate(invalid="ignore"):
        hi = np.where((b > 0) & (d > 0), np.minimum(a, c) + margin, -np.inf)
        near = (X > -margin) & (X < hi)
    kk = np.flatnonzero(near)                                 # candidates, flat in (3, n)
    i = kk - (kk // n) * n                                    # their points (kk // n: slot)
    x = _polish(X.take(kk), B[i], C[i], D[i], steps=POLISH_STEPS, lim=_POLISH_MARGIN)
    ai, bi, ci, di, fi = (v[i] for v in an)
    A = ai - x
    with np.errstate(invalid="ignore", divide="ignore"):
        cX = ci - x
        dA = di * A
        N = bi * di
        e = fi + bi
        M = fi * e - dA
        sN = bi * cX + dA - e * e                             # s N
        pN = A * cX                                           # p^2 N
        pp = pN / N
        p = np.sqrt(pp)
        # the four terms of G (module docstring, as boundary_function) and their scale
        t1, t2, t3, t4 = A * M, A * (sN + N * p), fi * M * p, (fi * N) * pp
        G = (t1 + t2) - (t3 - t4)
        scale = (np.abs(t1) + np.abs(t2)) + (np.abs(t3) + np.abs(t4))
        # inside (b, d > 0 already), decaying (both kappa with positive real part, so that
        # p = kappa_1 kappa_2 = +sqrt(p^2) in G) and the unsquared condition
        ok = ((x > 0) & (x < np.minimum(ai, ci)) & ((sN * sN < 4.0 * pN * N) | (sN > 0))
              & (np.abs(G) <= rtol * scale))
    j = i[ok]
    Xr = np.full(n, np.nan)
    Xr[j] = x[ok]
    has = np.zeros(n, dtype=bool)
    has[j] = True
    if j.size > np.count_nonzero(has):  # some point has two admissible roots: the smallest |G|/scale
        with np.errstate(invalid="ignore", divide="ignore"):
            bad = np.abs(G[ok]) / np.where(scale[ok] > 0, scale[ok], 1.0)
        order = np.lexsort((kk[ok] // n, bad, j))       # by point, |G|/scale, then larger X
        js = j[order]
        first = np.r_[True, js[1:] != js[:-1]]
        Xr[js[first]] = x[ok][order][first]
    return Xr * unit, has


def select_root(a, b, c, d, f, rtol: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """The admissible root X = rho c_R^2 of Eq. (17) and whether one exists, any shape.

    The five components broadcast together; see :func:`_select_flat` for the rule.
    """
    a, b, c, d, f = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, b, c, d, f)))
    comp = np.stack([np.ravel(v) for v in (a, b, c, d, f)])
    X, has = _select_flat(comp, np.abs(comp).max(axis=0), rtol)
    return X.reshape(a.shape), has.reshape(a.shape)


def _solve_flat(S: np.ndarray, rtol: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """Orthotropy check and root of Eq. (17) for S (..., d, d, d, d); X and has, shape (n,).

    Blocks of :data:`BLOCK` points: each is read once from memory for the one-pass
    orthotropy bound and the gather of a..f, and its temporaries stay in the CPU cache. If
    a block's bound fails, the exact point-by-point check runs once over all of S.
    """
    flat = _flat_tensor(S)
    n = flat.shape[0]
    X = np.empty(n)
    has = np.zeros(n, dtype=bool)
    checked = False
    edges = np.linspace(0, n, max(1, round(n / BLOCK)) + 1).astype(int) if n else [0]  # ~BLOCK points
    for lo, hi in zip(edges[:-1], edges[1:]):
        block = flat[lo:hi]
        comp = _gather(block)                                 # (5, m): a, b, c, d, f
        unit = np.abs(comp).max(axis=0)
        if not (checked or _surely_orthotropic(block, unit, ORTHOTROPY_TOL)):
            _orthotropy_error(S, flat, ORTHOTROPY_TOL)        # raises unless all points pass
            checked = True
        X[lo:hi], has[lo:hi] = _select_flat(comp, unit, rtol)
    return X, has


def solve(S: np.ndarray, rho: ArrayLike = 1.0, c2_SH: np.ndarray | None = None,
          rtol: float = 1e-7) -> dict[str, np.ndarray]:
    """Rayleigh velocity with root selection and wave type, vectorised over leading axes.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d), d = 2 or 3
        Stress derivatives (Eq. A11) in the lab frame (x propagation, y surface normal).
    rho : float or ndarray broadcastable to S.shape[:-4]
        Density in the units of S (1 when S is V S and m = 1).
    c2_SH : ndarray, optional
        Squared SH bulk speed; defaults to S_xzzx / rho for d = 3, none for d = 2.
    rtol : float
        Relative tolerance on the unsquared boundary condition G(X) = 0.

    Returns
    -------
    dict
        ``c2_R`` (float, NaN where none), ``wave_type`` (str), ``reason`` (str, "" if fine),
        ``kappa1``, ``kappa2`` (complex), all shape S.shape[:-4].
    """
    S = np.asarray(S, dtype=float)
    shape = S.shape[:-4]
    Xr, has = (v.reshape(shape) for v in _solve_flat(S, rtol))
    rho = np.asarray(rho, dtype=float)
    a, b, c, d, f = _sagittal_components(S)
    if c2_SH is None:
        c2_SH = S[..., 0, 2, 2, 0] / rho if S.shape[-1] == 3 else np.full(shape, np.nan)
    c2_SH = np.broadcast_to(np.asarray(c2_SH, dtype=float), shape)
    K1, K2 = decay_constants(Xr, a, b, c, d, f)
    c2_R = np.where(has, Xr / rho, np.nan)
    nan_c = complex(np.nan, np.nan)
    reason = _reasons(has, b, c, d)
    wave_type = np.where(has, np.where(np.isfinite(c2_SH) & (c2_R >= c2_SH), "supersonic_decoupled", "surface"), "none")
    return {
        "c2_R": c2_R,
        "wave_type": wave_type.astype(object),
        "reason": reason.astype(object),
        "kappa1": np.where(has, K1, nan_c),
        "kappa2": np.where(has, K2, nan_c),
    }


def _reasons(has: np.ndarray, b, c, d) -> np.ndarray:
    """Why c2_R is NaN where ``has`` is False ("" where it is not), object array like ``has``."""
    reason = np.full(np.shape(has), "", dtype=object)
    reason = np.where(~has, REASON_NOROOT, reason)
    reason = np.where(~has & ((b <= 0) | (d <= 0)), REASON_PERP, reason)
    return np.where(~has & (c <= 0), REASON_SHEAR, reason).astype(object)


def _check_rho(rho) -> np.ndarray:
    """rho as a float array; InputError naming rho unless every value is positive and finite."""
    from surfwave.errors import InputError

    try:
        r = np.asarray(rho, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"rho must be a positive number or array of them, got {rho!r}") from None
    if not (np.all(r > 0) and np.all(np.isfinite(r))):
        bad = np.atleast_1d(r)[~((np.atleast_1d(r) > 0) & np.isfinite(np.atleast_1d(r)))]
        raise InputError(f"rho must be positive and finite (a density), got {bad[:3].tolist()}")
    return r


@overload
def rayleigh_c2(S: np.ndarray, rho: ArrayLike = 1.0, *, reasons: Literal[False] = False) -> np.ndarray: ...
@overload
def rayleigh_c2(S: np.ndarray, rho: ArrayLike = 1.0, *, reasons: Literal[True]) -> tuple[np.ndarray, np.ndarray]: ...
def rayleigh_c2(S: np.ndarray, rho: ArrayLike = 1.0, *,
                reasons: bool = False) -> np.ndarray | tuple[np.ndarray, np.ndarray]:
    """Squared Rayleigh speed from the stress derivatives; NaN where no surface wave exists.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d)
        Lab-frame stress derivatives (Eq. A11); times V with ``rho = 1`` in reduced units.
    rho : float or ndarray broadcastable to S.shape[:-4]
        Positive and finite (else InputError naming rho).
    reasons : bool, keyword only
        Also return why each NaN is NaN (the reasons of :func:`solve`). Off by default: the
        reasons cost a second pass over S (about as much as the solve itself), the default
        path does not pay for them.

    Returns
    -------
    c2 : ndarray, shape S.shape[:-4]
        c_R^2 in the units of S / rho. Supersonic decoupled sagittal waves are included
        (see :func:`solve` for the wave type).
    reason : ndarray of str (object), shape S.shape[:-4]
        Only with ``reasons=True``: "" where c2 is a number, else :data:`REASON_SHEAR`,
        :data:`REASON_PERP` or :data:`REASON_NOROOT`.

    Raises
    ------
    InputError
        rho not positive and finite.
    SymmetryError
        S not orthotropic in the lab frame (Eq. 17 does not apply).

    Examples
    --------
    >>> import numpy as np
    >>> S = np.zeros((2, 2, 2, 2))        # isotropic, lambda = mu = 1
    >>> S[0,0,0,0] = S[1,1,1,1] = 3.0
    >>> S[0,1,0,1] = S[0,1,1,0] = S[1,1,0,0] = 1.0
    >>> round(float(rayleigh_c2(S)), 6)  # 2 - 2/sqrt(3)
    0.845299
    >>> S[0, 1, 0, 1] = S[0, 1, 1, 0] = -1.0  # shear-unstable along the surface
    >>> c2, why = rayleigh_c2(S, reasons=True)
    >>> bool(np.isnan(c2)), str(why) == REASON_SHEAR
    (True, True)
    """
    r = _check_rho(rho)
    S = real_array(S, "S")                                    # numbers only (one line, not a numpy error)
    if S.ndim < 4 or S.shape[-4:] not in ((2, 2, 2, 2), (3, 3, 3, 3)):
        raise InputError(f"S must have shape (..., 2, 2, 2, 2) or (..., 3, 3, 3, 3) (stress derivatives, lab "
                         f"frame), got {S.shape}")
    X, has = (v.reshape(S.shape[:-4]) for v in _solve_flat(S))
    c2 = np.where(has, X / r, np.nan)
    if not reasons:
        return c2
    _, b, c, d, _ = _sagittal_components(S)
    return c2, _reasons(np.broadcast_to(has, c2.shape), b, c, d)


def cauchy_c2(c2_L_par: np.ndarray, c2_T_par: np.ndarray, c2_L_perp: np.ndarray, c2_T_perp: np.ndarray) -> np.ndarray:
    """Eq. (20): c_R^2 from the four sound speeds when S_xyxy = S_yyxx (pair forces, sigma_yy = 0)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return 0.5 * (c2_L_par + c2_T_par) - 0.5 * np.sqrt(
            (c2_L_par - c2_T_par) ** 2 + 4.0 * c2_T_perp**3 / c2_L_perp
        )


def triangular_c2(d_over_d0: ArrayLike) -> np.ndarray:
    """Eq. (16): (m / K d0^2) c_R^2 of the harmonic triangular lattice, x = d_x/d0 = d_over_d0/2."""
    x = 0.5 * np.asarray(d_over_d0, dtype=float)
    return 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)


def unstressed_residual(gamma: ArrayLike, C11: float, C12: float, C44: float, C22: float | None = None) -> np.ndarray:
    """Eq. (21) residual, gamma = rho c_R^2 / C44 (Voigt constants; C22 defaults to C11).

    gamma^2 (gamma - C11/C44) - (C22/C44)(gamma - 1)[gamma - C11/C44 + C12^2/(C22 C44)]^2.
    """
    C22 = C11 if C22 is None else C22
    g = np.asarray(gamma, dtype=float)
    return g**2 * (g - C11 / C44) - (C22 / C44) * (g - 1) * (g - C11 / C44 + C12**2 / (C22 * C44)) ** 2
