"""Leaky (pseudo) surface waves: surfwave.solvers.leaky.leaky_wave.

References used below (each test names its own):
* exact mirror-symmetric supersonic wave of Cu(001)[110]: the sagittal Rayleigh root of
  ``surfwave.material('Cu', direction='[110]')`` (Eq. 17 closed form, an independent solver);
* the relation dp/dX = 1 / (2 rho v V_g2) for a real bulk root (implicit differentiation of the
  bulk dispersion relation) for the outgoing-wave choice;
* the real-speed minimum of |det| (second route), with the closed-form O(eta^2) offset below;
* LiNbO3 / LiTaO3 leaky speeds quoted in the brief (64Y-X 4742 / 4478, 41Y-X 4792 / 4379,
  36Y-X LiTaO3 4212 free / 4112 metallized m/s) and Yamanouchi & Shibayama, J. Appl. Phys. 43, 856
  (1972): 64Y-X LiNbO3 K^2 = 0.113, attenuation 0.036 dB per wavelength free and "goes to zero"
  metallized; Y-Z LiNbO3 subsonic 3488 / 3404 m/s (Slobodnik 1973). Constants and cuts come from
  the database (piezoelectric.yaml): each named cut carries the set that reproduces its quote
  (LiNbO3: Warner 1967; LiTaO3: the Kovacs 1990 set as held, unverified); the published-value
  comparisons with stated tolerances live in tests/real_crystals/test_named_cuts.py.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals.piezo_materials import get_cut, lab_tensors
from surfwave.solvers import leaky as L
from surfwave.solvers import leaky_search as LS
from surfwave.solvers import orientation, tensors
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.leaky import EPS0, leaky_wave

#: The LiNbO3 set behind the quoted rotated Y-X leaky speeds (database cut record).
LN = get_cut("64Y-X").material
LT = get_cut("36Y-X").material


def _partial_waves(Q, R, T, X, d):
    """Stroh roots p (m, 2d) and eigenvectors (m, 2d, 2d) at X (m,) from the scaled blocks."""
    return LS._roots_at(LS._stroh_base(Q, R, T, d), X, d)


def rotated(material, phi, theta, psi):
    """Lab-frame C (m,3,3,3,3) Pa, e (m,3,3,3), eps (m,3,3) and rho of a database set for SAW
    Euler angles (degrees, arrays of shape (m,))."""
    R = euler_lab_axes(np.asarray(phi, float), np.asarray(theta, float), np.asarray(psi, float)).reshape(-1, 3, 3)
    t = lab_tensors(material, R)
    return t["C"], t["e"], t["eps"], t["rho"]

CU = dict(C=tensors.voigt_to_tensor(tensors.cubic_voigt(168.4e9, 121.4e9, 75.4e9)), rho=8960.0)


def cu_A(angles):
    return tensors.rotate4(CU["C"], orientation.lab_axes("(001)", np.atleast_1d(np.asarray(angles, float))))


def scaled_blocks(A, e=None, eps=None):
    """The solver's dimensionless blocks (max|A| = 1; e / sqrt(s EPS0); eps / EPS0) and the scale s."""
    s = np.abs(A).max(axis=(1, 2, 3, 4))
    if e is None:
        An = A / s[:, None, None, None, None]
        return An[:, :, 0, :, 0], An[:, :, 0, :, 1], An[:, :, 1, :, 1], s
    Q, R, T = L.generalised_blocks(A / s[:, None, None, None, None], e / np.sqrt(s * EPS0)[:, None, None, None],
                                    eps / EPS0)
    return Q, R, T, s


def test_cu_branch_runs_into_the_exact_mirror_wave():
    """Cu(001) near [110]: the leaky branch exists where material() reports 'pseudo' (and on the
    whole approach to 45 deg), its speed tends to the exact supersonic_decoupled speed of [110]
    (reference: the sagittal closed-form root via material('Cu', direction='[110]'), an
    independent solver) to 1e-8, and its attenuation vanishes there as (45 - theta)^2 (mirror
    symmetry makes delta even in theta - 45 and the radiated amplitude linear in it)."""
    ang = np.array([44.0, 44.9, 44.95, 44.97, 44.98, 44.99, 44.995, 45.0])
    r = leaky_wave(cu_A(ang), CU["rho"])
    mat = surfwave.material("Cu", angle=ang)
    assert list(mat["wave_type"][-1:]) == ["supersonic_decoupled"]
    pseudo = mat["wave_type"] == "pseudo"
    assert pseudo.any(), "reference solver should see the subsonic wave leave near 45 deg"
    assert np.all(r["reason"] == ""), r["reason"]
    c45 = surfwave.material("Cu", direction="[110]")["c_R"]
    assert abs(r["c_leaky"][-1] - c45) < 1e-8 * c45
    assert r["leaky_attenuation"][-1] < 1e-9
    # continuous, monotone approach to the mirror value
    assert np.all(np.diff(r["c_leaky"]) > 0)
    att = r["leaky_attenuation"]
    assert np.all(np.diff(att) < 0)
    # quadratic vanishing: att(44.9) / att(44.99) = (0.1 / 0.01)^2
    assert att[1] / att[5] == pytest.approx(100.0, rel=0.02)
    # at the mirror direction the wave is sagittal: u3 = 0 (decoupled SH motion)
    assert abs(r["polarisation"][-1, 2]) < 1e-6 and abs(r["polarisation"][0, 2]) > 1e-4
    # radiating partial wave grows with depth (Im p < 0), the others decay
    p = r["decay"][:-1]
    assert np.all(p[:, 0].imag < 0) and np.all(p[:, 1:].imag > 0)


def test_outgoing_root_has_positive_group_velocity():
    """The root chosen by the energy flux Re(a^H b) > 0 satisfies dp/dX > 0 (reference: implicit
    differentiation of the bulk dispersion relation, dp/dX = 1 / (2 rho v V_g2), so V_g2 > 0 into
    the crystal), for elastic Cu(001) 40 deg and piezoelectric 64Y-X LiNbO3."""
    cases = [scaled_blocks(cu_A(40.0)) + (3,)]
    A, e, eps, _ = rotated(LN, [0.0], [-26.0], [0.0])
    cases.append(scaled_blocks(A, e, eps) + (4,))
    for Q, R, T, _, d in cases:
        XL = L._limits(Q, R, T, d)
        X = np.array([0.5 * (XL[0, 0] + XL[0, 1])])
        p, xi = _partial_waves(Q, R, T, X, d)
        out = p[0, LS._choose_real(p, xi, d)[0, 0]]
        assert abs(out.imag) < 1e-8
        h = 1e-7 * X
        p2, _ = _partial_waves(Q, R, T, X + h, d)
        moved = p2[0, np.argmin(np.abs(p2[0] - out))]
        assert (moved.real - out.real) / h[0] > 0


def _min_abs_det(Q, R, T, XL, d, electrical, t0, width):
    """Golden-section minimum of |det| over real t in [t0 - width, t0 + width] (outgoing choice)."""
    def f(t):
        X = np.array([XL[0, 0] + (XL[0, 1] - XL[0, 0]) * t * t])
        p, xi = _partial_waves(Q, R, T, X, d)
        return abs(LS._boundary(xi, LS._choose_real(p, xi, d), d, electrical)[0][0])
    lo, hi = t0 - width, t0 + width
    g = 0.5 * (np.sqrt(5) - 1)
    for _ in range(80):
        a, b = hi - g * (hi - lo), lo + g * (hi - lo)
        if f(a) < f(b):
            hi = b
        else:
            lo = a
    return 0.5 * (lo + hi)


@pytest.mark.parametrize("case", ["Cu35", "LiNbO3_64Y_free"])
def test_second_route_real_minimum_of_det(case):
    """Second route: the minimum of |f(X)| over real X. With f = f'(X - X0)(1 + kappa (X - X0))
    near the complex root X0 = X_r + i eta, the real minimum sits at X_r - Re(kappa) eta^2 + O(eta^3)
    (closed form; kappa = f''/(2 f') from finite differences on the tracked sheet). Checked: the
    measured offset equals that prediction to 10 %, and it is O(delta^2) relative."""
    if case == "Cu35":
        A, rho, e, eps, el = cu_A(35.0), CU["rho"], None, None, "free"
        Q, R, T, s = scaled_blocks(A)
        d = 3
    else:
        # A test of the numerical route, not of a constant set: the Kovacs set as held, on which
        # the O(delta^2) bound (factor 50) was set; Warner's 64Y-X sits at 50.2 delta^2.
        A, e, eps, rho = rotated("LiNbO3-Kovacs1990", [0.0], [-26.0], [0.0])
        el = "free"
        Q, R, T, s = scaled_blocks(A, e, eps)
        d = 4
    r = leaky_wave(A, rho, e, eps, electrical=el)
    assert r["reason"][0] == ""
    X0 = complex(r["c_leaky_complex"][0] ** 2 * rho / s[0])
    XL = L._limits(Q, R, T, d)
    p_root = r["decay"][0]

    def f(X):
        p, xi = _partial_waves(Q, R, T, np.array([X]), d)
        idx, ok = LS._track(p_root[None], p)
        assert ok[0]
        return LS._boundary(xi, idx, d, el)[0][0]
    h = 1e-4 * abs(X0.imag) + 1e-7 * abs(X0)
    f1 = (f(X0 + h) - f(X0 - h)) / (2 * h)
    f2 = (f(X0 + h) - 2 * f(X0) + f(X0 - h)) / h ** 2
    kappa = f2 / (2 * f1)
    eta = X0.imag
    predicted = -(kappa.real) * eta ** 2
    tr = np.sqrt((X0.real - XL[0, 0]) / (XL[0, 1] - XL[0, 0]))
    tmin = _min_abs_det(Q, R, T, XL, d, el, tr, 0.02)
    measured = XL[0, 0] + (XL[0, 1] - XL[0, 0]) * tmin ** 2 - X0.real
    delta = r["delta"][0]
    print(f"{case}: delta={delta:.3e} offset measured={measured / X0.real:.3e} predicted={predicted / X0.real:.3e}")
    assert abs(measured - predicted) <= 0.1 * abs(predicted) + 1e-11 * abs(X0)
    assert abs(measured) / abs(X0) < 50 * delta ** 2


def test_linbo3_64y_and_41y_against_literature():
    """64Y-X LiNbO3 free 4742 / metallized 4478 m/s and 41Y-X free 4792 / metallized 4379 m/s
    (quoted in the brief), with the database's set for these cuts (Warner 1967, which reproduces
    them to 0.2-3.2 m/s): agreement within 0.1 %; K^2 of 64Y-X ~ 0.113 (Yamanouchi & Shibayama
    1972) within 0.005. The 41Y-X free wave lies just below the fast-shear limiting speed v_L2
    (4793.1 m/s with this set)."""
    A, e, eps, rho = rotated(LN, [0.0, 0.0], [-26.0, -49.0], [0.0, 0.0])
    fr = leaky_wave(A, rho, e, eps, electrical="free")
    me = leaky_wave(A, rho, e, eps, electrical="metallized")
    assert np.all(fr["reason"] == "") and np.all(me["reason"] == "")
    np.testing.assert_allclose(fr["c_leaky"], [4742.0, 4792.0], rtol=1e-3)
    np.testing.assert_allclose(me["c_leaky"], [4478.0, 4379.0], rtol=1e-3)
    K2 = 2 * (fr["c_leaky"][0] - me["c_leaky"][0]) / fr["c_leaky"][0]
    assert K2 == pytest.approx(0.113, abs=0.005)
    assert np.all(fr["c_leaky"] < fr["c_limits"][:, 1])
    # free faster than metallized; attenuations small and non-negative
    assert np.all(fr["c_leaky"] > me["c_leaky"])
    assert 0 <= me["leaky_attenuation"][0] < fr["leaky_attenuation"][0] < 0.2


def test_litao3_36y():
    """36Y-X LiTaO3 (Kovacs 1990 set as held in the database): the brief's ~4112 m/s matches the
    METALLIZED leaky wave here (within 0.5 %); the free one is the widely quoted 4212 m/s (within
    0.5 %), just below the fast-shear limit v_L2; both nearly lossless (< 0.01 dB per wavelength)."""
    A, e, eps, rho = rotated(LT, [0.0], [-54.0], [0.0])
    me = leaky_wave(A, rho, e, eps, electrical="metallized")
    fr = leaky_wave(A, rho, e, eps, electrical="free")
    assert me["c_leaky"][0] == pytest.approx(4112.0, rel=5e-3)
    assert fr["c_leaky"][0] == pytest.approx(4212.0, rel=5e-3)
    assert me["leaky_attenuation"][0] < 0.01 and fr["leaky_attenuation"][0] < 0.01


def test_yz_linbo3_vacuum_sign_free_above_metallized():
    """Sign of the vacuum condition b4 = +i EPS0 a4: on Y-Z LiNbO3 the subsonic roots of the same
    boundary functions (all partial waves decaying) give free 3488 / metallized 3404 m/s
    (literature, within 0.5 %), free ABOVE metallized; the opposite sign would not."""
    A, e, eps, rho = rotated(get_cut("Y-Z").material, [0.0], [90.0], [90.0])
    Q, R, T, s = scaled_blocks(A, e, eps)
    XL = L._limits(Q, R, T, 4)
    X = XL[0, 0] * np.linspace(0.8, 0.99999, 4000)
    n = X.size
    p, xi = _partial_waves(*(np.repeat(B, n, 0) for B in (Q, R, T)), X, 4)
    idx = np.argsort(-p.imag, axis=1)[:, :4]
    v = {}
    for el in ("free", "metallized"):
        f = np.abs(LS._boundary(xi, idx, 4, el)[0])
        v[el] = np.sqrt(X[np.argmin(f)] * s[0] / rho)
    assert v["free"] == pytest.approx(3488.0, rel=5e-3)
    assert v["metallized"] == pytest.approx(3404.0, rel=5e-3)
    assert v["free"] > v["metallized"]


@pytest.mark.parametrize("electrical, near", [("metallized", 64.0), ("free", 41.0)])
def test_attenuation_touches_zero_over_cut_angle(electrical, near):
    """Rotated Y-X LiNbO3: the attenuation touches zero at a cut angle near 64Y metallized and near
    41Y free (brief; Yamanouchi & Shibayama 1972: "goes to zero" for the metallized 64Y cut). The
    radiated power is |radiated amplitude|^2, so delta touches zero quadratically without a sign
    change: interior minimum within 8 deg of the quoted cut, below 1e-2 of the sweep's ends."""
    th = np.arange(near - 12.0, near + 12.5, 1.0)
    A, e, eps, rho = rotated(LN, 0 * th, th - 90, 0 * th)
    r = leaky_wave(A, rho, e, eps, electrical=electrical)
    att = r["leaky_attenuation"]
    assert np.all(np.isfinite(att)), r["reason"]
    j = int(np.argmin(att))
    assert 0 < j < th.size - 1 and abs(th[j] - near) <= 8
    assert att[j] < 1e-2 * min(att[0], att[-1])
    assert np.all(r["delta"] > -L.GROW_TOL)


def test_zero_piezo_equals_elastic_and_batch_equals_single():
    """e = 0 (phi decouples): the piezoelectric path equals the elastic one (both electrical
    conditions); a batch equals one-by-one solves (reference: the same solver, element-wise)."""
    A = cu_A([35.0, 40.0, 44.9])
    el = leaky_wave(A, CU["rho"])
    z = np.zeros((3, 3, 3, 3))
    eps = np.broadcast_to(EPS0 * np.eye(3) * 10, (3, 3, 3))
    for cond in ("free", "metallized"):
        pz = leaky_wave(A, CU["rho"], z, eps, electrical=cond)
        np.testing.assert_allclose(pz["c_leaky"], el["c_leaky"], rtol=1e-9)
        np.testing.assert_allclose(pz["leaky_attenuation"], el["leaky_attenuation"], rtol=1e-6, atol=1e-12)
    Ap, e, epsl, rho = rotated(LN, [0.0, 0.0, 0.0], [-26.0, -20.0, -49.0], [0.0, 0.0, 0.0])
    batch = leaky_wave(Ap, rho, e, epsl, electrical="metallized")
    for i in range(3):
        one = leaky_wave(Ap[i:i + 1], rho, e[i:i + 1], epsl[i:i + 1], electrical="metallized")
        np.testing.assert_allclose(one["c_leaky"], batch["c_leaky"][i:i + 1], rtol=1e-10)
        np.testing.assert_allclose(one["delta"], batch["delta"][i:i + 1], rtol=1e-6, atol=1e-12)


def test_no_leaky_wave_gives_nan_and_reason():
    """Cu(001) at 20 deg: the only |det| minimum lies where the slowest sheet is cuspidal (more
    than one real pair): NaN with a reason, never a number (the subsonic SAW exists there)."""
    r = leaky_wave(cu_A([20.0]), CU["rho"])
    assert np.isnan(r["c_leaky"][0]) and np.isnan(r["leaky_attenuation"][0])
    assert r["reason"][0] != "" and r["radiating_sheet"][0] == -1


def test_bad_input():
    """Bad shapes, relative permittivity given as absolute, unknown electrical condition: InputError."""
    A = cu_A([30.0])
    with pytest.raises(InputError, match="shape"):
        leaky_wave(A[0], CU["rho"])
    with pytest.raises(InputError, match="electrical"):
        leaky_wave(A, CU["rho"], electrical="open")
    with pytest.raises(InputError, match="F/m"):
        leaky_wave(A, CU["rho"], np.zeros((1, 3, 3, 3)), np.eye(3)[None] * 40.0)
    with pytest.raises(InputError, match="rho"):
        leaky_wave(A, -1.0)
