"""Bulk waves along x1 and x2 (surfwave.solvers.bulk_waves) against independent values."""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.real_crystals.piezo_materials import get_piezo_material
from surfwave.solvers.bulk_waves import BULK_POLARISATIONS, BULK_SPEEDS, axis_waves
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.piezo_tensors import rotate3
from surfwave.solvers.tensors import rotate2, rotate4
from tests.piezo_saw_brute import generalised_tensor

C11, C12, C44, RHO = 168.4, 121.4, 75.4, 8960.0          # Cu (PHYSICS.md), GPa, kg/m^3


def test_cubic_closed_forms_along_100_and_110():
    """Closed forms of a cubic crystal (any textbook, e.g. Auld Vol. I, Table 7.4): along [100]
    rho v^2 = C11 (L) and C44 (both shears); along [110] (C11 + C12 + 2 C44)/2 (L), C44
    (polarised [001]) and (C11 - C12)/2 (polarised [1-10]). Surface (001), x1 = [110]: x2 = [001]
    is a cube axis. The names follow the polarisation, and so do the vectors."""
    r = surfwave.material(C11, C12, C44, RHO, "[110]")
    v = {k: np.sqrt(x * 1e9 / RHO) for k, x in {"L": C11, "T": C44, "L110": (C11 + C12 + 2 * C44) / 2,
                                                 "T110": (C11 - C12) / 2}.items()}
    assert r["c_L_par"] == pytest.approx(v["L110"], rel=1e-12)
    assert r["c_T_par"] == pytest.approx(v["T"], rel=1e-12)          # polarised along x2 = [001]
    assert r["c_SH"] == pytest.approx(v["T110"], rel=1e-12)          # polarised along x3 = [-110]
    assert r["c_L_perp"] == pytest.approx(v["L"], rel=1e-12)
    assert r["c_T_perp"] == r["c_SH_perp"] == pytest.approx(v["T"], rel=1e-12)   # degenerate pair
    for name, axis in (("L_par", 0), ("T_par", 1), ("SH", 2), ("T_perp", 0), ("L_perp", 1), ("SH_perp", 2)):
        np.testing.assert_allclose(r[f"polarisation_{name}"], np.eye(3)[axis], atol=1e-12)


def test_prestress_enters_like_the_acoustic_tensor():
    """A uniaxial sigma along x1 = [100] adds sigma to rho v^2 of every wave along x1 and nothing
    along x2 (A_ijkl n_j n_l = C_ijkl n_j n_l + sigma_jl n_j n_l delta_ik, PHYSICS.md)."""
    base = surfwave.material(C11, C12, C44, RHO, "[100]")
    s = -2.0
    r = surfwave.material(C11, C12, C44, RHO, "[100]", stress=s)
    for key in ("c_L_par", "c_T_par", "c_SH"):
        assert r[key] ** 2 == pytest.approx(base[key] ** 2 + s * 1e9 / RHO, rel=1e-12)
    for key in ("c_L_perp", "c_T_perp", "c_SH_perp"):
        assert r[key] == pytest.approx(base[key], rel=1e-12)


def _lab(mat, euler):
    R = euler_lab_axes(np.asarray(euler, dtype=float)).reshape(-1, 3, 3)
    C = rotate4(np.broadcast_to(mat.C_tensor, (len(R), 3, 3, 3, 3)), R)
    e = rotate3(np.broadcast_to(mat.e_tensor, (len(R), 3, 3, 3)), R)
    eps = rotate2(np.broadcast_to(mat.eps, (len(R), 3, 3)), R)
    return C, e, eps


def test_stiffened_speeds_are_roots_of_the_coupled_4x4_problem():
    """Independent route: a plane wave exp(ik(n.x - vt)) of the coupled (u, phi) problem needs
    det(E_iJKl n_i n_l - rho v^2 I') = 0 with the 4 x 4 generalised tensor of the brute-force
    test helper (phi block -eps, no Schur complement taken). Each returned speed along x1 and x2
    (LiNbO3, 12 random Euler angles) is such a root, its polarisation the displacement part of
    the null vector."""
    mat = get_piezo_material("LiNbO3")
    rng = np.random.default_rng(7)
    euler = rng.uniform(-180, 180, (12, 3))
    C, e, eps = _lab(mat, euler)
    r = axis_waves(C, np.full(len(C), mat.rho), e, eps)
    for i in range(len(C)):
        E = generalised_tensor(C[i], e[i], eps[i])
        for axis, names in ((0, ("L_par", "T_par", "SH")), (1, ("T_perp", "L_perp", "SH_perp"))):
            M0 = E[:, axis, :, axis]
            scale = np.abs(M0[:3, :3]).max()
            for name in names:
                v = r[f"c_{name}"][i]
                M = M0.copy()
                M[:3, :3] -= mat.rho * v ** 2 * np.eye(3)
                M[3] /= np.sqrt(abs(M0[3, 3]) * scale) / scale        # rows of one scale
                M[:, 3] /= np.sqrt(abs(M0[3, 3]) * scale) / scale
                s = np.linalg.svd(M, compute_uv=False)
                assert s[-1] / s[0] < 1e-9, (i, name)
                null = np.linalg.svd(M)[2][-1]
                u = null[:3] / np.linalg.norm(null[:3])
                assert abs(abs(u @ r[f"polarisation_{name}"][i]) - 1) < 1e-8, (i, name)


def test_stiffening_only_raises_and_vanishes_with_e():
    """Weyl: the stiffening g g^T / (n eps n) is positive semi-definite, so each ordered speed
    can only rise; with e = 0 the speeds are those of the elastic Christoffel tensor (numpy
    eigvalsh of A n n / rho, computed here)."""
    mat = get_piezo_material("LiNbO3")
    euler = np.random.default_rng(3).uniform(-90, 90, (20, 3))
    C, e, eps = _lab(mat, euler)
    rho = np.full(len(C), mat.rho)
    stiff, bare = axis_waves(C, rho, e, eps), axis_waves(C, rho)
    for names in (BULK_SPEEDS[:3], BULK_SPEEDS[3:]):
        s = np.sort(np.stack([stiff[k] for k in names], -1), -1)
        b = np.sort(np.stack([bare[k] for k in names], -1), -1)
        assert np.all(s >= b * (1 - 1e-12))
    for axis, names in ((0, BULK_SPEEDS[:3]), (1, BULK_SPEEDS[3:])):
        want = np.sqrt(np.linalg.eigvalsh(C[:, :, axis, :, axis]) / mat.rho)
        got = np.sort(np.stack([bare[k] for k in names], -1), -1)
        np.testing.assert_allclose(got, want, rtol=1e-12)


@pytest.mark.filterwarnings("ignore::surfwave.errors.ConstantsNote")   # langasite is a provisional set
def test_langasite_z_cut_slowest_speed_follows_psi():
    """Issue 27: on Z-cut langasite the slowest bulk speed along x1 runs from about 2711 m/s
    (psi = 30) to about 2380 m/s (psi = 0), while the diagonal of the acoustic tensor gave a
    constant 2718.1 m/s. Elastic (e = 0) eigen-speeds checked against the issue's figures to
    0.3 %; the stiffened ones are not below them."""
    m = get_piezo_material("langasite")
    euler = [[0, 0, 0], [0, 0, 30]]
    bare = surfwave.material(voigt=m.voigt, rho=m.rho, euler=euler)
    stiff = surfwave.material("langasite", euler=euler)
    slow = np.min([bare[k] for k in ("c_L_par", "c_T_par", "c_SH")], axis=0)
    assert slow[0] == pytest.approx(2380, rel=3e-3) and slow[1] == pytest.approx(2711, rel=3e-3)
    slow_stiff = np.min([stiff[k] for k in ("c_L_par", "c_T_par", "c_SH")], axis=0)
    assert np.all(slow_stiff >= slow - 1e-9)


def test_no_bulk_speed_along_x1_below_the_limiting_speed():
    """The limiting speed is the lowest trace speed along x1 over all sagittal slownesses, and
    the bulk waves along x1 are three of those: none may be slower (the diagonal of the acoustic
    tensor failed this on LiNbO3 at random Euler angles, issue 27), nor the SAW faster."""
    euler = np.random.default_rng(11).uniform(-180, 180, (16, 3))
    r = surfwave.material("LiNbO3", euler=euler, leaky=False)
    slowest = np.min([r[k] for k in ("c_L_par", "c_T_par", "c_SH")], axis=0)
    assert np.all(slowest >= r["c_limit"] * (1 - 1e-9))
    ok = r["wave_type"] == "surface"
    assert ok.sum() > 8 and np.all(r["c_R"][ok] <= slowest[ok])


def test_pure_longitudinal_along_x_of_a_rotated_y_cut():
    """Along crystal X of LiNbO3 (3m, mirror normal to X) the longitudinal wave is pure and
    unstiffened (g = (0, -e22, e15) has no u1 part): c_L_par = sqrt(C11 / rho) = 6572.0 m/s for
    every rotated Y cut, polarised exactly along u1."""
    m = get_piezo_material("LiNbO3")
    r = surfwave.material("LiNbO3", euler=[[0, -26, 0], [0, 38, 0], [0, -49, 0]], leaky=False)
    np.testing.assert_allclose(r["c_L_par"], np.sqrt(m.voigt[0, 0] * 1e9 / m.rho), rtol=1e-12)
    np.testing.assert_allclose(r["polarisation_L_par"], np.tile([1.0, 0, 0], (3, 1)), atol=1e-12)


def test_every_key_and_nan_without_a_state():
    """The six speeds and six polarisations come from every point; a point without a stressed
    state (Cu, third-order constants, -20 GPa along [100]: no homogeneous state) is NaN in all."""
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.stressed_wave import Constants, stress_tensor, surface_wave
    from surfwave.solvers.orientation import lab_axes

    R = lab_axes("(001)", "[100]")
    r = surface_wave(Constants.from_material(get_material("Cu")), R, stress_tensor("along", np.array([0.0, -20.0]), R),
                     toec=True, leaky=False)
    assert r["ok"].tolist() == [True, False]
    for key in BULK_SPEEDS + BULK_POLARISATIONS:
        assert np.all(np.isfinite(r[key][0])) and np.all(np.isnan(r[key][1])), key


def test_model_crystals_keep_the_papers_definitions():
    """The model crystals' speeds stay Eq. (A7) (PHYSICS.md): c2_T_par = S_xyyx, c2_L_par = S_xxxx,
    c2_SH = S_xzzx (per volume, m = 1), also at a general FCC angle (20 deg, LJ, d/d0 = 0.97)
    where the coupled eigen-speeds of the same acoustic tensor differ from them."""
    r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", 20.0, 0.97)
    S = r["S"][0]
    assert r["c2_T_par"][0] == S[0, 1, 1, 0] and r["c2_L_par"][0] == S[0, 0, 0, 0] and r["c2_SH"][0] == S[0, 2, 2, 0]
    eig = np.linalg.eigvalsh(S[:, 0, :, 0])                 # Q_ik = S_i1k1, volume-weighted, m = 1
    assert np.min(np.abs(eig - r["c2_SH"][0])) > 1e-4     # not the same numbers: the paper's stay
