"""Building blocks of the piezoelectric SAW solver (:mod:`surfwave.solvers.piezo`).

Generalised (4 x 4) Stroh blocks of E_IjKl (index 3 electric: E_ijkl = A_ijkl, E_ij3l = e_lij,
E_3jkl = e_jkl, E_3j3l = -eps_jl), the 8 x 8 Stroh matrix N(X) with the mass X only in the
mechanical block, its characteristic (Stroh) polynomial, the generalised surface impedance
Z = -i B A^-1, the piezoelectrically stiffened bulk speeds and the limiting speed.
Physics: docs/physics/piezoelectric.md.
"""
from __future__ import annotations

import numpy as np

from surfwave.solvers.impedance import _monic, _pmul, track_roots

#: Wave-normal grid and refinement of the limiting-speed search.
LIMIT_GRID = 48
LIMIT_CANDIDATES = 3
#: ... among those within this relative distance of the grid's best value.
LIMIT_WINDOW = 0.1
LIMIT_STEPS = 16


def generalised_blocks(A, e, eps) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Generalised Stroh blocks Q_JK = E_J1K1, R_JK = E_J1K2, T_JK = E_J2K2 (index 3 electric).

    Parameters
    ----------
    A : ndarray, shape (m, 3, 3, 3, 3)
        Wave-propagation tensor, lab frame (any units, e.g. Pa).
    e : ndarray, shape (m, 3, 3, 3)
        Piezoelectric stress tensor e_kij, lab frame (units consistent with A and eps, C/m^2).
    eps : ndarray, shape (m, 3, 3)
        Permittivity eps_kl, lab frame (F/m).

    Returns
    -------
    Q, R, T : ndarray, shape (m, 4, 4) each, float
    """
    E = generalised_tensor(A, e, eps)
    return E[:, :, 0, :, 0], E[:, :, 0, :, 1], E[:, :, 1, :, 1]


def generalised_tensor(A, e, eps) -> np.ndarray:
    """E_IjKl, shape (m, 4, 3, 4, 3): E_ijkl = A_ijkl, E_ij3l = e_lij, E_3jkl = e_jkl, E_3j3l = -eps_jl."""
    A, e, eps = (np.asarray(x, dtype=float) for x in (A, e, eps))
    m = A.shape[0]
    E = np.zeros((m, 4, 3, 4, 3))
    E[:, :3, :, :3, :] = A
    E[:, :3, :, 3, :] = np.einsum("mlij->mijl", e)
    E[:, 3, :, :3, :] = e
    E[:, 3, :, 3, :] = -eps
    return E


def piezo_bulk_speeds(A, e, eps, rho, n) -> np.ndarray:
    """Speeds of the three piezoelectrically stiffened bulk waves along unit wave normals n.

    Eigenvalues of Gamma_ik + gamma_i gamma_k / epsilon(n), Gamma_ik = A_ijkl n_j n_l,
    gamma_i = e_kij n_k n_j, epsilon(n) = eps_kl n_k n_l, divided by rho.

    Parameters
    ----------
    A : (m, 3, 3, 3, 3) Pa; e : (m, 3, 3, 3) C/m^2; eps : (m, 3, 3) F/m; rho : (m,) or scalar kg/m^3
    n : array_like, shape (m, 3) or (3,)
        Wave normals, lab frame (normalised here).

    Returns
    -------
    ndarray, shape (m, 3), m/s, ascending (NaN where rho v^2 < 0).
    """
    A, e, eps = (np.asarray(x, dtype=float) for x in (A, e, eps))
    n = np.broadcast_to(np.asarray(n, dtype=float), (A.shape[0], 3))
    n = n / np.linalg.norm(n, axis=-1, keepdims=True)
    G = np.einsum("mijkl,mj,ml->mik", A, n, n)
    g = np.einsum("mkij,mk,mj->mi", e, n, n)
    en = np.einsum("mkl,mk,ml->m", eps, n, n)
    w = np.linalg.eigvalsh(G + g[:, :, None] * g[:, None, :] / en[:, None, None])
    with np.errstate(invalid="ignore"):
        return np.sqrt(w / np.broadcast_to(np.asarray(rho, dtype=float), (A.shape[0],))[:, None])


def _stiffened_trace_x(Q, R, T, phi, exact: bool = True) -> np.ndarray:
    """Lowest stiffened rho v_trace^2 along x1 for sagittal normals (cos phi, sin phi, 0); (m, k).

    ``exact``: LAPACK eigenvalues; else the trigonometric solution of the characteristic cubic
    (cheap, ~1e-8 relative near degenerate eigenvalues: used for the coarse grid only).
    """
    c, s = np.cos(phi)[..., None, None], np.sin(phi)[..., None, None]
    G = c * c * Q[:, None] + s * c * (R + np.swapaxes(R, -1, -2))[:, None] + s * s * T[:, None]
    S = G[..., :3, :3] - G[..., :3, 3:] * G[..., 3:, :3] / G[..., 3:, 3:]
    lam = np.linalg.eigvalsh(S)[..., 0] if exact else _lowest_sym3(S)
    return lam / np.cos(phi) ** 2


def _lowest_sym3(S) -> np.ndarray:
    """Lowest eigenvalue of real symmetric 3 x 3 matrices (..., 3, 3) by the trigonometric formula."""
    q = np.trace(S, axis1=-2, axis2=-1) / 3.0
    a, b, c = S[..., 0, 0] - q, S[..., 1, 1] - q, S[..., 2, 2] - q
    d, e, f = S[..., 0, 1], S[..., 0, 2], S[..., 1, 2]
    p = np.sqrt((a * a + b * b + c * c + 2.0 * (d * d + e * e + f * f)) / 6.0)
    det = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e)
    with np.errstate(all="ignore"):
        r = np.nan_to_num(det / (2.0 * p ** 3))
    return q + 2.0 * p * np.cos(np.arccos(np.clip(r, -1.0, 1.0)) / 3.0 + 2.0 * np.pi / 3.0)


def limiting_x(Q, R, T) -> np.ndarray:
    """Limiting X_L = min over sagittal wave normals of the stiffened trace rho v^2, shape (m,).

    A grid of ``LIMIT_GRID`` angles (closed-form eigenvalues), then the ``LIMIT_CANDIDATES``
    lowest local minima (those within ``LIMIT_WINDOW`` of the best grid value) refined by ``LIMIT_STEPS`` parabolic steps (LAPACK eigenvalues) on a
    stencil that shrinks with the step (to 1e-5 rad at least: the vertex error is then ~1e-11
    rad, a relative error ~1e-20 in X_L) or, where the minimum lies outside the stencil, walks
    one stencil width and doubles it; the lowest value seen is kept.
    Q, R, T: generalised blocks (m, 4, 4).
    """
    m = Q.shape[0]
    h = np.pi / LIMIT_GRID
    grid = -0.5 * np.pi + h * (np.arange(LIMIT_GRID) + 0.5)
    g = _stiffened_trace_x(Q, R, T, grid[None], exact=False)
    pad = np.pad(g, ((0, 0), (1, 1)), mode="wrap")
    gl = np.where((g <= pad[:, :-2]) & (g <= pad[:, 2:]), g, np.inf)
    order = np.argsort(gl, axis=1)[:, :LIMIT_CANDIDATES]
    cand = np.take_along_axis(gl, order, axis=1)
    keep = np.isfinite(cand) & (cand <= cand[:, :1] + LIMIT_WINDOW * np.abs(cand[:, :1]))
    keep[:, 0] = True
    rows, cols = np.nonzero(keep)                                   # flat candidates
    phi = grid[order[rows, cols]]
    best = np.full(phi.shape, np.inf)
    step = np.full(phi.shape, h)
    act = np.arange(phi.size)
    for _ in range(LIMIT_STEPS):
        if act.size == 0:
            break
        r, ph, st = rows[act], phi[act], step[act]
        f = _stiffened_trace_x(Q[r], R[r], T[r], ph[:, None] + st[:, None] * np.array([-1.0, 0.0, 1.0]))
        best[act] = np.minimum(best[act], f.min(axis=-1))
        curv = f[:, 0] - 2 * f[:, 1] + f[:, 2]
        with np.errstate(all="ignore"):
            d = 0.5 * st * (f[:, 0] - f[:, 2]) / curv
        smooth = (curv > 0) & (np.abs(d) <= st)
        d = np.where(smooth, d, (np.argmin(f, axis=-1) - 1) * st)
        phi[act] = ph + np.nan_to_num(d)
        step[act] = np.where(smooth, np.clip(4.0 * np.abs(d), 1e-5, 0.25 * st), 2.0 * st)   # else: walk, widen
        act = act[~(smooth & (st <= 1e-5))]                        # a smooth step on the finest stencil
    f = _stiffened_trace_x(Q[rows], R[rows], T[rows], phi[:, None])[:, 0]
    XL = np.full(m, np.inf)
    np.minimum.at(XL, rows, np.minimum(best, f))
    return XL


def stroh_matrix(Q, R, T, X) -> np.ndarray:
    """Generalised 8 x 8 Stroh matrix N(X) (mass X only in the mechanical block), (m, 8, 8)."""
    Ti = np.linalg.inv(T)
    RT = np.swapaxes(R, -1, -2)
    N1 = -Ti @ RT
    N3 = R @ Ti @ RT - Q + X[:, None, None] * np.diag([1.0, 1.0, 1.0, 0.0])
    return np.concatenate([np.concatenate([N1, Ti], -1), np.concatenate([N3, np.swapaxes(N1, -1, -2)], -1)], -2)


def _padd(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Sum of stacked ascending polynomials of different lengths (..., k) + (..., l)."""
    n = max(a.shape[-1], b.shape[-1])
    return (np.pad(a, [(0, 0)] * (a.ndim - 1) + [(0, n - a.shape[-1])])
            + np.pad(b, [(0, 0)] * (b.ndim - 1) + [(0, n - b.shape[-1])]))


def _poly_det(G: np.ndarray) -> np.ndarray:
    """Determinant of a matrix of polynomials, G (m, n, n, k) ascending coefficients -> (m, n (k - 1) + 1)."""
    n = G.shape[1]
    if n == 1:
        return G[:, 0, 0]
    out = np.zeros((G.shape[0], 1))
    for j in range(n):
        minor = np.delete(np.delete(G, 0, axis=1), j, axis=2)
        out = _padd(out, (-1) ** j * _pmul(G[:, 0, j], _poly_det(minor)))
    return out


def stroh_polynomial_parts(Q, R, T) -> np.ndarray:
    """Coefficients of P(p, X) = det(Q + p (R + R^T) + p^2 T - X D) by powers of X and p, (m, 4, 9).

    D = diag(1, 1, 1, 0); by multilinearity P = sum over S in {0, 1, 2} of (-X)^|S| times the
    principal minor of G(p) = Q + p (R + R^T) + p^2 T without the rows and columns S
    (expanded exactly as polynomials in p). The roots in p are the eigenvalues of N(X).
    """
    G = np.stack([Q, R + np.swapaxes(R, -1, -2), T], axis=-1)       # (m, 4, 4, 3)
    parts = np.zeros((Q.shape[0], 4, 9))
    for k in range(4):
        for S in ([()], [(0,), (1,), (2,)], [(0, 1), (0, 2), (1, 2)], [(0, 1, 2)])[k]:
            keep = [i for i in range(4) if i not in S]
            d = _poly_det(G[:, keep][:, :, keep])
            parts[:, k, :d.shape[-1]] += (-1.0) ** k * d
    return parts


def impedance(Q, R, T, X, p_guess=None, parts=None) -> dict:
    """Generalised surface impedance Z = -i B A^-1 (4 x 4 Hermitian) at real X, vectorised.

    The decaying subspace is the column space of W = prod_j (N - conj(p_j)) over the decaying
    p_j (Cayley-Hamilton; no eigenvectors, so (near-)degenerate p lose no accuracy);
    M = B A^-1 = W2 W1^H (W1 W1^H)^-1. The p are tracked by Newton's method on the Stroh
    polynomial from ``p_guess`` (m, 4) where given (``parts`` from :func:`stroh_polynomial_parts`)
    and accepted only if 4 distinct roots with Im p > 0 converged (:func:`impedance.track_roots`);
    elsewhere they are the eigenvalues of N.

    Returns
    -------
    dict: ``Z`` (m, 4, 4) complex (NaN where not subsonic), ``M`` (m, 4, 4), ``N`` (m, 8, 8),
    ``p`` (m, 4) decaying Stroh eigenvalues (ascending Im p), ``subsonic`` (m,) bool.
    """
    N = stroh_matrix(Q, R, T, X)
    m = len(X)
    up = np.full((m, 4), np.nan + 0j)
    ok = np.zeros(m, dtype=bool)
    subsonic = np.ones(m, dtype=bool)
    if p_guess is not None:
        c = parts[:, 3]
        for k in (2, 1, 0):
            c = c * X[:, None] + parts[:, k]
        up, ok = track_roots(c, p_guess)
    miss = ~ok
    if miss.any():
        ev = np.linalg.eigvals(N[miss])
        ev = np.take_along_axis(ev, np.argsort(ev.imag, axis=-1), axis=-1)
        lo, upm = ev[:, :4], ev[:, 4:]
        scale = np.abs(ev).max(axis=-1)
        subsonic[miss] = (lo.imag[:, -1] < -1e-10 * scale) & (upm.imag[:, 0] > 1e-10 * scale)
        up[miss] = upm
    up = np.take_along_axis(up, np.argsort(up.imag, axis=-1), axis=-1)
    c = _monic(np.conj(up))
    W = c[:, 0, None, None] * np.eye(8) + c[:, 1, None, None] * N
    Nk = N
    for k in range(2, 5):
        Nk = Nk @ N
        W = W + c[:, k, None, None] * Nk
    W1, W2 = W[:, :4], W[:, 4:]
    W1h = np.conj(np.swapaxes(W1, -1, -2))
    with np.errstate(all="ignore"):
        M = np.swapaxes(np.linalg.solve(np.swapaxes(W1 @ W1h, -1, -2), np.swapaxes(W2 @ W1h, -1, -2)), -1, -2)
    Z = -1j * M
    Z = 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))
    Z[~subsonic] = np.nan
    return {"Z": Z, "M": M, "N": N, "p": up, "subsonic": subsonic}
