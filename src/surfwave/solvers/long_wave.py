"""Long-wave stability: the acoustic tensor over all propagation directions.

Every bulk acoustic wave of the prestressed crystal must have rho c^2 > 0 in every
direction n: the acoustic tensor Q_ik(n) = (C_ijkl + sigma_jl delta_ik) n_j n_l (times V,
lab frame, docs/physics/paper.md) must be positive definite for all n (strong ellipticity).

Three routes, fastest first, all giving the flags of the direction scan:

* :func:`strongly_convex`: a sufficient test without directions (A - t N positive definite
  for some weight t of the null Lagrangian N);
* :func:`_surely_unstable`: a clearly negative eigenvalue along a symmetry direction that
  the scan visits;
* :func:`long_wave_stability`: the direction scan (grid and local refinement), which also
  gives the lowest eigenvalue and its direction.

:func:`long_wave_stable` chains them. The tensors come from
:mod:`surfwave.model_crystals.elastic`, which re-exports the public functions here.
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError

#: Accuracy of the long-wave stability search (directions on the half sphere).
STABILITY_DIRECTIONS = 400


#: The 13 high-symmetry directions (lab axes, face and body diagonals, one of each +-n pair)
#: that every 3D direction grid of :func:`_sphere_directions` contains.
_SYMMETRY_DIRECTIONS = np.array(
    [[1, 0, 0], [0, 1, 0], [0, 0, 1], [1, 1, 0], [1, -1, 0], [1, 0, 1], [1, 0, -1],
     [0, 1, 1], [0, 1, -1], [1, 1, 1], [1, 1, -1], [1, -1, 1], [-1, 1, 1]], dtype=float
) / np.sqrt(np.array([1, 1, 1, 2, 2, 2, 2, 2, 2, 3, 3, 3, 3], dtype=float))[:, None]


def _sphere_directions(dim: int, n: int, octant: bool = False) -> np.ndarray:
    """Unit vectors covering half the circle/sphere (n and -n are equivalent), shape (k, dim).

    With ``octant`` only the directions with non-negative components, at the same density
    (about n / 2 in 2D, n / 4 in 3D): enough when the lab axes are mirror planes, since the
    acoustic tensor's eigenvalues are then even in each component of n.
    """
    if dim == 2:
        if octant:
            phi = np.linspace(0.0, 0.5 * np.pi, n // 2 + 1)
        else:
            phi = np.linspace(0.0, np.pi, n, endpoint=False)
        return np.column_stack([np.cos(phi), np.sin(phi)])
    n_fib = max(n // _OCTANT_DIVISOR, 1) if octant else n
    i = np.arange(n_fib) + 0.5
    zc = i / n_fib  # upper hemisphere z in (0, 1)
    azimuth = np.pi * (1 + 5**0.5) * i
    rxy = np.sqrt(1 - zc**2)
    fib = np.column_stack([rxy * np.cos(azimuth), rxy * np.sin(azimuth), zc])
    out = np.vstack([_SYMMETRY_DIRECTIONS, fib])
    return np.unique(np.abs(out).round(15), axis=0) if octant else out


def _lab_mirror_symmetric(M: np.ndarray, rtol: float = 1e-12) -> np.ndarray:
    """Whether each lab axis is a mirror plane of the wave-propagation tensor, shape (s,).

    Under the mirror x_a -> -x_a every component of A_ijkl with an odd number of indices
    equal to a changes sign, so it must vanish; in the (p, p) form of
    :func:`_wave_tensor_matrix` these are the entries whose row pair and column pair
    together hold the axis an odd number of times.
    """
    dim = int(round((np.sqrt(8 * M.shape[-1] + 1) - 1) / 2))
    pairs = _pairs(dim)
    odd = np.zeros(M.shape[-2:], bool)
    for a in range(dim):
        count = np.array([(i == a) + (k == a) for i, k in pairs])
        odd |= (count[:, None] + count[None, :]) % 2 == 1
    scale = np.abs(M).max(axis=(-2, -1))
    return np.abs(M[:, odd]).max(axis=-1, initial=0.0) <= rtol * scale


def acoustic_tensor(C: np.ndarray, sigma: np.ndarray, n: np.ndarray) -> np.ndarray:
    """Q_ik(n) = (C_ijkl + sigma_jl delta_ik) n_j n_l.

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
    sigma : ndarray, shape (s, d, d)
    n : ndarray, shape (s, k, d) or (k, d)
        Unit propagation directions.

    Returns
    -------
    ndarray, shape (s, k, d, d)
    """
    if n.ndim == 2:
        n = np.broadcast_to(n, (C.shape[0],) + n.shape)
    q = np.einsum("sijkl,snj,snl->snik", C, n, n)
    q += np.einsum("sjl,snj,snl->sn", sigma, n, n)[..., None, None] * np.eye(C.shape[-1])
    return q


def _pairs(dim: int) -> list[tuple[int, int]]:
    """Independent (i, k) index pairs of a symmetric d x d matrix: diagonal first."""
    return [(i, i) for i in range(dim)] + [(i, k) for i in range(dim) for k in range(i + 1, dim)]


def _wave_tensor_matrix(C: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """The acoustic tensor as a linear map of the direction dyad, shape (s, p, p).

    With p = d(d+1)/2 independent components, row (i, k) of Q and column (j, l) of
    n_j n_l: Q_ik = sum_jl A_ijkl n_j n_l, A_ijkl = C_ijkl + sigma_jl delta_ik, the
    off-diagonal columns counting (j, l) and (l, j) together. Q for k directions is then
    one matrix product with the (p, k) dyads (:func:`_dyads`).
    """
    dim = C.shape[-1]
    A = C + sigma[:, None, :, None, :] * np.eye(dim)[:, None, :, None]
    pairs = _pairs(dim)
    rows = [(i, k) for i, k in pairs]
    M = np.empty(C.shape[:1] + (len(pairs), len(pairs)))
    for a, (i, k) in enumerate(rows):
        for b, (j, l) in enumerate(pairs):
            M[:, a, b] = A[:, i, j, k, l] if j == l else A[:, i, j, k, l] + A[:, i, l, k, j]
    return M


def _dyads(n: np.ndarray) -> np.ndarray:
    """n_j n_l for the independent pairs (j, l), shape (..., p) from n of shape (..., d)."""
    return np.stack([n[..., j] * n[..., l] for j, l in _pairs(n.shape[-1])], axis=-1)


def _lowest_eigenvalue(q: np.ndarray) -> np.ndarray:
    """Lowest eigenvalue of symmetric 2x2 or 3x3 matrices given by components, closed form.

    Parameters
    ----------
    q : ndarray, shape (p, ...)
        Components in the order of :func:`_pairs` (2D: xx, yy, xy; 3D: xx, yy, zz, xy, xz, yz).

    Returns
    -------
    ndarray, shape q.shape[1:]
        2D: exact formula. 3D: the trigonometric solution of the characteristic cubic
        (accurate to ~1e-8 of the matrix scale near a double root), used to *choose*
        directions; the reported minimum is recomputed with LAPACK at the chosen direction.
    """
    if q.ndim == 1:
        return _lowest_eigenvalue(q[:, None])[0]
    if q.shape[0] == 3:
        h = 0.5 * (q[0] - q[1])
        return 0.5 * (q[0] + q[1]) - np.sqrt(h * h + q[2] * q[2])
    # m = tr/3, a, b, c = diagonal - m, p2 = |q - m I|^2 / 6, det = det(q - m I),
    # r = det / (2 p^3), lowest = m + 2 p cos(arccos(r)/3 + 2 pi/3); written with in-place
    # buffers (the grid search calls this on ~1e5 directions per strain block), in the
    # same order of operations as the plain expressions, so bit for bit the same values.
    xx, yy, zz, xy, xz, yz = q
    m = xx + yy
    m += zz
    m /= 3.0
    a, b, c = xx - m, yy - m, zz - m
    w = xy * xy                    # off-diagonal sum of squares, then 2 x it
    t = xz * xz
    w += t
    np.multiply(yz, yz, out=t)
    w += t
    p2 = a * a
    np.multiply(b, b, out=t)
    p2 += t
    np.multiply(c, c, out=t)
    p2 += t
    w *= 2.0
    p2 += w
    p2 /= 6.0
    p = np.sqrt(p2)
    det = b * c                    # a (b c - yz^2) - xy (xy c - yz xz) + xz (xy yz - b xz)
    np.multiply(yz, yz, out=t)
    det -= t
    det *= a
    np.multiply(xy, c, out=w)
    np.multiply(yz, xz, out=t)
    w -= t
    w *= xy
    det -= w
    np.multiply(xy, yz, out=w)
    np.multiply(b, xz, out=t)
    w -= t
    w *= xz
    det += w
    np.multiply(p2, 2.0, out=t)
    t *= p
    with np.errstate(invalid="ignore", divide="ignore"):
        np.divide(det, t, out=det)  # r
    det[~(p2 > 0)] = 0.0
    np.clip(det, -1.0, 1.0, out=det)
    np.arccos(det, out=det)
    det /= 3.0
    det += 2.0 * np.pi / 3.0
    np.cos(det, out=det)
    p *= 2.0
    p *= det
    p += m
    return p


#: Strain points per block of the direction search (~200 kB per array: cache-sized).
_BLOCK = 64

#: The octant grid holds n_directions / _OCTANT_DIVISOR directions (1: four times the
#: density of the half-sphere grid, at the same cost).
_OCTANT_DIVISOR = 1


def _checked_tensors(C, sigma) -> tuple[np.ndarray, np.ndarray]:
    """C (s, d, d, d, d) and sigma (s, d, d) as float arrays, d = 2 or 3; InputError otherwise."""
    C = np.asarray(C, dtype=float)
    sigma = np.asarray(sigma, dtype=float)
    if C.ndim != 5 or sigma.shape != C.shape[:1] + C.shape[-1:] * 2 or C.shape[-1] not in (2, 3):
        raise InputError(
            f"need C of shape (s, d, d, d, d) and sigma of shape (s, d, d) with d = 2 or 3; "
            f"got {C.shape} and {sigma.shape}"
        )
    return C, sigma


def long_wave_stability(
    C: np.ndarray, sigma: np.ndarray, n_directions: int = 400, refine: int = 12
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lowest eigenvalue of the acoustic tensor over all propagation directions.

    Every bulk acoustic wave must have rho c^2 > 0 in every direction (strong ellipticity
    of A_ijkl = C_ijkl + sigma_jl delta_ik, docs/physics/paper.md); the paper checks only
    c_T,par. A grid of directions (high-symmetry ones included) is searched, then the best
    direction of each strain is refined by a shrinking local pattern search, vectorised
    over strain. The search compares directions with the closed-form lowest eigenvalue
    (the acoustic tensor of all directions is one matrix product); the minimum reported
    is the LAPACK eigenvalue at the direction found.

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
        V C.
    sigma : ndarray, shape (s, d, d)
        V sigma.
    n_directions : int
        Size of the initial direction grid (half sphere/circle).
    refine : int
        Number of refinement rounds (each halves the step).

    Returns
    -------
    stable : ndarray of bool, shape (s,)
        True if the lowest eigenvalue is positive.
    min_eig : ndarray, shape (s,)
        Lowest eigenvalue of V Q, K d0^2.
    direction : ndarray, shape (s, d)
        Unit vector where it occurs.
    """
    C, sigma = _checked_tensors(C, sigma)
    dim = C.shape[-1]
    s = C.shape[0]
    M = _wave_tensor_matrix(C, sigma)
    mirror = _lab_mirror_symmetric(M)
    n_best = np.empty((s, dim))
    for sym in (True, False):
        grid = _sphere_directions(dim, n_directions, octant=sym)
        grid_dyads = _dyads(grid).T  # (p, k)
        idx = np.flatnonzero(mirror == sym)
        for lo in range(0, idx.size, _BLOCK):
            block = idx[lo:lo + _BLOCK]
            e = _lowest_eigenvalue(np.swapaxes(M[block], 0, 1) @ grid_dyads)  # (b, k)
            n_best[block] = grid[np.argmin(e, axis=1)]
    e_best = _lowest_eigenvalue((M @ _dyads(n_best)[:, :, None])[:, :, 0].T)
    # Local refinement: perturb along the tangent plane with a shrinking step.
    step = 0.5 * np.sqrt(4.0 * np.pi / n_directions) if dim == 3 else np.pi / n_directions
    if dim == 3:
        offsets = np.array([[a, b] for a in (-1, 0, 1) for b in (-1, 0, 1) if (a, b) != (0, 0)], float)
    else:
        offsets = np.array([[-1.0], [1.0]])
    rows = np.arange(s)
    for _ in range(refine):
        # candidates component by component (length-3 axes make slow numpy reductions)
        if dim == 3:
            tx = np.abs(n_best[:, 0]) < 0.9  # t1 = n x e_x there, else n x e_y; t2 = n x t1
            t1 = np.column_stack([np.where(tx, 0.0, -n_best[:, 2]), np.where(tx, n_best[:, 2], 0.0),
                                  np.where(tx, -n_best[:, 1], n_best[:, 0])])
            t1 /= np.sqrt((t1[:, :1] * t1[:, :1] + t1[:, 1:2] * t1[:, 1:2]) + t1[:, 2:] * t1[:, 2:])
            t2 = np.cross(n_best, t1)
            cand = [n_best[:, None, a] + step * (offsets[:, 0] * t1[:, None, a] + offsets[:, 1] * t2[:, None, a])
                    for a in range(3)]
        else:
            tangent = (-n_best[:, 1], n_best[:, 0])
            cand = [n_best[:, None, a] + step * offsets[:, 0] * tangent[a][:, None] for a in range(2)]
        norm = cand[0] * cand[0]
        for c in cand[1:]:
            norm += c * c
        np.sqrt(norm, out=norm)
        cand = [c / norm for c in cand]                                            # (s, k) each
        dyads = np.stack([cand[j] * cand[l] for j, l in _pairs(dim)], axis=1)    # (s, p, k)
        e_c = _lowest_eigenvalue(np.ascontiguousarray(np.moveaxis(M @ dyads, 1, 0)))
        j = np.argmin(e_c, axis=1)
        e_j = e_c[rows, j]
        better = e_j < e_best
        n_best = np.where(better[:, None], np.column_stack([c[rows, j] for c in cand]), n_best)
        e_best = np.where(better, e_j, e_best)
        step *= 0.5
    e_best = np.linalg.eigvalsh(acoustic_tensor(C, sigma, n_best[:, None, :])[:, 0])[:, 0]
    return e_best > 0.0, e_best, n_best


#: Relative margin of the sufficient test: every Cholesky pivot must exceed this times the
#: largest |entry| of the matrix before the direction scan is skipped, so that rounding
#: cannot turn a marginal point into a false "stable".
_CONVEX_RTOL = 1e-9

#: Weights t (times the largest |A_ijkl|) of the null Lagrangian tried in turn by
#: :func:`strongly_convex`; the first one that makes the matrix positive definite decides.
_NULL_WEIGHTS = (0.05, 0.2, 0.01, 0.1, 0.003, 0.3, 0.03)


def _positive_definite(B: np.ndarray, tol: np.ndarray) -> np.ndarray:
    """Whether each symmetric matrix of B (shape (s, m, m)) has all Cholesky pivots > tol (s,).

    Gaussian elimination without pivoting, vectorised over s: a symmetric matrix is
    positive definite if and only if all its pivots are positive.
    """
    B = B.copy()
    ok = np.ones(B.shape[0], bool)
    for k in range(B.shape[-1]):
        piv = B[:, k, k]
        ok &= piv > tol
        safe = np.where(piv > tol, piv, 1.0)
        B[:, k + 1:, k + 1:] -= B[:, k + 1:, k, None] * B[:, None, k, k + 1:] / safe[:, None, None]
    return ok


def _odd_entries(dim: int) -> np.ndarray:
    """Mask of the (d^2, d^2) entries ((i j), (k l)) in which some axis occurs an odd number
    of times: the entries a mirror x_a -> -x_a of every lab axis forces to zero."""
    idx = np.array(list(np.ndindex(dim, dim, dim, dim)))
    counts = np.stack([(idx == a).sum(axis=1) for a in range(dim)], axis=1)
    return (counts % 2 == 1).any(axis=1).reshape(dim * dim, dim * dim)


_ODD_ENTRIES = {dim: _odd_entries(dim) for dim in (2, 3)}


def _mirror_blocks(A: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The blocks of A (s, d^2, d^2) when every lab axis is a mirror plane, symmetrised.

    Only ((i i), (k k)) and ((i j), (i j) or (j i)) entries survive, so A splits into the
    (d, d) block D_ik = A_iikk and one (2, 2) block [[a, b], [b, c]] per axis pair i < j
    (a = A_ijij, b = A_ijji, c = A_jiji); the null Lagrangian N has the blocks
    delta_ik - 1 and [[0, 1], [1, 0]]. Returns D (s, d, d) and a, b, c (s, q), q = d(d-1)/2.
    """
    dim = int(round(np.sqrt(A.shape[-1])))
    diag = [i * dim + i for i in range(dim)]
    ij = np.array([i * dim + j for i in range(dim) for j in range(i + 1, dim)])
    ji = np.array([j * dim + i for i in range(dim) for j in range(i + 1, dim)])
    D = A[:, diag][:, :, diag]
    return 0.5 * (D + np.swapaxes(D, 1, 2)), A[:, ij, ij], 0.5 * (A[:, ij, ji] + A[:, ji, ij]), A[:, ji, ji]


def _blocks_positive(blocks, t: np.ndarray, tol: np.ndarray) -> np.ndarray:
    """Whether A - t N has all Cholesky pivots > tol, from the blocks of :func:`_mirror_blocks`.

    t has shape (w, s) (w trial weights, absolute), tol (s,); returns (w, s). The pivots
    of a block-diagonal matrix are those of its blocks, each in its own order.
    """
    D, a, b, c = blocks
    bt = b[None] - t[..., None]  # (w, s, q)
    with np.errstate(divide="ignore", invalid="ignore"):
        ok = np.all((a > tol[:, None]) & (c - bt * bt / np.where(a > 0, a, 1.0) > tol[:, None]), axis=-1)
    dim = D.shape[-1]
    Dt = D[None] + t[..., None, None] * (1.0 - np.eye(dim))  # (w, s, d, d)
    w, s = t.shape
    return ok & _positive_definite(Dt.reshape(w * s, dim, dim), np.tile(tol, w)).reshape(w, s)


def _blocks_lowest(blocks, t: np.ndarray) -> np.ndarray:
    """Lowest eigenvalue of A - t N (t absolute, shape (s,)) from its blocks, closed forms."""
    D, a, b, c = blocks
    bt = b - t[:, None]
    e = np.min(0.5 * (a + c) - np.sqrt(0.25 * (a - c) ** 2 + bt * bt), axis=-1)
    dim = D.shape[-1]
    Dt = D + t[:, None, None] * (1.0 - np.eye(dim))
    return np.minimum(e, _lowest_eigenvalue(np.stack([Dt[:, i, k] for i, k in _pairs(dim)])))


def _best_null_weight(blocks, scale: np.ndarray, rounds: int = 40) -> np.ndarray:
    """The weight t (absolute, shape (s,)) that maximises the lowest eigenvalue of A - t N.

    That eigenvalue is a concave function of t (the minimum of linear functions u^T (A -
    t N) u), so a golden-section search on t in [-2, 2] times the largest |A_ijkl| (beyond
    it a 2 x 2 block is indefinite) finds the maximum, to 2e-8 of that scale in 40 rounds.
    """
    g = 0.5 * (np.sqrt(5.0) - 1.0)
    lo, hi = -2.0 * scale, 2.0 * scale
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = _blocks_lowest(blocks, x1), _blocks_lowest(blocks, x2)
    for _ in range(rounds):
        left = f1 > f2  # the maximum lies in [lo, x2], else in [x1, hi]
        lo, hi = np.where(left, lo, x1), np.where(left, x2, hi)
        xn = np.where(left, hi - g * (hi - lo), lo + g * (hi - lo))
        fn = _blocks_lowest(blocks, xn)
        x1, x2 = np.where(left, xn, x2), np.where(left, x1, xn)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    return 0.5 * (lo + hi)


def strongly_convex(C: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """Sufficient test of long-wave stability without a direction scan, shape (s,).

    With A_ijkl = C_ijkl + sigma_jl delta_ik read as a (d^2, d^2) matrix of the index pairs
    (ij) and (kl) (symmetric: C_ijkl = C_klij and sigma_jl delta_ik = sigma_lj delta_ki),
    u_i Q_ik(n) u_k = X_ij A_ijkl X_kl for the rank-one matrix X = u n^T. If a form
    positive definite on all d x d matrices agrees with A on the rank-one ones, Q(n) is
    positive definite for every n (strong convexity implies strong ellipticity). The
    null Lagrangian N(X) = tr(X^2) - (tr X)^2 vanishes on rank-one X, so A - t N is such a
    form for every t; t = 0 alone fails whenever sigma has a zero or negative eigenvalue
    (the antisymmetric X then see only sigma, e.g. the free lateral directions of a
    uniaxial load), hence several weights t are tried (:data:`_NULL_WEIGHTS`) and, where
    every lab axis is a mirror plane (A then splits into small blocks,
    :func:`_mirror_blocks`) and those fail, the best t (:func:`_best_null_weight`). In 2D
    a strictly stable point always has some such t (rank-one convex quadratic forms in
    two dimensions are polyconvex), in 3D not always, so False means "scan the
    directions", not "unstable".

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
        V C, lab frame.
    sigma : ndarray, shape (s, d, d)
        V sigma.

    Returns
    -------
    ndarray of bool, shape (s,)
        True where some A - t N is positive definite with pivots above ``_CONVEX_RTOL``
        times the largest |A_ijkl|.
    """
    dim = C.shape[-1]
    A = C.reshape(C.shape[0], dim * dim, dim * dim).copy()
    for i in range(dim):  # + sigma_jl delta_ik: sigma on the diagonal blocks i = k
        A[:, i * dim:(i + 1) * dim, i * dim:(i + 1) * dim] += sigma
    scale = np.abs(A).max(axis=(1, 2))
    tol = _CONVEX_RTOL * scale
    if _all_certified(A, _NULL_WEIGHTS[0] * scale, tol):
        return np.ones(C.shape[0], bool)
    ok = np.zeros(C.shape[0], bool)
    # lab mirrors: the entries they force to zero are below 1e-12 of the scale, which moves
    # no eigenvalue by more than 1e-10 of it, far inside the pivot margin _CONVEX_RTOL
    mirror = np.abs(A[:, _ODD_ENTRIES[dim]]).max(axis=-1, initial=0.0) <= 1e-12 * scale
    idx = np.flatnonzero(mirror)
    blocks = _mirror_blocks(A[idx]) if idx.size else ()
    for t in _NULL_WEIGHTS:  # in turn, each on the points the previous ones left
        if not idx.size:
            break
        passed = _blocks_positive(blocks, t * scale[idx][None], tol[idx])[0]
        ok[idx[passed]] = True
        idx, blocks = idx[~passed], tuple(x[~passed] for x in blocks)
    if idx.size:  # the best weight where the listed ones fail
        ok[idx] = _blocks_positive(blocks, _best_null_weight(blocks, scale[idx])[None], tol[idx])[0]
    g = np.flatnonzero(~mirror)  # no lab mirrors: the full (d^2, d^2) matrices
    if g.size:
        N = _NULL_LAGRANGIAN[dim]
        Ag = 0.5 * (A[g] + np.swapaxes(A[g], 1, 2))
        for t in _NULL_WEIGHTS:
            rest = np.flatnonzero(~ok[g])
            if not rest.size:
                break
            ok[g[rest]] = _pivots_above(Ag[rest] - t * scale[g[rest], None, None] * N, tol[g[rest]])
    return ok


def _null_lagrangian(dim: int) -> np.ndarray:
    """N_ijkl = delta_il delta_jk - delta_ij delta_kl as a (d^2, d^2) matrix of (ij), (kl)."""
    eye = np.eye(dim)
    return (np.einsum("il,jk->ijkl", eye, eye) - np.einsum("ij,kl->ijkl", eye, eye)).reshape(dim * dim, -1)


_NULL_LAGRANGIAN = {dim: _null_lagrangian(dim) for dim in (2, 3)}


def _all_certified(A: np.ndarray, t: np.ndarray, tol: np.ndarray) -> bool:
    """Whether every point passes :func:`strongly_convex` at its first null weight, by one LAPACK
    Cholesky factorisation of the whole stack of (A + A^T)/2 - t N - 2 tol I (A of shape (s, d^2, d^2)).

    Success puts each lowest eigenvalue of (A + A^T)/2 - t N above 2 tol less rounding (~1e-15 of
    max|A|; tol is 1e-9 of it). Then every pivot the test takes exceeds tol: the full matrix's
    (:func:`_pivots_above`) and, at points with lab mirrors, its blocks' (:func:`_blocks_positive`:
    the blocks leave out entries below 1e-12 of max|A|, which move no eigenvalue by more than 1e-10
    of it); a pivot is at least the lowest eigenvalue. So the flags are all True, as the test
    gives them. False: let the test decide.
    """
    if not A.shape[0]:
        return False
    dim2 = A.shape[-1]
    B = 0.5 * (A + np.swapaxes(A, 1, 2)) - t[:, None, None] * _NULL_LAGRANGIAN[int(round(dim2 ** 0.5))]
    try:
        np.linalg.cholesky(B - 2.0 * tol[:, None, None] * np.eye(dim2))
    except np.linalg.LinAlgError:
        return False
    return True


def _pivots_above(B: np.ndarray, tol: np.ndarray) -> np.ndarray:
    """:func:`_positive_definite` (the same flags), with a sufficient test first.

    Where LAPACK's Cholesky factorisation of B - 2 tol I succeeds for the whole stack, each
    matrix's lowest eigenvalue exceeds 2 tol less rounding (~1e-15 of max|B|, tol being 1e-9 of
    it), and every pivot of the elimination, at least that eigenvalue less rounding, exceeds tol:
    all True without the elimination's Python loop. Otherwise the elimination decides.
    B must be exactly symmetric (LAPACK reads the lower triangle).
    """
    if B.shape[0]:
        try:
            np.linalg.cholesky(B - 2.0 * tol[:, None, None] * np.eye(B.shape[-1]))
            return np.ones(B.shape[0], dtype=bool)
        except np.linalg.LinAlgError:
            pass
    return _positive_definite(B, tol)


#: Margin (times the largest |Q entry|) below zero of the probe eigenvalue that
#: :func:`_surely_unstable` needs; far above the ~1e-8 error of the closed-form eigenvalue.
_UNSTABLE_RTOL = 1e-6


def _surely_unstable(C: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """Points whose acoustic tensor has a clearly negative eigenvalue along one of the 13
    :data:`_SYMMETRY_DIRECTIONS`, shape (s,); 3D only.

    Every direction grid of :func:`long_wave_stability` contains these directions and its
    search only ever lowers the eigenvalue it found, so the scan calls these points
    unstable too; skipping it there leaves the flags unchanged.
    """
    M = _wave_tensor_matrix(C, sigma)
    e = _lowest_eigenvalue(np.moveaxis(M @ _dyads(_SYMMETRY_DIRECTIONS).T, 1, 0))  # (s, 13)
    return e.min(axis=-1) < -_UNSTABLE_RTOL * np.abs(M).max(axis=(-2, -1))


def long_wave_stable(C: np.ndarray, sigma: np.ndarray, n_directions: int = 400, refine: int = 12) -> np.ndarray:
    """The ``stable`` flag of :func:`long_wave_stability`, scanning only where needed.

    Points passing the sufficient test :func:`strongly_convex` are stable without a
    direction scan; in 3D, points with a clearly negative eigenvalue along a symmetry
    direction the scan also visits are unstable without it (:func:`_surely_unstable`); the
    others get the full search of :func:`long_wave_stability`. The flags are those of the
    scan (neither shortcut can disagree with it).

    Parameters
    ----------
    C : ndarray, shape (s, d, d, d, d)
    sigma : ndarray, shape (s, d, d)
    n_directions, refine : int
        As for :func:`long_wave_stability`.

    Returns
    -------
    ndarray of bool, shape (s,)
    """
    C, sigma = _checked_tensors(C, sigma)
    stable = strongly_convex(C, sigma)
    scan = np.flatnonzero(~stable)
    if scan.size and C.shape[-1] == 3:
        scan = scan[~_surely_unstable(C[scan], sigma[scan])]
    if scan.size:
        stable[scan] = long_wave_stability(C[scan], sigma[scan], n_directions, refine)[0]
    return stable
