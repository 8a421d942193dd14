"""Stroh blocks, the limiting speed and the surface impedance (building blocks of :mod:`stroh`).

Lab frame: x1 = propagation, x2 = inward surface normal. For the wave-propagation tensor A
(``shape (..., d, d, d, d)``, d = 3, or d = 2 for the sagittal sub-problem) the Stroh blocks
are Q_ik = A_i1k1, R_ik = A_i1k2, T_ik = A_i2k2. A partial wave u = a exp(ik(x1 + p x2))
has traction b = (R^T + p T) a on the planes x2 = const (divided by ik) and

    p [a; b] = N [a; b],   N = [[-T^-1 R^T, T^-1], [R T^-1 R^T - Q + X I, -R T^-1]],

with X = rho v^2. Below the limiting speed the six eigenvalues p are complex in conjugate
pairs; the three with Im p > 0 decay into the crystal. Their invariant subspace is spanned by
the columns of W = prod_j (N - conj(p_j) I) over the decaying p_j (Cayley-Hamilton: the
product annihilates the growing generalised eigenspace and is invertible on the decaying
one). This needs no eigenvectors, so equal or nearly equal p (isotropic crystals, Jordan
blocks) cost no accuracy: W depends on the roots only through symmetric functions. With
W = [W1; W2] the surface impedance is Z = -i B A^-1 = -i W2 W1^H (W1 W1^H)^-1 (Hermitian).
"""
from __future__ import annotations

import numpy as np

#: Points of the initial grid of wave-normal angles in the limiting-speed search.
LIMIT_GRID = 48
#: Local minima of the grid refined (the lowest ones).
LIMIT_CANDIDATES = 3
#: Successive parabolic-interpolation steps refining the limiting speed.
LIMIT_STEPS = 14


def stroh_blocks(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Q, R, T of a lab-frame tensor A, shape (..., d, d, d, d) -> three (..., d, d)."""
    return A[..., :, 0, :, 0], A[..., :, 0, :, 1], A[..., :, 1, :, 1]


def acoustic(Q, R, T, phi) -> np.ndarray:
    """Acoustic tensor Gamma(n) for the wave normal n = (cos phi, sin phi) in the sagittal plane.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)
    phi : ndarray, shape (m, k)

    Returns
    -------
    ndarray, shape (m, k, d, d)
        cos^2 Q + sin cos (R + R^T) + sin^2 T; its eigenvalues are rho v^2 of the bulk waves.
    """
    c, s = np.cos(phi)[..., None, None], np.sin(phi)[..., None, None]
    RR = (R + np.swapaxes(R, -1, -2))[:, None]
    return c * c * Q[:, None] + s * c * RR + s * s * T[:, None]


def _trace_x(Q, R, T, phi) -> np.ndarray:
    """Lowest rho v_trace^2 = lambda_min(Gamma(n)) / cos^2 phi of the bulk waves, shape (m, k)."""
    lam = np.linalg.eigvalsh(acoustic(Q, R, T, phi))[..., 0]
    return lam / np.cos(phi) ** 2


def limiting_x(Q, R, T) -> tuple[np.ndarray, np.ndarray]:
    """Limiting X_L = rho v_L^2 = min over real p of the lowest eigenvalue of Q + p(R+R^T) + p^2 T.

    With p = tan phi (phi the angle of the bulk wave normal from x1 in the sagittal plane)
    this is the lowest trace velocity along x1 of all bulk waves. A grid of ``LIMIT_GRID``
    angles finds the local minima; the ``LIMIT_CANDIDATES`` lowest are refined by successive
    parabolic interpolation (golden-section when a parabola step is not admissible) and the
    lowest result is kept; the value at a smooth minimum is then accurate to rounding.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)

    Returns
    -------
    X_L : ndarray, shape (m,)
    p_L : ndarray, shape (m,)
        tan(phi) at the minimum (the slope of the limiting bulk wave's normal).
    """
    m = Q.shape[0]
    h = np.pi / LIMIT_GRID
    grid = -0.5 * np.pi + h * (np.arange(LIMIT_GRID) + 0.5)
    g = _trace_x(Q, R, T, np.broadcast_to(grid, (m, LIMIT_GRID)))
    # refine the LIMIT_CANDIDATES lowest local minima of the grid: two branches may have
    # minima within the grid's resolution of each other (e.g. SH at p = 0, sagittal at p != 0)
    pad = np.pad(g, ((0, 0), (1, 1)), constant_values=np.inf)
    local = (g <= pad[:, :-2]) & (g <= pad[:, 2:])
    order = np.argsort(np.where(local, g, np.inf), axis=1)[:, :LIMIT_CANDIDATES]
    cand = np.take_along_axis(np.where(local, g, np.inf), order, axis=1)
    order = np.where(np.isfinite(cand), order, order[:, :1])                # pad with the best
    k = order.shape[1]
    rep = lambda M: np.repeat(M, k, axis=0)
    xf, pf = _refine(rep(Q), rep(R), rep(T), grid[order].reshape(-1), h)
    xf, pf = xf.reshape(m, k), pf.reshape(m, k)
    j = np.argmin(xf, axis=1)[:, None]
    return np.take_along_axis(xf, j, 1)[:, 0], np.tan(np.take_along_axis(pf, j, 1)[:, 0])


def _refine(Q, R, T, x, h):
    """Minimise _trace_x from x (shape (m,)) inside (x - h, x + h): successive parabolic
    interpolation with golden-section fallback (Brent's minimiser, vectorised).

    Returns
    -------
    fx, x : ndarray, shape (m,)
        The minimum value and its angle phi.
    """
    fx = _trace_x(Q, R, T, x[:, None])[:, 0]
    a = np.maximum(x - h, -0.5 * np.pi + 1e-9)
    b = np.minimum(x + h, 0.5 * np.pi - 1e-9)
    w, fw = x.copy(), fx.copy()
    v, fv = x.copy(), fx.copy()
    gold = 0.3819660112501051
    for _ in range(LIMIT_STEPS):
        # parabola through (v, w, x); its vertex u unless outside (a, b) or degenerate
        r = (x - w) * (fx - fv)
        q = (x - v) * (fx - fw)
        num = (x - v) * q - (x - w) * r
        den = 2.0 * (q - r)
        with np.errstate(all="ignore"):
            u = x - num / den
        mid = 0.5 * (a + b)
        golden = x + gold * np.where(x < mid, b - x, a - x)
        ok = np.isfinite(u) & (u > a) & (u < b) & (np.abs(u - x) > 1e-15)
        u = np.where(ok, u, golden)
        fu = _trace_x(Q, R, T, u[:, None])[:, 0]
        better = fu <= fx
        left = u < x
        a = np.where(better, np.where(left, a, x), np.where(left, u, a))
        b = np.where(better, np.where(left, x, b), np.where(left, b, u))
        second = ~better & (fu <= fw)
        v, fv = np.where(better | second, w, v), np.where(better | second, fw, fv)
        w, fw = np.where(better, x, np.where(second, u, w)), np.where(better, fx, np.where(second, fu, fw))
        x, fx = np.where(better, u, x), np.where(better, fu, fx)
    return fx, x


def stroh_matrix(Q, R, T, X) -> np.ndarray:
    """Real Stroh matrix N(X), shape (m, 2d, 2d), for X shape (m,)."""
    d = Q.shape[-1]
    Ti = np.linalg.inv(T)
    RT = np.swapaxes(R, -1, -2)
    N1 = -Ti @ RT
    N3 = R @ Ti @ RT - Q + X[:, None, None] * np.eye(d)
    top = np.concatenate([N1, Ti], axis=-1)
    bottom = np.concatenate([N3, np.swapaxes(N1, -1, -2)], axis=-1)
    return np.concatenate([top, bottom], axis=-2)


def impedance(Q, R, T, X) -> dict:
    """Surface impedance Z(X) and the decaying Stroh eigenvalues, vectorised.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)
        Stroh blocks (scaled so that their entries are of order one).
    X : ndarray, shape (m,)
        rho v^2 in the units of Q.

    Returns
    -------
    dict
        ``Z`` (m, d, d) complex Hermitian impedance (NaN where not subsonic); ``p`` (m, d)
        complex, the eigenvalues with Im p > 0 in ascending Im p; ``subsonic`` (m,) bool:
        no eigenvalue within 1e-10 of the real axis; ``f`` (m,) real: det Z, whose sign
        change in X marks the surface wave.
    """
    d = Q.shape[-1]
    N = stroh_matrix(Q, R, T, X)
    ev = np.linalg.eigvals(N)
    order = np.argsort(ev.imag, axis=-1)
    ev = np.take_along_axis(ev, order, axis=-1)
    lower, upper = ev[:, :d], ev[:, d:]
    subsonic = (lower.imag[:, -1] < -1e-10) & (upper.imag[:, 0] > 1e-10)
    eye = np.eye(2 * d)
    W = N - lower[:, 0, None, None] * eye
    for j in range(1, d):
        W = W @ (N - lower[:, j, None, None] * eye)
    W1, W2 = W[:, :d, :], W[:, d:, :]
    W1H = np.conj(np.swapaxes(W1, -1, -2))
    with np.errstate(all="ignore"):
        M = np.linalg.solve(np.swapaxes(W1 @ W1H, -1, -2), np.swapaxes(W2 @ W1H, -1, -2))
    Z = -1j * np.swapaxes(M, -1, -2)
    Z = 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))
    f = np.linalg.det(Z).real
    bad = ~subsonic
    if bad.any():
        Z[bad] = np.nan
        f[bad] = np.nan
    return {"Z": Z, "p": upper, "subsonic": subsonic, "f": f}
