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
The p are also the roots of the Stroh polynomial det(Q - X I + p (R + R^T) + p^2 T); in a root
search they are tracked from one X to the next by Newton's method on it (:func:`track_roots`),
the eigenvalues of N serving the first step and any row where tracking cannot vouch for them.
"""
from __future__ import annotations

import numpy as np

#: Points of the initial grid of wave-normal angles in the limiting-speed search.
LIMIT_GRID = 48
#: Local minima of the grid refined (the lowest ones).
LIMIT_CANDIDATES = 3
#: ... among those within this relative distance of the grid's best value.
LIMIT_WINDOW = 0.05
#: Newton steps at most refining the limiting speed (rows stop once the predicted gain is below
#: rounding). 4 was too few where the grid's best points lie on the concave part of a shallow
#: double well (Pb (110) at 60.42 deg: 6 steps, 3e-9 high after 4).
LIMIT_STEPS = 12


def stroh_blocks(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Q, R, T of a lab-frame tensor A, shape (..., d, d, d, d) -> three (..., d, d)."""
    return A[..., :, 0, :, 0], A[..., :, 0, :, 1], A[..., :, 1, :, 1]


def acoustic(Q: np.ndarray, R: np.ndarray, T: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Acoustic tensor Gamma(n) for the wave normal n = (cos phi, sin phi) in the sagittal plane.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)
    phi : ndarray, shape (m, k) or (1, k)

    Returns
    -------
    ndarray, shape (m, k, d, d)
        cos^2 Q + sin cos (R + R^T) + sin^2 T; its eigenvalues are rho v^2 of the bulk waves.
    """
    c, s = np.cos(phi)[..., None, None], np.sin(phi)[..., None, None]
    RR = (R + np.swapaxes(R, -1, -2))[:, None]
    return c * c * Q[:, None] + s * c * RR + s * s * T[:, None]


def _lowest_eig_closed(Q, R, T, phi) -> np.ndarray:
    """Lowest eigenvalue of Gamma(n) (see :func:`acoustic`) in closed form, shape (m, k).

    Built component by component (no (m, k, d, d) temporaries); 2 x 2 directly, 3 x 3 by the
    trigonometric solution of the characteristic cubic: cheap but only accurate to ~1e-8
    relative near degenerate eigenvalues, so used for the coarse grid only.
    """
    c, s = np.cos(phi), np.sin(phi)
    cc, sc, ss = c * c, s * c, s * s

    def comp(i, j):
        if phi.shape[0] == 1:                                      # one grid for all: a BLAS product
            coef = np.stack([Q[:, i, j], R[:, i, j] + R[:, j, i], T[:, i, j]], axis=-1)
            return coef @ np.concatenate([cc, sc, ss])
        return cc * Q[:, i, j, None] + sc * (R[:, i, j] + R[:, j, i])[:, None] + ss * T[:, i, j, None]

    if Q.shape[-1] == 2:
        a, b, c2 = comp(0, 0), comp(0, 1), comp(1, 1)
        return 0.5 * (a + c2) - np.hypot(0.5 * (a - c2), b)
    g00, g11, g22, d, e, f = comp(0, 0), comp(1, 1), comp(2, 2), comp(0, 1), comp(0, 2), comp(1, 2)
    q = (g00 + g11 + g22) / 3.0
    a, b, c3 = g00 - q, g11 - q, g22 - q
    p = np.sqrt((a * a + b * b + c3 * c3 + 2.0 * (d * d + e * e + f * f)) / 6.0)
    det = a * (b * c3 - f * f) - d * (d * c3 - f * e) + e * (d * f - b * e)
    with np.errstate(all="ignore"):
        r = det / (2.0 * p**3)
    ang = np.arccos(np.clip(np.nan_to_num(r), -1.0, 1.0)) / 3.0
    return q + 2.0 * p * np.cos(ang + 2.0 * np.pi / 3.0)


def _trace_x(Q, R, T, phi, exact: bool = True) -> np.ndarray:
    """Lowest rho v_trace^2 = lambda_min(Gamma(n)) / cos^2 phi of the bulk waves, shape (m, k).

    ``exact``: LAPACK eigenvalues (accurate to rounding); else the closed form.
    """
    lam = np.linalg.eigvalsh(acoustic(Q, R, T, phi))[..., 0] if exact else _lowest_eig_closed(Q, R, T, phi)
    return lam / np.cos(phi) ** 2


def limiting_x(Q: np.ndarray, R: np.ndarray, T: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Limiting X_L = rho v_L^2 = min over real p of the lowest eigenvalue of Q + p(R+R^T) + p^2 T.

    With p = tan phi (phi the angle of the bulk wave normal from x1 in the sagittal plane)
    this is the lowest trace velocity along x1 of all bulk waves. A grid of ``LIMIT_GRID``
    angles finds the local minima; the ``LIMIT_CANDIDATES`` lowest are refined by Newton's
    method on the branch and the lowest result is kept; the value at a smooth minimum is then accurate to rounding.
    (Newton on the branch, :func:`_refine`.)

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
    g = _trace_x(Q, R, T, grid[None], exact=False)                # (m, LIMIT_GRID)
    # refine the lowest local minima of the grid (up to LIMIT_CANDIDATES, those within
    # LIMIT_WINDOW of the best): two branches may have minima within the grid's resolution
    # of each other (e.g. SH at p = 0, sagittal at p != 0)
    pad = np.pad(g, ((0, 0), (1, 1)), constant_values=np.inf)
    local = (g <= pad[:, :-2]) & (g <= pad[:, 2:])
    gl = np.where(local, g, np.inf)
    order = np.argsort(gl, axis=1)[:, :LIMIT_CANDIDATES]
    cand = np.take_along_axis(gl, order, axis=1)
    best = cand[:, :1]
    keep = np.isfinite(cand) & (cand <= best + LIMIT_WINDOW * np.abs(best))
    keep[:, 0] = True
    rows, cols = np.nonzero(keep)
    xf, pf = _refine(Q[rows], R[rows], T[rows], grid[order[rows, cols]], h)
    X_L = np.full(m, np.inf)
    np.minimum.at(X_L, rows, xf)
    win = xf == X_L[rows]
    phi = np.empty(m)
    phi[rows[win]] = pf[win]
    return X_L, np.tan(phi)


def _refine(Q, R, T, phi0, h):
    """Minimise the lowest branch lam(p) of Gamma(p) = Q + p (R + R^T) + p^2 T from p = tan(phi0).

    Newton's method on lam'(p) = 0 with analytic derivatives (eigenvectors a_j, eigenvalues
    w_j of Gamma): lam' = a_0 . Gamma' a_0, lam'' = 2 a_0 . T a_0 + 2 sum_j (a_j . Gamma' a_0)^2 /
    (w_0 - w_j), Gamma' = R + R^T + 2 p T; steps limited to the grid cell, a non-positive
    curvature steps downhill by half a cell; the lowest value seen is kept. Degenerate pairs
    (|w_0 - w_j| < 1e-9 scale, e.g. isotropic SH and SV) contribute nothing to lam''.

    Returns
    -------
    fx, phi : ndarray, shape (m,)
        The minimum value of lam and its angle phi = arctan p.
    """
    p = np.tan(phi0)
    trust = h * (1.0 + p * p)                                      # the grid cell in p
    RR = R + np.swapaxes(R, -1, -2)
    best, best_p = np.full(p.shape, np.inf), p.copy()
    idx = np.arange(len(p))                                        # rows still iterating
    for _ in range(LIMIT_STEPS + 1):
        if idx.size == 0:
            break
        q, r, t, pi = Q[idx], RR[idx], T[idx], p[idx]
        G = q + pi[:, None, None] * r + (pi * pi)[:, None, None] * t
        w, V = np.linalg.eigh(G)
        lam = w[:, 0]
        better = lam < best[idx]
        best[idx], best_p[idx] = np.where(better, lam, best[idx]), np.where(better, pi, best_p[idx])
        a0 = V[:, :, 0]
        G1a = np.einsum("mij,mj->mi", r + 2.0 * pi[:, None, None] * t, a0)
        d2 = 2.0 * np.einsum("mi,mij,mj->m", a0, t, a0)
        step, done = lowest_eigenvalue_step(w, V, G1a, d2, trust[idx])
        p[idx] = pi + step
        idx = idx[~done]
    return best, np.arctan(best_p)


def lowest_eigenvalue_step(w: np.ndarray, V: np.ndarray, S1a: np.ndarray, d2: np.ndarray,
                           trust: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Newton step on the lowest eigenvalue lam(p) of a symmetric matrix S(p), kept in a trust range.

    Shared by the elastic and the piezoelectric limiting-speed refinements.

    Parameters
    ----------
    w, V : ndarray, shapes (m, n) and (m, n, n)
        Eigenvalues (ascending) and eigenvectors of S(p).
    S1a : ndarray, shape (m, n)
        S'(p) a0, with a0 = V[:, :, 0] (so d lam / dp = a0 . S1a).
    d2 : ndarray, shape (m,)
        a0 . S''(p) a0; the second-order perturbation sum over the other eigenpairs is added here.
    trust : ndarray, shape (m,)
        Largest step; a non-positive curvature steps downhill by half of it.

    Returns
    -------
    step : ndarray, shape (m,)
    done : ndarray of bool, shape (m,)
        Near a smooth minimum lam(p + step) = lam(p) - d2 step^2 / 2 + ...: rows whose gain is
        below the rounding of lam (eps max|w|).
    """
    d1 = np.einsum("mi,mi->m", V[:, :, 0], S1a)
    scale = np.abs(w).max(axis=1)
    for j in range(1, w.shape[-1]):
        gap = w[:, 0] - w[:, j]
        c = np.einsum("mi,mi->m", V[:, :, j], S1a)
        with np.errstate(all="ignore"):
            d2 = d2 + np.where(np.abs(gap) > 1e-9 * scale, 2.0 * c * c / gap, 0.0)
    with np.errstate(all="ignore"):
        step = np.where(d2 > 0, -d1 / d2, -0.5 * np.sign(d1) * trust)
    step = np.clip(np.nan_to_num(step), -trust, trust)
    return step, (d2 > 0) & (0.5 * d2 * step * step <= 1e-16 * scale)


def stroh_matrix(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Real Stroh matrix N(X), shape (m, 2d, 2d), for X shape (m,)."""
    d = Q.shape[-1]
    Ti = np.linalg.inv(T)
    RT = np.swapaxes(R, -1, -2)
    N1 = -Ti @ RT
    N3 = R @ Ti @ RT - Q + X[:, None, None] * np.eye(d)
    top = np.concatenate([N1, Ti], axis=-1)
    bottom = np.concatenate([N3, np.swapaxes(N1, -1, -2)], axis=-1)
    return np.concatenate([top, bottom], axis=-2)


#: Newton steps allowed when tracking the Stroh roots from a guess (else: eigenvalues of N).
TRACK_STEPS = 8
#: Tracked roots must be apart by this much relative to max |p|, and Im p above it (else: eigenvalues).
TRACK_SEPARATION = 1e-6


def pmul(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Product of stacked polynomials, ascending coefficients (..., k) x (..., l) -> (..., k + l - 1)."""
    out = np.zeros(np.broadcast_shapes(a.shape[:-1], b.shape[:-1]) + (a.shape[-1] + b.shape[-1] - 1,))
    for i in range(a.shape[-1]):
        out[..., i:i + b.shape[-1]] += a[..., i, None] * b
    return out


def stroh_polynomial_parts(Q: np.ndarray, R: np.ndarray, T: np.ndarray) -> np.ndarray:
    """Coefficients of det(G(p) - X I), G(p) = Q + p (R + R^T) + p^2 T, by powers of X and p.

    Returns
    -------
    ndarray, shape (m, d + 1, 2d + 1)
        ``parts[:, k, j]`` multiplies X^k p^j: det(G - X I) = det G - X m2(G) + X^2 tr G - X^3
        (d = 3; m2 the sum of the principal 2 x 2 minors), det G - X tr G + X^2 (d = 2), each a
        polynomial in p expanded exactly (products of the quadratic entries).
    """
    d = Q.shape[-1]
    G = np.stack([Q, R + np.swapaxes(R, -1, -2), T], axis=-1)       # (m, d, d, 3): entries in p
    parts = np.zeros((Q.shape[0], d + 1, 2 * d + 1))
    tr = sum(G[:, i, i] for i in range(d))
    parts[:, d, 0] = (-1.0) ** d
    parts[:, d - 1, :3] = (-1.0) ** (d - 1) * tr
    if d == 2:
        parts[:, 0] = pmul(G[:, 0, 0], G[:, 1, 1]) - pmul(G[:, 0, 1], G[:, 1, 0])
        return parts

    def minor(i, j, k, l):                                         # G_ik G_jl - G_il G_jk
        return pmul(G[:, i, k], G[:, j, l]) - pmul(G[:, i, l], G[:, j, k])
    m12, m02, m01 = minor(1, 2, 1, 2), minor(1, 2, 0, 2), minor(1, 2, 0, 1)
    parts[:, 0] = pmul(G[:, 0, 0], m12) - pmul(G[:, 0, 1], m02) + pmul(G[:, 0, 2], m01)
    parts[:, 1, :5] = -(m12 + minor(0, 2, 0, 2) + minor(0, 1, 0, 1))
    return parts


def stroh_polynomial(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray,
                     parts: np.ndarray | None = None) -> np.ndarray:
    """Coefficients of det(Q - X I + p (R + R^T) + p^2 T), ascending in p, shape (m, 2d + 1).

    Its roots are the Stroh eigenvalues p (the eigenvalues of N(X)): a partial wave
    a exp(ik(x1 + p x2)) solves the equation of motion iff this matrix annihilates a.
    Expanded exactly (:func:`stroh_polynomial_parts`, which ``parts`` may pass precomputed).
    """
    if parts is None:
        parts = stroh_polynomial_parts(Q, R, T)
    c = parts[:, -1]
    for k in range(parts.shape[1] - 2, -1, -1):                    # Horner in X
        c = c * X[:, None] + parts[:, k]
    return c


def track_roots(c: np.ndarray, guess: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The d roots with Im p > 0 of the real polynomials c (m, 2d + 1), from nearby guesses (m, d).

    Newton's method on each guess (the roots move little between the evaluations of a root
    search). Accepted only where every root converged (last step below 1e-13 |p|, so that the
    quadratic convergence has reached rounding), the d roots are distinct and off the real
    axis by ``TRACK_SEPARATION`` relative: d distinct roots in the upper half plane of a real
    polynomial of degree 2d with no real root are all of them (the others are their
    conjugates). Elsewhere ``ok`` is False and the caller uses the eigenvalues of N.

    Returns
    -------
    p : ndarray, shape (m, d), complex
    ok : ndarray, shape (m,), bool
    """
    z = np.array(guess, dtype=complex)
    ok = np.isfinite(z).all(axis=-1)
    z = np.where(np.isfinite(z), z, 1j)
    cc = c[:, ::-1, None]                                          # descending, broadcast over roots
    conv = np.zeros(z.shape, dtype=bool)
    with np.errstate(all="ignore"):
        for _ in range(TRACK_STEPS):
            P, dP = cc[:, 0] + 0j, np.zeros(z.shape, dtype=complex)
            for k in range(1, cc.shape[1]):
                dP = dP * z + P
                P = P * z + cc[:, k]
            step = P / dP
            z = np.where(conv, z, z - step)                        # converged roots stay put: a row's
            conv |= np.abs(step) <= 1e-13 * np.abs(z)              # result does not depend on its batch
            if conv.all():
                break
        scale = np.abs(z).max(axis=-1)
        ok &= (conv.all(axis=-1) & np.isfinite(z).all(axis=-1)
               & (z.imag > TRACK_SEPARATION * scale[:, None]).all(axis=-1))
        d = z.shape[-1]
        for i in range(d):
            for j in range(i + 1, d):
                ok &= np.abs(z[:, i] - z[:, j]) > TRACK_SEPARATION * scale
    return z, ok


def lowest_eigenpair(Z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Lowest eigenvalue and a unit eigenvector of Hermitian Z, shape (m, d, d) -> (m,), (m, d).

    For d = 3 in closed form: the trigonometric solution of the characteristic cubic, polished
    by two Newton steps on det(Z - lam I) (the closed form alone loses accuracy when the upper
    two eigenvalues nearly coincide), the eigenvector as the largest cross product of two rows
    of Z - lam I (r_i . (r_i x r_j) = 0 holds for complex rows too). Rows whose lowest
    eigenvalue is within 1e-4 max|Z| of the next one (eigenvector ill-determined, the cubic's
    Newton step ill-conditioned) and d = 2 use LAPACK (numpy.linalg.eigh).
    """
    m, d = Z.shape[0], Z.shape[-1]
    if d != 3:
        w, v = np.linalg.eigh(Z)
        return w[:, 0], v[:, :, 0]
    a, b, c = Z[:, 0, 0].real, Z[:, 1, 1].real, Z[:, 2, 2].real
    x, y, z = Z[:, 0, 1], Z[:, 0, 2], Z[:, 1, 2]
    xx, yy, zz = x.real ** 2 + x.imag ** 2, y.real ** 2 + y.imag ** 2, z.real ** 2 + z.imag ** 2
    rexyz = (x * z * np.conj(y)).real
    q = (a + b + c) / 3.0
    a1, b1, c1 = a - q, b - q, c - q
    with np.errstate(all="ignore"):
        pp = np.sqrt((a1 * a1 + b1 * b1 + c1 * c1 + 2.0 * (xx + yy + zz)) / 6.0)
        det = a1 * b1 * c1 + 2.0 * rexyz - a1 * zz - b1 * yy - c1 * xx
        phi = np.arccos(np.clip(np.nan_to_num(det / (2.0 * pp ** 3)), -1.0, 1.0)) / 3.0
        lam = q + 2.0 * pp * np.cos(phi + 2.0 * np.pi / 3.0)
        top = q + 2.0 * pp * np.cos(phi)
        gap = (3.0 * q - top - lam) - lam                             # middle minus lowest
        for _ in range(2):
            al, bl, cl = a - lam, b - lam, c - lam
            chi = al * bl * cl + 2.0 * rexyz - al * zz - bl * yy - cl * xx
            dchi = xx + yy + zz - (bl * cl + al * cl + al * bl)
            lam = lam - np.where(dchi != 0, chi / dchi, 0.0)
        H = Z - lam[:, None, None] * np.eye(3)
        r0, r1, r2 = H[:, 0], H[:, 1], H[:, 2]
        cands = np.stack([np.cross(r0, r1), np.cross(r0, r2), np.cross(r1, r2)], axis=1)   # (m, 3, 3)
        nrm = np.linalg.norm(cands, axis=-1)
        k = np.argmax(nrm, axis=1)
        u = cands[np.arange(m), k] / nrm[np.arange(m), k, None]
    scale = np.abs(Z).max(axis=(1, 2))
    fall = ~(np.isfinite(u).all(axis=-1) & np.isfinite(lam) & (gap > 1e-4 * scale))
    if fall.any():
        w, v = np.linalg.eigh(Z[fall])
        lam[fall], u[fall] = w[:, 0], v[:, :, 0]
    return lam, u


def monic(roots: np.ndarray) -> np.ndarray:
    """Ascending coefficients c (m, d + 1) of prod_j (z - roots_j), roots (m, d); c_d = 1."""
    c = np.zeros(roots.shape[:-1] + (roots.shape[-1] + 1,), dtype=complex)
    c[..., 0] = 1.0
    for j in range(roots.shape[-1]):                               # multiply by (z - r_j), descending
        c[..., 1:j + 2] = c[..., 1:j + 2] - roots[..., j, None] * c[..., 0:j + 1]
    return c[..., ::-1]


def impedance(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray, derivative: bool = False,
              N0: np.ndarray | None = None, p_guess: np.ndarray | None = None, parts: np.ndarray | None = None) -> dict:
    """Surface impedance Z(X) and the decaying Stroh eigenvalues, vectorised.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)
        Stroh blocks (scaled so that their entries are of order one).
    X : ndarray, shape (m,)
        rho v^2 in the units of Q.
    derivative : bool
        Also return the lowest eigenvalue of Z and its derivative in X (below).
    N0 : ndarray, shape (m, 2d, 2d), optional
        ``stroh_matrix(Q, R, T, 0)``, to save its recomputation in a root search
        (N(X) = N0 + X [[0, 0], [I, 0]]).
    p_guess : ndarray, shape (m, d), complex, optional
        The decaying p at a nearby X (the previous step of a root search): they are then
        refined by :func:`track_roots` on :func:`stroh_polynomial` instead of computing the
        eigenvalues of N, where that succeeds.
    parts : ndarray, shape (m, d + 1, 2d + 1), optional
        ``stroh_polynomial_parts(Q, R, T)``, to save its recomputation in a root search.

    Returns
    -------
    dict
        ``Z`` (m, d, d) complex Hermitian impedance (NaN where not subsonic); ``p`` (m, d)
        complex, the eigenvalues with Im p > 0 in ascending Im p; ``subsonic`` (m,) bool:
        no eigenvalue within 1e-10 of the real axis; ``f`` (m,) real: det Z, whose sign
        change in X marks the surface wave (not computed, NaN, with ``derivative``). With
        ``derivative``: ``lam`` (m,) the lowest
        eigenvalue of Z, ``u`` (m, d) its unit eigenvector, ``dlam`` (m,) d lam / dX.

    Notes
    -----
    The derivative: M = B A^-1 solves the Riccati equation M N1 + M N2 M = N3 + N4 M (N in
    blocks N1..N4); as dN3/dX = I, dM/dX solves the Sylvester equation
    dM K1 - K2 dM = I with K1 = N1 + N2 M (eigenvalues: the decaying p) and K2 = N4 - M N2
    (the growing ones). With f(z) = prod_j (z - conj p_j) = sum_k c_k z^k, f(K2) = 0 and
    dM K1^k - K2^k dM = sum_{j<k} K2^j K1^(k-1-j), so dM = G f(K1)^-1 with
    G = sum_k c_k sum_{j<k} K2^j K1^(k-1-j) (f(K1) is invertible: the spectra are disjoint).
    Like W, this uses the roots only through f, so degenerate p cost no accuracy. Then
    dZ = -i dM and d lam / dX = u^H dZ u (first-order perturbation of a simple eigenvalue).
    """
    d = Q.shape[-1]
    if N0 is None:
        N = stroh_matrix(Q, R, T, X)
    else:
        N = N0.copy()
        N[:, d:, :d] += X[:, None, None] * np.eye(d)
    upper = np.full((len(X), d), np.nan + 0j)
    ok = np.zeros(len(X), dtype=bool)
    subsonic = np.ones(len(X), dtype=bool)                        # tracked roots have Im p > 0
    if p_guess is not None:
        upper, ok = track_roots(stroh_polynomial(Q, R, T, X, parts), p_guess)
    if not ok.all():
        miss = ~ok
        ev = np.linalg.eigvals(N[miss])
        order = np.argsort(ev.imag, axis=-1)
        ev = np.take_along_axis(ev, order, axis=-1)
        lo, up = ev[:, :d], ev[:, d:]
        # N is real: the lower eigenvalues are the conjugates of the upper ones (to rounding)
        subsonic[miss] = (lo.imag[:, -1] < -1e-10) & (up.imag[:, 0] > 1e-10)
        upper[miss] = up
    lower = np.conj(upper)
    # a pair p, -conj(p) has equal Im p (mirror directions): order it by Re p as well, so that
    # the decay constants come out in the same order whatever the rounding of the input
    scale = np.abs(upper).max(axis=-1, keepdims=True) + 1e-300
    upper = np.take_along_axis(upper, np.lexsort((upper.real, np.round(upper.imag / scale, 9)), axis=-1),
                               axis=-1)
    # W = f(N), f(z) = prod_j (z - conj p_j) = sum_k c_k z^k: real powers of the real N
    c = monic(lower)
    W = c[:, 0, None, None] * np.eye(2 * d) + c[:, 1, None, None] * N
    Nk = N
    for k in range(2, d + 1):
        Nk = Nk @ N
        W = W + c[:, k, None, None] * Nk
    W1, W2 = W[:, :d, :], W[:, d:, :]
    W1c = np.conj(W1)
    with np.errstate(all="ignore"):                                # (W1 W1^H)^T, (W2 W1^H)^T
        M = np.linalg.solve(np.einsum("mik,mjk->mji", W1, W1c), np.einsum("mik,mjk->mji", W2, W1c))
    M = np.swapaxes(M, -1, -2)                                     # B A^-1
    Z = -1j * M
    Z = 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))
    f = np.linalg.det(Z).real if not derivative else np.full(len(X), np.nan)
    bad = ~subsonic
    if bad.any():
        Z[bad] = np.nan
        f[bad] = np.nan
    out = {"Z": Z, "p": upper, "subsonic": subsonic, "f": f}
    if derivative:
        Zs = np.where(bad[:, None, None], np.eye(d), Z)
        lam, u = lowest_eigenpair(Zs)
        n1, n2, n4 = N[:, :d, :d], N[:, :d, d:], N[:, d:, d:]
        # f(K2) = 0 (Cayley-Hamilton: K2's eigenvalues are the growing p), so the Sylvester
        # equation gives dM f(K1) = G := sum_k c_k sum_{j<k} K2^j K1^(k-1-j); and as N [I; M] =
        # [I; M] K1 (the Riccati equation), f(K1) = W11 + W12 M. Only u^H G f(K1)^-1 u is needed:
        # with y = f(K1)^-1 u, a_j = u^H K2^j, b_i = K1^i y it is sum_k c_k sum_{j<k} a_j . b_(k-1-j)
        # (vector-matrix products only).
        fK1 = W1[:, :, :d] + np.einsum("mik,mkj->mij", W1[:, :, d:], M)
        with np.errstate(all="ignore"):
            y = np.linalg.solve(np.where(bad[:, None, None], np.eye(d), fK1), u[..., None])[..., 0]
        uc = np.conj(u)
        aj, bi = [uc], [y]
        for _ in range(1, d):
            aM = np.einsum("mi,mij->mj", aj[-1], M)
            aj.append(np.einsum("mi,mij->mj", aj[-1], n4) - np.einsum("mi,mij->mj", aM, n2))
            bi.append(np.einsum("mij,mj->mi", n1, bi[-1])
                      + np.einsum("mij,mj->mi", n2, np.einsum("mij,mj->mi", M, bi[-1])))
        uGy = sum(c[:, k] * sum(np.einsum("mi,mi->m", aj[j], bi[k - 1 - j]) for j in range(k)) for k in range(1, d + 1))
        out["lam"] = np.where(bad, np.nan, lam)
        out["u"] = u
        # d lam / dX = u^H dZ u, dZ = -i dM = -i G f(K1)^-1
        out["dlam"] = np.where(bad, np.nan, (-1j * uGy).real)
    return out
