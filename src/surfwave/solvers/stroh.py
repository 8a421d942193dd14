"""General surface-wave solver: any anisotropy, any surface and direction, under prestress.

Physics (docs/physics/general-solver.md): with the wave-propagation coefficients
A_ijkl = C_ijkl + sigma0_jl delta_ik (C: constants of the stressed crystal, sigma0 the
prestress, which must lie in the surface plane) the incremental motion obeys
rho u_i,tt = A_ijkl u_k,jl and the free surface x2 = 0 carries no incremental nominal
traction, A_i2kl u_k,l = 0. Stroh blocks, limiting speed and impedance: :mod:`impedance`.

Root finding. The impedance Z(X) (X = rho v^2) is Hermitian below the limiting X_L, positive
definite at X = 0 for a stable crystal and decreasing in X; a subsonic surface wave is where
the lowest eigenvalue lam of Z crosses zero (at most once). The root is bracketed in
X = X_L (1 - t^2), t in (T_MIN, 1] (t removes the square-root behaviour of Z at X_L), and
found by Newton's method in t (then inverse cubic Hermite steps through the two latest
points) safeguarded by bisection, with d lam / dX from the Sylvester equation of the
impedance's Riccati equation (:func:`impedance.impedance`); after the first step the decaying
Stroh roots are tracked from the previous step (Newton on the Stroh polynomial) instead of
recomputed as eigenvalues of N.

Where the sagittal plane x1 x2 is a mirror (the components of A with an odd number of
indices 3 vanish) the sagittal motion decouples; its 2 x 2 problem may hold a surface wave
above X_L (``supersonic_decoupled``). If the sagittal plane is moreover orthotropic, that
root is Eq. (17) (:mod:`surfwave.solvers.rayleigh`, exact and fast); otherwise the same
impedance root search runs on the sagittal 2 x 2 blocks.
"""
from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.solvers import impedance as imp
from surfwave.solvers import rayleigh
from surfwave.vocab import WAVE_TYPES  # noqa: F401 (re-exported: the wave types solve() reports)

#: Smallest t = sqrt(1 - X/X_L) searched: roots closer to X_L than T_MIN^2 relative are "none".
T_MIN = 1e-6
#: Relative size below which a component of A counts as zero (symmetry detection).
SYMMETRY_TOL = 1e-10
MAX_ITER = 100
#: Starting point of the Newton iteration, t = sqrt(1 - X/X_L) (X = 0.91 X_L).
T_START = 0.3


REASON_UNSTABLE = "no surface wave: a bulk wave in the sagittal plane has rho v^2 <= 0 (unstable crystal)"
REASON_T = "no surface wave: T_ik = A_i2k2 is not positive definite (unstable normal to the surface)"
REASON_PSEUDO = ("pseudo-surface wave: no subsonic root (the lowest eigenvalue of the impedance stays "
                 "positive up to v_L (1 - 1e-12)): off a mirror the surface wave has left the subsonic "
                 "range through v_L and leaks into the bulk; its complex speed is not computed")
REASON_NOROOT_MIRROR = ("no surface wave: neither below v_L nor, for the decoupled sagittal motion, "
                        "below its own limiting speed")



def wave_propagation_tensor(C: ArrayLike, sigma: ArrayLike, *, rtol: float = 1e-9) -> np.ndarray:
    """A_ijkl = C_ijkl + sigma_jl delta_ik, refusing prestress that loads the surface.

    Parameters
    ----------
    C : array_like, shape (..., 3, 3, 3, 3)
        Elastic constants of the stressed crystal, lab frame (x2 = surface normal).
    sigma : array_like, shape (..., 3, 3)
        Cauchy prestress, lab frame, same units as C.
    rtol : float
        sigma_2j must vanish to rtol times the largest |sigma| (plus 1e-13 max|C|).

    Returns
    -------
    ndarray, shape broadcast (..., 3, 3, 3, 3)

    Raises
    ------
    InputError
        sigma . n != 0 (the component and its size are named): the free surface would not
        be in equilibrium.
    """
    C = np.asarray(C, dtype=float)
    sigma = np.asarray(sigma, dtype=float)
    d = C.shape[-1]
    if C.shape[-4:] != (d,) * 4 or sigma.shape[-2:] != (d, d):
        raise InputError(f"C must have shape (..., d, d, d, d) and sigma (..., d, d), got {C.shape}, {sigma.shape}")
    s_scale = np.abs(sigma).max(axis=(-2, -1))
    c_scale = np.abs(C).max(axis=(-4, -3, -2, -1))
    tol = rtol * s_scale + 1e-13 * c_scale
    normal = np.abs(sigma[..., 1, :])
    excess = normal - np.asarray(tol)[..., None]
    if np.any(excess > 0):
        flat = np.moveaxis(excess, -1, 0).reshape(d, -1)
        j, k = np.unravel_index(np.argmax(flat), flat.shape)
        val = np.moveaxis(sigma[..., 1, :], -1, 0).reshape(d, -1)[j, k]
        scale = np.broadcast_to(s_scale, excess.shape[:-1]).reshape(-1)[k]
        raise InputError(f"prestress must lie in the surface plane (sigma . n = 0), but sigma_2{j + 1} = "
                         f"{val:.6g} (largest |sigma| = {scale:.6g}) at point {k}")
    return C + np.einsum("...jl,ik->...ijkl", sigma, np.eye(d))


def _odd_components(d: int, axis: int) -> tuple[np.ndarray, ...]:
    """Index arrays of the components of a rank-4 tensor with an odd number of ``axis``."""
    idx = [c for c in itertools.product(range(d), repeat=4) if sum(i == axis for i in c) % 2 == 1]
    return tuple(np.array(col) for col in zip(*idx))


def _relative_max(A: np.ndarray, comps, scale: np.ndarray | float) -> np.ndarray:
    return np.abs(A[(slice(None),) + comps]).max(axis=-1) / scale


def _root_search(Q, R, T, XL, tol: float) -> tuple[np.ndarray, ...]:
    """Subsonic root X of Z(X)'s lowest eigenvalue lam in (0, XL) per point; NaN where none.

    Returns X (m,), found (m,) bool, and from the last evaluation (within ``tol`` of the root)
    the unit null vector u (m, d) of Z (the surface displacement) and the decaying p (m, d).

    Safeguarded Newton in t = sqrt(1 - X/XL) from ``T_START`` (d lam / dX from the Sylvester
    equation of :func:`impedance.impedance`; from the second step on, inverse cubic Hermite
    steps, :func:`_hermite_correction`), vectorised over the points not yet converged; the
    decaying p of each step are the guesses for the next (``p_guess``).
    The bracket (lo, hi) starts as (T_MIN, 1) and shrinks with the sign of each lam
    (lam decreases with X, i.e. increases with t); a Newton step that leaves it is replaced
    by bisection. A point driven to t = T_MIN with lam > 0 there has no subsonic root (within
    T_MIN^2 of X_L); one converging near X = 0 has lam(X = 0) > 0 verified. Converged when the
    Newton step changes X by less than ``tol`` relative.
    """
    m = Q.shape[0]
    X = np.full(m, np.nan)
    found = np.zeros(m, dtype=bool)
    d = Q.shape[-1]
    U = np.full((m, d), np.nan + 0j)
    P = np.full((m, d), np.nan + 0j)
    if m == 0:
        return X, found, U, P
    N0 = imp.stroh_matrix(Q, R, T, np.zeros(m))
    parts = imp.stroh_polynomial_parts(Q, R, T)

    def ev(i, t, guess=None):
        r = imp.impedance(Q[i], R[i], T[i], XL[i] * (1.0 - t * t), derivative=True, N0=N0[i], p_guess=guess,
                          parts=parts[i])
        return r["lam"], r["dlam"] * (-2.0 * t * XL[i]), r["u"], r["p"]   # d lam / dt

    idx = np.arange(m)
    lo, hi = np.full(m, T_MIN), np.ones(m)
    hi_checked = np.zeros(m, dtype=bool)
    t = np.full(m, T_START)
    guess = None                                                   # the decaying p of the last step
    tp, lp, gp = (np.full(m, np.nan) for _ in range(3))            # the last step's t, lam, d lam / dt
    for _ in range(MAX_ITER):
        if idx.size == 0:
            break
        lam, dlam, u, p = ev(idx, t, guess)
        bad = ~np.isfinite(lam)
        lam = np.where(bad, -1.0, lam)                             # supersonic by rounding: root lies above
        neg, lo, hi, new, done = bracketed_step(lam, dlam, t, lo, hi, bad, (tp, lp, gp), XL[idx], tol)
        hi_checked |= ~neg
        none = ~neg & (t <= T_MIN)                                 # lam > 0 even at X_L (1 - T_MIN^2)
        # a root near X = 0 needs lam(X = 0) > 0 verified; points converging there check it
        need = done & ~hi_checked & (new > 0.99)
        if need.any():
            lam1 = ev(idx[need], np.ones(need.sum()))[0]
            bad1 = np.flatnonzero(need)[~(np.isfinite(lam1) & (lam1 > 0))]
            new[bad1] = np.nan
        new = np.where(none, np.nan, new)
        done |= none
        X[idx[done]] = XL[idx[done]] * (1.0 - new[done] ** 2)
        found[idx[done]] = np.isfinite(new[done])
        U[idx[done]], P[idx[done]] = u[done], p[done]
        keep = ~done
        tp, lp, gp = (np.where(bad, np.nan, v)[keep] for v in (t, lam, dlam))
        idx, lo, hi, t, hi_checked, guess = idx[keep], lo[keep], hi[keep], new[keep], hi_checked[keep], p[keep]
    return X, found, U, P


def bracketed_step(lam: np.ndarray, dlam: np.ndarray, t: np.ndarray, lo: np.ndarray, hi: np.ndarray, bad: np.ndarray,
                   previous: tuple[np.ndarray, np.ndarray, np.ndarray], XL: np.ndarray,
                   tol: float) -> tuple[np.ndarray, ...]:
    """One safeguarded step of the root search in t = sqrt(1 - X/X_L) (elastic and piezoelectric).

    Newton's step lam / (d lam/dt) with the inverse cubic Hermite correction through the previous
    point, kept inside the bracket [lo, hi] (bisection otherwise).

    Parameters
    ----------
    lam, dlam : ndarray, shape (k,)
        Lowest impedance eigenvalue at t and its derivative d lam / dt (``bad`` rows: lam = -1).
    t, lo, hi : ndarray, shape (k,)
        Current point and bracket (lam(lo) <= 0 < lam(hi) once both are known).
    bad : ndarray of bool, shape (k,)
        Rows whose evaluation failed (supersonic by rounding).
    previous : tuple of ndarray, shape (k,) each
        (t, lam, d lam/dt) of the previous step (NaN where there is none).
    XL : ndarray, shape (k,)
        Limiting X of each row.
    tol : float
        Relative tolerance on X.

    Returns
    -------
    neg, lo, hi, new, done : ndarray, shape (k,)
        lam <= 0, the updated bracket, the next t, and rows converged (step or bracket below tol,
        or t the root to rounding).
    """
    tp, lp, gp = previous
    neg = lam <= 0
    lo, hi = np.where(neg, t, lo), np.where(neg, hi, t)
    with np.errstate(all="ignore"):
        step = lam / dlam
        step = step - _hermite_correction(lam, t, 1.0 / dlam, lp, tp, 1.0 / gp, step)
    new = np.maximum(t - step, T_MIN)
    inside = np.isfinite(new) & (new >= lo) & (new < hi) & ~bad & (new != t)
    # lam = 0, or a step below the resolution of t (t - step == t in floating point): t is the
    # root to rounding (else such a step would count as leaving the bracket and bisect away)
    exact = (lam == 0) | (np.isfinite(step) & ~bad & (t - step == t))
    new = np.where(exact, t, np.where(inside, new, 0.5 * (lo + hi)))
    dX = np.abs(2.0 * t * step) * XL                               # |dX| of the step, to first order
    Xn = XL * (1.0 - new * new)
    done = (inside & (dX <= tol * Xn)) | exact
    done |= (hi - lo) * 2.0 * hi * XL <= tol * Xn                  # bracket below tolerance
    return neg, lo, hi, new, done


def _hermite_correction(y1, s1, ds1, y0, s0, ds0, newton):
    """Correction c2 y1^2 - c3 y1^3 to the Newton step ``newton`` = y1 ds1 towards y = 0.

    Inverse cubic Hermite interpolation: s(y) = s1 + (y - y1) ds1 + c2 (y - y1)^2 + c3 (y - y1)^3
    through the two latest points (y, s, ds/dy) of the search (y = lam, s = t); it converges
    with order 1 + sqrt 3 per evaluation (Newton: 2). Zero where the previous point is missing
    (NaN) or the correction is not small against the Newton step (far from the root).
    """
    D = y0 - y1
    r1 = (s0 - s1 - D * ds1) / (D * D)
    r2 = (ds0 - ds1) / D
    c3 = (r2 - 2.0 * r1) / D
    c2 = r1 - c3 * D
    corr = c2 * y1 * y1 - c3 * y1 ** 3
    return np.where(np.isfinite(corr) & (np.abs(corr) < 0.5 * np.abs(newton)), corr, 0.0)


def _null_vector(Z: np.ndarray) -> np.ndarray:
    """Unit eigenvector of the Hermitian Z (m, d, d) with the smallest |eigenvalue|; u2 real >= 0."""
    w, v = np.linalg.eigh(Z)
    j = np.argmin(np.abs(w), axis=-1)
    return _phase(np.take_along_axis(v, j[:, None, None], axis=-1)[..., 0])


def _phase(u: np.ndarray) -> np.ndarray:
    """Unit vectors u (m, d) with the phase convention of :func:`surface_wave`."""
    u = u / np.linalg.norm(u, axis=-1, keepdims=True)
    # phase convention: u2 real and non-negative; if u2 ~ 0, u1 real and non-negative
    ref = np.where(np.abs(u[:, 1]) > 1e-8, u[:, 1], u[:, 0])
    phase = np.where(np.abs(ref) > 0, np.conj(ref) / np.where(np.abs(ref) > 0, np.abs(ref), 1), 1)
    return u * phase[:, None]


def surface_wave(A: ArrayLike, rho: ArrayLike = 1.0, *, mirror: ArrayLike | None = None, tol: float = 1e-12) -> dict:
    """Surface wave of a half space with wave-propagation tensor A, vectorised.

    Parameters
    ----------
    A : array_like, shape (..., d, d, d, d), d = 3 (or 2: sagittal-only media)
        Wave-propagation tensor in the lab frame (x1 propagation, x2 inward normal), with
        the major symmetry A_ijkl = A_klij. Any units: the solver normalises by max |A|.
    rho : float or array_like broadcastable to A.shape[:-4]
        Density; speeds come out in sqrt(A / rho).
    mirror : None or bool array_like broadcastable to A.shape[:-4]
        Whether the sagittal plane is a mirror (the x3 motion decouples). None: detected
        from A (odd-in-3 components below ``SYMMETRY_TOL`` relative).
    tol : float
        Relative accuracy of X = rho c^2 in the root search.

    Returns
    -------
    dict of ndarray, each of shape A.shape[:-4] (plus a trailing axis where said)
        ``c`` phase speed (NaN where none), ``c_imag`` (0 for real waves), ``c_limit`` v_L,
        ``wave_type`` (object: "surface", "supersonic_decoupled", "pseudo", "none"),
        ``reason`` (object str, "" when fine), ``polarisation`` (..., d) complex unit
        surface displacement, lab frame, phase such that u2 is real and >= 0 (u1 if u2 = 0);
        ``decay`` (..., d) complex Stroh eigenvalues p with Im p > 0, ascending Im p (for a
        decoupled mirror wave: the two sagittal ones, then the SH one or NaN);
        ``penetration_depth`` 1/(2 pi min Im p) over the partial waves carrying the wave,
        in wavelengths; ``mirror`` (bool), ``method`` ("eq17" or "stroh").

    Raises
    ------
    InputError
        Wrong shape, non-finite values, A without major symmetry, rho <= 0.

    Examples
    --------
    >>> import numpy as np
    >>> from surfwave.solvers.tensors import voigt_to_tensor, cubic_voigt
    >>> A = voigt_to_tensor(cubic_voigt(3.0, 1.0, 1.0))   # isotropic, Poisson ratio 1/4
    >>> r = surface_wave(A, 1.0)
    >>> round(float(r["c"]), 6), str(r["wave_type"])    # sqrt(2 - 2/sqrt 3)
    (0.919402, 'surface')
    """
    Af, rho_f, scale, shape = _checked_input(A, rho)
    Ah = Af / scale[:, None, None, None, None]
    Q, R, T = imp.stroh_blocks(Ah)
    mir, eq17 = _mirror_points(Ah, mirror, shape)
    Tpd = np.linalg.eigvalsh(T)[:, 0] > 0
    XL, _ = imp.limiting_x(Q, R, T)
    stable = Tpd & (XL > 0)
    XL = np.where(stable, XL, np.nan)
    X, found, method, pol, decay = _roots(Ah, Q, R, T, XL, stable, mir, eq17, tol)
    wave_type, reason = _classify(X, XL, found, stable, Tpd, mir)
    pol, decay, depth = _mode_shapes(Q, R, T, X, found, mir, pol, decay)
    rho_s = scale / rho_f
    out = {
        "c": np.sqrt(X * rho_s),
        "c_imag": np.where(found, 0.0, np.nan),
        "c_limit": np.sqrt(XL * rho_s),
        "wave_type": wave_type,
        "reason": reason,
        "polarisation": pol,
        "decay": decay,
        "penetration_depth": depth,
        "mirror": mir,
        "method": method,
    }
    return {k: (v.reshape(shape + v.shape[1:]) if v.ndim > 1 else v.reshape(shape)) for k, v in out.items()}


def _checked_input(A: ArrayLike, rho: ArrayLike) -> tuple[np.ndarray, np.ndarray, np.ndarray, tuple[int, ...]]:
    """The solver's input checks (shape, finite values, major symmetry, rho > 0), flattened.

    Parameters
    ----------
    A : array_like, shape (..., d, d, d, d), d = 2 or 3
        Wave-propagation tensor, any units.
    rho : float or array_like broadcastable to A.shape[:-4]
        Density.

    Returns
    -------
    Af : ndarray, shape (n, d, d, d, d)
        A flattened over its leading axes (n points), same units.
    rho_f : ndarray, shape (n,)
        Density per point.
    scale : ndarray, shape (n,)
        max |A| per point (units of A), > 0.
    shape : tuple of int
        A.shape[:-4], the shape of the results.

    Raises
    ------
    InputError
        Wrong shape, non-finite values, A = 0 at a point, A without major symmetry, rho <= 0.
    """
    A = np.asarray(A, dtype=float)
    d = A.shape[-1] if A.ndim >= 4 else 0
    if A.ndim < 4 or A.shape[-4:] != (d,) * 4 or d not in (2, 3):
        raise InputError(f"A must have shape (..., d, d, d, d) with d = 2 or 3, got {A.shape}")
    shape = A.shape[:-4]
    Af = A.reshape((-1,) + (d,) * 4)
    rho_f = np.broadcast_to(np.asarray(rho, dtype=float), shape).reshape(-1)
    if not np.all(np.isfinite(Af)):
        raise InputError("A contains non-finite values")
    if np.any(~np.isfinite(rho_f) | (rho_f <= 0)):
        raise InputError(f"density rho must be positive and finite, got {rho_f[~(rho_f > 0)][:3]}")
    scale = np.abs(Af).max(axis=(1, 2, 3, 4))
    if np.any(scale == 0):
        raise InputError("A vanishes at some point")
    asym = np.abs(Af - Af.transpose(0, 3, 4, 1, 2)).max(axis=(1, 2, 3, 4)) / scale
    if np.any(asym > 1e-9):
        k = int(np.argmax(asym))
        raise InputError(f"A lacks the major symmetry A_ijkl = A_klij: |A - A^T| = {asym[k]:.3g} of max|A| "
                         f"at point {k}")
    return Af, rho_f, scale, shape


def _mirror_points(Ah: np.ndarray, mirror: ArrayLike | None, shape: tuple[int, ...]) -> tuple[np.ndarray, np.ndarray]:
    """Which points have a mirror sagittal plane, and which of those Eq. (17) solves.

    Parameters
    ----------
    Ah : ndarray, shape (n, d, d, d, d)
        A / max|A| (dimensionless), lab frame.
    mirror : None or bool array_like broadcastable to ``shape``
        The caller's answer; None: detected from ``Ah`` (odd-in-3 components below
        :data:`SYMMETRY_TOL`; always True for d = 2).
    shape : tuple of int
        Leading shape of the caller's A (n = its product).

    Returns
    -------
    mir : ndarray of bool, shape (n,)
        Sagittal plane x1 x2 is a mirror (x3 motion decouples).
    eq17 : ndarray of bool, shape (n,)
        Mirror points whose sagittal problem is orthotropic and of the S form (Eq. 17 applies).
    """
    n, d = Ah.shape[0], Ah.shape[-1]
    if mirror is None:
        mir = np.ones(n, dtype=bool) if d == 2 else _relative_max(Ah, _odd_components(d, 2), 1.0) <= SYMMETRY_TOL
    else:
        mir = np.broadcast_to(np.asarray(mirror, dtype=bool), shape).reshape(-1).copy()
    # Eq. (17) applies to mirror points whose sagittal problem is orthotropic and of the S form
    ortho = _relative_max(Ah[:, :2, :2, :2, :2], _odd_components(2, 0), 1.0) <= SYMMETRY_TOL
    sform = (np.abs(Ah[:, 0, 1, 0, 1] - Ah[:, 0, 1, 1, 0]) <= SYMMETRY_TOL) & \
            (np.abs(Ah[:, 0, 1, 0, 1] - Ah[:, 1, 0, 0, 1]) <= SYMMETRY_TOL)
    return mir, mir & ortho & sform


def _roots(Ah: np.ndarray, Q: np.ndarray, R: np.ndarray, T: np.ndarray, XL: np.ndarray, stable: np.ndarray,
           mir: np.ndarray, eq17: np.ndarray, tol: float
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The surface-wave roots: coupled search off mirrors, Eq. (17) or the sagittal search on them.

    Parameters
    ----------
    Ah : ndarray, shape (n, d, d, d, d)
        A / max|A|, lab frame (dimensionless).
    Q, R, T : ndarray, shape (n, d, d)
        Stroh blocks of ``Ah`` (:func:`impedance.stroh_blocks`).
    XL : ndarray, shape (n,)
        Scaled limiting X = rho v_L^2 / max|A| (NaN where not ``stable``).
    stable, mir, eq17 : ndarray of bool, shape (n,)
        Points with a stable crystal, a mirror sagittal plane, Eq. (17) applicable.
    tol : float
        Relative accuracy of X.

    Returns
    -------
    X : ndarray, shape (n,)
        Scaled root X / max|A| (NaN where none).
    found : ndarray of bool, shape (n,)
    method : ndarray of object, shape (n,)
        "eq17" or "stroh".
    pol, decay : ndarray, shape (n, d), complex
        Off-mirror points with a root: the search's surface displacement and Stroh roots p
        (NaN elsewhere; the mirror points' are made by :func:`_mode_shapes`).
    """
    n, d = Ah.shape[0], Ah.shape[-1]
    X = np.full(n, np.nan)
    found = np.zeros(n, dtype=bool)
    method = np.full(n, "stroh", dtype=object)
    # 1. full (coupled) subsonic search where no mirror
    gen = stable & ~mir
    pol = np.full((n, d), np.nan + 0j)
    decay = np.full((n, d), np.nan + 0j)
    if gen.any():
        X[gen], found[gen], pol[gen], decay[gen] = _root_search(Q[gen], R[gen], T[gen], XL[gen], tol)
    # 2. mirror points: the sagittal 2 x 2 problem (Eq. 17 when orthotropic)
    Q2, R2, T2 = Q[:, :2, :2], R[:, :2, :2], T[:, :2, :2]
    e17 = stable & eq17
    if e17.any():
        a, b, c, dd, f = (Ah[e17, 0, 0, 0, 0], Ah[e17, 0, 1, 0, 1], Ah[e17, 1, 0, 1, 0],
                          Ah[e17, 1, 1, 1, 1], Ah[e17, 1, 1, 0, 0])
        Xr, has = rayleigh._select_root(a, b, c, dd, f)
        X[e17] = np.where(has, Xr, np.nan)
        found[e17] = has
        method[e17] = "eq17"
    sag = stable & mir & ~eq17
    XL2 = np.full(n, np.nan)
    if sag.any():
        XL2[sag], _ = imp.limiting_x(Q2[sag], R2[sag], T2[sag])
        X[sag], found[sag] = _root_search(Q2[sag], R2[sag], T2[sag], XL2[sag], tol)[:2]
    return X, found, method, pol, decay


def _classify(X: np.ndarray, XL: np.ndarray, found: np.ndarray, stable: np.ndarray, Tpd: np.ndarray,
              mir: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Wave type and reason of every point from its root (:data:`surfwave.vocab.WAVE_TYPES`).

    Parameters
    ----------
    X, XL : ndarray, shape (n,)
        Scaled root and limiting X (NaN where none).
    found, stable, Tpd, mir : ndarray of bool, shape (n,)
        Root found; stable crystal; T positive definite; mirror sagittal plane.

    Returns
    -------
    wave_type, reason : ndarray of object (str), shape (n,)
        "surface", "supersonic_decoupled", "pseudo" or "none"; "" where a wave was found.
    """
    supersonic = found & mir & (X >= XL * (1 - 1e-12))
    pseudo = stable & ~found & ~mir
    wave_type = np.where(found, np.where(supersonic, "supersonic_decoupled", "surface"),
                         np.where(pseudo, "pseudo", "none")).astype(object)
    reason = np.full(X.shape[0], "", dtype=object)
    reason[~found] = np.where(mir[~found], REASON_NOROOT_MIRROR, REASON_PSEUDO)
    reason[~stable] = REASON_UNSTABLE
    reason[~Tpd] = REASON_T
    return wave_type, reason


def _mode_shapes(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray, found: np.ndarray,
                 mir: np.ndarray, pol: np.ndarray, decay: np.ndarray
                 ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Polarisation, decay constants and penetration depth at the roots.

    Parameters
    ----------
    Q, R, T : ndarray, shape (n, d, d)
        Scaled Stroh blocks.
    X : ndarray, shape (n,)
        Scaled roots.
    found, mir : ndarray of bool, shape (n,)
    pol, decay : ndarray, shape (n, d), complex
        From :func:`_roots` (filled in place at the mirror points).

    Returns
    -------
    pol : ndarray, shape (n, d), complex
        Unit surface displacement, phase of :func:`surface_wave` (NaN where no root).
    decay : ndarray, shape (n, d), complex
        Stroh roots p of the partial waves (NaN where no root; a mirror point's third one is
        the decoupled SH wave's, NaN where it does not decay).
    depth : ndarray, shape (n,)
        1 / (2 pi min Im p), wavelengths (NaN where no root).
    """
    n, d = X.shape[0], Q.shape[-1]
    depth = np.full(n, np.nan)
    full = found & ~mir
    if full.any():
        pol[full] = _phase(pol[full])
        depth[full] = 1.0 / (2 * np.pi * decay[full].imag.min(axis=-1))
    sagf = found & mir
    if sagf.any():
        Q2, R2, T2 = Q[:, :2, :2], R[:, :2, :2], T[:, :2, :2]
        ev = imp.impedance(Q2[sagf], R2[sagf], T2[sagf], X[sagf])
        pol[sagf, :2] = _null_vector(ev["Z"])
        decay[sagf, :2] = ev["p"]
        depth[sagf] = 1.0 / (2 * np.pi * ev["p"].imag.min(axis=-1))
        if d == 3:
            pol[sagf, 2] = 0.0
            # the decoupled SH partial wave: A3131 + 2 p A3132 + p^2 A3232 = X
            q, r, t = Q[sagf, 2, 2], R[sagf, 2, 2], T[sagf, 2, 2]
            disc = (r * r - t * (q - X[sagf])).astype(complex)
            p3 = (-r + np.sqrt(disc)) / t
            p3 = np.where(p3.imag > 1e-12, p3, np.nan + 0j)
            decay[sagf, 2] = p3
    # no wave found (pseudo, none, unstable): no polarisation or decay to report
    pol[~found] = np.nan
    decay[~found] = np.nan
    return pol, decay, depth
