"""Guided modes of films on substrates against independent references (each test names its own)."""
from __future__ import annotations

import numpy as np
import pytest
from layers_collocation import collocation_speeds
from scipy.optimize import brentq

import surfwave
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import isotropic_voigt, resolve_stack
from surfwave.solvers import piezo_stroh, stroh
from surfwave.solvers.tensors import voigt_to_tensor

SIO2 = {"E": 70.0, "nu": 0.17, "rho": 2200.0}          # a slow isotropic film (illustrative numbers)
FAST = {"E": 400.0, "nu": 0.25, "rho": 3500.0}         # a fast isotropic half-space


def _iso(mat):
    C = isotropic_voigt(mat["E"], mat["nu"]) * 1e9
    return C[5, 5], C[0, 1], mat["rho"]                 # mu, lambda, rho (Pa, Pa, kg/m^3)


def love_closed_form(kh: float, n: int) -> float:
    """n-th Love mode: tan(kh q1) = mu2 q2 / (mu1 q1) + branch, q1 = sqrt(c^2/b1^2 - 1), q2 = sqrt(1 - c^2/b2^2).

    The textbook dispersion relation of SH waves in a layer on a half-space (e.g. Aki & Richards,
    Quantitative Seismology, sec. 7.2), solved here with brentq on each tangent branch.
    """
    mu1, _, r1 = _iso(SIO2)
    mu2, _, r2 = _iso(FAST)
    b1, b2 = np.sqrt(mu1 / r1), np.sqrt(mu2 / r2)

    def f(c):
        q1, q2 = np.sqrt(c * c / b1**2 - 1), np.sqrt(1 - c * c / b2**2)
        return np.arctan(mu2 * q2 / (mu1 * q1)) + n * np.pi - kh * q1

    return brentq(f, b1 * (1 + 1e-14), b2 * (1 - 1e-14), xtol=1e-13, rtol=1e-15)


def test_love_modes_closed_form():
    """SH family of an isotropic layer on an isotropic half-space = the Love equation (brentq), to 1e-11."""
    kh = np.array([0.5, 2.0, 6.0])
    r = surfwave.layered(FAST, [{**SIO2, "thickness": 1e-6}], kh=kh)
    for i, k in enumerate(kh):
        love = r["c"][i][np.char.startswith(r["mode"][i].astype(str), "L")]
        for n, c in enumerate(love):
            assert c == pytest.approx(love_closed_form(k, n), rel=1e-11)
        # the number of Love modes is the number of branches below the substrate's shear speed
        assert len(love) == int(np.floor(k * np.sqrt(_iso(FAST)[0] / FAST["rho"] / (_iso(SIO2)[0] / SIO2["rho"])
                                                  - 1) / np.pi)) + 1


def test_isotropic_stack_decouples():
    """An isotropic stack splits exactly into a sagittal (u1, u2) and an SH (u3) family."""
    b = scaled_blocks(resolve_stack(FAST, [{**SIO2, "thickness": 1e-6}]))
    assert [(f.idx, f.kind) for f in families(b)] == [((0, 1), "sagittal"), ((2,), "sh")]
    # off a mirror of an anisotropic substrate nothing decouples
    b = scaled_blocks(resolve_stack("Si", [{**SIO2, "thickness": 1e-6}], direction=20.0))
    assert [f.kind for f in families(b)] == ["coupled"]


def test_thin_film_limit_and_perturbation_slope():
    """kh = 0 gives material()'s c_R (1e-10); the slope dc/dkh at 0 is the first-order perturbation result.

    Reference slope (docs/physics/layered.md): dc/dkh = (a^H N3_f a) / (a^H dZ/dX a 2 rho_s c_R), with
    N3_f = R T^-1 R^T - Q + rho_f c^2 I of the film (mass and in-plane stiffness loading), a the bare
    substrate's surface displacement (stroh.surface_wave) and dZ/dX from piezo_stroh.impedance_slope.
    """
    film = {**SIO2, "thickness": 1e-6}
    r = surfwave.layered("Si", [film], direction="[110]", kh=[0.0, 1e-6, 1e-3, 2e-3])
    m = surfwave.material("Si", direction="[110]")
    c = np.array([row[lab == "R"][0] for row, lab in zip(r["c"], r["mode"])])   # Si [110]: R is above the SH
    assert c[0] == pytest.approx(m["c_R"], rel=1e-10)                          # limit (decoupled), L0 below it
    st = resolve_stack("Si", [film], direction="[110]")
    A, Af, rho_s, rho_f = st.substrate.A, st.films[0].A, st.substrate.rho, st.films[0].rho
    sw = stroh.surface_wave(A, rho_s)
    a = sw["polarisation"]
    sA = np.abs(A).max()
    Q, R, T = (A[:, 0, :, 0] / sA)[None], (A[:, 0, :, 1] / sA)[None], (A[:, 1, :, 1] / sA)[None]
    X = np.array([rho_s * float(sw["c"]) ** 2 / sA])
    imp = piezo_stroh.impedance(Q, R, T, X, nm=3)
    slope_Z = piezo_stroh.impedance_slope(imp, a[None], nm=3)[0]
    Qf, Rf, Tf = Af[:, 0, :, 0], Af[:, 0, :, 1], Af[:, 1, :, 1]
    N3 = Rf @ np.linalg.solve(Tf, Rf.T) - Qf + rho_f * float(sw["c"]) ** 2 * np.eye(3)
    slope_ref = (np.conj(a) @ N3 @ a).real / (slope_Z * 2 * rho_s * float(sw["c"]))
    s1, s2 = (c[2] - c[0]) / 1e-3, (c[3] - c[0]) / 2e-3
    assert 2 * s1 - s2 == pytest.approx(slope_ref, rel=1e-3)
    assert c[1] - c[0] == pytest.approx(slope_ref * 1e-6, rel=1e-3)


def test_film_of_substrate_material_changes_nothing():
    """A Si film on Si (001)[100] (same crystal axes: cubic, default film Euler angles) is bare Si at any kh."""
    r = surfwave.layered("Si", [{"name": "Si", "thickness": 1e-6}], kh=[0.0, 0.7, 3.0, 20.0])
    assert r["c"].shape[1] == 1
    np.testing.assert_allclose(r["c"][:, 0], surfwave.material("Si")["c_R"], rtol=1e-11)
    np.testing.assert_allclose(r["group_velocity"][:, 0], surfwave.material("Si")["c_R"], rtol=1e-9)


def test_zero_thickness_is_the_bare_substrate():
    """Films of zero thickness leave the substrate's Rayleigh wave (material()) at every kh."""
    r = surfwave.layered("Si", [{**SIO2, "thickness": 0.0}], kh=[0.0, 5.0])
    np.testing.assert_allclose(r["c"][:, 0], surfwave.material("Si")["c_R"], rtol=1e-10)
    assert np.isnan(r["frequency"]).all()


def test_slow_film_at_large_kh():
    """At kh = 100 the first mode is the film's own half-space c_R (stroh.surface_wave) and the next
    ones lie just above the film's shear speed (they converge to it as kh grows)."""
    r = surfwave.layered(FAST, [{**SIO2, "thickness": 1e-6}], kh=[100.0])
    A = voigt_to_tensor(isotropic_voigt(SIO2["E"], SIO2["nu"])) * 1e9
    cR = float(stroh.surface_wave(A, SIO2["rho"])["c"])
    vT = np.sqrt(_iso(SIO2)[0] / SIO2["rho"])
    assert r["c"][0, 0] == pytest.approx(cR, rel=1e-9)
    assert r["mode"][0, 0] == "R"
    assert r["mode"][0, 1] == "L0"
    assert r["c"][0, 1] == pytest.approx(love_closed_form(100.0, 0), rel=1e-10)
    assert vT < r["c"][0, 1] < vT * (1 + 2e-4)


def test_sezawa_cut_off_at_limiting_speed():
    """The first Sezawa mode enters at the substrate's limiting speed: just after its cut-off it lies
    within 1e-3 of c_limit, and no sagittal mode is ever reported above c_limit (Love modes of this
    mirror-symmetric stack may be: their own family's limit, the SH bulk wave, is higher)."""
    kh = np.linspace(0.5, 3.0, 126)
    r = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=kh)
    has = (r["mode"] == "S1").any(axis=1)
    first = int(np.argmax(has))
    assert 0 < first and has[first:].all()
    c_s1 = r["c"][first][r["mode"][first] == "S1"][0]
    assert r["c_limit"] * (1 - 1e-3) < c_s1 < r["c_limit"]
    sag = np.char.startswith(r["mode"].astype(str), "R") | np.char.startswith(r["mode"].astype(str), "S")
    assert np.nanmax(r["c"][sag]) < r["c_limit"]


def test_second_route_collocation():
    """Chebyshev collocation of the film + a clamped 40/k-deep substrate slice (tests/layers/layers_collocation.py)
    agrees with the recursion to 1e-8 for the coupled modes of a film on Si (001) at 20 deg."""
    film = {**SIO2, "thickness": 1e-6}
    st = resolve_stack("Si", [film], direction=20.0)
    for kh in (0.3, 1.0, 2.5):
        r = surfwave.layered("Si", [film], direction=20.0, kh=[kh])
        ref = collocation_speeds([st.films[0].A], [st.films[0].rho], [kh], st.substrate.A, st.substrate.rho)
        c0 = r["c"][0, 0]
        assert ref[np.argmin(np.abs(ref - c0))] == pytest.approx(c0, rel=1e-8)


def test_twenty_layers_equal_one_film():
    """Twenty 50 nm SiO2 layers are one 1 um SiO2 film (every interface bonded): same modes to 1e-11."""
    one = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=[0.5, 2.0, 8.0])
    many = surfwave.layered("Si", [{**SIO2, "thickness": 5e-8}] * 20, kh=[0.5, 2.0, 8.0])
    np.testing.assert_allclose(many["c"], one["c"], rtol=1e-11)
    assert (many["mode"] == one["mode"]).all()


def test_group_velocity_against_finite_differences():
    """Energy-velocity group velocity = c + kh dc/dkh by central differences (h = 1e-5), to 1e-6."""
    film = {**SIO2, "thickness": 1e-6}
    kh, h = 1.7, 1e-5
    r = surfwave.layered("Si", [film], direction=20.0, kh=[kh - h, kh, kh + h])
    for j in range(r["c"].shape[1]):
        fd = r["c"][1, j] + kh * (r["c"][2, j] - r["c"][0, j]) / (2 * h)
        assert r["group_velocity"][1, j] == pytest.approx(fd, rel=1e-6)


def test_near_mirror_finds_every_mode_next_to_a_pole():
    """0.2 deg off Si (001)[100] every family couples and the modes of the mirror stack stay within 1e-4;
    at kh = 5.12 the S2-like mode (5476.5 m/s) lies 2.5 m/s from a pole of the impedance (a mode of the
    clamped-top stack) and must still be found, alone at one kh and along a kh sweep (reference: the
    decoupled [100] stack, where the two families' poles and zeros do not mix)."""
    film = [{"name": "SiO2", "thickness": 1e-6}]
    kh = np.linspace(4.8, 6.0, 31)
    for k in ([5.12], kh):
        a = surfwave.layered("Si", film, direction="[100]", kh=k)
        b = surfwave.layered("Si", film, direction=0.2, kh=k)
        for ra, rb in zip(a["c"], b["c"]):
            x, y = np.sort(ra[ra < a["c_limit"]]), np.sort(rb[rb < b["c_limit"]])
            assert x.size == y.size
            np.testing.assert_allclose(y, x, rtol=1e-4)
