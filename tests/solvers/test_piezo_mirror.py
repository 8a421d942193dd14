"""Piezoelectric solver at sagittal mirrors (surfwave.solvers.piezo / piezo_search) and speed-up parts.

GaAs (class -43m): C11, C12, C44 = 118.8, 53.8, 59.4 GPa, e14 = -0.16 C/m^2, eps_r = 12.5,
rho = 5307 kg/m^3 (Auld, Acoustic Fields and Waves in Solids, vol. 1, appendix 2 / Slobodnik,
Conway, Delmonico, Microwave Acoustics Handbook 1A (1973), which gives 2864 m/s and K^2 ~ 0.07 %
for (001)[110]). Cu and Pb: C11, C12, C44 = 168.4, 121.4, 75.4 and 49.66, 42.31, 14.98 GPa,
rho 8960 and 11300 kg/m^3 (as in tests/solvers/test_stroh.py and the materials database).
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg

from surfwave.solvers import piezo, stroh
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.piezo import EPS0, piezo_surface_wave
from surfwave.solvers.piezo_search import mirror_partition
from surfwave.solvers.tensors import VOIGT_INDEX, cubic_voigt, rotate2, rotate4, voigt_to_tensor

CU = (168.4e9, 121.4e9, 75.4e9)
PB = (49.66e9, 42.31e9, 14.98e9)


def gaas(C=(118.8e9, 53.8e9, 59.4e9), e14=-0.16, rho=5307.0):
    """(C Pa, e_kij C/m^2, eps F/m, rho) of a -43m crystal, crystal axes (e_14 = e_25 = e_36)."""
    e6 = np.zeros((3, 6))
    e6[0, 3] = e6[1, 4] = e6[2, 5] = e14
    return voigt_to_tensor(cubic_voigt(*C)), e6[:, VOIGT_INDEX], np.eye(3) * 12.5 * EPS0, rho


def lab(mat, R):
    C, e, eps, rho = mat
    R = np.asarray(R, dtype=float).reshape(-1, 3, 3)
    return rotate4(C, R), np.einsum("mai,mbj,mck,ijk->mabc", R, R, R, e), rotate2(eps, R), rho


def _invariant(e, M):
    """Whether e_kij (m, 3, 3, 3) is invariant under the orthogonal map M (lab frame)."""
    eM = np.einsum("ai,bj,ck,mijk->mabc", M, M, M, e)
    return np.abs(eM - e).max(axis=(1, 2, 3)) <= 1e-12 * np.abs(e).max()


def test_mirror_partition_follows_the_symmetry_of_e():
    """The partition found from the blocks equals the symmetry of the lab-frame e itself (an
    independent check: e is invariant under the mirror x3 -> -x3 iff phi goes with (u1, u2);
    under the two-fold rotation about x3 iff phi goes with u3). GaAs (001)[110] (mirror (1-10)):
    sagittal+phi; (001)[100] (-4 axis along [010], no mirror): sagittal; 20 deg: none; Y-Z
    LiNbO3 (mirror normal to crystal X): sagittal+phi."""
    A, e, eps, rho = lab(gaas(), lab_axes("(001)", np.array([45.0, 0.0, 20.0])))
    Q, R, T = piezo.generalised_blocks(A / 1e11, e / 10 ** 0.5, eps / 1e-10)
    got = list(mirror_partition(Q, R, T))
    assert got == ["sagittal+phi", "sagittal", ""]
    mirror, twofold = _invariant(e, np.diag([1.0, 1, -1])), _invariant(e, np.diag([-1.0, -1, 1]))
    assert list(mirror) == [True, False, False] and list(twofold) == [False, True, False]


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_zero_e_mirrors_equal_elastic_solver(electrical):
    """e = 0: wave_type, c and c_limit equal surfwave.solvers.stroh.surface_wave (Eq. 17 at these
    orthotropic mirrors, an independent closed form) to 1e-12: Cu and Pb (001) at 0 deg
    (surface) and 45 deg (supersonic_decoupled: the sagittal wave outruns the SH bulk wave)."""
    A = rotate4(voigt_to_tensor(cubic_voigt(*np.array([CU, PB]).repeat(2, 0).T)),
                lab_axes("(001)", np.array([0.0, 45.0, 0.0, 45.0])))
    rho = np.array([8960.0, 8960.0, 11300.0, 11300.0])
    ref = stroh.surface_wave(A, rho)
    r = piezo_surface_wave(A, np.zeros((4, 3, 3, 3)), np.broadcast_to(np.eye(3) * 1e-11, (4, 3, 3)), rho,
                           electrical=electrical)
    assert list(ref["wave_type"]) == ["surface", "supersonic_decoupled"] * 2
    assert list(r["wave_type"]) == list(ref["wave_type"])
    np.testing.assert_allclose(r["c"], ref["c"], rtol=1e-12)
    np.testing.assert_allclose(r["c_limit"], ref["c_limit"], rtol=1e-12)


def test_gaas_001_110_is_a_piezo_coupled_supersonic_mirror_wave():
    """GaAs (001)[110]: the sagittal wave (2864 m/s, K^2 ~ 0.07 %, Slobodnik et al. 1973) lies above
    the SH bulk wave (C11 - C12)/2 (v_L = 2475 m/s) and exists only by the mirror: both
    conditions supersonic_decoupled, free > metallized. Independent route: scipy eigenvectors of
    the 6 x 6 Stroh matrix of the (u1, u2, phi) sub-problem at the found X; the boundary matrix
    [B_1, B_2; B_phi - i EPS0 A_phi] (free) or [B_1, B_2; A_phi] (metallized) is singular.
    (001)[100]: phi decouples from the sagittal wave (K^2 = 0 exactly)."""
    A, e, eps, rho = lab(gaas(), lab_axes("(001)", np.array([45.0, 0.0])))
    k = piezo.coupling_coefficient(A, e, eps, rho)
    assert list(k["free"]["wave_type"]) == ["supersonic_decoupled", "surface"]
    assert list(k["metallized"]["wave_type"]) == ["supersonic_decoupled", "surface"]
    assert k["c_free"][0] == pytest.approx(2864.0, rel=2e-3) and k["c_free"][0] > k["free"]["c_limit"][0]
    assert 5e-4 < k["K2"][0] < 9e-4 and k["K2"][1] == 0.0
    assert k["free"]["power_flow_angle"][0] == 0.0
    Q, R, T = piezo.generalised_blocks(A[:1] / 1e11, e[:1] / 10 ** 0.5, eps[:1] / 1e-10)
    S = [0, 1, 3]
    q, r, t = (B[:, S][:, :, S] for B in (Q, R, T))
    for el in ("free", "metallized"):
        X = rho * k["c_" + el][:1] ** 2 / 1e11
        w, V = scipy.linalg.eig(piezo.stroh_matrix(q, r, t, X, 2)[0])
        V = V[:, w.imag > 0]
        assert V.shape[1] == 3
        Am, Bm = V[:3], V[3:]
        last = Bm[2] - 1j * EPS0 / 1e-10 * Am[2] if el == "free" else Am[2]
        s = np.linalg.svd(np.vstack([Bm[:2], last]), compute_uv=False)
        assert s[-1] / s[0] < 1e-8


def test_piezo_supersonic_tends_to_elastic_as_e_vanishes():
    """Pb elastic constants with GaAs's e14 at (001)[110] (a strongly supersonic mirror wave):
    K^2 scales as s^2 when e is scaled by s (first-order perturbation), and at s = 0 both
    conditions equal the elastic solver's supersonic_decoupled speed (Eq. 17) to 1e-12."""
    s = np.array([1.0, 1e-2, 1e-3, 0.0])
    mats = [lab(gaas(C=PB, e14=-0.16 * x, rho=11300.0), lab_axes("(001)", 45.0)) for x in s]
    A, e, eps = (np.concatenate([m[i] for m in mats]) for i in range(3))
    k = piezo.coupling_coefficient(A, e, eps, 11300.0)
    assert np.all(k["free"]["wave_type"] == "supersonic_decoupled")
    ref = stroh.surface_wave(A[-1], 11300.0)
    assert ref["wave_type"] == "supersonic_decoupled"
    np.testing.assert_allclose([k["c_free"][-1], k["c_metallized"][-1]], ref["c"], rtol=1e-12)
    assert k["K2"][1] / s[1] ** 2 == pytest.approx(k["K2"][2] / s[2] ** 2, rel=1e-3)
    assert np.all(k["K2"][:3] > 0)


def test_coupling_in_one_call_equals_two_calls():
    """coupling_coefficient shares the limiting speed and the first step between the two
    conditions; its speeds equal two separate piezo_surface_wave calls (1e-13)."""
    A, e, eps, rho = lab(gaas(), lab_axes("(111)", np.array([3.0, 17.0, 40.0])))
    k = piezo.coupling_coefficient(A, e, eps, rho)
    for el in ("free", "metallized"):
        np.testing.assert_allclose(k["c_" + el], piezo_surface_wave(A, e, eps, rho, electrical=el)["c"], rtol=1e-13)


def test_impedance_slope_equals_finite_difference():
    """The closed-form a^H dZ/dX a (Sylvester / Cayley-Hamilton) against a central difference of
    the impedance (h = 1e-6 X, error ~1e-10), for a = (u, phi) generic complex vectors."""
    A, e, eps, rho = lab(gaas(), lab_axes("(111)", np.array([17.0])))
    Q, R, T = piezo.generalised_blocks(A / 1e11, e / 10 ** 0.5, eps / 1e-10)
    X = np.array([0.3 * piezo.limiting_x(Q, R, T)[0]])
    a = np.array([[0.3 + 0.1j, -0.5j, 0.7, 0.2 - 0.4j]])
    slope = piezo.impedance_slope(piezo.impedance(Q, R, T, X), a)
    h = 1e-6 * X
    dZ = (piezo.impedance(Q, R, T, X + h)["Z"] - piezo.impedance(Q, R, T, X - h)["Z"]) / (2 * h)
    assert slope[0] == pytest.approx(np.einsum("mi,mij,mj->m", np.conj(a), dZ, a).real[0], rel=1e-7)
