"""Exact FCC surface entropy (log-determinant route) against finite slabs and its own consistency."""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.dynamics import fcc_layers as layers
from surfwave.dynamics.fcc_surface_entropy import bottom_block, q_log_dets, slab_log_det, surface_entropy


@pytest.mark.parametrize("surface, loading, ld", [
    ("(001)", "in_plane_hydrostatic", None), ("(111)", "uniaxial", None), ("(110)", "uniaxial", "[100]"),
])
def test_surface_term_matches_finite_slabs(surface, loading, ld):
    """Reference: ln det H_N of free slabs by block LU (no fixed point, no Widom constant):
    ln det H_N - N B(q) -> X(q) exponentially in N, so slabs of 100 and 200 layers agree
    with the semi-infinite X to rounding."""
    sc = layers.surface_crystal(surface, loading, "lj", [1.01], ld)
    qr = np.array([[0.3, 0.2], [0.5, 0.5], [0.05, 0.02], [-0.4, 0.1]])
    blocks = layers.plane_blocks(sc, "lj", layers.cartesian_q(sc, qr))
    h00, h00s, h01 = layers.principal_blocks(blocks)
    hb = bottom_block(blocks)
    res = q_log_dets(h00, h00s, hb, h01)
    for n in (100, 200):
        diff = slab_log_det(h00, h00s, hb, h01, n) - n * res["bulk_log_det"] - res["x"]
        assert np.abs(diff).max() < 1e-9 * n


def test_bulk_mean_independent_of_the_cut():
    """Reference: the same uniaxially stressed crystal cut along (001), (111) and (110): the
    bulk mean of ln omega is a bulk property, so the three layerings must agree (to the
    quadrature error of the different q grids)."""
    vals = [surface_entropy("lj", "uniaxial", [0.98, 1.02], surface=s, load_direction="[110]", n_grid=32,
                            estimate=False)["bulk_mean_log_omega"] for s in ("(001)", "(111)", "(110)")]
    np.testing.assert_allclose(vals[1], vals[0], rtol=1e-6)
    np.testing.assert_allclose(vals[2], vals[0], rtol=1e-6)


def test_zone_mean_error_estimate_is_honest():
    """Reference: the same quantity on a grid twice as fine: the difference is within the
    reported error of the coarser result."""
    a = surface_entropy("harmonic", "in_plane_hydrostatic", [0.97], n_grid=32, estimate=False)
    b = surface_entropy("harmonic", "in_plane_hydrostatic", [0.97], n_grid=64, estimate=False)
    assert abs(a["S_surface_exact"][0] - b["S_surface_exact"][0]) <= a["S_surface_exact_error"][0]
    assert b["S_surface_exact_error"][0] < 1e-4


def test_unstable_bulk_gives_nan_with_reason():
    """Reference: surfwave.point(...)["stable"] is False at LJ in-plane hydrostatic 1.2."""
    r = surface_entropy("lj", "in_plane_hydrostatic", [1.0, 1.2], n_grid=16, estimate=False)
    assert np.isfinite(r["S_surface_exact"][0]) and np.isnan(r["S_surface_exact"][1])
    assert "unstable" in r["reason"][1]


def test_log_det_route_reproduces_the_triangular_code():
    """Reference: surfwave.dynamics.surface_green.theta_log_dets, the project's exact surface
    entropy of the triangular lattice (checked there against finite slabs and Eq. 26): the
    general log-determinant route of this module applied to the triangular row blocks gives the
    same bulk term and the same s(theta), including the -X/4 convention."""
    from surfwave.dynamics.surface_green import theta_log_dets
    from surfwave.dynamics.triangular import row_matrices

    theta = np.array([0.2, 0.7, 1.5, 2.6])
    a0, a0s, a1 = row_matrices("lj", [0.97, 1.03], theta)
    ref = theta_log_dets(a0, a0s, a1)
    mine = q_log_dets(a0, a0s, a0s, a1)
    np.testing.assert_allclose(mine["bulk_log_det"], ref["bulk_log_det"], rtol=1e-11)
    np.testing.assert_allclose(mine["s_q"], ref["s_theta"], rtol=1e-9, atol=1e-12)
