"""Exact classical harmonic surface entropy of the prestressed FCC surfaces, and its estimate.

The log-determinant route of the triangular lattice (:mod:`surfwave.dynamics.surface_green`,
:mod:`surfwave.dynamics.entropy`), for any block size and without a mirror between the two
sides. At fixed in-plane q the static slab matrix H_N (N principal layers, both surfaces
free) satisfies ln det H_N = N B(q) + X(q) + o(1), and the classical entropy of a set of
modes is -(1/2) ln det H + const per mode, so the surface entropy per surface cell (one
atom per plane per cell: "per surface atom") at q is s(q) = -X(q)/4 (two equal surfaces,
related by inversion). With S_dn = H00 - H01 S_dn^{-1} H01^H and S_up = H00 - H01^H S_up^{-1} H01
(a layer with the half crystal below, resp. above, eliminated; det S_dn = det S_up = e^B,
Szego) and dA_top = H00 - H00_surface, dA_bot = H00 - H00_bottom:

    X = ln det(1 - S_dn^{-1} dA_top) + ln det(1 - S_up^{-1} dA_bot)
        - ln det(1 - S_up^{-1} H01 S_dn^{-1} H01^H)

(the last term is minus the log of Widom's constant, both surfaces clamped). Checked against
finite-slab log-determinants (block LU, no fixed point) in the tests.

The surface-zone mean of s(q) has an integrable ln|q| singularity at Gamma; the midpoint
rule on an n x n grid of reduced q (n divisible by 4: Gamma is never a node) converges like
n^-2 (measured ratio ~4 per doubling), so the result is the Richardson value
R_n = (4 S_n - S_{n/2})/3 with |R_n - R_{n/2}| as its error estimate. B(q) has a cone
(a + b|q|) at Gamma, its mean converges like n^-3 and is extrapolated as (8 B_n - B_{n/2})/7.

Estimate, the FCC analogue of the corrected Eq. (25) (three degrees of freedom per atom):

    S_est = <ln(omega_1 omega_2 omega_3)>_q - <ln omega_R>_q - 2 <ln omega>_bulk,

omega_i(q) the bulk modes at normal wavevector 0, omega_R(q) the lowest surface mode (the
bottom of the projected bulk band where no true surface mode exists) and <ln omega>_bulk
= <B(q)>_q / (6 m) the mean over all bulk modes; the q means of the estimate use the
n/2 grid (no extrapolation: it is an estimate).
"""
from __future__ import annotations

import numpy as np

from surfwave.dynamics import fcc_layers as layers
from surfwave.dynamics.fcc_surface_green import decimate, herm
from surfwave.dynamics.fcc_surface_phonons import bulk_stability, surface_phonons
from surfwave.errors import InputError
from surfwave.model_crystals.potentials import PairPotential, get_potential

#: Default reduced-q grid of the zone mean (n x n midpoints).
N_GRID = 64


def bottom_block(blocks: dict) -> np.ndarray:
    """H00 of the bottom principal layer of a slab (its planes lack the bonds below).

    Parameters
    ----------
    blocks : dict
        From :func:`surfwave.dynamics.fcc_layers.plane_blocks`.

    Returns
    -------
    ndarray, shape (n, n_q, 3m, 3m)
        By inversion symmetry of the bond set, plane m-1-l lacks the same bond sum as plane
        l of the top layer.
    """
    h00, _, _ = layers.principal_blocks(blocks)
    m = blocks["D"].shape[0] - 1
    out = h00.copy()
    for layer in range(m):
        a = m - 1 - layer
        out[..., 3 * a:3 * a + 3, 3 * a:3 * a + 3] -= blocks["missing"][layer]
    return out


def _logdet(m: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(ln |det|, det > 0 and finite) of real-determinant blocks."""
    sign, val = np.linalg.slogdet(m)
    return val, (sign.real > 0.5) & np.isfinite(val)


def q_log_dets(h00: np.ndarray, h00s: np.ndarray, h00b: np.ndarray, h01: np.ndarray) -> dict:
    """Per-q bulk and surface log-determinants of the semi-infinite crystal.

    Parameters
    ----------
    h00, h00s, h00b, h01 : ndarray, shape (..., d, d)
        Bulk, top-surface and bottom-surface diagonal blocks and the coupling, K/m.

    Returns
    -------
    dict of ndarray, shape (...)
        ``bulk_log_det`` B = ln det S (ln of (K/m)^d); ``x`` the surface term X; ``s_q``
        = -X/4 (k_B per surface cell); ``ok``: both fixed points converged and every
        determinant positive (else NaN).
    """
    zero = np.zeros(h00.shape[:-2])
    dn = decimate(zero, h00, h00, h01)
    up = decimate(zero, h00, h00, herm(h01))
    with np.errstate(all="ignore"):
        s_dn, s_up = dn["eps_b"], up["eps_b"]  # at z = 0: H00 + H01 (-S^{-1}) H01^H = S
        eye = np.eye(h00.shape[-1])
        inv_dn, inv_up = np.linalg.inv(s_dn), np.linalg.inv(s_up)
        b, ok_b = _logdet(s_dn)
        top, ok_t = _logdet(eye - inv_dn @ (h00 - h00s))
        bot, ok_u = _logdet(eye - inv_up @ (h00 - h00b))
        clamp, ok_c = _logdet(eye - inv_up @ h01 @ inv_dn @ herm(h01))
    ok = dn["converged"] & up["converged"] & ok_b & ok_t & ok_u & ok_c
    x = top + bot - clamp
    return {"bulk_log_det": np.where(ok, b, np.nan), "x": np.where(ok, x, np.nan),
            "s_q": np.where(ok, -0.25 * x, np.nan), "ok": ok}


def slab_log_det(h00: np.ndarray, h00s: np.ndarray, h00b: np.ndarray, h01: np.ndarray, n_layers: int) -> np.ndarray:
    """ln det of a free slab of ``n_layers`` principal layers by block LU (no fixed point).

    Returns
    -------
    ndarray, shape (...)
        NaN where a pivot is not positive definite.
    """
    piv = h00s.copy()
    total = np.zeros(h00.shape[:-2])
    ok = np.ones(h00.shape[:-2], bool)
    for layer in range(1, n_layers + 1):
        val, good = _logdet(piv)
        total += val
        ok &= good
        if layer == n_layers:
            break
        diag = h00b if layer == n_layers - 1 else h00
        piv = diag - herm(h01) @ np.linalg.solve(piv, h01)
    return np.where(ok, total, np.nan)


def _grid(n: int) -> np.ndarray:
    g = (np.arange(n) + 0.5) / n - 0.5
    return np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)


def _zone_terms(sc: layers.SurfaceCrystal, pot: PairPotential, n: int) -> dict:
    """Zone means of s(q) and B(q) on the n x n midpoint grid, per strain."""
    qr = _grid(n)
    blocks = layers.plane_blocks(sc, pot, layers.cartesian_q(sc, qr))
    h00, h00s, h01 = layers.principal_blocks(blocks)
    res = q_log_dets(h00, h00s, bottom_block(blocks), h01)
    d = blocks["D"]
    kperp0 = d[0] + sum(d[j] + herm(d[j]) for j in range(1, d.shape[0]))  # bulk D at k_perp = 0
    return {"s": res["s_q"].mean(axis=-1), "b": res["bulk_log_det"].mean(axis=-1), "qr": qr, "kperp0": kperp0}


def surface_entropy(potential: str | PairPotential, loading: str, d_over_d0, *, surface: str = "(001)",
                    load_direction: str | None = None, n_grid: int = N_GRID, estimate: bool = True) -> dict:
    """Exact harmonic surface entropy of the semi-infinite prestressed FCC crystal, and its estimate.

    Parameters
    ----------
    potential, loading, d_over_d0, surface, load_direction
        As for :func:`surfwave.surface_phonons`.
    n_grid : int
        Size of the reduced-q midpoint grid, divisible by 4 (n_grid / 2 and / 4 are used too).
    estimate : bool
        Also compute the Eq. (25)-type estimate (needs the surface modes on the grid).

    Returns
    -------
    dict of ndarray, shape (n,)
        ``S_surface_exact`` and ``S_surface_exact_error`` (k_B per surface cell),
        ``bulk_mean_log_omega`` (<ln omega/omega0> over all bulk modes),
        ``S_surface_estimate`` (NaN unless ``estimate``), ``reason`` (object str).
    """
    if not (isinstance(n_grid, int | np.integer) and n_grid >= 8 and n_grid % 4 == 0):
        raise InputError(f"n_grid must be an integer >= 8 divisible by 4, got {n_grid!r}")
    pot = get_potential(potential)
    sc = layers.surface_crystal(surface, loading, pot, d_over_d0, load_direction)
    stable, _, reason = bulk_stability(sc, pot)
    fine, half, quarter = (_zone_terms(sc, pot, n_grid // k) for k in (1, 2, 4))
    m = sc.depth
    rich, rich_half = (4.0 * fine["s"] - half["s"]) / 3.0, (4.0 * half["s"] - quarter["s"]) / 3.0
    s_exact = np.where(stable, rich, np.nan)
    err = np.where(stable, np.abs(rich - rich_half), np.nan)
    # B(q) = a + b |q| + ... at Gamma: its midpoint mean converges like n^-3 (measured ratio 8)
    bulk_mean = np.where(stable, (8.0 * fine["b"] - half["b"]) / (42.0 * m), np.nan)  # Richardson, / (6 m)
    reason = np.where(stable & ~np.isfinite(s_exact), "free surface unstable (a surface mode with omega^2 <= 0)",
                      reason).astype(object)
    est = np.full(sc.d_over_d0.shape, np.nan)
    if estimate:
        w2 = np.linalg.eigvalsh(half["kperp0"])  # (n, n_q, 3)
        with np.errstate(all="ignore"):
            lw = 0.5 * np.log(w2).sum(axis=-1).mean(axis=-1)
        if stable.any():
            r = surface_phonons(pot, loading, sc.d_over_d0[stable], surface=surface, q=half["qr"],
                                load_direction=load_direction)  # the half grid: an estimate
            w2 = r["omega2"][:, :, 0]
            low = np.where(np.isfinite(w2), w2, r["band_edges_omega2"][:, :, 0, 0])
            with np.errstate(all="ignore"):
                est[stable] = lw[stable] - 0.5 * np.log(low).mean(axis=-1) - 2.0 * bulk_mean[stable]
    return {"d_over_d0": sc.d_over_d0, "S_surface_exact": s_exact, "S_surface_exact_error": err,
            "bulk_mean_log_omega": bulk_mean, "S_surface_estimate": est, "reason": reason}
