"""Surface entropy of the triangular lattice: references, independent routes, extremes."""
from __future__ import annotations

import warnings

import numpy as np
import pytest
from scipy import integrate

from surfwave.data.variables import CUBES
from surfwave.dynamics.entropy import (
    OUTPUTS,
    band_edge_coefficients,
    estimate_terms,
    rayleigh_c2,
    surface_entropy,
    theta_integrals,
    theta_rule,
)
from surfwave.dynamics.surface_green import (
    bulk_schur,
    hermitian,
    positive_definite2,
    slab_log_det,
    slab_s_theta,
    theta_log_dets,
)
from surfwave.dynamics.triangular import row_matrices
from surfwave.errors import GeometryError, InputError

#: Huckaby's mean of ln(omega/omega0) over the bulk modes of the unstressed harmonic
#: triangular lattice, quoted in the paper before Eq. (26) and in docs/physics/paper.md.
HUCKABY = 0.4126784
#: Harmonic bulk limit: c_T,par^2 = 0 from Eq. (A14), 6x^2 - 2x^4 - 2x = 0 with x = s/2,
#: i.e. s^3 - 12 s + 8 = 0 (root in (0, 1)).
S_BULK = float(np.real([r for r in np.roots([1.0, 0.0, -12.0, 8.0]) if 0 < r.real < 1][0]))
#: Harmonic surface limit: c_R^2 = 0 in Eq. (16) at x^2 - 6x + 2 = 0, x = 3 - sqrt 7.
S_SURF = 2.0 * (3.0 - np.sqrt(7.0))


def _blocks(potential, d, theta):
    a0, a0s, a1 = row_matrices(potential, [d], np.asarray(theta, dtype=float))
    return a0[0], a0s[0], a1[0]


def jensen_bulk_log_det(a0: np.ndarray, a1: np.ndarray) -> np.ndarray:
    """B(theta) from the roots of det(A1 z^2 + A0 z + A1^H) (Jensen's formula).

    B = ln|det A1| + sum over roots with |z| > 1 of ln|z|. An independent route to
    ln det S, here the test's reference (the quartic's roots as eigenvalues of its
    companion matrix, vectorised over theta).

    Parameters
    ----------
    a0, a1 : ndarray, shape (m, 2, 2)

    Returns
    -------
    ndarray, shape (m,)
    """
    p = [hermitian(a1), a0, a1]  # coefficients of z^0, z^1, z^2, each (m, 2, 2)
    # det(P0 + P1 z + P2 z^2) of 2x2 polynomial matrices: coefficients by convolution
    coef = np.zeros((a0.shape[0], 5), dtype=complex)
    for j in range(3):
        for k in range(3):
            coef[:, j + k] += p[j][:, 0, 0] * p[k][:, 1, 1] - p[j][:, 0, 1] * p[k][:, 1, 0]
    companion = np.zeros((a0.shape[0], 4, 4), dtype=complex)
    companion[:, 0, :] = -coef[:, 3::-1] / coef[:, 4:5]  # monic, descending powers z^3 .. z^0
    companion[:, 1:, :-1] = np.eye(3)
    mod = np.abs(np.linalg.eigvals(companion))
    return np.log(np.abs(coef[:, 4])) + np.sum(np.log(np.where(mod > 1.0, mod, 1.0)), axis=-1)


# --- zero stress: the acceptance numbers -------------------------------------------------

def test_zero_stress_harmonic_reference_values():
    """bulk mean = Huckaby's 0.4126784 (paper, before Eq. 26) to 1e-7; estimate = Eq. (26)
    evaluated from its closed form (1/2) ln 3 - (1/2) ln(3/4 - sqrt 3/4) - 0.4126784
    = 0.7110745 to 1e-6; exact value converged to 1e-8 by its own error estimate."""
    r = surface_entropy("harmonic", [1.0], tol=1e-8)
    eq26 = 0.5 * np.log(3.0) - 0.5 * np.log(0.75 - np.sqrt(3.0) / 4.0) - HUCKABY
    # Huckaby's 7 decimals carry a rounding of 5e-8
    assert abs(r["bulk_mean_log_omega"][0] - HUCKABY) < 5e-8 + r["bulk_mean_log_omega_error"][0]
    assert r["bulk_mean_log_omega_error"][0] < 1e-8
    assert abs(r["S_surface_estimate"][0] - eq26) < 1e-6
    assert abs(r["S_surface_estimate"][0] - 0.711075) < 1e-6  # Eq. (26) with Huckaby's bulk term
    assert r["S_surface_exact_error"][0] < 1e-8
    assert r["reason"][0] == ""
    # the paper's numerical lattice dynamics (Ref. 23) gives 0.66, cell cluster 0.62
    assert abs(r["S_surface_exact"][0] - 0.66) < 0.005


def test_eq26_terms_separately():
    """Eq. (26) term by term at zero stress: <ln omega_L omega_T> = (1/2) ln 3 and
    <ln omega_R> = (1/2) ln c_R^2 with c_R^2 = (3 - sqrt 3)/4 (Eq. 16 at x = 1/2, docs/physics/paper.md)."""
    t = estimate_terms("harmonic", 1.0)
    assert t["log_omega_LT"] == pytest.approx(0.5 * np.log(3.0), abs=1e-14)
    assert t["log_omega_R"] == pytest.approx(0.5 * np.log((3 - np.sqrt(3)) / 4), abs=1e-14)


def test_api_keys_shapes_and_metadata():
    """Every returned array has shape (n,) and CF metadata in VARIABLES (the workflow's contract)."""
    r = surface_entropy("lj", [0.95, 1.0, 1.05])
    assert set(r) == set(OUTPUTS) == set(CUBES["entropy"])
    for name, arr in r.items():
        assert arr.shape == (3,)
        meta = CUBES["entropy"][name]
        assert {"long_name", "dims"} <= set(meta) and ("units" in meta) != (name == "reason")
    assert CUBES["entropy"]["S_surface_exact"]["units"] == "k_B"


def test_separable_per_strain():
    """The cache stores strain points one by one: [a, b] must equal [a] and [b] bitwise."""
    grid = [0.72, 1.0, 1.4]
    together = surface_entropy("harmonic", grid)
    for i, d in enumerate(grid):
        alone = surface_entropy("harmonic", [d])
        for k in together:
            assert np.array_equal(together[k][i:i + 1], alone[k]), k


# --- independent routes -------------------------------------------------------------------

@pytest.mark.parametrize("pot,d", [("harmonic", 1.0), ("harmonic", 0.8), ("lj", 1.05), ("lj", 0.92)])
def test_bulk_log_det_szego_vs_jensen_and_p_grid(pot, d):
    """B(theta) = ln det S (cyclic reduction) against Jensen's formula on the roots of
    det(A1 z^2 + A0 z + A1^H) and against a trapezoid p-average (exponentially accurate at
    theta away from 0)."""
    theta = np.array([0.01, 0.2, 0.7, 1.3])
    a0, _, a1 = _blocks(pot, d, theta)
    s, ok, _ = bulk_schur(a0, a1)
    assert ok.all()
    b = np.log(np.linalg.det(s).real)
    np.testing.assert_allclose(b, jensen_bulk_log_det(a0, a1), atol=1e-11)
    p = np.arange(512) * (2 * np.pi / 512)
    z = np.exp(1j * p)[:, None, None, None]
    dd = a0[None] + a1[None] * z + hermitian(a1)[None] / z
    trap = np.log(np.linalg.det(dd).real).mean(axis=0)
    np.testing.assert_allclose(b[1:], trap[1:], atol=1e-11)


@pytest.mark.parametrize("pot,d", [("harmonic", 1.0), ("harmonic", 1.3), ("harmonic", 0.8), ("lj", 1.05)])
def test_semi_infinite_vs_slab_per_theta(pot, d):
    """s(theta) of the semi-infinite closed form against two finite slabs (block LU of N and
    2N rows, s = -(2 ln det H_N - ln det H_2N)/4, no bulk reference, no fixed point)."""
    theta = np.array([0.1, 0.4, 1.0, 1.5])
    a0, a0s, a1 = _blocks(pot, d, theta)
    semi = theta_log_dets(a0, a0s, a1)["s_theta"]
    np.testing.assert_allclose(slab_s_theta(a0, a0s, a1, 200), semi, atol=1e-10)


def test_dense_slab_eigenvalues_match_block_lu():
    """The block-LU slab log-det equals the sum of ln omega^2 over the eigenvalues of the
    dense 2N x 2N slab matrix (a direct lattice-dynamics slab solve)."""
    a0, a0s, a1 = _blocks("harmonic", 1.0, [0.6])
    n = 30
    h = np.zeros((2 * n, 2 * n), dtype=complex)
    for i in range(n):
        h[2 * i:2 * i + 2, 2 * i:2 * i + 2] = a0s[0] if i in (0, n - 1) else a0[0]
        if i < n - 1:
            h[2 * i:2 * i + 2, 2 * i + 2:2 * i + 4] = a1[0]
            h[2 * i + 2:2 * i + 4, 2 * i:2 * i + 2] = hermitian(a1[0])
    w2 = np.linalg.eigvalsh(h)
    assert w2.min() > 0
    assert slab_log_det(a0, a0s, a1, n)[0] == pytest.approx(np.log(w2).sum(), abs=1e-10)


@pytest.mark.parametrize("d", [1.0, 1.3, 0.8])
def test_exact_entropy_vs_slab_route(d):
    """Whole theta average from finite slabs (2048 and 4096 rows, block LU) on the same
    nodes: an independent route to S_surface_exact. The slab error ~ exp(-2 kappa theta N)
    is largest at the smallest node, theta = 0.0083; at d/d0 = 0.8 (soft c_T,par, small
    kappa) N = 1024 still misses by 1e-7, N = 2048 agrees to 1e-10."""
    theta, w = theta_rule(16)
    a0, a0s, a1 = _blocks("harmonic", d, theta)
    s = slab_s_theta(a0, a0s, a1, 2048)
    slab = np.sum(w * (s + 0.5 * np.log(np.sin(theta)))) + 0.5 * np.log(2.0)
    exact = surface_entropy("harmonic", [d], tol=1e-10)["S_surface_exact"][0]
    assert slab == pytest.approx(exact, abs=1e-9)


def test_theta_quadrature_vs_adaptive_quadpack():
    """Gauss-Legendre with the -(1/2) ln sin(theta) subtraction against QUADPACK's adaptive
    rule (epsilon extrapolation at the log singularity) applied to the raw s(theta) and B."""
    for pot, d in [("harmonic", 1.0), ("lj", 0.95)]:
        def s_of(t, key):
            a0, a0s, a1 = _blocks(pot, d, [t])
            return float(theta_log_dets(a0, a0s, a1)[key][0])
        ref_s = integrate.quad(lambda t: s_of(t, "s_theta"), 0, np.pi / 2, epsabs=1e-12, limit=200)[0]
        ref_b = integrate.quad(lambda t: s_of(t, "bulk_log_det"), 0, np.pi / 2, epsabs=1e-12, limit=200)[0]
        r = surface_entropy(pot, [d], tol=1e-10)
        assert r["S_surface_exact"][0] == pytest.approx(ref_s * 2 / np.pi, abs=1e-9)
        assert r["bulk_mean_log_omega"][0] == pytest.approx(0.25 * ref_b * 2 / np.pi, abs=1e-9)


def test_estimate_averages_vs_quadrature():
    """The closed forms of <ln omega_L omega_T> (over 0..pi) against adaptive quadrature of
    the eigenvalues of the row matrices A0 + A1 + A1^H (normal wave-number 0)."""
    for pot, d in [("harmonic", 0.8), ("lj", 1.05)]:
        def f(t):
            a0, _, a1 = _blocks(pot, d, [t])
            return 0.5 * np.log(np.linalg.eigvalsh(a0[0] + a1[0] + hermitian(a1[0]))).sum()
        ref = integrate.quad(f, 0, np.pi, epsabs=1e-12, limit=200)[0] / np.pi
        assert estimate_terms(pot, d)["log_omega_LT"] == pytest.approx(ref, abs=1e-9)


def test_band_edges_are_eq4a():
    """omega_L^2, omega_T^2 of the harmonic lattice: corrected Eq. (4a) of the paper,
    2(1 - cos 2t) + 4x^2(1 - cos t) and [2 - 1/x'](1 - cos 2t) + 4 y^2 (1 - cos t) with
    x = d_x, y = d_y (d0 = 1), 1/x' = d0/d_x; and the row matrices at q = 0 are diagonal."""
    for d in (0.8, 1.0, 1.4):
        t = np.array([0.3, 1.1, 2.5])
        x = d / 2
        y2 = 1 - x * x
        a, b = band_edge_coefficients("harmonic", [d])
        model = (1 - np.cos(t))[:, None] * (a + b * np.cos(t)[:, None])
        eq4a = np.column_stack([2 * (1 - np.cos(2 * t)) + 4 * x * x * (1 - np.cos(t)),
                                (2 - 1 / x) * (1 - np.cos(2 * t)) + 4 * y2 * (1 - np.cos(t))])
        np.testing.assert_allclose(model, eq4a, atol=1e-13)
        a0, _, a1 = _blocks("harmonic", d, t)
        m = a0 + a1 + hermitian(a1)
        np.testing.assert_allclose(np.abs(m[:, 0, 1]), 0, atol=1e-14)
        np.testing.assert_allclose(np.stack([m[:, 0, 0].real, m[:, 1, 1].real], 1), eq4a, atol=1e-13)


def test_rayleigh_speed_eq16_and_eq15_for_lj():
    """Eq. (20) from the bond sums equals Eq. (16) for the harmonic lattice; and for LJ the
    surface-mode frequency of the semi-infinite lattice (bisection on omega^2 until S - dA
    stops being positive definite) equals Eq. (15), (c_R/d_x) sin theta, so the estimate's
    omega_R is exact for LJ too."""
    for d in (0.75, 1.0, 1.5):
        x = d / 2
        eq16 = 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)
        assert rayleigh_c2("harmonic", d) == pytest.approx(eq16, rel=1e-12)
    theta = np.array([0.3, 1.2])
    for pot, d in [("lj", 0.92), ("lj", 1.08)]:
        a0, a0s, a1 = _blocks(pot, d, theta)
        lo, hi = np.zeros(2), np.full(2, 4.0)
        for _ in range(55):
            mid = 0.5 * (lo + hi)
            s, ok, _ = bulk_schur(a0 - mid[:, None, None] * np.eye(2), a1)
            pd = ok & positive_definite2(s - (a0 - a0s))
            lo, hi = np.where(pd, mid, lo), np.where(pd, hi, mid)
        eq15 = np.sqrt(rayleigh_c2(pot, d)) / (d / 2) * np.sin(theta)
        np.testing.assert_allclose(np.sqrt(lo), eq15, rtol=1e-7)


def test_rayleigh_matches_general_eq17_solver():
    """Eq. (20) here against the general Eq. (17) solver with root selection by the unsquared
    boundary condition (``surfwave.point``, surfwave.solvers.rayleigh)."""
    import surfwave

    grid = np.array([0.9, 1.0, 1.1])
    ref = surfwave.point("triangular", "uniaxial", "lj", "[10]", grid)["c2_R"]
    # both routes are closed-form roots (Eq. 20 and the cubic of Eq. 17): they agree to 1e-14
    np.testing.assert_allclose([rayleigh_c2("lj", d) for d in grid], ref, rtol=1e-12)


def test_clamped_fixed_point_is_mirror_image():
    """St = M S M (mirror x -> -x) used for Widom's constant: check against a second cyclic
    reduction run from the other side, St = A0 - A1 St^{-1} A1^H."""
    a0, _, a1 = _blocks("lj", 1.05, [0.05, 0.9])
    s, _, _ = bulk_schur(a0, a1)
    st, _, _ = bulk_schur(a0, hermitian(a1))
    m = np.diag([-1.0, 1.0])
    np.testing.assert_allclose(st, m @ s @ m, atol=1e-13)


# --- extremes -----------------------------------------------------------------------------

@pytest.mark.parametrize("pot,d", [("harmonic", 1.0), ("harmonic", 0.72), ("lj", 1.1), ("lj", 0.9)])
def test_log_singularity_at_theta_zero(pot, d):
    """s(theta) = -(1/2) ln theta + analytic as theta -> 0 (what the quadrature subtracts):
    the slope d s / d ln theta tends to -1/2, for any stable strain."""
    theta = np.array([1e-5, 1e-4])
    s = theta_log_dets(*_blocks(pot, d, theta))["s_theta"]
    slope = (s[1] - s[0]) / np.log(10.0)
    assert slope == pytest.approx(-0.5, abs=2e-3)


def test_harmonic_instabilities():
    """Bulk limit s^3 - 12 s + 8 = 0 (c_T,par = 0, Eq. A14) and surface limit
    2(3 - sqrt 7) (c_R = 0, Eq. 16): NaN with a reason beyond them, values inside; between
    them the bulk mean exists but the free surface is unstable (the exact semi-infinite
    solve and Eq. (20) agree on where)."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = surface_entropy("harmonic", [S_BULK - 1e-6, S_BULK + 1e-6, S_SURF - 1e-6, S_SURF + 1e-6])
    assert np.isnan(r["bulk_mean_log_omega"][0]) and "bulk unstable" in r["reason"][0]
    assert np.isfinite(r["bulk_mean_log_omega"][1:]).all()
    for i in (1, 2):
        assert np.isnan(r["S_surface_exact"][i]) and np.isnan(r["S_surface_estimate"][i])
        assert "surface unstable" in r["reason"][i] and "no Rayleigh wave" in r["reason"][i]
    assert r["reason"][3] == ""
    # the soft Rayleigh wave makes both entropies large near the surface limit
    assert r["S_surface_exact"][3] > 3 and r["S_surface_estimate"][3] > 3


@pytest.mark.parametrize("pot,lo,hi", [("harmonic", S_SURF + 1e-4, 1.99), ("lj", 0.8937, 1.1139)])
def test_no_nan_inside_stable_range(pot, lo, hi):
    """Every quantity is finite, converged (error <= tol) and without reason across the
    stable range (LJ surface limits 0.89362 and 1.11393, derived independently in
    test_golden_constants.py; cf. the harmonic ones from Eq. 16), including the edges,
    without RuntimeWarnings."""
    grid = np.linspace(lo, hi, 9)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = surface_entropy(pot, grid, tol=1e-8)
    for k in ("S_surface_estimate", "bulk_mean_log_omega", "S_surface_exact"):
        assert np.isfinite(r[k]).all(), k
    assert (r["reason"] == "").all()
    assert (r["S_surface_exact_error"][1:-1] < 1e-8).all()


def test_lj_unstable_both_sides():
    """LJ: compression and tension beyond the limits give NaN with a reason, no exception."""
    r = surface_entropy("lj", [0.85, 1.2])
    assert np.isnan(r["S_surface_exact"]).all() and np.isnan(r["bulk_mean_log_omega"]).all()
    assert all("bulk unstable" in x for x in r["reason"])


def test_slab_buckles_under_compression_semi_infinite_does_not():
    """Why a semi-infinite method: a 50-row slab at d/d0 = 0.75 has omega^2 < 0 at small
    theta (buckling, NaN), while the semi-infinite crystal is stable there."""
    a0, a0s, a1 = _blocks("harmonic", 0.75, [0.005, 0.3])
    assert np.isnan(slab_log_det(a0, a0s, a1, 50)[0])
    assert np.isfinite(slab_log_det(a0, a0s, a1, 50)[1])
    assert theta_log_dets(a0, a0s, a1)["surface_ok"].all()


def test_tolerance_controls_error():
    """A loose tolerance uses fewer nodes; its reported error bounds the true difference to
    a tight run."""
    loose = surface_entropy("lj", [0.9], tol=1e-3, n_theta_start=4)
    tight = surface_entropy("lj", [0.9], tol=1e-11)
    assert loose["n_theta"][0] < tight["n_theta"][0]
    for k in ("S_surface_exact", "bulk_mean_log_omega"):
        assert abs(loose[k][0] - tight[k][0]) <= loose[k + "_error"][0] + tight[k + "_error"][0]
        assert loose[k + "_error"][0] <= 1e-3


def test_fixed_depth_converges_to_machine_precision():
    """Cyclic reduction depth 2^levels rows: the error of theta_integrals falls to rounding."""
    ref = theta_integrals("harmonic", 1.0, 32)["S_surface_exact"]
    errs = [abs(theta_integrals("harmonic", 1.0, 32, levels=k)["S_surface_exact"] - ref) for k in (6, 10, 14)]
    assert errs[0] > 1e-4 and errs[2] < 1e-12 and errs[1] < errs[0]


def test_bad_inputs_raise():
    """Impossible geometry (d/d0 outside (0, 2)) and unknown potentials are input errors."""
    with pytest.raises(GeometryError):
        surface_entropy("harmonic", [2.0])
    with pytest.raises(InputError):
        surface_entropy("nope", [1.0])


def test_timing_target():
    """Target: S_surface_exact to 1e-8 in under 0.5 s per strain on one core (CPU time
    of this process, so that a loaded machine running other tests does not make it flaky)."""
    import time
    t0 = time.process_time()
    r = surface_entropy("lj", np.linspace(0.9, 1.1, 5), tol=1e-8)
    assert (time.process_time() - t0) / 5 < 0.5
    assert (r["S_surface_exact_error"] < 1e-8).all()


def test_entropy_figure_is_written(tmp_path):
    """plots_entropy.entropy_vs_strain renders a cube with an unstable (NaN) point to PNG."""
    from surfwave.plots.entropy import entropy_vs_strain, to_dataset

    grid = np.array([0.7, 0.9, 1.0, 1.2])
    ds = to_dataset(surface_entropy("harmonic", grid), grid, "harmonic")
    assert ds["S_surface_exact"].attrs["units"] == "k_B"
    out = entropy_vs_strain(ds, tmp_path / "entropy.png")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
