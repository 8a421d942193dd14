"""General (Stroh/impedance) surface-wave solver: closed forms, Eq. (17), another route, extremes.

Constants typed here (the materials database is a separate module):
copper C11, C12, C44 = 168.4, 121.4, 75.4 GPa, rho = 8960 kg/m^3 (README, docs/materials.md);
lead 49.5, 42.3, 14.9 GPa (Kittel, Introduction to Solid State Physics, table of cubic elastic
constants, 4.95, 4.23, 1.49 x 10^11 dyn/cm^2), rho = 11340 kg/m^3 (CRC handbook, 11.34 g/cm^3).
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import brentq

import surfwave
from surfwave.errors import InputError, SymmetryError
from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.solvers import impedance, rayleigh, stroh
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.tensors import cubic_voigt, rotate4, voigt_to_tensor

CU = dict(C11=168.4, C12=121.4, C44=75.4, rho=8960.0)
PB = dict(C11=49.5, C12=42.3, C44=14.9, rho=11340.0)


def _cubic_A(C11, C12, C44, surface="(001)", direction=0.0):
    return rotate4(voigt_to_tensor(cubic_voigt(C11, C12, C44)), lab_axes(surface, direction))


def _classical_xi(r: float) -> float:
    """Root xi = c_R^2/c_T^2 of (2 - xi)^2 = 4 sqrt(1 - xi) sqrt(1 - r xi), r = c_T^2/c_L^2 (textbook)."""
    return brentq(lambda x: (2 - x) ** 2 - 4 * np.sqrt(1 - x) * np.sqrt(1 - r * x), 1e-12, 1 - 1e-15, xtol=1e-16)


@pytest.mark.parametrize("scale", [1.0, 1e9, 1e-3])
@pytest.mark.parametrize("mirror", [None, False])
def test_isotropic_exact_speed_polarisation_decay(scale, mirror):
    """Isotropic, Poisson ratio 1/4 (lambda = mu = 1): c_R = sqrt(2 - 2/sqrt 3) (docs/physics/paper.md), at an
    arbitrary angle; polarisation |u1/u2| = (2 - xi)/(2 q) with u1 90 deg ahead (potential theory,
    q = sqrt(1 - xi/3), s = sqrt(1 - xi)); decay p = i q, i s, i s (the SH pair degenerate with the
    SV one: a degenerate Stroh eigenvalue); depth 1/(2 pi s). Both routes (Eq. 17 and Stroh with
    the mirror ignored), in reduced units, Pa and 1e-3 scale."""
    A = _cubic_A(3.0, 1.0, 1.0, direction=17.0) * scale
    r = stroh.surface_wave(A, scale, mirror=mirror)
    xi = 2 - 2 / np.sqrt(3)
    assert r["c"] == pytest.approx(np.sqrt(xi), rel=1e-12)
    assert r["c_limit"] == pytest.approx(1.0, rel=1e-12)
    assert r["wave_type"] == "surface" and r["reason"] == ""
    q, s = np.sqrt(1 - xi / 3), np.sqrt(1 - xi)
    u = r["polarisation"]
    assert u[0] / u[1] == pytest.approx(1j * (2 - xi) / (2 * q), rel=1e-9)
    assert abs(u[2]) < 1e-12 and np.linalg.norm(u) == pytest.approx(1.0, rel=1e-12)
    p = r["decay"]
    got = np.sort(p[np.isfinite(p)].imag)
    np.testing.assert_allclose(got, np.sort([s, s, q])[: got.size], rtol=1e-9)
    assert r["penetration_depth"] == pytest.approx(1 / (2 * np.pi * s), rel=1e-9)


@pytest.mark.parametrize("nu", [-0.5, 0.0, 0.2, 0.45, 0.49])
def test_isotropic_any_poisson_ratio_stroh_route(nu):
    """Any Poisson ratio through the coupled 3 x 3 Stroh search (mirror ignored): matches the
    textbook Rayleigh equation solved by bisection to 1e-12."""
    mu = 1.0
    lam = 2 * mu * nu / (1 - 2 * nu)
    A = _cubic_A(lam + 2 * mu, lam, mu, direction=33.0)
    r = stroh.surface_wave(A, 1.0, mirror=False)
    assert r["c"] ** 2 == pytest.approx(_classical_xi(mu / (lam + 2 * mu)), rel=1e-12)


def test_nearly_isotropic_is_continuous():
    """Anisotropy 1 + 1e-9 at a non-mirror angle (nearly degenerate Stroh eigenvalues): the
    speed moves by O(1e-9) from the exact isotropic value, no loss of accuracy, same type."""
    xi = 2 - 2 / np.sqrt(3)
    for eps in (1e-12, 1e-9, 1e-6):
        r = stroh.surface_wave(_cubic_A(3.0, 1.0, 1.0 + eps, direction=22.0), 1.0)
        assert r["wave_type"] == "surface"
        assert abs(r["c"] / np.sqrt(xi) - 1) < 2 * eps + 1e-13


LOADINGS = [("in_plane_hydrostatic", d) for d in ("[100]", "[110]")] + [("uniaxial", d) for d in ("[100]", "[110]")]


@pytest.mark.parametrize("loading, direction", LOADINGS)
@pytest.mark.parametrize("potential", ["harmonic", "lj", "morse"])
def test_mirror_directions_reproduce_eq17(loading, direction, potential):
    """Eq. (17) (rayleigh_c2 with its root selection, S of Eq. A11) versus A_ijkl = C_ijkl +
    sigma_jl delta_ik with the nominal-traction condition solved by the Stroh impedance route
    (the sagittal 2 x 2 blocks, Eq. 17 switched off), FCC strains 0.93-1.06: 1e-12 relative;
    for subsonic points also the full coupled 3 x 3 search."""
    s = np.linspace(0.93, 1.06, 14)
    p = surfwave.point("fcc", loading, potential, direction, s)
    crystal = build("fcc", loading, potential, direction, s)
    A = stroh.wave_propagation_tensor(p["C"], elastic.stress(crystal.bonds, potential))
    ref = rayleigh.rayleigh_c2(p["S"])
    sag = stroh.surface_wave(A[:, :2, :2, :2, :2], 1.0, mirror=False)
    ok = np.isfinite(ref)
    assert ok.sum() >= 8
    np.testing.assert_allclose(sag["c"][ok] ** 2, ref[ok], rtol=1e-12)
    assert np.all(np.isnan(sag["c"][~ok]))
    full = stroh.surface_wave(A, 1.0, mirror=False)
    sub = ok & (full["wave_type"] == "surface")
    np.testing.assert_allclose(full["c"][sub] ** 2, ref[sub], rtol=1e-12)
    assert np.all((p["wave_type"][ok] == "surface") <= sub[ok])  # every subsonic point was found


def test_triangular_lattice_2d():
    """2D triangular lattice (d = 2): the Stroh route equals Eq. (16) to 1e-12 (closed form)."""
    d = np.linspace(0.8, 1.2, 9)
    p = surfwave.point("triangular", "uniaxial", "harmonic", "[10]", d)
    crystal = build("triangular", "uniaxial", None, "[10]", d)
    A = stroh.wave_propagation_tensor(p["C"], elastic.stress(crystal.bonds, "harmonic"))
    r = stroh.surface_wave(A, 1.0, mirror=False)
    np.testing.assert_allclose(r["c"] ** 2, rayleigh.triangular_c2(d), rtol=1e-12)


def test_copper_readme_value_and_limit():
    """README: unstressed Cu (001)[100] c_R = 2012.12 m/s; v_L along [100] is the SH... here the
    slow transverse bulk wave of the sagittal plane at p != 0: checked as the minimum of the
    bulk trace velocity over a fine grid of wave normals (brute force, independent of the
    solver's parabolic refinement)."""
    r = surfwave.material(**CU, direction="[100]")
    assert round(r["c_R"], 2) == 2012.12
    A = _cubic_A(CU["C11"], CU["C12"], CU["C44"]) * 1e9
    Q, R, T = impedance.stroh_blocks(A[None])
    phi = np.linspace(-np.pi / 2 + 1e-6, np.pi / 2 - 1e-6, 200001)
    lam = np.linalg.eigvalsh(impedance.acoustic(Q, R, T, phi[None]))[0, :, 0] / np.cos(phi) ** 2
    assert r["c_limit"] == pytest.approx(np.sqrt(lam.min() / CU["rho"]), rel=1e-9)


def _stroh_by_eigenvectors(A, X):
    """Another route: Stroh eigenvectors (scipy), the 3 decaying ones, B = traction matrix;
    returns the smallest singular value of B over its largest and the displacement A c."""
    Q, R, T = (m[0] for m in impedance.stroh_blocks(A[None]))
    N = impedance.stroh_matrix(Q[None], R[None], T[None], np.array([X]))[0]
    w, v = scipy.linalg.eig(N)
    up = v[:, w.imag > 0]
    a, b = up[:3], up[3:]
    _, sv, vh = np.linalg.svd(b)
    u = a @ vh[-1].conj()
    return sv[-1] / sv[0], u / np.linalg.norm(u)


@pytest.mark.parametrize("surface, angle", [("(001)", 20.0), ("(110)", 37.0), ("(111)", 10.0)])
def test_non_mirror_root_by_eigenvector_route(surface, angle):
    """Another route for non-mirror directions of Cu: at the solver's c_R the traction matrix
    B of the decaying Stroh eigenvectors (computed with scipy's eig, not the projector) is
    singular, and its null displacement is the solver's polarisation (up to phase)."""
    A = _cubic_A(CU["C11"], CU["C12"], CU["C44"], surface, angle)
    r = stroh.surface_wave(A, CU["rho"] * 1e-9)
    assert r["wave_type"] == "surface" and not r["mirror"]
    X = r["c"] ** 2 * CU["rho"] * 1e-9
    smin, u = _stroh_by_eigenvectors(A, X)
    assert smin < 1e-9
    assert abs(np.vdot(u, r["polarisation"])) == pytest.approx(1.0, abs=1e-9)
    smin_off, _ = _stroh_by_eigenvectors(A, X * (1 - 1e-4))
    assert smin_off > 1e3 * smin


def test_symmetry_of_speed_versus_angle():
    """Cubic symmetry: on (001) c_R(theta) has period 90 deg with mirrors at 0 and 45
    (c(-t) = c(t), c(45 + t) = c(45 - t)); on (111) period 60 with a mirror at 90 ([11-2])."""
    t = np.array([3.0, 11.0, 17.5, 29.0, 38.0])
    c = lambda s, a: surfwave.material(**CU, angle=a, surface=s)["c_R"]
    np.testing.assert_allclose(c("(001)", -t), c("(001)", t), rtol=1e-11)
    np.testing.assert_allclose(c("(001)", t + 90), c("(001)", t), rtol=1e-11)
    np.testing.assert_allclose(c("(001)", 45 + t / 4), c("(001)", 45 - t / 4), rtol=1e-11)
    np.testing.assert_allclose(c("(111)", t + 60), c("(111)", t), rtol=1e-11)
    np.testing.assert_allclose(c("(111)", 90 + t), c("(111)", 90 - t), rtol=1e-11)


def test_either_side_of_a_mirror_and_merging_into_the_bulk():
    """Cu (001): at 0 deg +- 1e-6 the coupled solver continues Eq. (17) (to 1e-11); toward
    45 deg the surface wave merges into the bulk: v_L - c_R decreases monotonically to 0
    with no NaN or spurious root before, c_R <= v_L; at exactly 45 deg the mirror makes it
    supersonic_decoupled (Eq. 17), and 1e-6 deg off it is subsonic and within 1e-12 of v_L or none."""
    r0 = surfwave.material(**CU, angle=[-1e-6, 0.0, 1e-6])
    np.testing.assert_allclose(r0["c_R"], r0["c_R"][1], rtol=1e-11)
    assert list(r0["method"]) == ["stroh", "eq17", "stroh"]
    a = np.linspace(40.0, 44.9, 50)
    r = surfwave.material(**CU, angle=a)
    gap = (r["c_limit"] - r["c_R"]) / r["c_limit"]
    assert np.all(np.isfinite(gap)) and np.all(gap >= 0) and np.all(np.diff(gap) < 0)
    assert gap[-1] < 1e-8
    r45 = surfwave.material(**CU, angle=[45.0 - 1e-6, 45.0, 45.0 + 1e-6])
    assert r45["wave_type"][1] == "supersonic_decoupled" and r45["c_R"][1] > r45["c_limit"][1]
    for i in (0, 2):
        assert r45["wave_type"][i] in ("surface", "pseudo")
        if r45["wave_type"][i] == "surface":
            assert r45["c_R"][i] == pytest.approx(r45["c_limit"][i], rel=1e-11)
    np.testing.assert_allclose(r45["c_limit"], r45["c_limit"][1], rtol=1e-11)
    # within ~0.03 deg of the mirror the subsonic root is closer to v_L than 1e-12: flagged pseudo
    r99 = surfwave.material(**CU, angle=44.99)
    assert r99["wave_type"] == "pseudo" and np.isnan(r99["c_R"]) and "pseudo-surface" in r99["reason"]


def test_strongly_anisotropic_lead():
    """Pb (Zener ratio 4.1): c_R < v_L off the mirrors, Eq. (17) at 0 and 45 deg equals the
    Stroh route (sagittal blocks) to 1e-12, and the speeds vary smoothly with angle."""
    a = np.linspace(0.0, 45.0, 19)
    r = surfwave.material(**PB, angle=a)
    assert r["wave_type"][0] == "surface" and r["wave_type"][-1] == "supersonic_decoupled"
    assert np.all(r["c_R"][:-1] <= r["c_limit"][:-1])
    for angle in (0.0, 45.0):
        A = _cubic_A(PB["C11"], PB["C12"], PB["C44"], direction=angle)
        sag = stroh.surface_wave(A[:2, :2, :2, :2], PB["rho"] * 1e-9, mirror=False)
        ref = surfwave.material(**PB, angle=angle)["c_R"]
        assert sag["c"] == pytest.approx(ref, rel=1e-12)


def test_born_unstable_gives_nan_reason_and_not_stable():
    """C11 = 50, C12 = -80 GPa: C11 + 2 C12 < 0, a negative bulk modulus (Born criteria for cubic
    crystals: C11 - C12 > 0, C11 + 2 C12 > 0, C44 > 0)."""
    r = surfwave.material(50.0, -80.0, 30.0, 5000.0, "[100]")
    assert np.isnan(r["c_R"]) and r["stable"] is False and r["wave_type"] == "none"
    assert "Born" in r["reason"]


def test_bad_input_refused_with_names():
    with pytest.raises(InputError, match="looks like Pa"):
        surfwave.material(168.4e9, 121.4e9, 75.4e9, 8960.0, "[100]")
    with pytest.raises(InputError, match=r"\[111\].*\(001\)"):
        surfwave.material(**CU, direction="[111]")
    with pytest.raises(InputError, match="sigma_23"):
        C = voigt_to_tensor(cubic_voigt(1.0, 0.5, 0.4))
        stroh.wave_propagation_tensor(C, np.array([[0, 0, 0], [0, 0, 0.1], [0, 0.1, 0]]))
    with pytest.raises(InputError, match="traction"):
        surfwave.material(**CU, direction="[100]", stress=np.diag([1.0, 0.0, 1.0]))
    with pytest.raises(InputError, match="major symmetry"):
        A = voigt_to_tensor(cubic_voigt(3.0, 1.0, 1.0))
        A[0, 0, 1, 1] += 0.1
        stroh.surface_wave(A)


def test_stress_tensor_equals_scalar_uniaxial():
    """A 3 x 3 stress sigma x1 x1 (crystal axes) equals the scalar uniaxial stress along x1."""
    x1 = lab_axes("(001)", 30.0)[0]
    a = surfwave.material(**CU, angle=30.0, stress=-1.5)
    b = surfwave.material(**CU, angle=30.0, stress=-1.5 * np.outer(x1, x1))
    assert a["c_R"] == pytest.approx(b["c_R"], rel=1e-13)
    assert a["c_R"] != pytest.approx(surfwave.material(**CU, angle=30.0)["c_R"], rel=1e-4)


def test_voigt_input_equals_cubic_constants():
    """voigt= with the cubic 6x6 matrix gives the same answer as C11, C12, C44 (any surface)."""
    C6 = cubic_voigt(CU["C11"], CU["C12"], CU["C44"])
    a = surfwave.material(voigt=C6, rho=CU["rho"], direction="[1-10]", surface="(111)")
    b = surfwave.material(**CU, direction="[1-10]", surface="(111)")
    assert a["c_R"] == pytest.approx(b["c_R"], rel=1e-14)


def test_rayleigh_c2_refuses_non_orthotropic_and_is_scale_invariant(monkeypatch):
    """rayleigh_c2 names the components that break the sagittal mirror/orthotropy; a single
    tensor in Pa works and a batch in Pa takes the vectorised path (np.roots, the per-point
    fallback for a degenerate cubic, is never called), equal to the GPa result."""
    with pytest.raises(SymmetryError, match="S_"):
        rayleigh.rayleigh_c2(_cubic_A(CU["C11"], CU["C12"], CU["C44"], direction=22.5))
    S = _cubic_A(CU["C11"], CU["C12"], CU["C44"])
    monkeypatch.setattr(np, "roots", lambda *a: (_ for _ in ()).throw(AssertionError("slow path")))
    one = np.sqrt(rayleigh.rayleigh_c2(S * 1e9, CU["rho"]))
    assert one == pytest.approx(2012.1220619, rel=1e-9)
    batch = np.sqrt(rayleigh.rayleigh_c2(np.broadcast_to(S * 1e9, (50, 3, 3, 3, 3)), CU["rho"]))
    np.testing.assert_allclose(batch, np.sqrt(rayleigh.rayleigh_c2(S, CU["rho"] * 1e-9)), rtol=1e-14)


def test_point_angles_shapes_and_mirror_consistency():
    """point() with angles: shape (strain, angle); at 0 and 45 deg it equals the "[100]" and
    "[110]" results (Eq. 17) to 1e-12; a Miller string in (001) equals its angle."""
    s = [0.97, 1.0, 1.03]
    r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", np.array([0.0, 20.0, 45.0]), s)
    assert r["c2_R"].shape == (3, 3) and r["polarisation"].shape == (3, 3, 3) and r["stable"].shape == (3,)
    for j, d in ((0, "[100]"), (2, "[110]")):
        ref = surfwave.point("fcc", "in_plane_hydrostatic", "lj", d, s, details=True)
        np.testing.assert_allclose(r["c2_R"][:, j], ref["c2_R"], rtol=1e-12)
        np.testing.assert_allclose(r["c2_limit"][:, j], ref["c2_limit"], rtol=1e-12)
    a = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[210]", s)
    b = surfwave.point("fcc", "in_plane_hydrostatic", "lj", float(np.degrees(np.arctan(0.5))), s)
    np.testing.assert_allclose(a["c2_R"], b["c2_R"], rtol=1e-12)
    with pytest.raises(InputError, match="load_direction"):
        surfwave.point("fcc", "uniaxial", "lj", 20.0, s)


def test_random_triclinic_crystals():
    """Triclinic media (random positive definite Voigt stiffness, no symmetry at all): every
    direction has a subsonic surface wave (Barnett-Lothe existence for a positive definite
    stiffness without exceptional limiting waves), confirmed by the scipy-eigenvector route."""
    rng = np.random.default_rng(3)
    B = rng.normal(size=(20, 6, 6))
    A = voigt_to_tensor(B @ np.swapaxes(B, 1, 2) + 2 * np.eye(6))
    r = stroh.surface_wave(A, 1.0)
    assert np.all(r["wave_type"] == "surface") and not r["mirror"].any()
    assert np.all(r["c"] < r["c_limit"])
    for i in range(0, 20, 4):
        smin, u = _stroh_by_eigenvectors(A[i], r["c"][i] ** 2)
        assert smin < 1e-9
        assert abs(np.vdot(u, r["polarisation"][i])) == pytest.approx(1.0, abs=1e-8)


def test_point_details_are_extra_outputs_only():
    """point(details=False) (the default) at mirror directions skips the Stroh solve: the
    same c2_R, wave type, speeds and stability as with details=True (the reference, which
    adds c2_limit, polarisation, decay and penetration depth), and none of those four keys."""
    s = np.linspace(0.9, 1.08, 25)
    for case in (("fcc", "in_plane_hydrostatic", "lj", "[110]"), ("fcc", "uniaxial", "harmonic", "[100]"),
                 ("triangular", "uniaxial", "lj", "[10]")):
        lean, full = surfwave.point(*case, s), surfwave.point(*case, s, details=True)
        for key in ("c2_R", "c2_L_par", "c2_T_par", "c2_SH", "stress"):
            np.testing.assert_array_equal(lean[key], full[key])
        assert (lean["wave_type"] == full["wave_type"]).all() and (lean["stable"] == full["stable"]).all()
        assert not {"c2_limit", "polarisation", "decay", "penetration_depth"} & set(lean)
        assert np.isfinite(full["c2_limit"]).any()


def test_decay_pair_order_does_not_follow_rounding():
    """Cu (001) along [100] is a mirror direction: the sagittal decay constants come as a pair
    p, -conj(p) with equal Im p. Their order must not depend on rounding of the input: a
    relative change of 1e-13 in the stiffness (the level at which the lateral-stretch solve or
    a rotation may differ) leaves the decay constants where they were (reference: the
    unperturbed solve)."""
    A = _cubic_A(CU["C11"], CU["C12"], CU["C44"])
    ref = stroh.surface_wave(A, CU["rho"], mirror=False)
    pair = ref["decay"][np.isfinite(ref["decay"])]
    assert pair.size >= 2 and abs(pair[0].imag - pair[1].imag) < 1e-9 * abs(pair[0])  # a +-Re pair
    rng = np.random.default_rng(1)
    for _ in range(5):
        noise = 1 + 1e-13 * rng.standard_normal(A.shape)
        got = stroh.surface_wave(A * noise, CU["rho"], mirror=False)
        np.testing.assert_allclose(got["decay"], ref["decay"], rtol=1e-9, atol=1e-12)


def test_tracked_stroh_roots_equal_eigenvalues_of_n():
    """The root search refines the decaying p of its last step by Newton on the Stroh
    polynomial det(Q - X + p (R + R^T) + p^2 T) instead of the eigenvalues of N. Reference:
    numpy's eigenvalues of N (LAPACK) for random triclinic media at X = X_L / 2: the
    polynomial's roots (numpy.roots) are N's eigenvalues; tracking from guesses off by 1e-2
    returns the decaying ones, and the impedance, its lowest eigenvalue and derivative are those
    of the eigenvalue route. Guesses collapsing onto one root, or X above X_L (real roots), are
    refused (ok False) so that the caller falls back to the eigenvalues."""
    rng = np.random.default_rng(5)
    B = rng.normal(size=(12, 6, 6))
    A = voigt_to_tensor(B @ np.swapaxes(B, 1, 2) + 2 * np.eye(6))
    A = A / np.abs(A).max(axis=(1, 2, 3, 4), keepdims=True)
    Q, R, T = impedance.stroh_blocks(A)
    X = 0.5 * impedance.limiting_x(Q, R, T)[0]
    c = impedance.stroh_polynomial(Q, R, T, X)
    ev = np.linalg.eigvals(impedance.stroh_matrix(Q, R, T, X))
    up = np.sort_complex(np.where(ev.imag > 0, ev, np.nan))[:, :3]        # NaN sorts last
    for k in range(len(X)):
        np.testing.assert_allclose(np.sort_complex(np.roots(c[k, ::-1])), np.sort_complex(ev[k]), atol=1e-10)
    Q2, R2, T2 = (m[:, :2, :2] for m in (Q, R, T))                          # the sagittal 2 x 2 problem
    ev2 = np.linalg.eigvals(impedance.stroh_matrix(Q2, R2, T2, 0.3 * X))
    c2 = impedance.stroh_polynomial(Q2, R2, T2, 0.3 * X)
    for k in range(len(X)):
        np.testing.assert_allclose(np.sort_complex(np.roots(c2[k, ::-1])), np.sort_complex(ev2[k]), atol=1e-10)
    got, ok = impedance.track_roots(c, up * (1 + 1e-2 * rng.standard_normal(up.shape)))
    assert ok.all()
    np.testing.assert_allclose(np.sort_complex(got), up, rtol=1e-12)
    ref = impedance.impedance(Q, R, T, X, derivative=True)
    new = impedance.impedance(Q, R, T, X, derivative=True, p_guess=up * (1 + 1e-3))
    for key in ("Z", "p", "lam", "dlam"):
        np.testing.assert_allclose(new[key], ref[key], rtol=1e-11, atol=1e-12)
    assert not impedance.track_roots(c, up[:, [0, 0, 2]])[1].any()                 # collapsed guesses
    XL = impedance.limiting_x(Q, R, T)[0]
    assert not impedance.track_roots(impedance.stroh_polynomial(Q, R, T, 1.2 * XL), up)[1].any()


@pytest.mark.parametrize("medium", ["triclinic", "isotropic"])
def test_impedance_derivative_by_cayley_hamilton(medium):
    """d lam / dX of the impedance's lowest eigenvalue, which the solver gets from the
    Sylvester equation dM K1 - K2 dM = I through Cayley-Hamilton (dM = G f(K1)^-1). References:
    (a) the same Sylvester equation solved as its d^2 x d^2 Kronecker linear system (numpy),
    (b) a central finite difference of lam (step 1e-6 X, error ~1e-8). Random triclinic media,
    and an isotropic one (equal Stroh roots: a Jordan block, where eigenvectors fail)."""
    rng = np.random.default_rng(7)
    if medium == "triclinic":
        B = rng.normal(size=(8, 6, 6))
        A = voigt_to_tensor(B @ np.swapaxes(B, 1, 2) + 2 * np.eye(6))
    else:
        A = np.stack([_cubic_A(3.0, 1.0, 1.0, "(001)", a) for a in (0.0, 17.0, 33.0)])
    A = A / np.abs(A).max(axis=(1, 2, 3, 4), keepdims=True)
    Q, R, T = impedance.stroh_blocks(A)
    X = 0.7 * impedance.limiting_x(Q, R, T)[0]
    r = impedance.impedance(Q, R, T, X, derivative=True)
    N = impedance.stroh_matrix(Q, R, T, X)
    M = 1j * r["Z"]
    K1, K2 = N[:, :3, :3] + N[:, :3, 3:] @ M, N[:, 3:, 3:] - M @ N[:, :3, 3:]
    e = np.eye(3)
    L = (np.einsum("ia,mbj->mijab", e, K1) - np.einsum("mia,bj->mijab", K2, e)).reshape(-1, 9, 9)
    dM = np.linalg.solve(L, np.broadcast_to(e.reshape(9, 1), (len(X), 9, 1)))[..., 0].reshape(-1, 3, 3)
    u = r["u"]
    ref = np.einsum("mi,mij,mj->m", np.conj(u), -1j * dM, u).real
    np.testing.assert_allclose(r["dlam"], ref, rtol=1e-9)
    h = 1e-6 * X
    fd = (impedance.impedance(Q, R, T, X + h, derivative=True)["lam"]
          - impedance.impedance(Q, R, T, X - h, derivative=True)["lam"]) / (2 * h)
    np.testing.assert_allclose(r["dlam"], fd, rtol=1e-6)
    assert np.all(r["dlam"] < 0)                                   # Z decreases with X


def test_root_search_equals_bracketing_root_finder():
    """The root search (Newton, then inverse cubic Hermite steps through the two latest points,
    safeguarded by a bracket) against scipy's brentq (bracketing only, no derivatives) on the
    impedance's lowest eigenvalue (numpy eigvalsh of Z, the eigenvalue route for the roots,
    no tracking) over (0, X_L): Cu on three surfaces at non-mirror angles, Pb (strongly
    anisotropic, root close to X_L) and a random triclinic medium; agreement to 1e-12."""
    rng = np.random.default_rng(11)
    B = rng.normal(size=(6, 6))
    As = [_cubic_A(CU["C11"], CU["C12"], CU["C44"], s, a) for s, a in (("(001)", 20.0), ("(110)", 61.0), ("(111)", 7.0))]
    As += [_cubic_A(PB["C11"], PB["C12"], PB["C44"], "(001)", 30.0), voigt_to_tensor(B @ B.T + 2 * np.eye(6))]
    A = np.stack(As)
    A = A / np.abs(A).max(axis=(1, 2, 3, 4), keepdims=True)
    r = stroh.surface_wave(A, 1.0, mirror=False, tol=1e-14)
    Q, R, T = impedance.stroh_blocks(A)
    XL = r["c_limit"] ** 2
    for k in range(len(A)):
        def lam(X):
            return np.linalg.eigvalsh(impedance.impedance(Q[k:k + 1], R[k:k + 1], T[k:k + 1], np.array([X]))["Z"][0])[0]
        X = brentq(lam, 1e-9 * XL[k], XL[k] * (1 - 1e-13), xtol=1e-16 * XL[k], rtol=1e-15)
        assert r["wave_type"][k] == "surface"
        assert r["c"][k] ** 2 == pytest.approx(X, rel=1e-12)


def test_lowest_eigenpair_closed_form_equals_lapack():
    """impedance.lowest_eigenpair (cubic in closed form, Newton-polished, cross-product
    eigenvector) against numpy's eigh (LAPACK) on random Hermitian 3 x 3 matrices, including
    ones with the upper two (closed form ill-conditioned) or lower two (fallback) eigenvalues
    equal to 1e-12, and on a 2 x 2 batch: eigenvalue to 1e-14 of max|Z|, eigenvector up to phase."""
    rng = np.random.default_rng(13)
    U, _ = np.linalg.qr(rng.normal(size=(300, 3, 3)) + 1j * rng.normal(size=(300, 3, 3)))
    w = np.sort(rng.normal(size=(300, 3)), axis=-1)
    w[100:200, 2] = w[100:200, 1] * (1 + 1e-12)                          # upper pair degenerate
    w[200:, 1] = w[200:, 0] + 1e-12                                      # lower pair degenerate
    Z = np.einsum("mij,mj,mkj->mik", U, w, np.conj(U))
    Z2 = Z[:50, :2, :2]
    for M, simple in ((Z, slice(0, 200)), (Z2, slice(None))):
        lam, u = impedance.lowest_eigenpair(M)
        ref, v = np.linalg.eigh(M)
        np.testing.assert_allclose(lam, ref[:, 0], atol=1e-14 * np.abs(M).max())
        np.testing.assert_allclose(np.linalg.norm(M @ u[..., None], axis=(1, 2)), np.abs(lam), atol=1e-13)
        np.testing.assert_allclose(np.abs(np.einsum("mi,mi->m", np.conj(u), v[:, :, 0]))[simple], 1.0, atol=1e-12)


def test_root_search_stops_at_rounding(monkeypatch):
    """A step below the resolution of t (t - step == t) means t is the root to rounding: the
    search stops there instead of counting it as leaving the bracket and bisecting away (which
    took up to ~30 further impedance evaluations for a few directions). Reference: Cu on
    (001), (110), (111) at 300 random angles, each solved to tol 1e-14 in at most 6 vectorised
    impedance evaluations (Newton then order-2.7 Hermite steps from t = 0.3), with the speeds
    those of the points solved one at a time (the same search, other batch neighbours)."""
    rng = np.random.default_rng(17)
    C = voigt_to_tensor(cubic_voigt(CU["C11"], CU["C12"], CU["C44"]))
    A = np.concatenate([rotate4(C, lab_axes(s, rng.uniform(0, 180, 100))) for s in ("(001)", "(110)", "(111)")])
    calls = []
    real = impedance.impedance
    monkeypatch.setattr(impedance, "impedance", lambda *a, **k: calls.append(len(a[3])) or real(*a, **k))
    r = stroh.surface_wave(A, CU["rho"], mirror=False, tol=1e-14)
    assert np.all(r["wave_type"] == "surface") and len(calls) <= 6
    for k in range(0, 300, 37):
        assert stroh.surface_wave(A[k], CU["rho"], mirror=False, tol=1e-14)["c"] == pytest.approx(r["c"][k], rel=1e-13)


def test_no_wave_no_polarisation():
    """Where no surface wave is found the polarisation and decay constants are NaN, not the
    values the search happened to stop at: Cu (001) at 44.99 deg is flagged pseudo (the
    subsonic root within 1e-12 of v_L, test_either_side_of_a_mirror_and_merging_into_the_bulk),
    20 deg has a surface wave, and C44 < 0 is unstable (reference: wave_type of the same call)."""
    A = _cubic_A(CU["C11"], CU["C12"], CU["C44"], direction=np.array([44.99, 20.0]))
    r = stroh.surface_wave(A, CU["rho"])
    assert list(r["wave_type"]) == ["pseudo", "surface"]
    assert np.isnan(r["polarisation"][0]).all() and np.isnan(r["decay"][0]).all()
    assert np.isfinite(r["polarisation"][1]).all()
    bad = stroh.surface_wave(_cubic_A(3.0, 1.0, -1.0), 1.0)
    assert bad["wave_type"] != "surface" and np.isnan(bad["polarisation"]).all()


@pytest.mark.parametrize("consts", [(49.66, 42.31, 14.98), (49.5, 42.3, 14.9)])
def test_limiting_speed_at_a_flat_double_well_minimum(consts):
    """Pb (110) at 60.42 deg: the lowest trace branch has a shallow double well around the sagittal
    normal (local maximum at 0, minima at +-2.8 deg), so the grid's best points sit on the
    concave part and Newton needs ~6 steps; with 4 it stopped 3e-9 (database constants) or 5.5e-8
    (this file's PB) high. Reference:
    brute force, 400001 sagittal normals (LAPACK eigenvalues) and the parabolic vertex."""
    A = _cubic_A(*consts, surface="(110)", direction=60.42)[None]   # the database's Pb, this file's PB
    A = A / np.abs(A).max()
    Q, R, T = impedance.stroh_blocks(A)
    XL = impedance.limiting_x(Q, R, T)[0][0]
    phi = np.linspace(-0.3, 0.3, 400001)
    lam = impedance._trace_x(Q, R, T, phi[None])[0]
    j = int(np.argmin(lam))
    y0, y1, y2 = lam[j - 1:j + 2]
    ref = y1 - 0.125 * (y2 - y0) ** 2 / (y0 - 2 * y1 + y2)
    assert XL == pytest.approx(ref, rel=1e-13) and XL <= lam.min() * (1 + 1e-15)
