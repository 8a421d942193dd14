"""Numbers of the piezoelectric path that reach the cubes, each against an independent value.

- K^2 (with and without the leaky solve), the penetration depth and the potential share against
  the brute-force piezoelectric solver of tests/piezo_saw_brute.py (its own Stroh matrix, its own
  boundary rows, its own minimisation), evaluated here into surface fields;
- the leaky wave's coupling K2_leaky against Yamanouchi & Shibayama, J. Appl. Phys. 43, 856
  (1972) (64Y-X LiNbO3: K^2 = 0.113, 0.036 dB per wavelength free, ~0 metallized; abstract) and
  the 41Y-X figure quoted with it, 17.2 % at 4792 m/s (e.g. device papers citing Shibayama et
  al.), and against two separate single-condition leaky solves;
- the grazing flag against the penetration depth threshold;
- the run-time note of an unverified constant set.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

import surfwave
from surfwave.errors import ConstantsNote
from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material, note_status
from surfwave.real_crystals.piezo_wave import piezo_wave
from surfwave.real_crystals.stressed_wave import GRAZING_DEPTH
from surfwave.solvers.leaky import leaky_wave
from tests.piezo_saw_brute import EPS0, generalised_tensor, saw_speed


def _brute_fields(C, e, eps, rho, v, free: bool) -> tuple[np.ndarray, complex, float]:
    """Surface (u, phi) with |u| = 1 (phi in V per m of displacement) and min Im p of the four
    decaying partial waves at speed v: the null vector of the brute helper's boundary rows."""
    E = generalised_tensor(C, e, eps)
    Q, R, T = E[:, 0, :, 0], E[:, 0, :, 1], E[:, 1, :, 1]
    M = Q.copy()
    M[:3, :3] -= rho * v * v * np.eye(3)
    Ti = np.linalg.inv(T)
    N = np.block([[np.zeros((4, 4)), np.eye(4)], [-Ti @ M, -Ti @ (R + R.T)]])
    p, vec = np.linalg.eig(N)
    keep = np.argsort(-p.imag)[:4]
    a = vec[:4, keep]
    a = a / np.linalg.norm(a[:3], axis=0)                # unit displacement per partial wave
    b = np.einsum("JKm,Km->Jm", R.T[:, :, None] + p[keep][None, None, :] * T[:, :, None], a)
    sC, sE = np.abs(C).max(), np.abs(eps).max()          # rows of one scale: Pa, sqrt(Pa F/m), V
    rows = np.vstack([b[:3] / sC, (b[3] - 1j * EPS0 * a[3]) / np.sqrt(sC * sE) if free
                      else a[3] / np.sqrt(sC / sE)])
    coef = np.linalg.svd(rows)[2][-1].conj()
    field = a @ coef
    return field[:3] / np.linalg.norm(field[:3]), field[3] / np.linalg.norm(field[:3]), float(p[keep].imag.min())


@pytest.fixture(scope="module")
def yz():
    """Y-Z LiNbO3 (Warner set) lab tensors and the brute-force free / metallized speeds."""
    cut = get_cut("Y-Z LiNbO3")
    r = piezo_wave(cut.material, cut.lab_axes)
    C, e, eps, rho = r["C"][0], r["e"][0], r["eps"][0], float(r["rho"][0])
    speeds = {el: saw_speed(C, e, eps, rho, 3300.0, float(r["c_limit"][0]) - 1e-3, el == "free")
              for el in ("free", "metallized")}
    return cut, C, e, eps, rho, speeds


@pytest.mark.parametrize("leaky", [True, False])
def test_k2_with_and_without_the_leaky_solve_against_brute_force(yz, leaky):
    """K^2 = 2 (v_free - v_met) / v_free from the brute-force speeds (1e-6 m/s bisection), the
    same whether or not the leaky wave is solved (``leaky=False`` must not take another route)."""
    cut, *_, speeds = yz
    r = surfwave.material(cut=cut.name, leaky=leaky)
    want = 2 * (speeds["free"] - speeds["metallized"]) / speeds["free"]
    assert r["c_free"] == pytest.approx(speeds["free"], abs=1e-4)
    assert r["c_metallized"] == pytest.approx(speeds["metallized"], abs=1e-4)
    assert r["K2"] == pytest.approx(want, rel=1e-6)


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_depth_and_potential_share_against_brute_force_fields(yz, electrical):
    """Penetration depth 1/(2 pi min Im p) and the potential share eps_bar |phi|^2 / (rho c^2 |u|^2
    + eps_bar |phi|^2), eps_bar = tr(eps)/3, from the brute-force partial waves and boundary null
    vector at the brute-force speed; the surface phi in V per m of displacement as well."""
    cut, C, e, eps, rho, speeds = yz
    v = speeds[electrical]
    u, phi, im = _brute_fields(C, e, eps, rho, v, electrical == "free")
    r = surfwave.material(cut=cut.name, electrical=electrical)
    assert r["penetration_depth"] == pytest.approx(1 / (2 * np.pi * im), rel=1e-5)
    ebar = np.trace(eps) / 3
    share = ebar * abs(phi) ** 2 / (rho * v ** 2 + ebar * abs(phi) ** 2)
    if electrical == "free":
        assert r["potential_share"] == pytest.approx(share, rel=1e-5)
        assert abs(r["polarisation"][3]) == pytest.approx(abs(phi), rel=1e-5)
    else:                                            # phi = 0 on a metallized surface
        assert r["potential_share"] < 1e-12 and share < 1e-12
    np.testing.assert_allclose(np.abs(r["polarisation"][:3]), np.abs(u), atol=1e-6)


@pytest.mark.parametrize("cut, k2, rel", [("64Y-X LiNbO3", 0.113, 0.01), ("41Y-X LiNbO3", 0.172, 0.01)])
def test_leaky_coupling_of_the_rotated_y_cuts(cut, k2, rel):
    """K2_leaky of 64Y-X (0.113, Yamanouchi & Shibayama 1972) and 41Y-X (17.2 %, quoted with
    4792 m/s) LiNbO3, Warner set, to 1 %; equal for either ``electrical``; c_leaky_free /
    c_leaky_metallized equal the c_leaky of each condition; and K2_leaky equals the coupling of
    two separate single-condition leaky solves (surfwave.solvers.leaky.leaky_wave)."""
    f = surfwave.material(cut=cut, electrical="free")
    m = surfwave.material(cut=cut, electrical="metallized")
    assert f["K2_leaky"] == pytest.approx(k2, rel=rel)
    assert f["K2_leaky"] == m["K2_leaky"] and f["c_leaky_free"] == m["c_leaky_free"]
    assert f["c_leaky_free"] == f["c_leaky"] and m["c_leaky_metallized"] == m["c_leaky"]
    c = get_cut(cut)
    t = piezo_wave(c.material, c.lab_axes, leaky=False)
    A = t["C"]                                          # natural constants, no prestress: A = C
    one = {el: leaky_wave(A, t["rho"], t["e"], t["eps"], electrical=el)["c_leaky"][0] for el in ("free", "metallized")}
    assert f["c_leaky_free"] == pytest.approx(one["free"], rel=1e-9)
    assert f["c_leaky_metallized"] == pytest.approx(one["metallized"], rel=1e-9)
    assert f["K2_leaky"] == pytest.approx(2 * (one["free"] - one["metallized"]) / one["free"], rel=1e-7)
    assert f["K2"] < 0.01 < f["K2_leaky"]                 # the weak Rayleigh wave's K2 is not it


def test_leaky_coupling_nan_where_no_leaky_root_and_with_leaky_false():
    """Y-Z LiNbO3 has no leaky root: K2_leaky NaN; with leaky=False every leaky output is NaN."""
    r = surfwave.material(cut="Y-Z LiNbO3")
    assert np.isnan(r["K2_leaky"]) and np.isnan(r["c_leaky_free"]) and r["leaky_reason"]
    off = surfwave.material(cut="64Y-X LiNbO3", leaky=False)
    assert np.isnan(off["K2_leaky"]) and np.isnan(off["c_leaky_metallized"])


def test_grazing_flag_on_rotated_y_litao3():
    """Rotated Y LiTaO3 near theta = 38 deg (128 deg rotated Y): the subsonic "SAW" lies
    ~1e-4 m/s below the limiting speed and hundreds of wavelengths deep (issue 27): flagged; the
    36Y-X SAW (a few wavelengths) is not. The flag is exactly depth > GRAZING_DEPTH."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConstantsNote)
        r = surfwave.material("LiTaO3", euler=[[0, 38, 0], [0, -54, 0], [0, 30, 0]], leaky=False)
    assert r["c_limit"][0] - r["c_R"][0] < 1e-3 and r["penetration_depth"][0] > 300
    assert r["grazing"].tolist() == [True, False, False]
    assert np.array_equal(r["grazing"], r["penetration_depth"] > GRAZING_DEPTH)


def test_unverified_constant_set_is_noted_once_per_place():
    """LiTaO3 (default set LiTaO3-Kovacs1990, UNVERIFIED in docs/piezoelectric-materials.md) and
    langasite (PROVISIONAL) give a one-line ConstantsNote naming the set; LiNbO3 (Warner, stored
    peers) gives none."""
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        surfwave.material("LiTaO3", cut="36Y-X", leaky=False)
        surfwave.material("LiNbO3", cut="Y-Z", leaky=False)
        surfwave.material("langasite", euler=[0, 0, 0], leaky=False)
    notes = [str(w.message) for w in seen if issubclass(w.category, ConstantsNote)]
    assert len(notes) == 2 and all("\n" not in n for n in notes)
    assert "LiTaO3-Kovacs1990 is unverified" in notes[0] and "langasite is provisional" in notes[1]
    assert note_status(get_piezo_material("LiNbO3")) == ""
    assert seen[0].filename == __file__                  # points at the caller's line


def test_deformed_surface_of_gaas_111_under_toec_stress():
    """GaAs (111), propagation [1-10], -0.5 GPa along it, third-order constants: the strain
    couples to the surface normal, which follows the material plane spanned by F m0 and F x3_0
    (Nanson's relation, built here from two cross products, not from F^-T); the propagation is
    F m0. With C*, rho* of the stressed state rotated into those axes, the SAW solved directly
    (surfwave.solvers.piezo.coupling_coefficient) matches the one path's c_free and c_metallized
    to 1e-6 m/s (a normal built with F instead of F^-T moves c_free by 0.12 m/s)."""
    from surfwave.real_crystals import toec as toec_model
    from surfwave.real_crystals.stressed_wave import Constants, stress_tensor
    from surfwave.solvers.orientation import lab_axes
    from surfwave.solvers.piezo import coupling_coefficient
    from surfwave.solvers.piezo_tensors import EPS0 as eps0
    from surfwave.solvers.piezo_tensors import piezo_voigt_to_tensor, rotate3
    from surfwave.solvers.stroh import wave_propagation_tensor
    from surfwave.solvers.tensors import rotate2, rotate4

    mat = get_piezo_material("GaAs")
    k = Constants.from_piezo_material(mat)
    R0 = lab_axes("(111)", "[1-10]")
    sigma = stress_tensor("along", -0.5, R0)
    st = toec_model.stressed_state(k.voigt, k.toec, sigma, k.rho)
    F = st["F"]
    x1 = F @ R0[0]
    n = np.cross(F @ R0[2], F @ R0[0])                  # the deformed surface plane's normal, inward
    x1, n = x1 / np.linalg.norm(x1), n / np.linalg.norm(n)
    axes = np.stack([x1, n, np.cross(x1, n)])
    assert np.linalg.norm(np.cross(F @ R0[1], n)) > 1e-5   # the normal tilts: F n0 is not along it
    A = wave_propagation_tensor(rotate4(st["C_star"] * 1e9, axes)[None], rotate2(sigma * 1e9, axes)[None])
    e = rotate3(piezo_voigt_to_tensor(mat.e), axes)[None]
    eps = rotate2(mat.eps_r * eps0, axes)[None]
    want = coupling_coefficient(A, e, eps, np.array([st["rho"]]))
    r = piezo_wave(mat, R0, -0.5, toec=True, leaky=False)
    np.testing.assert_allclose(r["axes"][0], axes, atol=1e-12)
    assert r["c_free"][0] == pytest.approx(want["c_free"][0], abs=1e-6)
    assert r["c_metallized"][0] == pytest.approx(want["c_metallized"][0], abs=1e-6)


def test_beside_the_gaas_110_mirror_the_wave_leaks():
    """GaAs (001)[110]: on the mirror the sagittal wave is an exact supersonic wave (its leakage
    vanishes by symmetry); 0.05 and 0.1 deg beside it the mirror is gone and the wave leaks, with
    an attenuation even in the angle from the mirror, so ~ (angle)^2: the ratio of the two is 4
    (2 %). Beside the mirror the wave must stay ``pseudo`` with no subsonic speed (an exactness
    threshold loosened from 1e-10 to 1e-4 in |Im k / Re k| calls it exact there)."""
    r = surfwave.material("GaAs", angle=[45.0, 45.05, 45.1], electrical="free")
    assert r["wave_type"][0] == "supersonic_decoupled" and r["leaky_attenuation"][0] < 1e-9
    assert r["wave_type"][1] == "pseudo" and np.isnan(r["c_R"][1]) and np.isnan(r["c_free"][1])
    assert r["leaky_attenuation"][1] > 0 and np.isfinite(r["c_leaky"][1])
    assert r["leaky_attenuation"][2] / r["leaky_attenuation"][1] == pytest.approx(4.0, rel=0.02)
    assert r["c_leaky"][1] == pytest.approx(r["c_R"][0], rel=1e-6)          # continuous through the mirror


def test_piezo_cube_carries_the_leaky_pair_and_selects_plates_by_euler_angle(tmp_path):
    """The cube of a scene listing only the free condition still has K2_leaky and both leaky
    speeds, equal to the API's; written and opened with open_cube, the plates are selected by
    their Euler angle (no swap_dims), the surface labels still work, and the bulk waves carry
    their polarisation on ``bulk_component``."""
    from surfwave.data.cube import open_cube, write
    from surfwave.real_crystals.piezo_sweep import piezo_wave_sweep

    ds = piezo_wave_sweep(["LiNbO3-Warner1967"], euler={"phi": 0, "theta": [-26.0, -49.0], "psi": 0},
                          electrical=["free"])
    back = open_cube(write(ds, tmp_path / "surface_wave.nc"))
    plate = back.sel(material="LiNbO3-Warner1967", euler_theta=-26.0).isel(angle=0)
    api = surfwave.material("LiNbO3", cut="64Y-X")
    for key in ("K2_leaky", "c_leaky_free", "c_leaky_metallized", "c_T_par", "c_SH"):
        assert float(plate[key]) == pytest.approx(api[key], rel=1e-12), key
    assert str(plate.surface.values) == "Euler (0, -26)"
    assert float(back.sel(surface="Euler (0, -49)").K2_leaky.squeeze()) == pytest.approx(0.172, rel=0.01)
    assert back.polarisation_L_par.dims[-1] == "bulk_component"
    np.testing.assert_allclose(plate.polarisation_L_par.values, api["polarisation_L_par"], atol=1e-12)
