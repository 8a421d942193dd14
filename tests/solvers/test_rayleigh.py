"""Rayleigh velocity: closed forms, independent routes, root selection and extremes.

References are stated per test: classical isotropic Rayleigh equation, docs/physics/paper.md closed
forms for nearest-neighbour FCC, the paper's Eqs. (16), (20) and (21).
"""
from __future__ import annotations

import functools

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from scipy.optimize import brentq

import surfwave
from surfwave.errors import SymmetryError
from surfwave.model_crystals import elastic
from surfwave.solvers import cubic, rayleigh, stroh
from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor

SQ3 = np.sqrt(3.0)


def isotropic_S(lam: float, mu: float, dim: int = 2) -> np.ndarray:
    """S = C of an unstressed isotropic medium, shape (dim,)*4."""
    eye = np.eye(dim)
    return (lam * np.einsum("ij,kl->ijkl", eye, eye)
            + mu * (np.einsum("ik,jl->ijkl", eye, eye) + np.einsum("il,jk->ijkl", eye, eye)))


def classical_rayleigh_xi(ratio: float) -> float:
    """Root xi = c_R^2/c_T^2 of (2 - xi)^2 = 4 sqrt(1 - xi) sqrt(1 - xi r), r = c_T^2/c_L^2 (textbook form)."""
    f = lambda x: (2 - x) ** 2 - 4 * np.sqrt(1 - x) * np.sqrt(1 - x * ratio)
    return brentq(f, 1e-12, 1 - 1e-15, xtol=1e-15)


def test_isotropic_poisson_quarter():
    """docs/physics/paper.md: isotropic, Poisson ratio 1/4 (lambda = mu): c_R/c_T = sqrt(2 - 2/sqrt 3) = 0.919402."""
    c2 = rayleigh.rayleigh_c2(isotropic_S(1.0, 1.0))
    assert np.sqrt(c2) == pytest.approx(np.sqrt(2 - 2 / SQ3), rel=1e-12)
    assert round(float(np.sqrt(c2)), 6) == 0.919402


@settings(max_examples=60, deadline=None)
@given(nu=st.floats(-0.95, 0.49), mu=st.floats(0.1, 10.0))
def test_isotropic_any_poisson_matches_classical_equation(nu, mu):
    """Any isotropic solid (3D, plane strain): matches the textbook Rayleigh equation solved by bisection."""
    lam = 2 * mu * nu / (1 - 2 * nu)
    c2 = rayleigh.rayleigh_c2(isotropic_S(lam, mu, 3))
    xi = classical_rayleigh_xi(mu / (lam + 2 * mu))
    assert c2 / mu == pytest.approx(xi, rel=1e-9)


@pytest.mark.parametrize("direction,gamma", [("[100]", (3 - SQ3) / 2), ("[110]", (7 - np.sqrt(17)) / 4)])
def test_fcc_211_closed_forms(direction, gamma):
    """docs/physics/paper.md: nearest-neighbour FCC at zero stress (C11:C12:C44 = 2:1:1),
    rho c_R^2 / C44 = (3 - sqrt 3)/2 along [100] and (7 - sqrt 17)/4 along [110]."""
    for pot in ("harmonic", "lj"):
        r = surfwave.point("fcc", "in_plane_hydrostatic", pot, direction, 1.0)
        c44 = r["S"][0, 1, 2, 1, 2]  # V C44 (y-z shear, a cube-axis pair in both frames)
        assert r["c2_R"][0] / c44 == pytest.approx(gamma, rel=1e-12)
    m = surfwave.material(2.0, 1.0, 1.0, 1e9, direction)  # GPa, kg/m^3 -> c^2 in m^2/s^2
    assert m["c_R"] ** 2 == pytest.approx(gamma, rel=1e-12)


def test_fcc_110_unstressed_is_supersonic_decoupled():
    """docs/physics/paper.md: along [110] the sagittal wave outruns the SH bulk wave ((C11-C12)/2 = C44/2 < rho c_R^2)
    and exists only by mirror symmetry: labelled, not dropped."""
    r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.0)
    assert r["c2_R"][0] > r["c2_SH"][0]
    assert r["wave_type"][0] == "supersonic_decoupled"
    assert surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[100]", 1.0)["wave_type"][0] == "surface"


def test_triangular_eq16_equals_eq20_and_general_solver_over_stable_range():
    """Eq. (16) (closed form) = Eq. (20) (Cauchy, four speeds) = Eq. (17) with root selection,
    harmonic triangular lattice, over its whole stable range (c_T,par^2 > 0)."""
    d = np.linspace(0.2, 1.98, 400)
    r = surfwave.point("triangular", "uniaxial", "harmonic", "[10]", d)
    eq16 = rayleigh.triangular_c2(d)
    ok = eq16 > 0
    assert ok.sum() > 250
    # c_R vanishes *before* the shear instability (paper, Sec. III.A): between the two the
    # lattice has c_T,par^2 > 0 but no surface wave, and the solver says so.
    gap = (eq16 < 0) & (r["c2_T_par"] > 0)
    assert gap.any() and np.all(np.isnan(r["c2_R"][gap]))
    eq20 = rayleigh.cauchy_c2(r["c2_L_par"], r["c2_T_par"], r["c2_L_perp"], r["c2_T_perp"])
    np.testing.assert_allclose(r["c2_R"][ok], eq16[ok], rtol=1e-9, atol=1e-13)
    np.testing.assert_allclose(eq20[ok], eq16[ok], rtol=1e-9, atol=1e-13)
    assert rayleigh.triangular_c2(1.0) == pytest.approx((3 - SQ3) / 4, rel=1e-14)


@settings(max_examples=80, deadline=None)
@given(c11=st.floats(1.0, 10.0), c12_frac=st.floats(-0.45, 0.95), c44=st.floats(0.2, 5.0),
       direction=st.sampled_from(["[100]"]))
def test_unstressed_cubic_satisfies_eq21(c11, c12_frac, c44, direction):
    """Eq. (21) (Dobrzynski-Maradudin form): the root we select zeroes its residual along [100]
    of a stable unstressed cubic crystal, and lies below c_T,par."""
    c12 = c12_frac * c11
    m = surfwave.material(c11, c12, c44, 1e9, direction)
    assume(np.isfinite(m["c_R"]))  # no Rayleigh root: not an example of Eq. (21)
    gamma = m["c_R"] ** 2 / c44
    scale = max(1.0, (c11 / c44) ** 3)
    assert abs(rayleigh.unstressed_residual(gamma, c11, c12, c44)) < 1e-9 * scale
    assert gamma < 1.0


LOADINGS = [("fcc", "in_plane_hydrostatic", d) for d in ("[100]", "[110]")] + [
    ("fcc", "uniaxial", d) for d in ("[100]", "[110]")] + [("triangular", "uniaxial", "[10]")]


@settings(max_examples=40, deadline=None)
@given(case=st.sampled_from(LOADINGS), pot=st.sampled_from(["harmonic", "lj"]),
       s=st.floats(0.8, 1.12))
def test_rayleigh_slower_than_transverse_parallel(case, pot, s):
    """Property (paper, after Eq. 24): c_T,par is a rigorous upper bound of c_R whenever a surface wave exists."""
    r = surfwave.point(case[0], case[1], pot, case[2], s)
    if np.isfinite(r["c2_R"][0]):
        assert 0 < r["c2_R"][0] < r["c2_T_par"][0]
        assert r["c2_R"][0] < r["c2_L_par"][0]
    else:
        assert r["wave_type"][0] == "none" and r["reason"][0]


@pytest.mark.parametrize("case", LOADINGS)
@pytest.mark.parametrize("pot", ["harmonic", "lj"])
def test_rayleigh_continuous_in_strain(case, pot):
    """Property: c_R^2 is a continuous function of strain where it exists (no root jumps)."""
    d = np.linspace(0.85, 1.12, 2001)
    c2 = surfwave.point(case[0], case[1], pot, case[2], d)["c2_R"]
    ok = np.isfinite(c2[:-1]) & np.isfinite(c2[1:])
    jumps = np.abs(np.diff(c2))[ok]
    assert jumps.max() < 2e-3, f"jump {jumps.max():.3g}"


@pytest.mark.parametrize("pot", ["harmonic", "lj"])
@pytest.mark.parametrize("direction", ["[100]", "[110]"])
def test_compression_to_instability(pot, direction):
    """Extreme: under compression (in-plane hydrostatic FCC) c_R -> 0 cleanly at s_R, located
    independently as the zero of the Cauchy closed form Eq. (20), just before the shear
    instability s_c (c_T,par^2 = 0): no spurious root below s_R, NaN with a reason instead."""
    point = lambda s: surfwave.point("fcc", "in_plane_hydrostatic", pot, direction, s)

    def eq20(s):
        r = point(s)
        return rayleigh.cauchy_c2(r["c2_L_par"], r["c2_T_par"], r["c2_L_perp"], r["c2_T_perp"])[0]

    s_c = brentq(lambda s: point(s)["c2_T_par"][0], 0.4, 0.999, xtol=1e-15)
    s_R = brentq(eq20, s_c + 1e-12, 0.999, xtol=1e-15)
    assert s_R > s_c  # "vanishing just before the onset of this shear instability"
    eps = np.array([1e-2, 1e-4, 1e-6, 1e-9])
    before = point(s_R + eps)
    assert np.all(before["c2_R"] > 0) and np.all(before["c2_R"] < before["c2_T_par"])
    assert np.all(np.diff(before["c2_R"]) < 0)  # decreasing towards the instability
    assert before["c2_R"][-1] < 1e-6
    between = point(np.linspace(s_c, s_R, 7)[1:-1])
    assert np.all(np.isnan(between["c2_R"])) and np.all(between["c2_T_par"] > 0)
    assert set(between["wave_type"]) == {"none"}
    after = point(s_c - eps)
    assert np.all(np.isnan(after["c2_R"]))
    assert all("c_T,par^2 <= 0" in r for r in after["reason"])


def test_unsquared_condition_rejects_spurious_roots():
    """Root selection: the cubic Eq. (17) has extra real roots in (0, min(a, c)) for some
    crystals; the accepted one satisfies the unsquared G = 0 with p > 0, the others do not."""
    d = np.linspace(0.85, 1.12, 200)
    r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", d)
    S = r["S"]
    args = [S[:, 0, 0, 0, 0], S[:, 0, 1, 0, 1], S[:, 0, 1, 1, 0], S[:, 1, 1, 1, 1], S[:, 1, 1, 0, 0]]
    roots = cubic.real_cubic_roots(*rayleigh.secular_coefficients(*args))
    n_spurious = 0
    for i in range(len(d)):
        for x in roots[i]:
            if 0 < x < min(args[0][i], args[2][i]):
                G, scale = rayleigh.boundary_function(x, *(v[i] for v in args))
                if not np.isclose(x, r["c2_R"][i], rtol=1e-8):
                    n_spurious += 1
                    assert abs(G) > 1e-6 * scale
    assert n_spurious > 0  # the test exercises real spurious roots


def _kappa_discriminant(d_over_d0):
    """s^2 - 4 p^2 of the kappa^2 quadratic at the Rayleigh root (0 where kappa_1 = kappa_2)."""
    r = surfwave.point("triangular", "uniaxial", "harmonic", "[10]", d_over_d0)
    S = r["S"]
    a, b, c, d, f = S[:, 0, 0, 0, 0], S[:, 0, 1, 0, 1], S[:, 0, 1, 1, 0], S[:, 1, 1, 1, 1], S[:, 1, 1, 0, 0]
    X = r["c2_R"]
    s = (b * (c - X) + d * (a - X) - (f + b) ** 2) / (b * d)
    p2 = (a - X) * (c - X) / (b * d)
    return s * s - 4 * p2


def test_nearly_equal_decay_constants():
    """Extreme: kappa_1 = kappa_2 (the long-wave end of the real-to-complex crossover of the
    decay constants; harmonic triangular lattice near d/d0 = 1.043, where theta_c -> 0).
    The boundary condition divides out (kappa_1 - kappa_2) analytically, so c_R stays exact
    there. Reference: Eq. (16) closed form."""
    d_star = brentq(lambda x: _kappa_discriminant([x])[0], 1.0, 1.2, xtol=1e-15)
    assert 1.03 < d_star < 1.06
    d = d_star + np.array([-1e-3, -1e-7, -1e-12, 0.0, 1e-12, 1e-7, 1e-3])
    r = surfwave.point("triangular", "uniaxial", "harmonic", "[10]", d)
    np.testing.assert_allclose(r["c2_R"], rayleigh.triangular_c2(d), rtol=1e-12)
    out = rayleigh.solve(r["S"])
    k1, k2 = out["kappa1"], out["kappa2"]
    assert np.all(np.isfinite(k1)) and np.all(k1.real > 0) and np.all(k2.real > 0)
    assert abs(k1[3] - k2[3]) < 1e-6 * abs(k1[3])     # coalesced at d_star
    assert np.all(np.abs(k1.imag[:2]) == 0)            # real pair on one side ...
    assert np.all(np.abs(k1.imag[-2:]) > 0)            # ... complex-conjugate pair on the other


def test_no_root_gives_nan_with_reason_not_crash():
    """A point without any admissible root (c_T,par^2 < 0, or zero shear) gives NaN + reason."""
    S = isotropic_S(1.0, 1.0)
    S[0, 1, 1, 0] = -0.1
    out = rayleigh.solve(S)
    assert np.isnan(out["c2_R"]) and out["wave_type"].item() == "none"
    assert "c_T,par" in out["reason"].item()


def test_vectorised_over_leading_axes():
    """rayleigh_c2 keeps leading shapes and treats each entry independently."""
    S = np.broadcast_to(isotropic_S(1.0, 1.0), (4, 5, 2, 2, 2, 2)).copy()
    S[1, 2] *= 2.0
    out = rayleigh.rayleigh_c2(S)
    assert out.shape == (4, 5)
    assert out[1, 2] == pytest.approx(2 * out[0, 0], rel=1e-12)
    assert rayleigh.rayleigh_c2(np.zeros((0, 3, 3, 3, 3))).shape == (0,)
    assert rayleigh.solve(np.zeros((2, 0, 2, 2, 2, 2)))["c2_R"].shape == (2, 0)


def test_cubic_roots_match_numpy():
    """The vectorised closed-form real cubic solver finds exactly the real roots numpy.roots finds
    (random cubics, plus a triple root and a double root)."""
    rng = np.random.default_rng(1)
    coef = np.vstack([rng.normal(size=(300, 4)), [[1, -3, 3, -1], [1, -4, 5, -2]]])
    ours = cubic.real_cubic_roots(*coef.T)
    for c, mine in zip(coef, ours):
        ref = np.roots(c)
        real = np.sort(ref[np.abs(ref.imag) < 1e-7].real)
        got = np.sort(mine[np.isfinite(mine)])
        if real.size == got.size:
            np.testing.assert_allclose(got, real, rtol=1e-5, atol=1e-5)
        else:  # only near-degenerate pairs may be classified differently
            assert np.min(np.abs(ref.imag)[np.abs(ref.imag) > 0]) < 1e-4


def test_material_stress_enters_through_A11():
    """An in-plane stress sigma_xx changes c_T,par^2 by sigma/rho (Eq. A11: S_xyyx = C44 + sigma_xx)."""
    base = surfwave.material(100.0, 60.0, 50.0, 8000.0, "[100]")
    pushed = surfwave.material(100.0, 60.0, 50.0, 8000.0, "[100]", stress=-5.0)
    assert pushed["c_T_par"] ** 2 == pytest.approx(base["c_T_par"] ** 2 - 5e9 / 8000.0, rel=1e-12)
    assert pushed["c_R"] < base["c_R"]


@settings(max_examples=40, deadline=None)
@given(case=st.sampled_from(LOADINGS), pot=st.sampled_from(["harmonic", "lj", "morse"]),
       s=st.floats(0.85, 1.15))
def test_general_solver_equals_cauchy_eq20_for_pair_forces(case, pot, s):
    """Eq. (20) (independent closed form, valid for pair forces with sigma_yy = 0 where
    S_xyxy = S_yyxx) equals the general Eq. (17) solver with root selection, every loading."""
    r = surfwave.point(case[0], case[1], pot, case[2], s)
    S = r["S"][0]
    assert S[0, 1, 0, 1] == pytest.approx(S[1, 1, 0, 0], abs=1e-12)  # Cauchy relation
    eq20 = rayleigh.cauchy_c2(r["c2_L_par"], r["c2_T_par"], r["c2_L_perp"], r["c2_T_perp"])[0]
    if np.isfinite(r["c2_R"][0]):
        assert r["c2_R"][0] == pytest.approx(eq20, rel=1e-9, abs=1e-12)
    else:  # no surface wave: Eq. (20) gives no admissible value either
        assert not (0 < eq20 < r["c2_T_par"][0]) or r["c2_T_perp"][0] <= 0


def _cubic(C11, C12, C44):
    return voigt_to_tensor(cubic_voigt(C11, C12, C44))


def _orthotropic_prestressed(n, rng, cauchy=False):
    """Random orthotropic C (Voigt, lab axes) with in-plane prestress sigma_xx, sigma_zz; (S, A), each
    (n, 3, 3, 3, 3). ``cauchy``: C12 = C66, so that S_xyxy = S_yyxx (sigma_yy = 0, Eq. A11)."""
    C11, C22, C33 = rng.uniform(1.0, 3.0, (3, n))
    C44, C55, C66 = rng.uniform(0.2, 1.0, (3, n))
    V = np.zeros((n, 6, 6))
    V[:, 0, 0], V[:, 1, 1], V[:, 2, 2] = C11, C22, C33
    V[:, 0, 1] = V[:, 1, 0] = C66 if cauchy else rng.uniform(-0.4, 0.8, n) * np.sqrt(C11 * C22)
    V[:, 0, 2] = V[:, 2, 0] = V[:, 1, 2] = V[:, 2, 1] = rng.uniform(0.0, 0.5, n)
    V[:, 3, 3], V[:, 4, 4], V[:, 5, 5] = C44, C55, C66
    C = voigt_to_tensor(V)
    sig = np.zeros((n, 3, 3))
    sig[:, 0, 0] = rng.uniform(-1.2 if cauchy else -0.25, 0.5 if cauchy else 0.25, n) * C66
    sig[:, 2, 2] = rng.uniform(-0.3, 0.3, n)
    return elastic.stress_derivatives(sig, C), stroh.wave_propagation_tensor(C, sig)


def test_non_cauchy_orthotropic_against_stroh_route():
    """Independent route: prestressed orthotropic crystals without the Cauchy relation
    (S_xyxy != S_yyxx), Eq. (17) on the 3D S against the Stroh/impedance root search of
    stroh.surface_wave on A = C + sigma delta (2 x 2 sagittal blocks, Eq. 17 switched off)."""
    S, A = _orthotropic_prestressed(300, np.random.default_rng(7))
    assert np.abs(S[:, 0, 1, 0, 1] - S[:, 1, 1, 0, 0]).min() > 1e-3   # really not Cauchy
    ref = stroh.surface_wave(A[:, :2, :2, :2, :2], 1.0, mirror=False)["c"] ** 2
    c2 = rayleigh.rayleigh_c2(S)
    np.testing.assert_array_equal(np.isfinite(c2), np.isfinite(ref))
    assert np.isfinite(c2).sum() > 250
    np.testing.assert_allclose(c2, ref, rtol=1e-11)


def test_cauchy_tensors_equal_eq20_across_blocks():
    """Eq. (20) (closed form from the four speeds of the same S) for 20000 random Cauchy-relation
    tensors, several vectorised blocks of rayleigh_c2; where Eq. (17) has no admissible root, Eq. (20)
    gives no speed in (0, c_T,par^2) either. Also the block loop against single-point calls."""
    S, _ = _orthotropic_prestressed(20000, np.random.default_rng(11), cauchy=True)
    assert S.shape[0] > 2 * rayleigh.BLOCK
    np.testing.assert_allclose(S[:, 0, 1, 0, 1], S[:, 1, 1, 0, 0], rtol=1e-15)
    c2 = rayleigh.rayleigh_c2(S)
    eq20 = rayleigh.cauchy_c2(S[:, 0, 0, 0, 0], S[:, 0, 1, 1, 0], S[:, 1, 1, 1, 1], S[:, 0, 1, 0, 1])
    ok = np.isfinite(c2)
    assert 0.5 < ok.mean() < 0.95
    np.testing.assert_allclose(c2[ok], eq20[ok], rtol=1e-9, atol=1e-12)
    assert not np.any((eq20[~ok] > 0) & (eq20[~ok] < S[~ok, 0, 1, 1, 0]))
    some = np.arange(0, S.shape[0], 997)
    np.testing.assert_array_equal([rayleigh.rayleigh_c2(s) for s in S[some]], c2[some])


def test_boundary_function_factorises():
    """Algebra (module docstring): the four-term G equals e [A (c - b - X) + p (d A - f^2)],
    e = f + b, A = a - X, p = sqrt(A (c - X) / (b d)), on random X inside (0, min(a, c))."""
    a, b, c, d, f = np.random.default_rng(2).uniform(0.1, 2.0, (5, 1000))
    X = np.random.default_rng(4).uniform(0, 1, 1000) * np.minimum(a, c)
    G, scale = rayleigh.boundary_function(X, a, b, c, d, f)
    A = a - X
    factored = (f + b) * (A * (c - b - X) + np.sqrt(A * (c - X) / (b * d)) * (d * A - f * f))
    assert np.all(np.abs(G - factored) <= 1e-13 * scale)


def _real_numpy_roots(c, tol):
    r = np.roots(c)
    return np.sort(r[np.abs(r.imag) <= tol * np.maximum(1.0, np.abs(r))].real)


@functools.lru_cache(maxsize=None)
def _mp_roots(c: tuple) -> np.ndarray:
    """All roots of the cubic c (highest power first) to 40 digits (mpmath), complex."""
    import mpmath as mp

    with mp.workdps(60):
        return np.array([complex(r) for r in mp.polyroots([mp.mpf(v) for v in c], maxsteps=400, extraprec=400)])


NEAR_DEGENERATE = [
    [1, -4, 5, -2],                 # (x - 1)^2 (x - 2): double root
    [1, -4, 5, -2 + 1e-13],         # ... split into a close pair or a complex pair
    [1, -4, 5, -2 - 1e-13],
    [8, -12, 6, -1],                # (2x - 1)^3: triple root
    [1, 0, -3, 2],                  # (x - 1)^2 (x + 2): discriminant exactly 0
    [1, 0, -3, 2 + 4e-16],
    [1, 0, -3, 2 - 4e-16],
    [1, 0, -3, -2],                 # (x + 1)^2 (x - 2)
    [1e-14, 1, -3, 2],              # vanishing leading coefficient: the numpy.roots path
    [1e-10, 1, -3, 2],              # tiny: a root near -1e10 and the quadratic's (numpy.roots)
    [2e-4, -1, 1e-3, -1e-7],        # small but kept: roots 1e-4, 9e-4 and 5e3 (closed form)
    [1, 1e-9, 1e-18, 0],            # clustered tiny roots
    [3, 0, 0, 0],                   # triple root at 0
]


@pytest.mark.parametrize("scale", [1.0, 1e30, 1e-30])
def test_cubic_roots_near_degenerate_against_numpy(scale):
    """References: numpy.roots (companion-matrix eigenvalues) for 200 random cubics with one or
    three real roots, and 60-digit mpmath roots for near-degenerate ones (double, triple and
    split double roots, discriminant ~ 0, tiny leading coefficient, clustered roots), all in one
    vectorised call of the closed forms (trigonometric / Cardano + Newton), in any units.
    Every root returned is a root (tiny residual) near a true root (or the real part of a pair
    split by rounding); every true real root apart from the others is found; random cubics
    give numpy's real roots."""
    rng = np.random.default_rng(3)
    rand = rng.normal(size=(200, 4))
    coef = np.vstack([NEAR_DEGENERATE, rand]) * scale
    ours = cubic.real_cubic_roots(*coef.T)
    assert ours.shape == (len(coef), 3)
    for k, (c, mine) in enumerate(zip(coef, ours)):
        got = np.sort(mine[np.isfinite(mine)])
        assert got.size >= 1                                   # a real cubic has a real root
        size = np.abs(c[0]) * np.abs(got) ** 3 + np.abs(c[1]) * got**2 + np.abs(c[2]) * np.abs(got) + np.abs(c[3])
        assert np.all(np.abs(np.polyval(c, got)) <= 1e-12 * size), (k, c, got)
        if k < len(NEAR_DEGENERATE):
            true = _mp_roots(tuple(float(v) for v in NEAR_DEGENERATE[k]))
            near_real = true[np.abs(true.imag) <= 1e-6 * np.maximum(1.0, np.abs(true))]
            for x in got:                                      # near a true (or split) root
                assert np.min(np.abs(near_real.real - x)) <= 2e-5 * max(1.0, abs(x)), (k, got, true)
            real = true[true.imag == 0].real
            for r in real:                                     # isolated real roots are found
                if np.sum(np.abs(real - r) <= 1e-4 * max(1.0, abs(r))) == 1:
                    assert np.min(np.abs(got - r)) <= 1e-9 * max(1.0, abs(r)), (k, got, r)
        else:
            ref = _real_numpy_roots(c, 1e-7)
            if ref.size == got.size:
                np.testing.assert_allclose(got, ref, rtol=1e-9, atol=1e-9 * scale ** 0)
            else:  # only near-degenerate pairs may be classified differently
                z = np.roots(c)
                assert np.min(np.abs(z.imag)[np.abs(z.imag) > 0]) < 1e-4


def test_orthotropy_check_exact_at_the_tolerance_and_mixed_scales():
    """SymmetryError exactly where the definition says (largest must-vanish component above
    ORTHOTROPY_TOL times max |S| of its point): components at 0.5 tol pass, also in a batch
    mixing S in Pa with reduced units (the one-pass bound fails there, the point-by-point test
    decides); 2 tol at one point is named with its point; a NaN point does not hide it."""
    S = np.broadcast_to(isotropic_S(1.0, 1.0, 3), (6, 3, 3, 3, 3)).copy()
    S[3] *= 1e9                                                # Pa next to reduced units
    tol = rayleigh.ORTHOTROPY_TOL
    S[:, 0, 0, 0, 1] = 0.5 * tol * np.abs(S).max(axis=(1, 2, 3, 4))
    ok = rayleigh.rayleigh_c2(S)
    np.testing.assert_allclose(ok[3], 1e9 * ok[0], rtol=1e-12)
    S[4, 0, 2, 1, 1] = 2 * tol * 3.0
    with pytest.raises(SymmetryError, match=r"at point \(np.int64\(4\),\)|at point \(4,\)") as err:
        rayleigh.rayleigh_c2(S)
    assert "S_xzyy" in str(err.value)
    S[1, 1, 1, 1, 1] = np.nan
    with pytest.raises(SymmetryError, match="S_xzyy"):
        rayleigh.rayleigh_c2(S)
    assert np.isnan(rayleigh.rayleigh_c2(S[:2])[1])           # NaN in, NaN out (no error)
    many = np.broadcast_to(isotropic_S(1.0, 1.0, 3), (13, 3, 3, 3, 3))  # 8 points per einsum row + 5
    for k in (3, 11):
        bad = many.copy()
        bad[k, 1, 2, 2, 2] = 1e-8
        with pytest.raises(SymmetryError, match=f"{k}.*S_yzzz"):
            rayleigh.rayleigh_c2(bad)
