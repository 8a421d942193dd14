"""Piezoelectric surface-wave solver (surfwave.solvers.piezo): limits, published cuts, power flow.

Crystal constants come from the materials database (surfwave.real_crystals.piezo_materials,
piezoelectric.yaml; one copy of each number, sources and provenance there): LiNbO3 is the set of
the Y-Z cut record (Warner, Onoe, Coquin, J. Acoust. Soc. Am. 42, 1223 (1967)), alpha-quartz the
set of the ST-X record (Bechmann, Phys. Rev. 110, 1060 (1958), IEEE-1949 right-handed axes).
Copper C11, C12, C44 = 168.4, 121.4, 75.4 GPa, rho = 8960 (as in tests/test_stroh.py).
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from surfwave.errors import InputError
from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material
from surfwave.solvers import piezo, stroh
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.piezo import EPS0, euler_lab_axes, piezo_surface_wave
from surfwave.solvers.tensors import cubic_voigt, rotate2, rotate4, voigt_to_tensor

CU = (168.4e9, 121.4e9, 75.4e9)
#: Voigt positions of C14 in the trigonal form (C14 at 14, 41, 56, 65; -C14 at 24, 42).
_C14_POSITIONS = ((0, 3), (3, 0), (1, 3), (3, 1), (4, 5), (5, 4))


def _crystal(name, flip_c14=False):
    """(C Pa, e_kij C/m^2, eps F/m, rho kg/m^3) in crystal axes from the database; ``flip_c14``
    changes the sign of C14 (the pre-IEEE-1978 sign confusion, for the trap test)."""
    m = get_piezo_material(name)
    if not flip_c14:
        return m.C_tensor, m.e_tensor, m.eps, m.rho
    V = np.array(m.voigt, dtype=float) * 1e9
    for i, j in _C14_POSITIONS:
        V[i, j] = -V[i, j]
    return voigt_to_tensor(V), m.e_tensor, m.eps, m.rho


def linbo3():
    """LiNbO3 (class 3m, mirror normal to crystal X), the set of the database's Y-Z record."""
    return _crystal(get_cut("Y-Z").material)


def quartz(flip_c14=False):
    """alpha-quartz (class 32, two-fold axis along crystal X), the set of the ST-X record."""
    return _crystal(get_cut("ST-X").material, flip_c14)


def lab(mat, R):
    """Lab-frame (A, e, eps, rho) of a crystal for lab axes R (..., 3, 3) -> batch (m, ...)."""
    C, e, eps, rho = mat
    R = np.asarray(R, dtype=float).reshape(-1, 3, 3)
    return (rotate4(C, R), np.einsum("mai,mbj,mck,ijk->mabc", R, R, R, e), rotate2(eps, R), rho)


def _rot_z(deg):
    c, s = np.cos(np.radians(deg)), np.sin(np.radians(deg))
    return np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])


@pytest.mark.parametrize("mat, second", [(linbo3(), np.diag([-1.0, 1, 1])),      # 3m: mirror x -> -x
                                         (quartz(), np.diag([1.0, -1, -1]))])     # 32: two-fold about X
def test_trigonal_forms_are_invariant_under_the_point_group(mat, second):
    """The database tensors used here have the standard trigonal forms: C, e, eps unchanged by the
    generators of the point group (Nye, Physical Properties of Crystals: 3m = {3z, m_x}, 32 = {3z, 2x})."""
    for g in (_rot_z(120.0), second):
        C, e, eps, _ = lab(mat, g)
        np.testing.assert_allclose(C[0], mat[0], atol=1e-6 * np.abs(mat[0]).max())
        np.testing.assert_allclose(e[0], mat[1], atol=1e-12)
        np.testing.assert_allclose(eps[0], mat[2], atol=1e-24)


def _random_stable(m, seed):
    rng = np.random.default_rng(seed)
    B = rng.normal(size=(m, 6, 6))
    return voigt_to_tensor(B @ np.swapaxes(B, 1, 2) + 2 * np.eye(6)) * 1e10


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_zero_e_equals_elastic_solver(electrical):
    """e = 0: phi decouples, so c and v_L must equal surfwave.solvers.stroh.surface_wave (an
    independent implementation: 6 x 6 Stroh, Newton root search) to 1e-12 relative; random
    triclinic stiffnesses, Cu (001) / (111) off the mirrors, Cu (001)[100] (a mirror: the elastic
    solver takes Eq. 17) and an isotropic medium (degenerate Stroh roots)."""
    A = np.concatenate([_random_stable(12, 3),
                        rotate4(voigt_to_tensor(cubic_voigt(*CU)), lab_axes("(001)", np.array([7.0, 20.0, 33.0]))),
                        rotate4(voigt_to_tensor(cubic_voigt(*CU)), lab_axes("(111)", np.array([11.0, 47.0]))),
                        rotate4(voigt_to_tensor(cubic_voigt(*CU)), lab_axes("(001)", np.array([0.0]))),
                        voigt_to_tensor(cubic_voigt(3e10, 1e10, 1e10))[None]])
    m = len(A)
    eps = np.broadcast_to(np.array([[3.0, 0.5, 0.2], [0.5, 4.0, -0.3], [0.2, -0.3, 5.0]]) * 1e-11, (m, 3, 3))
    r = piezo_surface_wave(A, np.zeros((m, 3, 3, 3)), eps, 8960.0, electrical=electrical)
    ref = stroh.surface_wave(A, 8960.0)
    assert np.all(ref["wave_type"] == "surface") and np.all(r["wave_type"] == "surface")
    np.testing.assert_allclose(r["c"], ref["c"], rtol=1e-12)
    np.testing.assert_allclose(r["c_limit"], ref["c_limit"], rtol=1e-12)
    overlap = np.abs(np.einsum("mi,mi->m", np.conj(r["polarisation"][:, :3]), ref["polarisation"]))
    np.testing.assert_allclose(overlap, 1.0, atol=1e-8)
    assert np.all(r["potential_share"] < 1e-20)


def _yz():
    return lab(linbo3(), euler_lab_axes(0.0, 90.0, 90.0))           # normal -Y (SAW outward), x1 = Z


def test_yz_linbo3_published_speeds_and_coupling():
    """Y-Z LiNbO3 with the Warner et al. (1967) set: v_free 3488, v_metallized 3404 m/s, K^2 4.8 %
    (Slobodnik, Conway, Delmonico, Microwave Acoustics Handbook 1A (1973); Campbell & Jones, IEEE
    Trans. Sonics Ultrason. 15, 209 (1968), computed from the same constants). The Euler frame
    (0, 90, 90) is checked against the explicit axes x1 = Z, x2 = +-Y (the sign of the normal
    cannot change the speed: inversion maps e -> -e, phi -> -phi)."""
    k = piezo.coupling_coefficient(*_yz())
    assert k["c_free"][0] == pytest.approx(3488.0, rel=3e-3)
    assert k["c_metallized"][0] == pytest.approx(3404.0, rel=3e-3)
    assert k["K2"][0] == pytest.approx(0.048, abs=5e-4)                # quoted to 0.1 %
    R = euler_lab_axes(0.0, 90.0, 90.0)
    np.testing.assert_allclose(R, [[0, 0, 1], [0, 1, 0], [-1, 0, 0]], atol=1e-15)
    k2 = piezo.coupling_coefficient(*lab(linbo3(), np.array([[0, 0, 1.0], [0, -1, 0], [1, 0, 0]])))
    np.testing.assert_allclose(k2["c_free"], k["c_free"], rtol=1e-12)
    np.testing.assert_allclose(k2["c_metallized"], k["c_metallized"], rtol=1e-12)


def test_st_x_quartz_and_the_c14_sign_trap():
    """ST-X quartz, Euler (0, 132.75, 0), Bechmann constants: 3158 m/s, K^2 ~ 0.11 % (Slobodnik et al.,
    Microwave Acoustics Handbook 1A; Schulz, Matsinger, Holland, J. Appl. Phys. 41, 2755 (1970)).
    (0, -47.25, 0) is the same cut (two-fold X axis). C14 -> -C14 (the pre-IEEE-1978 sign
    confusion) moves the speed by several per cent, so the convention is tested."""
    r = piezo.coupling_coefficient(*lab(quartz(), euler_lab_axes(0.0, [132.75, -47.25], 0.0)))
    assert r["c_free"][0] == pytest.approx(3158.0, rel=3e-3)
    np.testing.assert_allclose(r["c_free"][1], r["c_free"][0], rtol=1e-12)
    assert r["K2"][0] == pytest.approx(0.0011, abs=1e-4)
    flipped = piezo_surface_wave(*lab(quartz(flip_c14=True), euler_lab_axes(0.0, 132.75, 0.0)))
    assert abs(flipped["c"][0] / r["c_free"][0] - 1) > 0.02


def _fd_angle(mat, euler, electrical, h=1e-3):
    psi = euler[2] + np.array([-h, 0.0, h])
    r = piezo_surface_wave(*lab(mat, euler_lab_axes(euler[0], euler[1], psi)), electrical=electrical)
    dv = (r["c"][2] - r["c"][0]) / (2 * np.radians(h))
    return r["power_flow_angle"][1], np.degrees(np.arctan(dv / r["c"][1]))


@pytest.mark.parametrize("electrical", ["free", "metallized"])
@pytest.mark.parametrize("mat, euler", [(quartz(), (0.0, 132.75, 20.0)), (linbo3(), (0.0, 38.0, 25.0)),
                                        (linbo3(), (30.0, 50.0, 25.0))])
def test_power_flow_angle_equals_slowness_normal(mat, euler, electrical):
    """Energy velocity = group velocity: the flux angle (SAW convention, towards +x2_SAW) obeys
    tan(PFA) = (1/v) dv/dpsi, psi the third Euler angle (it turns x1 towards +x2_SAW), against a
    central finite difference of v (h = 1e-3 deg, error ~1e-7 deg). For the free surface the
    vacuum's flux matters: without it 128-ish Y LiNbO3 at psi = 25 is off by ~3e-3 deg."""
    pfa, ref = _fd_angle(mat, euler, electrical)
    assert abs(pfa) > 1.0
    assert pfa == pytest.approx(ref, abs=1e-6)


def test_power_flow_angle_elastic_and_symmetric_cuts():
    """Cu (001) at 20 deg, e = 0: lab_axes' angle theta turns x1 towards -x3, so
    tan(PFA) = -(1/v) dv/dtheta (finite difference). On symmetric cuts (Y-Z LiNbO3, ST-X
    quartz at psi = 0) v(psi) is even, so the flux angle is 0."""
    h = 1e-3
    th = 20.0 + np.array([-h, 0.0, h])
    A = rotate4(voigt_to_tensor(cubic_voigt(*CU)), lab_axes("(001)", th))
    r = piezo_surface_wave(A, np.zeros((3, 3, 3, 3)), np.broadcast_to(np.eye(3) * 1e-11, (3, 3, 3)), 8960.0)
    dv = (r["c"][2] - r["c"][0]) / (2 * np.radians(h))
    assert r["power_flow_angle"][1] == pytest.approx(np.degrees(np.arctan(-dv / r["c"][1])), abs=1e-6)
    for mat in (_yz(), lab(quartz(), euler_lab_axes(0.0, 132.75, 0.0))):
        for el in ("free", "metallized"):
            assert abs(piezo_surface_wave(*mat, electrical=el)["power_flow_angle"][0]) < 1e-10


def test_coupling_scales_as_e_squared():
    """Free > metallized and K^2 > 0 (Y-Z LiNbO3); scaling e by s, K^2 ~ s^2 (first-order
    perturbation: the speed shift is quadratic in e). K^2/s^2 at s = 1e-3 and 1e-2 agree to
    1e-3, and s = 1e-4 is still positive and on the same line to 1 %."""
    A, e, eps, rho = _yz()
    s = np.array([1e-4, 1e-3, 1e-2, 1.0])
    k = piezo.coupling_coefficient(np.repeat(A, 4, 0), s[:, None, None, None] * e, np.repeat(eps, 4, 0), rho)
    assert np.all(k["c_free"] > k["c_metallized"]) and np.all(k["K2"] > 0)
    ratio = k["K2"] / s ** 2
    assert ratio[1] == pytest.approx(ratio[2], rel=1e-3)
    assert ratio[0] == pytest.approx(ratio[1], rel=1e-2)
    assert np.all(np.diff(k["K2"]) > 0)


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_root_satisfies_boundary_conditions_by_eigenvectors(electrical):
    """Independent route: scipy eigenvectors of the 8 x 8 N at the found X; the 4 x 4 boundary
    matrix [B_1..3; B_4 - i EPS0 A_4] (free: D_2 continuous with the vacuum, b_4 = +i EPS0 phi)
    or [B_1..3; A_4] (metallized) is singular (smallest singular value / largest < 1e-8).
    In units of 100 GPa, 1e-10 F/m and sqrt(10) C/m^2 so that the rows are comparable."""
    A, e, eps, rho = lab(linbo3(), euler_lab_axes(0.0, 38.0, 25.0))
    r = piezo_surface_wave(A, e, eps, rho, electrical=electrical)
    Q, R, T = piezo.generalised_blocks(A / 1e11, e / 10 ** 0.5, eps / 1e-10)
    X = rho * r["c"] ** 2 / 1e11
    N = piezo.stroh_matrix(Q, R, T, X)[0]
    w, V = scipy.linalg.eig(N)
    V = V[:, w.imag > 0]
    Am, Bm = V[:4], V[4:]
    last = Bm[3] - 1j * EPS0 / 1e-10 * Am[3] if electrical == "free" else Am[3]
    s = np.linalg.svd(np.vstack([Bm[:3], last]), compute_uv=False)
    assert s[-1] / s[0] < 1e-8
    # the wrong sign of the vacuum term is not a root
    if electrical == "free":
        s2 = np.linalg.svd(np.vstack([Bm[:3], Bm[3] + 1j * EPS0 / 1e-10 * Am[3]]), compute_uv=False)
        assert s2[-1] / s2[0] > 1e-5


def test_outputs_pseudo_and_unstable():
    """Outputs: unit mechanical polarisation, Im p > 0, 0 < potential share < 1 for Y-Z LiNbO3;
    |phi|/|u| of order e22/eps11 (6e9 V/m). e = 0 Cu (001) at 44.99 deg: the elastic solver
    calls it pseudo (root within 1e-12 of v_L), so must this one; a negative bulk modulus (C11 +
    2 C12 < 0, Born) gives 'none'."""
    r = piezo_surface_wave(*_yz())
    assert np.linalg.norm(r["polarisation"][0, :3]) == pytest.approx(1.0, rel=1e-12)
    assert np.all(r["decay"].imag > 0) and 0 < r["potential_share"][0] < 1
    assert 1e9 < abs(r["polarisation"][0, 3]) < 2e10
    A = rotate4(voigt_to_tensor(np.stack([cubic_voigt(*CU), cubic_voigt(50e9, -80e9, 30e9)])),
                lab_axes("(001)", 44.99))
    out = piezo_surface_wave(A, np.zeros((2, 3, 3, 3)), np.broadcast_to(np.eye(3) * 1e-11, (2, 3, 3)), 8960.0)
    assert list(out["wave_type"]) == ["pseudo", "none"]
    assert np.all(np.isnan(out["c"])) and "pseudo" in out["reason"][0] and out["reason"][1]
    assert np.isfinite(out["c_limit"][0])


def test_bad_input():
    """InputError naming the value: eps not positive definite, e of the wrong shape, non-finite
    entries, rho <= 0, an unknown electrical condition."""
    A, e, eps, rho = _yz()
    with pytest.raises(InputError, match="positive definite.*-1"):
        piezo_surface_wave(A, e, -eps, rho)
    with pytest.raises(InputError, match=r"\(1, 3, 6\)"):
        piezo_surface_wave(A, np.zeros((1, 3, 6)), eps, rho)
    bad = e.copy()
    bad[0, 0, 0, 0] = np.nan
    with pytest.raises(InputError, match="nan"):
        piezo_surface_wave(A, bad, eps, rho)
    with pytest.raises(InputError, match="-1"):
        piezo_surface_wave(A, e, eps, -1.0)
    with pytest.raises(InputError, match="shorted"):
        piezo_surface_wave(A, e, eps, rho, electrical="shorted")


def test_batch_equals_one_by_one():
    """A batch of 9 LiNbO3 orientations with mixed electrical conditions equals the same points
    solved one at a time (each point's iteration is independent of the others)."""
    R = euler_lab_axes(np.array([0, 10, 20, 30, 40, 50, 60, 70, 80.0]), 40.0, np.linspace(0, 160, 9))
    A, e, eps, rho = lab(linbo3(), R)
    el = np.array(["free", "metallized"] * 4 + ["free"], dtype=object)
    r = piezo_surface_wave(A, e, eps, rho, electrical=el)
    for i in range(9):
        one = piezo_surface_wave(A[i:i + 1], e[i:i + 1], eps[i:i + 1], rho, electrical=el[i])
        for key in ("c", "c_limit", "power_flow_angle", "potential_share"):
            np.testing.assert_allclose(r[key][i], one[key][0], rtol=1e-13, atol=1e-13)


def test_stiffened_bulk_speeds_and_limiting_speed():
    """Along crystal Z of LiNbO3 the stiffened longitudinal wave has rho v^2 = C33 + e33^2/eps33 and
    the shear waves C44 (closed form: gamma = (0, 0, e33), Auld, Acoustic Fields and Waves, ch. 8).
    c_limit equals the minimum over a fine grid (20001 sagittal normals, then parabolic vertex) of
    the trace speeds v(n)/cos(phi) from piezo_bulk_speeds (brute force, independent of the search)."""
    C, e, eps, rho = lab(linbo3(), np.eye(3))
    v = piezo.piezo_bulk_speeds(C, e, eps, rho, [0.0, 0.0, 1.0])[0]
    m = get_piezo_material(get_cut("Y-Z").material)
    c44, c33, e33, eps33 = m.voigt[3, 3] * 1e9, m.voigt[2, 2] * 1e9, m.e[2, 2], m.eps_r[2, 2] * EPS0
    np.testing.assert_allclose(v ** 2 * rho, [c44, c44, c33 + e33 ** 2 / eps33], rtol=1e-13)
    A, e, eps, rho = lab(linbo3(), euler_lab_axes(20.0, 50.0, 35.0))
    phi = np.linspace(-1.5, 1.5, 20001)
    n = np.stack([np.cos(phi), np.sin(phi), np.zeros_like(phi)], axis=-1)
    k = phi.size
    tr = piezo.piezo_bulk_speeds(np.repeat(A, k, 0), np.repeat(e, k, 0), np.repeat(eps, k, 0), rho, n)[:, 0] / np.cos(phi)
    j = int(np.argmin(tr))
    y0, y1, y2 = tr[j - 1:j + 2]
    vmin = y1 - 0.125 * (y2 - y0) ** 2 / (y0 - 2 * y1 + y2)
    c_lim = piezo_surface_wave(A, e, eps, rho)["c_limit"][0]
    assert c_lim == pytest.approx(vmin, rel=1e-9) and c_lim <= tr.min() * (1 + 1e-14)
