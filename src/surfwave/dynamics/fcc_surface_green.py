"""Surface Green's function of a semi-infinite layered crystal: spectral density, bulk band
edges and true surface modes (below the bulk band and in its gaps).

Input: principal-layer blocks H00 (bulk), H00_surface (free surface layer) and H01
(H[P, P+1]; H[P+1, P] = H01^H), e.g. from :func:`surfwave.dynamics.fcc_layers.principal_blocks`,
with any leading axes (strain, q, ...) and block size d. Everything here is in omega^2 units
(K/m, m = 1) and vectorised over the leading axes.

* Decimation (Sancho-Rubio / cyclic reduction, as in :mod:`surfwave.dynamics.surface_green`
  for the triangular lattice, here for any d and complex z = omega^2 + i eta): level j
  eliminates every other layer; after j levels the couplings span 2^j layers and fall like
  rho^(2^j), rho < 1 the slowest evanescent factor. It gives eps_s, the surface layer's
  effective block with the whole crystal below it folded in (eps_s = H00_surface + Sigma(z)),
  and eps_b, the same for a semi-infinite bulk that starts with an H00 layer.
* G_00(z) = (z - eps_s)^{-1}; the spectral density of the top plane is
  rho(omega) = -(2 omega / pi) Im Tr_top G_00(omega^2 + i eta), normalised to 3 (the degrees
  of freedom of one atom) over omega.
* Bulk bands at fixed q: the eigenvalues of H00 + H01 e^{i phi} + H01^H e^{-i phi} over the
  phase phi per principal layer; each sorted branch's min and max (a phi grid, its lowest
  local extrema each refined by golden-section search) bound the projected bulk band.
* Surface modes: at real lambda = omega^2 outside the bulk band, M(lambda) = eps_s(lambda) is
  Hermitian and decreasing (dM/dlambda = -H01 g^2 H01^H <= 0), so each of its sorted
  eigenvalues mu_i makes f_i = lambda - mu_i(lambda) strictly increasing: each (gap, i) holds
  at most one root, found by bracketing (Illinois false position). The mode's top-layer
  displacement is mu_i's eigenvector (a root is kept only if the decimation converged
  there and |lambda - mu_i| is at rounding level); deeper layers follow U_{P+1} = T U_P with
  T = (lambda - eps_b)^{-1} H01^H, so the decay per layer is |T^K U_0|^(1/K) (K = 64).
"""
from __future__ import annotations

import numpy as np

_EPS = np.finfo(float).eps
#: Levels of decimation allowed (effective depth 2^60 layers).
MAX_LEVELS = 60
#: Distance (relative to the block scale) from a band edge at which a gap is probed.
EDGE_OFFSET = 1e-9
#: A root closer than this (relative) to a band edge, or decaying slower than
#: 1 - DECAY_MIN per layer, is a band-edge state, not a surface mode.
DECAY_MIN = 1e-6
#: Phase grid of the bulk band edges, refined by golden section.
N_PHI = 48
N_GOLDEN = 56
#: Local extrema of the phase grid refined per branch (several wells, see bulk_band_edges).
N_WELLS = 3
#: A root is accepted only if |omega^2 - mu(omega^2)| is below this (relative to the block scale).
RESIDUAL_TOL = 1e-9


def herm(m: np.ndarray) -> np.ndarray:
    """Conjugate transpose of the last two axes."""
    return np.conj(np.swapaxes(m, -1, -2))


def inv(m: np.ndarray) -> np.ndarray:
    """Inverse of small blocks (..., d, d); closed forms for d <= 3 (singular: inf/NaN)."""
    d = m.shape[-1]
    if d > 3:
        return np.linalg.inv(m)
    with np.errstate(all="ignore"):
        if d == 1:
            return 1.0 / m
        if d == 2:
            det = m[..., 0, 0] * m[..., 1, 1] - m[..., 0, 1] * m[..., 1, 0]
            out = np.empty_like(m)
            out[..., 0, 0], out[..., 1, 1] = m[..., 1, 1], m[..., 0, 0]
            out[..., 0, 1], out[..., 1, 0] = -m[..., 0, 1], -m[..., 1, 0]
            return out / det[..., None, None]
        a, b, c = m[..., 0, 0], m[..., 0, 1], m[..., 0, 2]
        d_, e, f = m[..., 1, 0], m[..., 1, 1], m[..., 1, 2]
        g, h, i = m[..., 2, 0], m[..., 2, 1], m[..., 2, 2]
        c00, c10, c20 = e * i - f * h, f * g - d_ * i, d_ * h - e * g
        det = a * c00 + b * c10 + c * c20
        out = np.empty_like(m)
        out[..., 0, 0], out[..., 1, 0], out[..., 2, 0] = c00, c10, c20
        out[..., 0, 1], out[..., 1, 1], out[..., 2, 1] = c * h - b * i, a * i - c * g, b * g - a * h
        out[..., 0, 2], out[..., 1, 2], out[..., 2, 2] = b * f - c * e, c * d_ - a * f, a * e - b * d_
        out /= det[..., None, None]
        return out


def decimate(z: np.ndarray, h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray,
             max_levels: int = MAX_LEVELS) -> dict:
    """Effective surface blocks of the semi-infinite crystal at z by decimation.

    Parameters
    ----------
    z : ndarray, shape (...)
        omega^2 (+ i eta), K/m; broadcast against the blocks' leading axes.
    h00, h00s, h01 : ndarray, shape (..., d, d)
        Principal-layer blocks, K/m.
    max_levels : int
        Upper bound on the levels (each doubles the depth).

    Returns
    -------
    dict
        ``eps_s`` (..., d, d): H00_surface + Sigma(z); ``eps_b``: H00 + Sigma(z) (semi-infinite
        bulk); ``converged`` (...) bool: the couplings fell below eps x scale.
    """
    z = np.asarray(z)
    lead = np.broadcast_shapes(z.shape, h00.shape[:-2], h00s.shape[:-2], h01.shape[:-2])
    d = h00.shape[-1]
    shape = lead + (d, d)
    n = int(np.prod(lead, dtype=int))
    zz = np.broadcast_to(z, lead).reshape(n).astype(complex)
    e = np.broadcast_to(h00, shape).reshape(n, d, d).astype(complex)
    es = np.broadcast_to(h00s, shape).reshape(n, d, d).astype(complex)
    eb = e.copy()
    al = np.broadcast_to(h01, shape).reshape(n, d, d).astype(complex)
    be = herm(al)
    scale = np.abs(e).max(axis=(-1, -2)) + np.abs(al).max(axis=(-1, -2)) + np.abs(zz)
    eye = np.eye(d)
    out_s, out_b = es.copy(), eb.copy()
    converged = np.zeros(n, bool)
    todo = np.arange(n)
    seen = np.zeros(n, bool)  # recorded: converged or failed (dropped at the next compaction)
    tol2 = (_EPS * scale) ** 2
    with np.errstate(all="ignore"):
        for _ in range(max_levels):
            g = inv(zz[todo, None, None] * eye - e)
            ag = al @ g
            bg = be @ g
            agb = ag @ be
            es = es + agb
            eb = eb + agb
            e = e + agb + bg @ al
            al = ag @ al
            be = bg @ be
            size2 = (al.real**2 + al.imag**2 + be.real**2 + be.imag**2).max(axis=(-1, -2))
            small = size2 <= tol2[todo]
            bad = ~np.isfinite(size2) | ~np.isfinite(es).all(axis=(-1, -2))
            new = (small | bad) & ~seen[todo]
            if new.any():
                idx = todo[new]
                out_s[idx], out_b[idx] = es[new], eb[new]
                converged[idx] = small[new] & ~bad[new]
                seen[idx] = True
            done = seen[todo]
            if done.all():
                todo = todo[:0]
                break
            if done.sum() > 0.25 * todo.size:  # compact now and then, not at every level
                keep = ~done
                todo, e, es, eb, al, be = todo[keep], e[keep], es[keep], eb[keep], al[keep], be[keep]
        left = ~seen[todo]
        out_s[todo[left]], out_b[todo[left]] = es[left], eb[left]
    return {"eps_s": out_s.reshape(shape), "eps_b": out_b.reshape(shape), "converged": converged.reshape(lead)}


def spectral_density(h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray, omega: np.ndarray,
                     eta: float = 1e-3, plane_dof: int = 3) -> np.ndarray:
    """Spectral density of the top plane's displacements, rho(omega), normalised to ``plane_dof``.

    Parameters
    ----------
    h00, h00s, h01 : ndarray, shape (..., d, d)
    omega : ndarray, shape (n_omega,)
        Frequencies, sqrt(K/m).
    eta : float
        Imaginary part added to omega^2 (K/m): each mode becomes a Lorentzian of that
        half-width in omega^2.
    plane_dof : int
        Rows of the top plane (3: the first atom of the principal layer).

    Returns
    -------
    ndarray, shape (..., n_omega)
        -(2 omega / pi) Im Tr_top G_00(omega^2 + i eta), per sqrt(K/m).
    """
    omega = np.asarray(omega, float)
    z = omega**2 + 1j * eta
    res = decimate(z, h00[..., None, :, :], h00s[..., None, :, :], h01[..., None, :, :])
    d = h00.shape[-1]
    g = inv(z[..., None, None] * np.eye(d) - res["eps_s"])
    tr = np.trace(g[..., :plane_dof, :plane_dof], axis1=-2, axis2=-1)
    return -2.0 * omega / np.pi * tr.imag


def eigvalsh_small(m: np.ndarray) -> np.ndarray:
    """Ascending eigenvalues of Hermitian blocks (..., d, d): closed forms for d <= 3, else LAPACK.

    d = 3 by the trigonometric (Cardano) solution: fast, but near a double eigenvalue its
    rounding grows to ~sqrt(eps) |m|; used to steer the band-edge search only (the edges
    are re-evaluated with LAPACK at the phase found).
    """
    d = m.shape[-1]
    if d == 1:
        return m[..., 0, :].real
    if d == 2:
        a, c = m[..., 0, 0].real, m[..., 1, 1].real
        r = np.sqrt(0.25 * (a - c) ** 2 + np.abs(m[..., 0, 1]) ** 2)
        return np.stack([0.5 * (a + c) - r, 0.5 * (a + c) + r], axis=-1)
    if d > 3:
        return np.linalg.eigvalsh(m)
    diag = np.stack([m[..., 0, 0].real, m[..., 1, 1].real, m[..., 2, 2].real], axis=-1)
    q = diag.mean(axis=-1)
    p1 = np.abs(m[..., 0, 1]) ** 2 + np.abs(m[..., 0, 2]) ** 2 + np.abs(m[..., 1, 2]) ** 2
    p = np.sqrt((((diag - q[..., None]) ** 2).sum(axis=-1) + 2.0 * p1) / 6.0)
    with np.errstate(all="ignore"):
        b = (m - q[..., None, None] * np.eye(3)) / p[..., None, None]
        det = (b[..., 0, 0] * (b[..., 1, 1] * b[..., 2, 2] - b[..., 1, 2] * b[..., 2, 1])
               - b[..., 0, 1] * (b[..., 1, 0] * b[..., 2, 2] - b[..., 1, 2] * b[..., 2, 0])
               + b[..., 0, 2] * (b[..., 1, 0] * b[..., 2, 1] - b[..., 1, 1] * b[..., 2, 0])).real
        phi = np.arccos(np.clip(0.5 * det, -1.0, 1.0)) / 3.0
    phi = np.where(p > 0, phi, 0.0)
    hi = q + 2.0 * p * np.cos(phi)
    lo = q + 2.0 * p * np.cos(phi + 2.0 * np.pi / 3.0)
    return np.stack([lo, 3.0 * q - hi - lo, hi], axis=-1)


def _branch(h00: np.ndarray, h01: np.ndarray, phi: np.ndarray, branch: np.ndarray, exact: bool = False) -> np.ndarray:
    """Eigenvalue number ``branch`` (sorted) of the bulk matrix at per-problem phases phi."""
    z = np.exp(1j * phi)[..., None, None]
    m = h00 + h01 * z + herm(h01) / z
    w = np.linalg.eigvalsh(m) if exact else eigvalsh_small(m)
    return np.take_along_axis(w, branch[..., None], axis=-1)[..., 0]


def bulk_band_edges(h00: np.ndarray, h01: np.ndarray, n_phi: int = N_PHI, n_golden: int = N_GOLDEN,
                    n_wells: int = N_WELLS) -> np.ndarray:
    """Min and max over the normal phase of each sorted bulk branch at fixed in-plane q.

    A branch may have several local minima in phi (strongly stressed crystals have narrow
    deep wells between grid points), so the ``n_wells`` lowest local minima of the grid are
    each refined by golden-section search (and likewise the maxima).

    Parameters
    ----------
    h00, h01 : ndarray, shape (..., d, d)
    n_phi, n_golden : int
        Phase grid over [0, 2 pi) and golden-section steps refining each extremum.
    n_wells : int
        Local extrema of the grid refined per branch and kind.

    Returns
    -------
    ndarray, shape (..., d, 2)
        [min, max] of omega^2 of branch nu (ascending), K/m.
    """
    lead = h00.shape[:-2]
    d = h00.shape[-1]
    phi = 2.0 * np.pi * np.arange(n_phi) / n_phi
    z = np.exp(1j * phi).reshape((n_phi,) + (1,) * (len(lead) + 2))
    w = np.linalg.eigvalsh(h00[None] + h01[None] * z + herm(h01)[None] / z)  # (n_phi, ..., d)
    out = np.empty(lead + (d, 2))
    step = 2.0 * np.pi / n_phi
    branch = np.broadcast_to(np.arange(d), lead + (d,))
    hb = np.broadcast_to(h00[..., None, :, :], lead + (d, d, d))
    cb = np.broadcast_to(h01[..., None, :, :], lead + (d, d, d))
    gr = (np.sqrt(5.0) - 1.0) / 2.0
    for k, sign in enumerate((1.0, -1.0)):  # min of w, then min of -w
        sw = sign * w
        local = (sw <= np.roll(sw, 1, axis=0)) & (sw <= np.roll(sw, -1, axis=0))
        ranked = np.argsort(np.where(local, sw, np.inf), axis=0)[:n_wells]  # (n_wells, ..., d)
        best = sw.min(axis=0)
        for i in ranked:
            a, b = phi[i] - step, phi[i] + step
            c, e = b - gr * (b - a), a + gr * (b - a)
            fc, fe = sign * _branch(hb, cb, c, branch), sign * _branch(hb, cb, e, branch)
            for _ in range(n_golden):
                left = fc < fe
                b = np.where(left, e, b)
                a = np.where(left, a, c)
                c_new = np.where(left, b - gr * (b - a), e)
                e_new = np.where(left, c, a + gr * (b - a))
                f_new = sign * _branch(hb, cb, np.where(left, c_new, e_new), branch)
                fc, fe = np.where(left, f_new, fe), np.where(left, fc, f_new)
                c, e = c_new, e_new
            at = np.where(fc < fe, c, e)
            best = np.minimum(best, sign * _branch(hb, cb, at, branch, exact=True))  # LAPACK at the phase
        out[..., k] = sign * best
    return out


def gaps(edges: np.ndarray, bound: np.ndarray) -> np.ndarray:
    """Intervals of omega^2 free of bulk states, from per-branch band edges.

    Parameters
    ----------
    edges : ndarray, shape (N, d, 2)
    bound : ndarray, shape (N,)
        |omega^2| bound of the whole spectrum (the outer gaps run to -bound and +bound).

    Returns
    -------
    ndarray, shape (N, d + 1, 2)
        [lo, hi] of each gap (below the band, between branches, above it), NaN where none.
    """
    n, d, _ = edges.shape
    lo = np.sort(edges[..., 0], axis=-1)
    order = np.argsort(edges[..., 0], axis=-1)
    hi = np.maximum.accumulate(np.take_along_axis(edges[..., 1], order, axis=-1), axis=-1)
    out = np.full((n, d + 1, 2), np.nan)
    out[:, 0] = np.column_stack([-bound, lo[:, 0]])
    for k in range(1, d):
        open_ = lo[:, k] > hi[:, k - 1]
        out[open_, k] = np.column_stack([hi[open_, k - 1], lo[open_, k]])
    out[:, d] = np.column_stack([hi[:, -1], bound])
    return out


def _effective(lam: np.ndarray, h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray) -> tuple[np.ndarray, dict]:
    """Hermitised eps_s(lambda) at real lambda (zeros where the decimation failed) and the raw result."""
    res = decimate(lam.astype(complex), h00, h00s, h01)
    m = 0.5 * (res["eps_s"] + herm(res["eps_s"]))
    ok = res["converged"] & np.isfinite(m).all(axis=(-1, -2))
    res["converged"] = ok
    return np.where(ok[:, None, None], m, 0.0), res


def _mu(lam: np.ndarray, h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray, index: np.ndarray) -> np.ndarray:
    """mu_index(lambda), the sorted eigenvalue of eps_s(lambda) (Hermitised); NaN if not converged."""
    m, res = _effective(lam, h00, h00s, h01)
    w = np.linalg.eigvalsh(m)
    mu = np.take_along_axis(w, index[:, None], axis=-1)[:, 0]
    return np.where(res["converged"], mu, np.nan)


def surface_modes(h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray, edges: np.ndarray,
                  tol: float = 4.0 * _EPS, max_iter: int = 200) -> dict:
    """True surface modes (real omega^2 outside the bulk band) of N semi-infinite crystals.

    Parameters
    ----------
    h00, h00s, h01 : ndarray, shape (N, d, d)
    edges : ndarray, shape (N, d, 2)
        Bulk band edges of the same blocks (:func:`bulk_band_edges`).
    tol : float
        Relative bracket width at which a root is accepted.
    max_iter : int

    Returns
    -------
    dict
        Flat lists over the modes found: ``problem`` (M,) int (which of the N), ``omega2`` (M,)
        K/m, ``vector`` (M, d) complex (surface principal layer, unit norm), ``decay`` (M,)
        amplitude ratio per principal layer.
    """
    n, d, _ = h00.shape
    scale = np.abs(h00).max(axis=(-1, -2)) + 2.0 * np.abs(h01).max(axis=(-1, -2))
    bound = 2.0 * d * (np.abs(h00s).max(axis=(-1, -2)) + 2.0 * np.abs(h01).max(axis=(-1, -2)))
    gp = gaps(edges, bound)  # (N, d + 1, 2)
    off = EDGE_OFFSET * scale[:, None]
    lo, hi = gp[..., 0] + off, gp[..., 1] - off
    lo[:, 0] = gp[:, 0, 0]
    hi[:, -1] = gp[:, -1, 1]
    ok = np.isfinite(lo) & (hi > lo)
    prob, gap = np.nonzero(ok)
    # f_i at both ends of every gap, all i at once
    ends = np.concatenate([lo[prob, gap], hi[prob, gap]])
    pp = np.concatenate([prob, prob])
    m, res = _effective(ends, h00[pp], h00s[pp], h01[pp])
    mu = np.linalg.eigvalsh(m)
    f = ends[:, None] - mu
    f = np.where(res["converged"][:, None], f, np.nan)
    f_lo, f_hi = f[: prob.size], f[prob.size:]
    sel_p, sel_i = np.nonzero((f_lo < 0) & (f_hi > 0))
    p = prob[sel_p]
    index = sel_i
    a, b = lo[p, gap[sel_p]], hi[p, gap[sel_p]]
    fa, fb = f_lo[sel_p, sel_i], f_hi[sel_p, sel_i]
    side = np.zeros(p.size, int)
    done = np.zeros(p.size, bool)
    for _ in range(max_iter):
        act = np.flatnonzero(~done)
        if not act.size:
            break
        x = (a[act] * fb[act] - b[act] * fa[act]) / (fb[act] - fa[act])
        mid = 0.5 * (a[act] + b[act])
        x = np.where(np.isfinite(x) & (x > a[act]) & (x < b[act]), x, mid)
        fx = x - _mu(x, h00[p[act]], h00s[p[act]], h01[p[act]], index[act])
        neg = fx < 0
        a[act] = np.where(neg, x, a[act])
        b[act] = np.where(neg, b[act], x)
        # Illinois: halve the stale end's value when the same side moves twice
        fa[act] = np.where(neg, fx, np.where(side[act] == -1, 0.5 * fa[act], fa[act]))
        fb[act] = np.where(neg, np.where(side[act] == 1, 0.5 * fb[act], fb[act]), fx)
        side[act] = np.where(neg, 1, -1)
        width = b[act] - a[act]
        done[act] = (width <= tol * scale[p[act]]) | (fx == 0) | ~np.isfinite(fx)
    lam = (a * fb - b * fa) / (fb - fa)
    lam = np.where(np.isfinite(lam), lam, 0.5 * (a + b))
    m, res = _effective(lam, h00[p], h00s[p], h01[p])
    mu_all, v = np.linalg.eigh(m)
    residual = np.abs(lam - np.take_along_axis(mu_all, index[:, None], axis=-1)[:, 0])
    vec = np.take_along_axis(v, index[:, None, None], axis=-1)[..., 0]
    t = inv(lam[:, None, None] * np.eye(d) - res["eps_b"]) @ herm(h01[p])
    for _ in range(6):
        t = t @ t
    with np.errstate(all="ignore"):
        decay = np.linalg.norm(np.einsum("mij,mj->mi", t, vec), axis=-1) ** (1.0 / 64.0)
    edge_dist = np.min(np.abs(lam[:, None, None] - edges[p]), axis=(-1, -2))
    keep = ((decay < 1.0 - DECAY_MIN) & (edge_dist > 10 * EDGE_OFFSET * scale[p]) & np.isfinite(lam)
            & res["converged"] & (residual <= RESIDUAL_TOL * scale[p]))
    return {"problem": p[keep], "omega2": lam[keep], "vector": vec[keep], "decay": decay[keep]}
