"""Semi-infinite triangular crystal at fixed theta: cyclic reduction and log-determinants.

At fixed theta = k d_x the static (omega = 0) row equations of :mod:`surfwave.dynamics.triangular`
form the Hermitian block-tridiagonal matrix H with diagonal blocks A0 (A0_surface on a free
surface row), H[I, I+1] = A1 and H[I+1, I] = A1^H. The classical harmonic entropy of a set
of modes is -sum ln(omega) = -(1/2) ln det H (+ const per mode), so everything the
entropy needs is a log-determinant of H relative to the bulk.

Let S solve S = A0 - A1^H S^{-1} A1 (the stable fixed point: the diagonal block of a row
after the half crystal on one side is eliminated). Then, per row and per surface:

* bulk, Szego: B(theta) = (1/2 pi) int ln det D(theta, p) dp = ln det S, with
  D(theta, p) = A0 + A1 e^{ip} + A1^H e^{-ip} (Wiener-Hopf factorisation
  D(z) = (1 + A1^H S^{-1}/z) S (1 + S^{-1} A1 z));
* a slab of N rows: ln det H_N = N B + X + o(1) with
  X = 2 ln det(1 - S^{-1} dA) - ln det(1 - S^{-1} A1 St^{-1} A1^H),
  dA = A0 - A0_surface (the bonds a surface row lacks) and St = M S M the fixed point seen
  from the other side (M = diag(-1, 1), the mirror x -> -x). The second term is ln E,
  E = 1/det(1 - S^{-1} A1 St^{-1} A1^H) the Widom constant of the block Toeplitz matrix
  (both surfaces clamped; scalar analogue E = 1/(1 - a1^2/S^2)); the first frees the two
  surfaces, one term each (the top one reads det(1 - St^{-1} dA), equal since M dA M = dA).
  The split is checked against finite-slab determinants in tests/dynamics/test_entropy.py.
* hence the surface entropy per surface atom at theta, in k_B:
  s(theta) = -X / 4 = -(1/2) ln det(1 - S^{-1} dA) + (1/4) ln det(1 - S^{-1} A1 St^{-1} A1^H).

S is computed by cyclic reduction (Sancho-Rubio decimation): level j eliminates every
other row, so after j levels the effective depth is 2^j rows and the error falls like
rho^(2^j) (rho < 1 the largest evanescent factor |e^{-q}|); ~log2(1/theta) + 6 levels
reach machine precision. Everything is vectorised over leading axes of the blocks.
"""
from __future__ import annotations

import numpy as np

#: Mirror x -> -x acting on (u, v), as an elementwise sign pattern for 2x2 blocks.
_MIRROR_SIGNS = np.array([[1.0, -1.0], [-1.0, 1.0]])
_EPS = np.finfo(float).eps


def det2(m: np.ndarray) -> np.ndarray:
    """Determinant of 2x2 blocks, shape (..., 2, 2) -> (...)."""
    return m[..., 0, 0] * m[..., 1, 1] - m[..., 0, 1] * m[..., 1, 0]


def inv2(m: np.ndarray) -> np.ndarray:
    """Inverse of 2x2 blocks, shape (..., 2, 2); singular blocks give inf/NaN (no warning)."""
    out = np.empty_like(m)
    out[..., 0, 0] = m[..., 1, 1]
    out[..., 1, 1] = m[..., 0, 0]
    out[..., 0, 1] = -m[..., 0, 1]
    out[..., 1, 0] = -m[..., 1, 0]
    with np.errstate(all="ignore"):
        return out / det2(m)[..., None, None]


def null_vector2(m: np.ndarray) -> np.ndarray:
    """Null vector of singular 2x2 blocks, shape (..., 2, 2) -> (..., 2), not normalised.

    Taken perpendicular to the row of larger norm: (-m01, m00) or (m11, -m10).
    """
    r0 = np.stack([-m[..., 0, 1], m[..., 0, 0]], axis=-1)
    r1 = np.stack([m[..., 1, 1], -m[..., 1, 0]], axis=-1)
    use0 = np.linalg.norm(r0, axis=-1) >= np.linalg.norm(r1, axis=-1)
    return np.where(use0[..., None], r0, r1)


def _fro(m: np.ndarray) -> np.ndarray:
    """Frobenius norm of the last two axes."""
    return np.sqrt((np.abs(m) ** 2).sum(axis=(-1, -2)))


def hermitian(m: np.ndarray) -> np.ndarray:
    """Conjugate transpose of the last two axes."""
    return np.conj(np.swapaxes(m, -1, -2))


def positive_definite2(m: np.ndarray) -> np.ndarray:
    """True where the Hermitian 2x2 block is positive definite (and finite), shape (...)."""
    with np.errstate(all="ignore"):
        tr = (m[..., 0, 0] + m[..., 1, 1]).real
        dt = det2(m).real
        return np.isfinite(tr) & np.isfinite(dt) & (tr > 0) & (dt > 0)


def bulk_schur(
    a0: np.ndarray, a1: np.ndarray, levels: int | None = None, max_levels: int = 80
) -> tuple[np.ndarray, np.ndarray, int]:
    """Stable solution S of S = A0 - A1^H S^{-1} A1 by cyclic reduction.

    Parameters
    ----------
    a0, a1 : ndarray, shape (..., 2, 2), complex
        Bulk row blocks (omega^2 units, K/m), e.g. from :func:`surfwave.dynamics.triangular.row_matrices`.
    levels : int, optional
        Fixed number of reduction levels (effective depth 2^levels rows), for convergence
        studies. Default: iterate until the update is below machine precision.
    max_levels : int
        Upper bound on the levels when ``levels`` is None.

    Returns
    -------
    S : ndarray, shape (..., 2, 2), complex
        Hermitian, positive definite where the bulk is stable.
    ok : ndarray of bool, shape (...)
        Every eliminated block stayed positive definite and the reduction converged
        (False means the bulk is unstable at that theta, or theta = 0 exactly).
    used : int
        Levels performed.
    """
    es = a0.copy()
    e = a0.copy()
    al = hermitian(a1)  # coupling target row -> the next row away (H[I+1, I])
    be = a1.copy()
    ok = positive_definite2(e)
    n = levels if levels is not None else max_levels
    used = 0
    converged = np.zeros(ok.shape, dtype=bool)
    with np.errstate(all="ignore"):
        for used in range(1, n + 1):  # noqa: B007 (returned: the levels used)
            g = inv2(e)
            agb = al @ g @ be
            bga = be @ g @ al
            es = es - agb
            e = e - agb - bga
            al = al @ g @ al
            be = be @ g @ be
            ok &= positive_definite2(e)
            scale = np.abs(es).max(axis=(-1, -2))
            converged = np.abs(agb).max(axis=(-1, -2)) <= 0.25 * _EPS * scale
            if levels is None and np.all(converged | ~ok):
                break
    if levels is None:
        ok &= converged
    ok &= positive_definite2(es)
    return es, ok, used


def theta_log_dets(
    a0: np.ndarray, a0_surface: np.ndarray, a1: np.ndarray, levels: int | None = None
) -> dict[str, np.ndarray]:
    """Per-theta bulk and surface log-determinants of the semi-infinite crystal.

    Parameters
    ----------
    a0, a0_surface, a1 : ndarray, shape (..., 2, 2), complex
        Row blocks at the quadrature nodes.
    levels : int, optional
        Fixed cyclic-reduction depth (see :func:`bulk_schur`).

    Returns
    -------
    dict of ndarray, shape (...)
        ``bulk_log_det`` B(theta) = ln det S (per row, ln of (K/m)^2 units);
        ``free_log_det`` ln det(1 - S^{-1} dA) (freeing a clamped surface);
        ``clamp_log_det`` ln det(1 - S^{-1} A1 St^{-1} A1^H) (minus Widom's constant);
        ``s_theta`` the surface entropy per surface atom at theta, k_B;
        ``s_rounding``: first-order bound of the rounding error of ``s_theta`` (k_B), from
        the conditioning of the two near-singular blocks at small theta;
        ``bulk_ok``, ``surface_ok`` (bool): stability at theta (bulk: every block positive
        definite; surface: S - dA positive definite, i.e. no surface mode with omega^2 <= 0).
        Values are NaN where not ok.
    """
    s, bulk_ok, _ = bulk_schur(a0, a1, levels=levels)
    si = inv2(s)
    st_inv = si * _MIRROR_SIGNS  # (M S M)^{-1} = M S^{-1} M
    eye = np.eye(2)
    da = a0 - a0_surface
    surf_block = s - da
    surface_ok = bulk_ok & positive_definite2(surf_block)
    with np.errstate(all="ignore"):
        det_s = det2(s).real
        free = det2(surf_block).real / det_s
        clamp_block = eye - si @ a1 @ st_inv @ hermitian(a1)
        clamp = det2(clamp_block).real
        # |d ln det X| <= |X^-1| |dX| with |dX| ~ (levels) eps |S| (|S^-1| |S| for the clamp)
        norm_s = _fro(s)
        cond_s = norm_s * _fro(si)
        rounding = 8.0 * _EPS * (0.5 * norm_s * _fro(inv2(surf_block))
                                 + 0.25 * cond_s * _fro(inv2(clamp_block)))
        good = surface_ok & (clamp > 0) & (free > 0)
        bulk = np.where(bulk_ok, np.log(np.where(bulk_ok, det_s, 1.0)), np.nan)
        free_ld = np.where(good, np.log(np.where(good, free, 1.0)), np.nan)
        clamp_ld = np.where(good, np.log(np.where(good, clamp, 1.0)), np.nan)
    return {
        "bulk_log_det": bulk,
        "free_log_det": free_ld,
        "clamp_log_det": clamp_ld,
        "s_theta": -0.5 * free_ld + 0.25 * clamp_ld,
        "s_rounding": np.where(good, rounding, np.nan),
        "bulk_ok": bulk_ok,
        "surface_ok": good,
    }


def slab_log_det(a0: np.ndarray, a0_surface: np.ndarray, a1: np.ndarray, n_rows: int) -> np.ndarray:
    """ln det H_N of a free slab of ``n_rows`` rows (two free surfaces) by block LU.

    Independent of the fixed point S: a direct O(N) elimination, vectorised over theta.

    Parameters
    ----------
    a0, a0_surface, a1 : ndarray, shape (..., 2, 2)
    n_rows : int
        N >= 2.

    Returns
    -------
    ndarray, shape (...)
        Real part of ln det H_N; NaN where a pivot block is not positive definite
        (a buckled slab, negative omega^2).
    """
    a1h = hermitian(a1)
    piv = a0_surface.copy()
    total = np.zeros(piv.shape[:-2])
    ok = np.ones(piv.shape[:-2], dtype=bool)
    with np.errstate(all="ignore"):
        for row in range(1, n_rows):
            ok &= positive_definite2(piv)
            total += np.log(np.abs(det2(piv).real))
            diag = a0_surface if row == n_rows - 1 else a0
            piv = diag - a1h @ inv2(piv) @ a1
        ok &= positive_definite2(piv)
        total += np.log(np.abs(det2(piv).real))
    return np.where(ok, total, np.nan)


def slab_s_theta(a0: np.ndarray, a0_surface: np.ndarray, a1: np.ndarray, n_rows: int) -> np.ndarray:
    """Surface entropy per surface atom at theta from two slabs, no bulk reference needed.

    ln det H_N = N B + X + O(rho^N) gives X = 2 ln det H_N - ln det H_2N, and s = -X/4
    (two surfaces per slab). Converges exponentially in N for theta >> 1/N; a slab under
    compression buckles at theta <~ 1/N (NaN there).

    Returns
    -------
    ndarray, shape (...)
        s(theta) in k_B per surface atom.
    """
    x = 2.0 * slab_log_det(a0, a0_surface, a1, n_rows) - slab_log_det(a0, a0_surface, a1, 2 * n_rows)
    return -0.25 * x


def zone_grid_mean_log_omega(a0: np.ndarray, a1: np.ndarray, n_p: int) -> np.ndarray:
    """Mean of ln omega over the bulk modes at each theta by an n_p-point p grid.

    The naive zone grid (midpoint in p, avoids Gamma): (1/4) mean_p ln det D(theta, p).

    Parameters
    ----------
    a0, a1 : ndarray, shape (..., 2, 2)
    n_p : int

    Returns
    -------
    ndarray, shape (...)
        NaN where D is not positive definite on the grid.
    """
    p = (np.arange(n_p) + 0.5) * (2.0 * np.pi / n_p)
    z = np.exp(1j * p).reshape((n_p,) + (1,) * (a0.ndim - 2) + (1, 1))
    d = a0[None] + a1[None] * z + hermitian(a1)[None] / z
    ok = positive_definite2(d).all(axis=0)
    with np.errstate(all="ignore"):
        val = 0.25 * np.log(np.abs(det2(d).real)).mean(axis=0)
    return np.where(ok, val, np.nan)
