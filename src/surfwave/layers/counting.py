"""Exact count of the guided modes below a speed (Wittrick-Williams): modes hidden next to a pole of Z.

Why. The boundary matrix Z(c) of :mod:`surfwave.layers.recursion` is a ratio: a mode trapped in a
slow layer buried under a stiff one has a tiny surface amplitude, and its zero of det Z lies next
to a pole (the same trapped mode with the top clamped), both within a window of relative width
~ exp(-2 k h_barrier Im p). Outside that window Z hardly notices them, so a grid scan of det Z, of
its eigenvalues or of any other function of Z sees no sign or count change across a cell holding
the pair; only a pole-free quantity can.

What. Split every film into sublayers thin enough to have no mode with both faces clamped below
the highest speed asked for (the bound of :func:`surfwave.layers.partial.korn_bounds`: a sublayer
of thickness t in 1/k has none with rho c^2 / sA < kappa (1 + (pi / t)^2)). The dynamic stiffness
matrix of the whole stack on the degrees of freedom of all sublayer interfaces and the top is then
Hermitian, continuous in c (no member has a pole) and decreasing (its derivative is minus the
kinetic-energy form), so its number of negative eigenvalues rises by one at each mode and never
falls (Wittrick & Williams 1971). By Sylvester's law of inertia that number is the sum of the
negative counts of the pivots of a block elimination from the bottom up: at each sublayer's lower
face the pivot is Z_below - Z_up (the impedance of everything below, from the recursion, minus the
one of the sublayer with its top clamped, seen from its lower face), and at the top the boundary
matrix itself. The count minus its value at the floor speed of the search is the number of modes
below c, free of poles; :mod:`surfwave.layers.modes` uses it to find the modes a scan of det Z
misses (bisection on the count).

Scope: elastic and piezoelectric films (the clamped faces are then grounded too), free or
metallized top, prestressed layers with a positive bound; not stacks with an electrode on an
interface (:func:`applicable`).
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.partial import Blocks, Family
from surfwave.layers.recursion import boundary_matrix, expi, layer_eigs
from surfwave.layers.scan import hermitian_eigenvalues
from surfwave.solvers.boundary import Boundary

__all__ = ["applicable", "bisect_counts", "mode_count", "needed", "sublayers"]

#: Safety factor on the clamped-sublayer bound.
MARGIN = 1.25
#: Most sublayers per film (thicker films are not counted: the search then keeps its own result).
MAX_SUB = 400


def applicable(b: Blocks) -> bool:
    """True when the count is defined for this stack: no interface electrode, a positive bound for every film."""
    L = len(b.frac)
    return (b.korn is not None and not any(b.electrode_below)
            and bool(np.all(b.korn[:L] > 0)))


def needed(b: Blocks, bulk: np.ndarray) -> bool:
    """True when a mode can hide next to a pole: some film lies under a film that is faster in some sheet.

    A mode is trapped away from the surface (its zero of det Z next to a pole) only in a film that
    carries a partial wave at its speed below a film that does not; ``bulk`` are the films' sheet
    speeds (:func:`surfwave.layers.modes.film_bulk_speeds`, shape (3 L,)).
    """
    L = len(b.frac)
    if L < 2 or not applicable(b):
        return False
    v = np.asarray(bulk).reshape(L, 3)
    lo, hi = v.min(axis=1), v.max(axis=1)
    return bool(any(lo[j] < hi[i] for i in range(L) for j in range(i + 1, L)))


def sublayers(b: Blocks, kh_max: float, c_max: float) -> np.ndarray | None:
    """Sublayers per film (L,) such that none has a clamped-clamped mode below c_max at any kh <= kh_max.

    None when some film would need more than :data:`MAX_SUB`.
    """
    L = len(b.frac)
    assert b.korn is not None
    X = MARGIN * b.rho[:L] * c_max * c_max / b.sA
    ratio = X / b.korn[:L] - 1.0
    with np.errstate(divide="ignore"):
        t_max = np.where(ratio > 0, np.pi / np.sqrt(np.maximum(ratio, 1e-300)), np.inf)
    n = np.maximum(np.ceil(kh_max * b.frac / t_max), 1.0)
    if np.any(n > MAX_SUB):
        return None
    return n.astype(int)


def _herm(Z: np.ndarray) -> np.ndarray:
    return 0.5 * (Z + np.conj(np.swapaxes(Z, -1, -2)))


def _solve(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """A^-1 B for stacks of square A; NaN where A is exactly singular (instead of LAPACK's error)."""
    try:
        return np.linalg.solve(A, B)
    except np.linalg.LinAlgError:
        bad = np.linalg.det(A) == 0
        out = np.linalg.solve(np.where(bad[..., None, None], np.eye(A.shape[-1]), A), B)
        out[np.broadcast_to(bad[..., None, None], out.shape)] = np.nan
        return out


def _right(Y: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Y X^-1 (NaN where X is singular)."""
    return np.swapaxes(_solve(np.swapaxes(X, -1, -2), np.swapaxes(Y, -1, -2)), -1, -2)


def _inertia(Z: np.ndarray, fast: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Number of negative eigenvalues (-10^6 where not finite) and log |det| of Hermitian matrices (..., n, n).

    ``fast``: closed-form eigenvalues for n <= 3 (:func:`surfwave.layers.scan.hermitian_eigenvalues`,
    absolute error ~ 1e-13 |Z|: the grid's counts), else LAPACK (the root's last digits).
    """
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(Z).all(axis=(-1, -2))
        Zs = np.where(bad[..., None, None], 0.0, Z)
        w = hermitian_eigenvalues(Zs) if fast else np.linalg.eigvalsh(Zs)
        return np.where(bad, -10**6, (w < 0).sum(axis=-1)), np.log(np.abs(w)).sum(axis=-1)


def mode_count(b: Blocks, fam: Family, c, kh, electrical: str | Boundary, nsub: np.ndarray,
               fast: bool = False, eigs: list | None = None) -> np.ndarray:
    """Negative eigenvalues of the stack's dynamic stiffness at speeds c (m,) and kh (m, k), int (m, k).

    Differences in c at fixed kh count the modes in between (module docstring); negative entries
    (below -1000) flag a failed evaluation. kh must be positive (at kh = 0 the films have no
    thickness and no mode can hide).
    """
    return stiffness(b, fam, c, kh, electrical, nsub, fast, eigs)[0]


def stiffness(b: Blocks, fam: Family, c, kh, electrical: str | Boundary,
              nsub: np.ndarray, fast: bool = False, eigs: list | None = None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`mode_count` and log |det K| of the dynamic stiffness K, both (m, k).

    det K is the product of the pivots' determinants (Schur); it is continuous in c (no member has
    a pole) and its sign, (-1)^count, changes at every mode: a pole-free secular function.
    ``eigs``: the layers' eigen-solutions at c (``surfwave.layers.recursion.layer_eigs``), if known.
    """
    c = np.atleast_1d(np.asarray(c, dtype=float))
    kh = np.broadcast_to(np.asarray(kh, dtype=float), (c.size, np.shape(kh)[-1]))
    if eigs is None:
        eigs = layer_eigs(b, fam, c)
    nf = len(fam.idx)
    ps, Vs = eigs[-1]
    with np.errstate(all="ignore"):
        M = np.broadcast_to(_right(Vs[:, nf:, nf:], Vs[:, :nf, nf:])[:, None], kh.shape + (nf, nf))
    neg = np.zeros(kh.shape, dtype=int)
    logdet = np.zeros(kh.shape)
    for layer in range(len(b.frac) - 1, -1, -1):
        if b.frac[layer] == 0:
            continue                                                           # no such layer
        p, V = eigs[layer]
        t = kh * (b.frac[layer] / nsub[layer])                                 # (m, k)
        Ad, Bd, Au, Bu = (V[:, None, :nf, nf:], V[:, None, nf:, nf:], V[:, None, :nf, :nf], V[:, None, nf:, :nf])
        Ed = expi(p[:, None, nf:] * t[..., None], True)                      # (m, k, nf), |.| <= 1
        Eu = expi(-p[:, None, :nf] * t[..., None], True)
        with np.errstate(all="ignore"):
            # the sublayer with its top clamped (and grounded): amplitudes [c_u; c_d] in the null space
            # of its top rows [A_u E_u, A_d]; its lower face's state is [V_u, V_d E_d] times them
            AuE = Au * Eu[..., None, :]
            top = np.concatenate([AuE, np.broadcast_to(Ad, AuE.shape)], axis=-1)
            ok = np.isfinite(top).all(axis=(-1, -2))
            _, _, vh = np.linalg.svd(np.where(ok[..., None, None], top, 0.0))
            N = np.conj(np.swapaxes(vh[..., nf:, :], -1, -2))                 # (m, k, 2 nf, nf)
            VdE = V[:, None, :, nf:] * Ed[..., None, :]
            low = np.concatenate([np.broadcast_to(V[:, None, :, :nf], VdE.shape), VdE], axis=-1) @ N
            Z_up = _herm(-1j * _right(low[..., nf:, :], low[..., :nf, :]))
        for _ in range(nsub[layer]):
            n_p, l_p = _inertia(_herm(-1j * M) - Z_up, fast)
            neg += n_p
            logdet += l_p
            with np.errstate(all="ignore"):
                Rr = -_solve(Bu - M @ Au, (Bd - M @ Ad) * Ed[..., None, :])
                XY = V[:, None, :, nf:] + V[:, None, :, :nf] @ (Eu[..., :, None] * Rr)
                M = _right(XY[..., nf:, :], XY[..., :nf, :])
    Z, _ = boundary_matrix(b, fam, M, electrical)
    n_p, l_p = _inertia(Z, fast)
    return neg + n_p, logdet + l_p


def bisect_counts(b: Blocks, fam: Family, lo, hi, n_lo, n_hi, kh, electrical: str | Boundary, nsub: np.ndarray,
                  rtol: float = 4e-15) -> tuple[np.ndarray, np.ndarray]:
    """Every jump of the mode count in the intervals (lo, hi) (r,), located by bisection to ``rtol``.

    Parameters
    ----------
    lo, hi : ndarray, shape (r,)
        Interval ends, m/s.
    n_lo, n_hi : ndarray of int, shape (r,)
        :func:`mode_count` there (n_hi > n_lo: that many modes inside).
    kh : ndarray, shape (r,)

    Returns
    -------
    c : ndarray, shape (s,)
        The modes (m/s; a jump by j gives j equal entries).
    row : ndarray of int, shape (s,)
        The interval of each.
    """
    lo, hi = np.asarray(lo, dtype=float).copy(), np.asarray(hi, dtype=float).copy()
    nl, nh = np.asarray(n_lo).copy(), np.asarray(n_hi).copy()
    kh = np.asarray(kh, dtype=float)
    row = np.arange(lo.size)
    out_c: list[np.ndarray] = []
    out_r: list[np.ndarray] = []
    single: list[tuple[np.ndarray, ...]] = []
    for _ in range(200):
        live = (nh > nl) & (nl > -1000)
        lo, hi, nl, nh, row = lo[live], hi[live], nl[live], nh[live], row[live]
        one = nh - nl == 1
        single.append((lo[one], hi[one], nl[one], row[one]))
        lo, hi, nl, nh, row = lo[~one], hi[~one], nl[~one], nh[~one], row[~one]
        if lo.size == 0:
            break
        mid = 0.5 * (lo + hi)
        done = (hi - lo <= rtol * mid) | (mid <= lo) | (mid >= hi)
        if done.any():
            reps = (nh - nl)[done]
            out_c.append(np.repeat(mid[done], reps))
            out_r.append(np.repeat(row[done], reps))
            lo, hi, nl, nh, row, mid = (v[~done] for v in (lo, hi, nl, nh, row, mid))
            if lo.size == 0:
                break
        nm = mode_count(b, fam, mid, kh[row][:, None], electrical, nsub)[:, 0]
        # both halves that hold a jump are kept
        lo, hi = np.r_[lo, mid], np.r_[mid, hi]
        nl, nh = np.r_[nl, nm], np.r_[nm, nh]
        row = np.r_[row, row]
    lo, hi, nl, row = (np.concatenate([s_[i] for s_ in single]) for i in range(4))
    if lo.size:
        out_c.append(_falsi(b, fam, lo, hi, nl, kh[row], electrical, nsub, rtol))
        out_r.append(row)
    if not out_c:
        return np.zeros(0), np.zeros(0, dtype=int)
    return np.concatenate(out_c), np.concatenate(out_r)


def _falsi(b: Blocks, fam: Family, lo: np.ndarray, hi: np.ndarray, n_lo: np.ndarray, kh: np.ndarray,
           electrical: str | Boundary, nsub: np.ndarray, rtol: float) -> np.ndarray:
    """The one mode in each (lo, hi) (r,): regula falsi (Illinois) on det K = (-1)^count |det K|, bisection as fallback.

    ``n_lo`` is the count at lo (the count at hi is one more). Returns speeds (r,), m/s.
    """
    def value(x, rows):
        n, ld = stiffness(b, fam, x, kh[rows][:, None], electrical, nsub)
        return n[:, 0], ld[:, 0]

    def signed(n, ld, ref):
        return np.where((n - n_lo[rows]) % 2 == 0, 1.0, -1.0) * np.exp(np.clip(ld - ref, -700, 700))

    rows = np.arange(lo.size)
    a, z = lo.copy(), hi.copy()
    na, la = value(a, rows)
    nz, lz = value(z, rows)
    ref = np.maximum(la, lz)
    fa, fz = signed(na, la, ref), signed(nz, lz, ref)
    out = 0.5 * (lo + hi)
    side = np.zeros(lo.size, dtype=int)
    for it in range(100):
        with np.errstate(all="ignore"):
            x = z - fz * (z - a) / (fz - fa)
        bad = ~np.isfinite(x) | (x <= np.minimum(a, z)) | (x >= np.maximum(a, z)) | (it % 6 == 5)
        x = np.where(bad, 0.5 * (a + z), x)
        nx, lx = value(x, rows)
        fx = signed(nx, lx, ref[rows] if ref.size != rows.size else ref)
        left = nx == n_lo[rows]                       # the mode lies above x
        right = nx == n_lo[rows] + 1
        # Illinois: halve the stale end's value when the same end is kept twice
        fa = np.where(right & (side == 1), 0.5 * fa, fa)
        fz = np.where(left & (side == -1), 0.5 * fz, fz)
        a, fa = np.where(left, x, a), np.where(left, fx, fa)
        z, fz = np.where(right, x, z), np.where(right, fx, fz)
        side = np.where(left, -1, np.where(right, 1, 0))
        width = np.abs(z - a)
        done = (width <= rtol * np.abs(x)) | ~(left | right)
        out[rows[done]] = np.where(left | right, 0.5 * (a + z), x)[done]
        keep = ~done
        rows, a, z, fa, fz, side = rows[keep], a[keep], z[keep], fa[keep], fz[keep], side[keep]
        ref = ref[keep] if ref.size == keep.size else ref
        if rows.size == 0:
            break
    out[rows] = 0.5 * (a + z)
    return out


#: The count is taken at every STRIDE-th point of the search grid.
STRIDE = 4


def recount(b: Blocks, fam: Family, grid: np.ndarray, kh: np.ndarray, ik: np.ndarray, roots: np.ndarray,
            electrical: str | Boundary, skip: np.ndarray, avoid: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The search's modes checked against the count; where they differ, the count's modes instead.

    Parameters
    ----------
    grid : ndarray, shape (n,)
        The search's ascending speed grid, m/s (its first point is the floor of the search).
    kh : ndarray, shape (k,)
    ik, roots : ndarray, shape (r,)
        The kh index and speed (m/s) of every mode the scan of det Z accepted.
    skip : ndarray of bool, shape (k,)
        kh rows left alone (unstable at the floor).
    avoid : ndarray, shape (v,)
        Speeds (m/s) where the layers' eigen-solutions are defective (films' bulk speeds along x1): no
        count is taken within 1e-8 of them.

    Returns
    -------
    ik, roots : ndarray, shape (r',)
        The modes, unordered: those of the scan in every stretch of STRIDE grid cells where its number
        of modes equals the count's rise, the count's own (bisection, :func:`bisect_counts`) elsewhere.
    """
    if kh.size == 0:
        return ik, roots
    # rows grouped by the sublayers they need (thin films at small kh need few)
    need = [sublayers(b, float(k), float(grid[-1])) for k in kh]
    keys = [tuple(int(2 ** np.ceil(np.log2(x))) for x in n) if n is not None and n.max() <= MAX_SUB // 2 else
            (tuple(n) if n is not None else None) for n in need]
    pts = grid[::STRIDE]
    if pts[-1] != grid[-1]:
        pts = np.r_[pts, grid[-1]]
    far = ~(np.abs(pts[:, None] / np.asarray(avoid)[None, :] - 1.0) <= 1e-8).any(axis=1)
    pts = pts[far | (np.arange(pts.size) == 0)]
    eigs = layer_eigs(b, fam, pts)
    keep = np.ones(ik.size, dtype=bool)
    add_k: list[np.ndarray] = []
    add_c: list[np.ndarray] = []
    for key in set(keys):
        if key is None:
            continue
        rows = np.flatnonzero([k == key for k in keys])
        mine = np.flatnonzero(np.isin(ik, rows))
        local = np.searchsorted(rows, ik[mine])
        drop, k_new, c_new = _recount_rows(b, fam, pts, eigs, kh[rows], local, roots[mine], electrical, skip[rows],
                                           np.array(key))
        keep[mine[drop]] = False
        add_k.append(rows[k_new])
        add_c.append(c_new)
    return np.concatenate([ik[keep], *add_k]), np.concatenate([roots[keep], *add_c])


def _recount_rows(b: Blocks, fam: Family, pts: np.ndarray, eigs: list, kh: np.ndarray, ik: np.ndarray,
                  roots: np.ndarray, electrical: str | Boundary, skip: np.ndarray,
                  nsub: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """:func:`recount` for kh rows that share their sublayers: which roots to drop, the count's modes (kh index, c).

    ``pts`` are the count's speeds (ascending, m/s) and ``eigs`` the layers' eigen-solutions there.
    """
    skip = skip | (kh <= 0)
    n = mode_count(b, fam, pts, np.where(kh > 0, kh, 1.0)[None, :], electrical, nsub, fast=True, eigs=eigs)
    cell = np.clip(np.searchsorted(pts, roots, side="right") - 1, 0, pts.size - 2)
    have = np.zeros((pts.size - 1, kh.size), dtype=int)
    np.add.at(have, (cell, ik), 1)
    rise = n[1:] - n[:-1]
    valid = (n[1:] > -1000) & (n[:-1] > -1000) & (rise >= 0) & ~skip[None, :]
    bad_c, bad_k = np.nonzero(valid & (rise != have))
    if bad_c.size == 0:
        return np.zeros(0, dtype=int), np.zeros(0, dtype=int), np.zeros(0)
    flag = np.zeros(have.shape, dtype=bool)
    flag[bad_c, bad_k] = True
    new_c, row = bisect_counts(b, fam, pts[bad_c], pts[bad_c + 1], n[bad_c, bad_k], n[bad_c + 1, bad_k], kh[bad_k],
                               electrical, nsub)
    return np.flatnonzero(flag[cell, ik]), bad_k[row], new_c

