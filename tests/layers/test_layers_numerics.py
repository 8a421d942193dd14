"""Numerical robustness of the layered solver: large kh, tiny kh, stress, piezoelectric stacks."""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import expm

import surfwave
from surfwave.errors import InputError
from surfwave.layers.partial import families, scaled_blocks, stroh_matrix
from surfwave.layers.recursion import top_impedance
from surfwave.layers.stack import resolve_stack
from surfwave.solvers import stroh

SIO2 = {"E": 70.0, "nu": 0.17, "rho": 2200.0}


def _plain_transfer_impedance(b, fam, c: float, kh: float) -> np.ndarray:
    """M_top by the plain transfer-matrix product: [a; b]_top = expm(-i kh N_film) [a; b]_substrate top."""
    nf = len(fam.idx)
    ix = np.ix_(fam.idx, fam.idx)
    Ns = stroh_matrix(b.Q[-1][ix], b.R[-1][ix], b.T[-1][ix], np.array([b.rho[-1] * c * c / b.sA]), fam.mech)[0]
    p, V = np.linalg.eig(Ns)
    d = np.argsort(p.imag)[nf:]
    Ms = V[nf:, d] @ np.linalg.inv(V[:nf, d])
    Nf = stroh_matrix(b.Q[0][ix], b.R[0][ix], b.T[0][ix], np.array([b.rho[0] * c * c / b.sA]), fam.mech)[0]
    P = expm(-1j * kh * Nf)
    top = P @ np.vstack([np.eye(nf), Ms])
    return top[nf:] @ np.linalg.inv(top[:nf])


def test_plain_transfer_matrix_fails_at_large_kh_recursion_does_not():
    """At kh = 1 both routes give the same impedance (1e-9); at kh = 50 the transfer-matrix product
    (exponentials exp(kh |Im p|) ~ 1e20) has lost it, while the recursion still gives the film's own
    Rayleigh speed (the kh -> infinity limit, stroh.surface_wave) to 1e-12."""
    b = scaled_blocks(resolve_stack("Si", [{**SIO2, "thickness": 1e-6}]))
    fam = families(b)[0]
    c = 3300.0
    for kh, agree in ((1.0, True), (50.0, False)):
        ours = top_impedance(b, fam, [c], [[kh]])["M"][0, 0]
        plain = _plain_transfer_impedance(b, fam, c, kh)
        err = np.abs(plain - ours).max() / np.abs(ours).max()
        assert (err < 1e-9) == agree, (kh, err)
    r = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=[50.0])
    cR = float(stroh.surface_wave(resolve_stack(SIO2, []).substrate.A, SIO2["rho"])["c"])
    assert r["c"][0, 0] == pytest.approx(cR, rel=1e-12)


def test_tiny_kh_is_first_order():
    """kh = 1e-6: the shift from c_R is 1e-6 times the slope between kh = 1e-4 and 2e-4 (to 1e-4)."""
    r = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=[0.0, 1e-6, 1e-4, 2e-4])
    c = r["c"][:, 0]
    slope = 2 * (c[2] - c[0]) / 1e-4 - (c[3] - c[0]) / 2e-4
    assert (c[1] - c[0]) / 1e-6 == pytest.approx(slope, rel=1e-4)


def test_film_stress_shifts_like_a_stressed_half_space():
    """At kh = 60 the first mode of a stressed film is the stressed film's own half-space c_R
    (stroh.surface_wave with A = C + sigma delta, the existing prestressed route); the stress is
    equibiaxial in the surface plane (SAW frame) and compression slows the wave."""
    out = []
    for s in (-1.0, 0.0, 1.0):
        r = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6, "stress": s}], kh=[60.0])
        film = resolve_stack("Si", [{**SIO2, "thickness": 1e-6, "stress": s}]).films[0]
        ref = float(stroh.surface_wave(film.A, film.rho)["c"])
        assert r["c"][0, 0] == pytest.approx(ref, rel=1e-10)
        out.append(r["c"][0, 0])
    assert out[0] < out[1] < out[2]


def test_substrate_stress_at_kh_zero_matches_material():
    """Substrate stress, kh = 0: a 3 x 3 uniaxial stress along x1 (SAW frame) gives material()'s c_R
    under the same uniaxial stress along the propagation direction (fixed constants)."""
    s = np.zeros((3, 3))
    s[0, 0] = 0.5
    r = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=[0.0], stress=s)
    assert r["c"][0, 0] == pytest.approx(surfwave.material("Si", stress=0.5)["c_R"], rel=1e-10)


def test_piezoelectric_film_of_substrate_material():
    """A 128Y-X LiNbO3 film on the same cut (same Euler angles) is the bare cut: c_free, c_metallized
    and K^2 of material() at every kh."""
    m = surfwave.material("LiNbO3", euler=(0, 38, 0))
    film = [{"name": "LiNbO3", "euler": (0, 38, 0), "thickness": 1e-6}]
    free = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.0, 2.0])
    met = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.0, 2.0], electrical="metallized")
    np.testing.assert_allclose(free["c"][:, 0], m["c_free"], rtol=1e-10)
    np.testing.assert_allclose(met["c"][:, 0], m["c_metallized"], rtol=1e-10)
    np.testing.assert_allclose(free["K2"][:, 0], m["K2"], rtol=1e-7)


def test_dielectric_gap_under_an_electrode():
    """A thin vacuum-permittivity film with a metallized top: as kh -> 0 the metallized speed tends to
    material()'s c_metallized, and the free one to c_free (the film's mass is second order here)."""
    m = surfwave.material("LiNbO3", euler=(0, 38, 0))
    film = [{**SIO2, "permittivity": 1.0, "thickness": 1e-6}]
    met = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[1e-7], electrical="metallized")
    free = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[1e-7])
    assert met["c"][0, 0] == pytest.approx(m["c_metallized"], rel=1e-6)
    assert free["c"][0, 0] == pytest.approx(m["c_free"], rel=1e-6)


def test_film_compressed_toward_and_beyond_buckling():
    """Fused silica (database: shear modulus 73/2.34 = 31.2 GPa) under equibiaxial compression.
    -25 GPa: every mode is still there, the Rayleigh mode at kh = 5 far below the unstressed one (the
    film's shear stiffness A_1212 = mu + sigma is small). -30 GPa: at kh = 0.1 the substrate still holds
    the thin film, at kh = 5 the stack has a mode with omega^2 < 0 (surface buckling sets in before the
    bulk instability): that row is empty with the reason. -40 GPa: the film's stressed state itself is
    unstable (a bulk wave with rho v^2 < 0, surfwave.solvers.long_wave): every row empty. No warnings."""
    import warnings

    film = {"name": "SiO2", "thickness": 1e-6}
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        free = surfwave.layered("Si", [film], kh=[5.0])
        near = surfwave.layered("Si", [{**film, "stress": -25.0}], kh=[5.0])
        wrinkled = surfwave.layered("Si", [{**film, "stress": -30.0}], kh=[0.1, 5.0])
        beyond = surfwave.layered("Si", [{**film, "stress": -40.0}], kh=[1.0, 5.0])
    assert (near["mode"][0] != "").sum() >= (free["mode"][0] != "").sum()   # a slower film holds more modes
    assert near["mode"][0, 0] == "R" and near["c"][0, 0] < 0.3 * free["c"][0, 0]
    assert np.isfinite(wrinkled["c"][0]).any() and wrinkled["reason"][0] == ""
    assert not np.isfinite(wrinkled["c"][1]).any() and "surface buckling" in wrinkled["reason"][1]
    assert beyond["c"].shape == (2, 0)
    assert all("unstable under its prestress" in s for s in beyond["reason"])


def test_equibiaxial_film_stress_is_the_existing_biaxial_loading():
    """A Si film on Si (001)[110] (film Euler angles turning its axes onto the substrate's) under a scalar
    stress of 0.3 GPa: at kh = 60 the first mode is the Si (001)[110] half-space under the existing
    equibiaxial loading (stressed_wave.stress_tensor('biaxial'), material()'s fixed-constants route)."""
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.stressed_wave import Constants, stress_tensor
    from surfwave.real_crystals.stressed_wave import surface_wave as stressed_surface_wave
    from surfwave.solvers.orientation import lab_axes

    R = lab_axes("(001)", "[110]")
    ref = stressed_surface_wave(Constants.from_material(get_material("Si")), R, stress_tensor("biaxial", 0.3, R))
    # SAW Euler angles (45, 180, 0): x1 = [110], outward normal -[001] -> our inward x2 = [001], as lab_axes
    film = {"name": "Si", "thickness": 1e-6, "euler": (45.0, 180.0, 0.0), "stress": 0.3}
    r = surfwave.layered("Si", [film], direction="[110]", kh=[60.0])
    j = list(r["mode"][0]).index("R")
    assert r["c"][0, j] == pytest.approx(float(ref["c_R"]), rel=1e-9)


def test_k2_at_frequency_input():
    """SiO2 on 128Y-X LiNbO3 at 1 GHz: K^2 at a given frequency (free and metallized speeds at the same f)
    is positive and within 5 % of K^2 at the same kh (the two differ by the film's dispersion only)."""
    film = [{"name": "SiO2", "thickness": 5e-7}]
    r = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), frequency=[1e9])
    rk = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[r["kh"][0, 0]])
    assert r["c"][0, 0] == pytest.approx(rk["c"][0, 0], rel=1e-10)
    assert 0 < r["K2"][0, 0] == pytest.approx(rk["K2"][0, 0], rel=0.05)


def test_power_flow_angle():
    """LiNbO3 (0, 38, 20) with a film of its own cut: the power-flow angle of the stack's mode is the
    half-space's of material() (solvers.piezo, a Lyapunov-equation flux), 1e-8, at kh = 0 and 1; a mirror
    stack (Si (001)[100]) has none."""
    m = surfwave.material("LiNbO3", euler=(0, 38, 20))
    f = [{"name": "LiNbO3", "euler": (0, 38, 20), "thickness": 1e-6}]
    r = surfwave.layered("LiNbO3", f, euler=(0, 38, 20), kh=[0.0, 1.0])
    np.testing.assert_allclose(r["power_flow_angle"][:, 0], m["power_flow_angle"], rtol=1e-8)
    s = surfwave.layered("Si", [{**SIO2, "thickness": 1e-6}], kh=[2.0])
    np.testing.assert_allclose(s["power_flow_angle"][np.isfinite(s["c"])], 0.0, atol=1e-9)


def test_grounded_electrode_under_a_film():
    """A 128Y-X LiNbO3 film on the same cut with a grounded electrode (phi = 0) on the interface: as kh -> 0
    the electrode is the surface, so the speed tends to material()'s c_metallized (kh = 1e-4: 1e-5); deep
    under a thick film (kh = 20) it no longer matters, c_free (1e-5); the free top is never slower than the
    metallized one; and the group velocity still equals c + kh dc/dkh (1e-6)."""
    m = surfwave.material("LiNbO3", euler=(0, 38, 0))
    f = [{"name": "LiNbO3", "euler": (0, 38, 0), "thickness": 1e-6, "electrode_below": True}]
    free = surfwave.layered("LiNbO3", f, euler=(0, 38, 0), kh=[1e-4, 0.5, 0.5 - 1e-5, 0.5 + 1e-5, 20.0])
    met = surfwave.layered("LiNbO3", f, euler=(0, 38, 0), kh=[0.5], electrical="metallized")
    c = free["c"][:, 0]
    assert c[0] == pytest.approx(m["c_metallized"], rel=1e-5)
    assert c[4] == pytest.approx(m["c_free"], rel=1e-5)
    assert c[1] > met["c"][0, 0]
    assert free["group_velocity"][1, 0] == pytest.approx(c[1] + 0.5 * (c[3] - c[2]) / 2e-5, rel=1e-6)
    with pytest.raises(InputError, match="electrode_below needs"):
        surfwave.layered("Si", [{**SIO2, "thickness": 1e-6, "electrode_below": True}], kh=[1.0])


def test_every_mode_against_a_fine_scan():
    """ZnO (c axis normal) on c-plane sapphire, a coupled piezoelectric family, kh = 8: the default search
    finds the same ten modes as a scan on a grid of 2000 speeds (free and metallized top); at 3195.2 m/s a
    mode sits 9 m/s from a pole of the impedance, inside one default grid cell, and is still found."""
    from surfwave.layers import modes

    b = scaled_blocks(resolve_stack("sapphire", [{"name": "ZnO", "thickness": 1e-6}]))
    fam = families(b)[0]
    for el in ("free", "metallized"):
        fine = modes._family_scan(b, fam, np.array([8.0]), el, 2000)
        ours = modes.family_modes(b, fam, [8.0], electrical=el)
        assert ours.shape == fine.shape == (1, 10)
        np.testing.assert_allclose(ours, fine, rtol=1e-12)
