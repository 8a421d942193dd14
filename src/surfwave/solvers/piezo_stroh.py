"""Building blocks of the piezoelectric SAW solver (:mod:`surfwave.solvers.piezo`).

Generalised (4 x 4) Stroh blocks of E_IjKl (index 3 electric: E_ijkl = A_ijkl, E_ij3l = e_lij,
E_3jkl = e_jkl, E_3j3l = -eps_jl), the 8 x 8 Stroh matrix N(X) with the mass X only in the
mechanical block, its characteristic (Stroh) polynomial, the generalised surface impedance
Z = -i B A^-1, the piezoelectrically stiffened bulk speeds and the limiting speed.
Physics: docs/physics/piezoelectric.md.
"""
from __future__ import annotations

import itertools

import numpy as np
from numpy.typing import ArrayLike

from surfwave.solvers.impedance import lowest_eigenvalue_step, monic, pmul, track_roots

#: Wave-normal grid and refinement of the limiting-speed search.
LIMIT_GRID = 48
LIMIT_CANDIDATES = 3
#: ... among those within this relative distance of the grid's best value.
LIMIT_WINDOW = 0.1
#: Newton steps at most (rows stop once the predicted gain is below rounding).
LIMIT_STEPS = 12


def generalised_blocks(A: np.ndarray, e: np.ndarray, eps: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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


def generalised_tensor(A: np.ndarray, e: np.ndarray, eps: np.ndarray) -> np.ndarray:
    """E_IjKl, shape (m, 4, 3, 4, 3): E_ijkl = A_ijkl, E_ij3l = e_lij, E_3jkl = e_jkl, E_3j3l = -eps_jl."""
    A, e, eps = (np.asarray(x, dtype=float) for x in (A, e, eps))
    m = A.shape[0]
    E = np.zeros((m, 4, 3, 4, 3))
    E[:, :3, :, :3, :] = A
    E[:, :3, :, 3, :] = np.einsum("mlij->mijl", e)
    E[:, 3, :, :3, :] = e
    E[:, 3, :, 3, :] = -eps
    return E


def piezo_bulk_speeds(A: np.ndarray, e: np.ndarray, eps: np.ndarray, rho: ArrayLike, n: ArrayLike) -> np.ndarray:
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
    u = np.broadcast_to(np.asarray(n, dtype=float), (A.shape[0], 3))
    u = u / np.linalg.norm(u, axis=-1, keepdims=True)
    G = np.einsum("mijkl,mj,ml->mik", A, u, u)
    g = np.einsum("mkij,mk,mj->mi", e, u, u)
    en = np.einsum("mkl,mk,ml->m", eps, u, u)
    w = np.linalg.eigvalsh(G + g[:, :, None] * g[:, None, :] / en[:, None, None])
    with np.errstate(invalid="ignore"):
        return np.sqrt(w / np.broadcast_to(np.asarray(rho, dtype=float), (A.shape[0],))[:, None])


def _nm(Q, nm):
    """Number of mechanical components (the electric one, if any, is the last): default n - 1."""
    return Q.shape[-1] - 1 if nm is None else nm


def _stiffen(G, nm: int) -> np.ndarray:
    """Mechanical block with the electric row eliminated (Schur complement), (..., nm, nm)."""
    if G.shape[-1] == nm:
        return G
    return G[..., :nm, :nm] - G[..., :nm, nm:] * G[..., nm:, :nm] / G[..., nm:, nm:]


def _stiffened_trace_x(Q, R, T, phi, exact: bool = True, nm=None) -> np.ndarray:
    """Lowest stiffened rho v_trace^2 along x1 for sagittal normals (cos phi, sin phi, 0); (m, k).

    ``exact``: LAPACK eigenvalues; else closed forms (the trigonometric solution of the cubic
    for nm = 3: ~1e-8 relative near degenerate eigenvalues, used for the coarse grid only).
    """
    nm = _nm(Q, nm)
    c, s = np.cos(phi)[..., None, None], np.sin(phi)[..., None, None]
    G = c * c * Q[:, None] + s * c * (R + np.swapaxes(R, -1, -2))[:, None] + s * s * T[:, None]
    S = _stiffen(G, nm)
    if exact or nm == 1:
        lam = np.linalg.eigvalsh(S)[..., 0]
    elif nm == 2:
        lam = 0.5 * (S[..., 0, 0] + S[..., 1, 1]) - np.hypot(0.5 * (S[..., 0, 0] - S[..., 1, 1]), S[..., 0, 1])
    else:
        lam = _lowest_sym3(S)
    return lam / np.cos(phi) ** 2


def _grid_trace_x(Q, R, T, grid, nm: int) -> np.ndarray:
    """:func:`_stiffened_trace_x` (closed form) on one grid of angles for all rows, (m, k).

    Built component by component with one BLAS product per component of G (no (m, k, n, n)
    temporaries); the electric row (if any) eliminated by the Schur complement.
    """
    c, s = np.cos(grid), np.sin(grid)
    trig = np.stack([c * c, s * c, s * s])                          # (3, k)
    RR = R + np.swapaxes(R, -1, -2)

    def comp(i, j):
        return np.stack([Q[:, i, j], RR[:, i, j], T[:, i, j]], axis=-1) @ trig

    n = Q.shape[-1]
    pairs = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)]
    G = {ij: comp(*ij) for ij in pairs}
    if n > nm:
        ge = [comp(i, n - 1) for i in range(3)]
        gee = comp(n - 1, n - 1)
        G = {(i, j): G[(i, j)] - ge[i] * ge[j] / gee for (i, j) in pairs}
    return _lowest_sym3_parts(*(G[ij] for ij in pairs)) / c ** 2


def _lowest_sym3(S) -> np.ndarray:
    """Lowest eigenvalue of real symmetric 3 x 3 matrices (..., 3, 3) by the trigonometric formula."""
    return _lowest_sym3_parts(S[..., 0, 0], S[..., 1, 1], S[..., 2, 2], S[..., 0, 1], S[..., 0, 2], S[..., 1, 2])


def _lowest_sym3_parts(s00, s11, s22, d, e, f) -> np.ndarray:
    """:func:`_lowest_sym3` from the six independent components (arrays of one shape)."""
    q = (s00 + s11 + s22) / 3.0
    a, b, c = s00 - q, s11 - q, s22 - q
    p = np.sqrt((a * a + b * b + c * c + 2.0 * (d * d + e * e + f * f)) / 6.0)
    det = a * (b * c - f * f) - d * (d * c - f * e) + e * (d * f - b * e)
    with np.errstate(all="ignore"):
        r = np.nan_to_num(det / (2.0 * p ** 3))
    return q + 2.0 * p * np.cos(np.arccos(np.clip(r, -1.0, 1.0)) / 3.0 + 2.0 * np.pi / 3.0)


def limiting_x(Q: np.ndarray, R: np.ndarray, T: np.ndarray, nm: int | None = None) -> np.ndarray:
    """Limiting X_L = min over sagittal wave normals of the stiffened trace rho v^2, shape (m,).

    A grid of ``LIMIT_GRID`` angles (closed-form eigenvalues) finds the local minima; the
    ``LIMIT_CANDIDATES`` lowest (within ``LIMIT_WINDOW`` of the best grid value) are refined by
    Newton's method on the stiffened branch lam(p), p = tan phi (:func:`_refine`, analytic
    derivatives of the Schur complement), and the lowest value seen is kept.
    Q, R, T: generalised blocks (m, n, n), the first ``nm`` components mechanical (default n - 1;
    nm = n: no electric component, the elastic limiting speed).
    """
    nm = _nm(Q, nm)
    m = Q.shape[0]
    h = np.pi / LIMIT_GRID
    grid = -0.5 * np.pi + h * (np.arange(LIMIT_GRID) + 0.5)
    g = _grid_trace_x(Q, R, T, grid, nm) if nm == 3 else _stiffened_trace_x(Q, R, T, grid[None], exact=False, nm=nm)
    pad = np.pad(g, ((0, 0), (1, 1)), mode="wrap")
    gl = np.where((g <= pad[:, :-2]) & (g <= pad[:, 2:]), g, np.inf)
    order = np.argsort(gl, axis=1)[:, :LIMIT_CANDIDATES]
    cand = np.take_along_axis(gl, order, axis=1)
    keep = np.isfinite(cand) & (cand <= cand[:, :1] + LIMIT_WINDOW * np.abs(cand[:, :1]))
    keep[:, 0] = True
    rows, cols = np.nonzero(keep)                                   # flat candidates
    best = _refine(Q[rows], R[rows], T[rows], nm, grid[order[rows, cols]], h)
    XL = np.full(m, np.inf)
    np.minimum.at(XL, rows, best)
    return XL


def _refine(Q, R, T, nm: int, phi0, h) -> np.ndarray:
    """Minimise the lowest eigenvalue lam(p) of the stiffened S(p) from p = tan(phi0); (k,).

    G(p) = Q + p (R + R^T) + p^2 T, S = G_mm - g g^T / h (g = G_me, h = G_ee; S = G without an
    electric component). Newton on lam'(p) = 0: lam' = a0 . S' a0,
    lam'' = a0 . S'' a0 + 2 sum_j (a_j . S' a0)^2 / (w0 - w_j) (eigenpairs w_j, a_j of S), with
    S' a = G'_mm a + (h'/h^2) g (g.a) - (g' (g.a) + g (g'.a)) / h and
    a.S''a = a.G''_mm a + (h''/h^2 - 2 h'^2/h^3)(g.a)^2 + 4 (h'/h^2)(g.a)(g'.a) - 2 ((g.a)(g''.a) + (g'.a)^2)/h.
    Steps limited to the grid cell; a non-positive curvature steps downhill by half a cell.
    A row stops when the predicted gain d2 step^2 / 2 is below the rounding of lam, or after
    ``LIMIT_STEPS`` steps; the lowest value seen is returned.
    """
    el = Q.shape[-1] > nm
    p = np.tan(phi0)
    trust = h * (1.0 + p * p)
    RR = R + np.swapaxes(R, -1, -2)
    best = np.full(p.shape, np.inf)
    idx = np.arange(len(p))
    for _ in range(LIMIT_STEPS + 1):
        if idx.size == 0:
            break
        q, r, t, pi = Q[idx], RR[idx], T[idx], p[idx]
        G = q + pi[:, None, None] * r + (pi * pi)[:, None, None] * t
        G1 = r + 2.0 * pi[:, None, None] * t
        w, V = np.linalg.eigh(_stiffen(G, nm))
        best[idx] = np.minimum(best[idx], w[:, 0])
        a0 = V[:, :, 0]
        S1a = np.einsum("mij,mj->mi", G1[:, :nm, :nm], a0)
        d2 = 2.0 * np.einsum("mi,mij,mj->m", a0, t[:, :nm, :nm], a0)
        if el:
            hh, h1, h2 = G[:, -1, -1], G1[:, -1, -1], 2.0 * t[:, -1, -1]
            g, g1 = G[:, :nm, -1], G1[:, :nm, -1]
            al, al1 = np.einsum("mi,mi->m", g, a0), np.einsum("mi,mi->m", g1, a0)
            al2 = 2.0 * np.einsum("mi,mi->m", t[:, :nm, -1], a0)
            S1a = S1a + (h1 / hh ** 2 * al)[:, None] * g - (al[:, None] * g1 + al1[:, None] * g) / hh[:, None]
            d2 = (d2 + (h2 / hh ** 2 - 2.0 * h1 * h1 / hh ** 3) * al * al + 4.0 * h1 / hh ** 2 * al * al1
                  - 2.0 * (al * al2 + al1 * al1) / hh)
        step, done = lowest_eigenvalue_step(w, V, S1a, d2, trust[idx])
        p[idx] = pi + step
        idx = idx[~done]
    return best


def stroh_matrix(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray, nm: int | None = None) -> np.ndarray:
    """Generalised Stroh matrix N(X), (m, 2n, 2n): mass X on the first ``nm`` (mechanical) components."""
    n = Q.shape[-1]
    D = np.diag((np.arange(n) < _nm(Q, nm)).astype(float))
    Ti = np.linalg.inv(T)
    RT = np.swapaxes(R, -1, -2)
    N1 = -Ti @ RT
    N3 = R @ Ti @ RT - Q + X[:, None, None] * D
    return np.concatenate([np.concatenate([N1, Ti], -1), np.concatenate([N3, np.swapaxes(N1, -1, -2)], -1)], -2)


def _minor(G: np.ndarray, rows: tuple, cols: tuple, cache: dict) -> np.ndarray:
    """Minor of a matrix of quadratics in p, G (m, n, n, 3), rows x cols -> (m, 2k + 1) ascending.

    Laplace expansion along the first row, the smaller minors memoised in ``cache`` (shared
    between all the minors of one G, so each 2 x 2 and 3 x 3 minor is expanded once).
    """
    key = (rows, cols)
    if key not in cache:
        if len(rows) == 1:
            cache[key] = G[:, rows[0], cols[0]]
        else:
            out: np.ndarray | float = 0.0
            for j, c in enumerate(cols):
                term = pmul(G[:, rows[0], c], _minor(G, rows[1:], cols[:j] + cols[j + 1:], cache))
                out = out + term if j % 2 == 0 else out - term
            cache[key] = out
    return cache[key]


def stroh_polynomial_parts(Q: np.ndarray, R: np.ndarray, T: np.ndarray, nm: int | None = None) -> np.ndarray:
    """Coefficients of P(p, X) = det(Q + p (R + R^T) + p^2 T - X D) by powers of X and p, (m, nm + 1, 2n + 1).

    D = diag(1, .., 1, 0) (mass on the ``nm`` mechanical components, default n - 1); by
    multilinearity P = sum over subsets S of the mechanical indices of (-X)^|S| times the principal
    minor of G(p) = Q + p (R + R^T) + p^2 T without the rows and columns S (expanded exactly as
    polynomials in p, :func:`_minor`). The roots in p are the eigenvalues of N(X).
    """
    n, nm = Q.shape[-1], _nm(Q, nm)
    G = np.stack([Q, R + np.swapaxes(R, -1, -2), T], axis=-1)       # (m, n, n, 3)
    parts = np.zeros((Q.shape[0], nm + 1, 2 * n + 1))
    cache: dict = {}
    for k in range(nm + 1):
        for S in itertools.combinations(range(nm), k):
            keep = tuple(i for i in range(n) if i not in S)
            d = _minor(G, keep, keep, cache) if keep else np.ones((Q.shape[0], 1))
            parts[:, k, :d.shape[-1]] += (-1.0) ** k * d
    return parts


def impedance(Q: np.ndarray, R: np.ndarray, T: np.ndarray, X: np.ndarray, p_guess: np.ndarray | None = None,
              parts: np.ndarray | None = None, nm: int | None = None, N0: np.ndarray | None = None) -> dict:
    """Generalised surface impedance Z = -i B A^-1 (n x n Hermitian) at real X, vectorised.

    The decaying subspace is the column space of W = f(N), f(z) = prod_j (z - conj(p_j)) over the
    decaying p_j (Cayley-Hamilton; no eigenvectors, so (near-)degenerate p lose no accuracy);
    M = B A^-1 = W2 W1^H (W1 W1^H)^-1. The p are tracked by Newton's method on the Stroh
    polynomial from ``p_guess`` (m, n) where given (``parts`` from :func:`stroh_polynomial_parts`)
    and accepted only if n distinct roots with Im p > 0 converged (:func:`impedance.track_roots`);
    elsewhere they are the eigenvalues of N. Q, R, T (m, n, n), the first ``nm`` components
    mechanical (default n - 1), X (m,); ``N0`` = ``stroh_matrix(Q, R, T, 0, nm)`` (optional, saves
    its recomputation in a root search: N(X) = N0 + X [[0, 0], [D, 0]]).

    Returns
    -------
    dict: ``Z`` (m, n, n) complex (NaN where not subsonic), ``M`` (m, n, n), ``N`` (m, 2n, 2n),
    ``W1`` (m, n, 2n) the upper rows of f(N), ``c`` (m, n + 1) the coefficients of f (ascending),
    ``p`` (m, n) decaying Stroh eigenvalues (ascending Im p), ``subsonic`` (m,) bool.
    """
    n, nm = Q.shape[-1], _nm(Q, nm)
    if N0 is None:
        N = stroh_matrix(Q, R, T, X, nm)
    else:
        N = N0.copy()
        diag = np.arange(nm)
        N[:, n + diag, diag] += X[:, None]
    m = len(X)
    up = np.full((m, n), np.nan + 0j)
    ok = np.zeros(m, dtype=bool)
    subsonic = np.ones(m, dtype=bool)
    if p_guess is not None:
        assert parts is not None  # given with p_guess (docstring)
        c = parts[:, -1]
        for k in range(parts.shape[1] - 2, -1, -1):
            c = c * X[:, None] + parts[:, k]
        up, ok = track_roots(c, p_guess)
    miss = ~ok
    if miss.any():
        ev = np.linalg.eigvals(N[miss])
        ev = np.take_along_axis(ev, np.argsort(ev.imag, axis=-1), axis=-1)
        lo, upm = ev[:, :n], ev[:, n:]
        scale = np.abs(ev).max(axis=-1)
        subsonic[miss] = (lo.imag[:, -1] < -1e-10 * scale) & (upm.imag[:, 0] > 1e-10 * scale)
        up[miss] = upm
    up = np.take_along_axis(up, np.argsort(up.imag, axis=-1), axis=-1)
    c = monic(np.conj(up))
    # W = sum_k c_k N^k, real and imaginary parts in real arithmetic (mixed complex x real
    # broadcasting is several times slower in numpy)
    cr, ci = c.real[:, :, None, None], c.imag[:, :, None, None]
    Wr, Wi = cr[:, 1] * N, ci[:, 1] * N
    Nk = N
    for k in range(2, n + 1):
        Nk = Nk @ N
        Wr += cr[:, k] * Nk
        Wi += ci[:, k] * Nk
    d = np.arange(2 * n)
    Wr[:, d, d] += c.real[:, 0, None]
    Wi[:, d, d] += c.imag[:, 0, None]
    W = np.empty(Wr.shape, dtype=complex)
    W.real, W.imag = Wr, Wi
    W1, W2 = W[:, :n], W[:, n:]
    W1h = np.conj(np.swapaxes(W1, -1, -2))
    with np.errstate(all="ignore"):
        M = np.swapaxes(np.linalg.solve(np.swapaxes(W1 @ W1h, -1, -2), np.swapaxes(W2 @ W1h, -1, -2)), -1, -2)
    Z = -1j * M
    Z = 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))
    Z[~subsonic] = np.nan
    return {"Z": Z, "M": M, "N": N, "W1": W1, "c": c, "p": up, "subsonic": subsonic}


def impedance_slope(r: dict, a: np.ndarray, nm: int | None = None) -> np.ndarray:
    """a^H (dZ/dX) a for the impedance ``r`` of :func:`impedance` and vectors a (m, n); (m,) real.

    M = B A^-1 solves the Riccati equation M N1 + M N2 M = N3 + N4 M; dN3/dX = D (the mass
    pattern), so dM K1 - K2 dM = D with K1 = N1 + N2 M (eigenvalues: the decaying p) and
    K2 = N4 - M N2 (the growing ones). With f(z) = sum_k c_k z^k, f(K2) = 0 (Cayley-Hamilton)
    and dM K1^k - K2^k dM = sum_{j<k} K2^j D K1^(k-1-j), so dM = G f(K1)^-1 with
    G = sum_k c_k sum_{j<k} K2^j D K1^(k-1-j), f(K1) = W11 + W12 M; dZ = -i dM. Only
    vector-matrix products: a_j = a^H K2^j, b_i = K1^i f(K1)^-1 a.
    For the free surface's Schur complement Z_eff (u) the same number is d(u^H Z_eff u)/dX with
    a = (u, phi), phi = -Z_em u / (Z_ee - eps0) (the derivative of a Schur complement's
    quadratic form is the full form at the extended vector).
    """
    N, M, W1, c = r["N"], r["M"], r["W1"], r["c"]
    n = M.shape[-1]
    mask = (np.arange(n) < _nm(M, nm)).astype(float)
    n1, n2, n4 = N[:, :n, :n], N[:, :n, n:], N[:, n:, n:]
    fK1 = W1[:, :, :n] + W1[:, :, n:] @ M
    bad = ~np.isfinite(fK1).all(axis=(1, 2))
    with np.errstate(all="ignore"):
        y = np.linalg.solve(np.where(bad[:, None, None], np.eye(n), fK1), a[..., None])[..., 0]
    # rows a_j = a^H K2^j (m, 1, n) and columns b_i = K1^i y (m, n, 1), by stacked matmul
    aj, bi = [np.conj(a)[:, None, :]], [y[:, :, None]]
    for _ in range(1, n):
        aj.append(aj[-1] @ n4 - (aj[-1] @ M) @ n2)
        bi.append(n1 @ bi[-1] + n2 @ (M @ bi[-1]))
    dots = {(j, i): ((aj[j] * mask) @ bi[i])[:, 0, 0] for j in range(n) for i in range(n - j)}
    aGy = sum(c[:, k] * sum(dots[(j, k - 1 - j)] for j in range(k)) for k in range(1, n + 1))
    return np.where(bad, np.nan, (-1j * aGy).real)
