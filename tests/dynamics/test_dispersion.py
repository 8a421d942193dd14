"""Tests of the analytic triangular-lattice surface-wave solution (surfwave.dynamics.dispersion).

Reference values come from closed forms (Eq. 16, the paper's Eqs. 3a/6a/8a as corrected in
docs/physics/paper.md, Eq. 20 with bond sums of Eq. A12) or from plugging the result back into the row
equations of surfwave.dynamics.triangular (an independent statement of the lattice dynamics).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from surfwave.data.variables import CUBES
from surfwave.dynamics import dispersion as D
from surfwave.dynamics.triangular import row_matrices
from surfwave.errors import GeometryError
from surfwave.model_crystals import elastic
from surfwave.solvers import rayleigh

TH = np.array([1e-3, np.pi / 20, np.pi / 8, np.pi / 4, 1.3, np.pi / 2, 2.2, np.pi - 1e-3])
# 4 cos(80 deg) = 2 x with x^3 - 3x + 1 = 0: c_T,par^2 = 0 of the harmonic lattice (Eq. A14).
D_SHEAR_HARMONIC = 4 * np.cos(np.radians(80.0))


def eq16(d):
    """Eq. (16), harmonic triangular lattice, x = d_x/d0."""
    x = 0.5 * np.asarray(d)
    return 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)


def eq20_elastic(name, d):
    """Eq. (20) (``rayleigh.cauchy_c2``) with the long-wave speeds of the bond sums, Eqs. (A7,
    A11, A12) (``elastic.properties``, checked against Table I in test_table1.py): a route
    through the elastic constants only, independent of the row equations."""
    sp = elastic.properties("triangular", "uniaxial", name, "[10]", d)
    return rayleigh.cauchy_c2(sp["c2_L_par"], sp["c2_T_par"], sp["c2_L_perp"], sp["c2_T_perp"])


def crossover_from_row_equations(pot, d, c2_R):
    """theta_c computed from the bulk row equations of surfwave.dynamics.triangular, not from
    the Eq. (6a) coefficients of surfwave.dynamics.dispersion.

    A bulk mode U_I = U z^I (z = e^{-q}) at omega^2 = (c_R^2 / d_x^2) sin^2 theta (Eq. 15)
    needs det(A0 - omega^2 + A1 z + A1^H / z) = 0. A0 and A1 + A1^H are diagonal and
    A1 - A1^H is off-diagonal, so the determinant is a real quadratic in s = z + 1/z = 2 cosh q
    (through z - 1/z only as (z - 1/z)^2 = s^2 - 4). q is complex exactly where that
    quadratic's discriminant is negative; its first sign change in (0, pi/2) is theta_c.
    """
    from scipy.optimize import brentq

    def disc(th):
        a0, _, a1 = (m[0, 0] for m in row_matrices(pot, [d], [th]))
        w2 = c2_R / (0.5 * d) ** 2 * np.sin(th) ** 2
        z = np.array([0.3, 0.6, 0.9, 0.45])
        det = np.array([np.linalg.det(a0 - w2 * np.eye(2) + a1 * zi + a1.conj().T / zi) for zi in z])
        assert np.abs(det.imag).max() < 1e-12
        coef = np.polyfit(z[:3] + 1 / z[:3], det[:3].real, 2)
        assert abs(np.polyval(coef, z[3] + 1 / z[3]) - det[3].real) < 1e-10  # a quadratic in s
        return coef[1] ** 2 - 4 * coef[0] * coef[2]

    th = np.linspace(1e-3, np.pi / 2, 24)
    neg = np.flatnonzero([disc(t) < 0 for t in th])
    assert neg.size and neg[0] > 0
    return brentq(disc, th[neg[0] - 1], th[neg[0]], xtol=1e-14)


def plug_in_residual(pot, d, th, u, v, omega):
    """Max residual of the bulk and surface row equations (surfwave.dynamics.triangular) for (u, v)."""
    A0, A0s, A1 = row_matrices(pot, d, th)
    U = np.stack([u, v], axis=-1)  # (n, m, rows, 2)
    w2 = (omega**2)[..., None]
    surf = w2 * U[:, :, 0] - np.einsum("nmij,nmj->nmi", A0s, U[:, :, 0]) \
        - np.einsum("nmij,nmj->nmi", A1, U[:, :, 1])
    bulk = w2[..., None] * U[:, :, 1:-1] - np.einsum("nmij,nmrj->nmri", A0, U[:, :, 1:-1]) \
        - np.einsum("nmij,nmrj->nmri", A1, U[:, :, 2:]) \
        - np.einsum("nmji,nmrj->nmri", A1.conj(), U[:, :, :-2])
    return np.abs(surf).max(), np.abs(bulk).max()


@pytest.mark.parametrize("d", [0.75, 1.0, 1.4])
def test_row_matrices_are_eq2a(d):
    """The row matrices of surfwave.dynamics.triangular against the corrected Eq. (2a) of docs/physics/paper.md
    (harmonic, hand-written): the y-equation
    -v''_00 = [1 - 1/(2 d_x)](2v_00 - v_01 - v_0-1) + d_y^2 (4v_00 - v_10 - v_-10 - v_1-1 - v_-11)
              - d_x d_y (u_10 + u_-10 - u_1-1 - u_-11)
    and its x-partner (in-row spring phi''(2 d_x) = 1, inclined bonds d_x^2, d_x d_y), with
    u_IJ = U_I exp(i theta (I + 2J)); the free surface row lacks the neighbours of row -1."""
    th = np.array([1e-3, 0.4, 1.3, 2.9])
    dx = d / 2
    dy = np.sqrt(1 - dx**2)
    A0, A0s, A1 = row_matrices("harmonic", [d], th)
    ep, em = np.exp(1j * th), np.exp(-1j * th)
    ring = 2 - 2 * np.cos(2 * th)  # 2 - e^{2i theta} - e^{-2i theta} from v_0,+-1
    z = np.zeros_like(th)
    a0 = np.array([[ring + 4 * dx**2, z], [z, (1 - 1 / (2 * dx)) * ring + 4 * dy**2]])
    a0s = np.array([[ring + 2 * dx**2, z], [z, (1 - 1 / (2 * dx)) * ring + 2 * dy**2]])
    # neighbours in row +1: (1, 0) at (d_x, d_y), phase e^{i theta}; (1, -1) at (-d_x, d_y), e^{-i theta}
    a1 = np.array([[-dx**2 * (ep + em), -dx * dy * (ep - em)], [-dx * dy * (ep - em), -dy**2 * (ep + em)]])
    np.testing.assert_allclose(A0[0], np.moveaxis(a0, -1, 0), atol=1e-14)
    np.testing.assert_allclose(A0s[0], np.moveaxis(a0s, -1, 0), atol=1e-14)
    np.testing.assert_allclose(A1[0], np.moveaxis(a1, -1, 0), atol=1e-14)


def test_c2R_matches_eq16_harmonic():
    """Closed form: Eq. (16), and (3 - sqrt 3)/4 at zero stress (docs/physics/paper.md)."""
    d = np.linspace(0.72, 1.95, 30)
    r = D.solve("harmonic", d, [0.5])
    np.testing.assert_allclose(r["c2_R"], eq16(d), rtol=1e-12)
    assert D.solve("harmonic", [1.0], [0.5])["c2_R"][0] == pytest.approx((3 - np.sqrt(3)) / 4, rel=1e-14)


@pytest.mark.parametrize("name,d", [("lj", np.linspace(0.895, 1.11, 12)),
                                    ("morse", np.linspace(0.85, 1.2, 8)),
                                    ("harmonic", np.linspace(0.71, 1.9, 8))])
def test_c2R_matches_long_wave_eq20(name, d):
    """The lattice quadratic's c_R^2 (row equations) equals Eq. (20) built from the elastic
    constants of the bond sums (Eq. A12): two independent routes to the long-wave limit."""
    np.testing.assert_allclose(D.solve(name, d, [0.5])["c2_R"], eq20_elastic(name, d), rtol=1e-11)


@pytest.mark.parametrize("name,d", [("harmonic", [0.7093, 0.8, 1.0, 1.4]), ("lj", [0.9, 1.0, 1.1])])
def test_eq3a_and_eq6a_hold(name, d):
    """q and R satisfy the corrected Eq. (3a) and the quadratic Eq. (6a) (docs/physics/paper.md)."""
    r = D.solve(name, d, TH)
    dx = 0.5 * np.asarray(d)[:, None]
    dy = np.sqrt(1 - dx**2)
    C, S = np.cos(TH), np.sin(TH)
    dl = (r["omega"] ** 2 - r["omega_L"] ** 2) / (4 * dx**2)
    dt = (r["omega"] ** 2 - r["omega_T"] ** 2) / (4 * dy**2)
    for q, R in ((r["q1"], r["R1"]), (r["q2"], r["R2"])):
        assert np.all(q.real > 0)
        X = np.cosh(q)
        np.testing.assert_allclose(C * (1 - X) - S * np.sinh(q) / R, dl, atol=1e-10)
        np.testing.assert_allclose(C * (1 - X) + R * S * np.sinh(q), dt, atol=1e-10)
        eq6a = X**2 + ((dl + dt) * C - 2 * C**2) * X + dl * dt - (dl + dt) * C + C**2 - S**2
        assert np.abs(eq6a).max() < 1e-10


def test_omega_is_eq15_and_symmetric():
    """Eq. (15): omega = (c_R/d_x) sin theta; theta -> pi - theta is a symmetry of the zone."""
    d = np.array([0.75, 1.0, 1.3])
    r = D.solve("harmonic", d, TH)
    np.testing.assert_allclose(r["omega"], np.sqrt(eq16(d))[:, None] / (d[:, None] / 2) * np.sin(TH),
                               rtol=1e-13)
    back = D.solve("harmonic", d, np.pi - TH)
    np.testing.assert_allclose(back["omega"], r["omega"], rtol=1e-12)
    np.testing.assert_allclose(np.abs(np.exp(-back["q1"])), np.abs(np.exp(-r["q1"])), rtol=1e-9)


def test_amplitude_ratio_satisfies_both_boundary_rows():
    """Eq. (8a): both forms (x and y rows of Eq. 7a) give the same V1/V2 (the unsquared Eq. 9a)."""
    d = [0.75, 1.0, 1.5]
    th = TH[(TH > 0.01) & (np.abs(TH - np.pi / 2) > 0.01) & (TH < 3.1)]
    r = D.solve("harmonic", d, th)
    q1, q2, R1, R2 = r["q1"], r["q2"], r["R1"], r["R2"]
    e1, e2, C, S = np.exp(q1), np.exp(q2), np.cos(th), np.sin(th)
    first = -(R2 * (e2 * C - 1) + e2 * S) / (R1 * (e1 * C - 1) + e1 * S)
    second = -(R2 * e2 * S - (e2 * C - 1)) / (R1 * e1 * S - (e1 * C - 1))
    np.testing.assert_allclose(r["amplitude_ratio"], first, rtol=1e-8)
    np.testing.assert_allclose(first, second, rtol=1e-7)


@pytest.mark.parametrize("name,d", [("harmonic", [0.7085 * 1.005, 1.0, 1.8]), ("lj", [0.8937 * 1.005, 1.0, 1.105]),
                                    ("morse", [1.0, 1.1])])
def test_displacements_satisfy_equations_of_motion(name, d):
    """Plugging (u, v) into the bulk and free-surface row equations gives 0 to 1e-10."""
    tc = D.solve(name, [1.0], [1.0])["theta_c"][0]
    th = np.concatenate([TH, [tc - 1e-3, tc + 1e-3]])
    r = D.solve(name, d, th)
    disp = D.displacements(name, d, th, n_rows=40)
    assert np.isfinite(disp["u"]).all() and disp["u"].shape == (len(d), th.size, 40)
    surf, bulk = plug_in_residual(name, d, th, disp["u"], disp["v"], r["omega"])
    assert surf < 1e-10 and bulk < 1e-10
    norm = np.sqrt(np.abs(disp["u"]) ** 2 + np.abs(disp["v"]) ** 2).max(axis=-1)
    np.testing.assert_allclose(norm, 1.0, rtol=1e-12)


def test_displacements_equal_paper_superposition():
    """The Lambda-propagated rows equal (R1 d_y/d_x, i) V1 e^{-q1 I} + (R2 d_y/d_x, i) V2 e^{-q2 I}
    with V1/V2 from Eq. (8a) (the paper's construction, Eqs. 1a, 3a, 8a)."""
    d, th = [1.0, 0.8], np.array([np.pi / 20, np.pi / 4, 2.0])
    r = D.solve("harmonic", d, th)
    disp = D.displacements("harmonic", d, th, n_rows=12)
    dx = 0.5 * np.asarray(d)[:, None, None]
    dy = np.sqrt(1 - dx**2)
    rows = np.arange(12)
    V1 = r["amplitude_ratio"][..., None] * np.exp(-r["q1"][..., None] * rows)
    V2 = np.exp(-r["q2"][..., None] * rows)
    u = dy / dx * (r["R1"][..., None] * V1 + r["R2"][..., None] * V2)
    v = 1j * (V1 + V2)
    scale = disp["v"][..., :1] / v[..., :1]
    np.testing.assert_allclose(disp["u"], u * scale, atol=1e-10)
    np.testing.assert_allclose(disp["v"], v * scale, atol=1e-10)


def test_fig3_claims():
    """Paper Sec. III.B: noticeable displacements 9 rows deep at theta = pi/20; q complex above
    theta_c ~ pi/8 at zero stress; theta_c larger under compression; successive rows at
    theta = pi/2 alternate between x and y motion."""
    disp = D.displacements("harmonic", [1.0], [np.pi / 20, np.pi / 2], n_rows=10)
    amp = np.sqrt(np.abs(disp["u"]) ** 2 + np.abs(disp["v"]) ** 2)[0]
    assert amp[0, 9] > 0.3
    assert amp[1, 9] < 1e-3
    u, v = np.abs(disp["u"][0, 1]), np.abs(disp["v"][0, 1])
    assert np.all(np.minimum(u, v)[:6] < 1e-12 * np.maximum(u, v)[:6])  # purely x or purely y
    assert np.all((u[:5] > v[:5]) != (u[1:6] > v[1:6]))  # alternating
    d = np.linspace(0.75, 1.0, 6)
    tc = D.solve("harmonic", d, [0.5])["theta_c"]
    np.testing.assert_allclose(tc, [crossover_from_row_equations("harmonic", x, eq16(x)) for x in d],
                               rtol=0, atol=1e-11)
    assert abs(tc[-1] - np.pi / 8) < 0.5 * (np.pi / 8 - np.pi / 9)  # "about pi/8": 0.119 pi
    assert np.all(np.diff(tc) < 0)
    r = D.solve("harmonic", [1.0], [tc[-1] - 1e-3, tc[-1] + 1e-3])
    assert r["q1"][0, 0].imag == 0 and abs(r["q1"][0, 1].imag) > 1e-3


def test_instability_edges():
    """Harmonic: c_T,par^2 = 0 at d/d0 = 4 cos 80 deg (Eq. A14 closed form), and the surface goes
    first: c_R^2 = 0 at d/d0 = 2(3 - sqrt 7) = 0.70850 > 0.69459 ('vanishing just before the
    shear instability'). Eq. (16) = 0 squares to x^2 - 6x + 2 = 0 (x = d_x/d0, the root with
    5x^2 - x >= 0), so x = 3 - sqrt 7; the edge is checked to 1e-9 relative."""
    lc = D.lattice_constants("harmonic", D_SHEAR_HARMONIC * np.array([1 - 1e-9, 1 + 1e-9]))
    assert lc["c2_T_par"][0] < 0 < lc["c2_T_par"][1]
    d_surface = 2 * (3 - np.sqrt(7))
    assert eq16(d_surface) == pytest.approx(0.0, abs=1e-15)
    c2 = D.lattice_constants("harmonic", d_surface * np.array([1 - 1e-9, 1 + 1e-9, 1.01]))["c2_R"]
    assert not c2[0] > 0 and 0 < c2[1] < 1e-8 and c2[2] == pytest.approx(eq16(d_surface * 1.01), rel=1e-12)
    assert d_surface > D_SHEAR_HARMONIC + 0.0139


def test_invalid_points_are_nan_with_reason_and_no_warning():
    """Outside (0, pi) and at unstable strains: NaN with a reason, never a warning or exception."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = D.solve("lj", [0.85, 1.0, 1.2], [-0.1, 0.0, 0.5, np.pi, 4.0])
        disp = D.displacements("lj", [0.85, 1.0, 1.2], [-0.1, 0.0, 0.5, np.pi, 4.0])
    valid = np.zeros((3, 5), dtype=bool)
    valid[1, 2] = True
    for key in ("omega", "q1", "q2", "R1", "R2", "amplitude_ratio", "omega_L", "omega_T"):
        assert np.array_equal(np.isfinite(r[key]), valid), key
    assert np.array_equal(r["reason"] == "", valid)
    assert r["reason"][1, 0] == D.REASON_THETA and r["reason"][0, 2] == D.REASON_BULK
    assert r["reason"][2, 2] == D.REASON_SURFACE
    assert np.isnan(r["theta_c"][[0, 2]]).all() and np.isfinite(disp["u"][1, 2]).all()
    with pytest.raises(GeometryError):
        D.solve("harmonic", [2.0], [0.5])


def test_no_warning_or_nan_inside_valid_range():
    """Dense grid over the valid strains (harmonic 1.001 x surface edge .. 1.95): all finite."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        d = np.linspace(0.7085 * 1.001, 1.95, 60)
        th = np.linspace(1e-4, np.pi - 1e-4, 301)
        r = D.solve("harmonic", d, th)
    for key in ("omega", "q1", "q2", "R1", "R2", "amplitude_ratio", "omega_L", "omega_T", "theta_c"):
        assert np.isfinite(r[key]).all(), key
    assert np.all(r["omega"][:, th < np.pi / 2] < r["omega_T"][:, th < np.pi / 2])


@pytest.mark.parametrize("name,d", [("harmonic", [0.7085 * 1.0001, 1.0, 1.99]),
                                    ("lj", [0.8937 * 1.0001, 1.0, 1.1139])])
def test_extreme_theta_is_finite_and_exact(name, d):
    """theta down to 1e-12 from 0 and from pi, at the edges of the stable range: Eq. (15) is
    finite (the valid range is the open interval), the unsquared surface condition holds to
    rounding (its rows are formed with expm1 and pi - theta to full precision). Displacements
    are finite there and satisfy the row equations (same plug-in reference as above) to 1e-10
    down to theta = 1e-6 from either end; closer, the propagator Lambda inverts an
    O(theta)-singular matrix and the residual grows like eps / theta (documented limit)."""
    th = np.array([1e-12, 1e-9, 1e-6, np.pi - 1e-6, np.pi - 1e-9, np.pi - 1e-12])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = D.solve(name, d, th)
        disp = D.displacements(name, d, th, n_rows=12)
    assert (r["reason"] == "").all()
    for key in ("omega", "q1", "q2", "R1", "R2", "amplitude_ratio"):
        assert np.isfinite(r[key]).all(), key
    assert np.isfinite(disp["u"]).all() and np.isfinite(disp["v"]).all()
    assert r["boundary_residual"].max() < 1e-12
    mid = [2, 3]  # theta = 1e-6 and pi - 1e-6
    surf, bulk = plug_in_residual(name, d, th[mid], disp["u"][:, mid], disp["v"][:, mid], r["omega"][:, mid])
    assert surf < 1e-10 and bulk < 1e-10


def test_variables_metadata_covers_outputs():
    """Every returned array has CF metadata with dims among (strain, theta, row)."""
    r = D.solve("harmonic", [1.0], [0.5])
    disp = D.displacements("harmonic", [1.0], [0.5])
    for key in list(r) + ["u", "v", "row"]:
        meta = CUBES["dispersion"][key]
        assert {"long_name", "dims"} <= set(meta) and ("units" in meta) != key.startswith("reason")
        assert set(meta["dims"]) <= {"strain", "theta", "row"}
    assert disp["row"].tolist() == list(range(disp["u"].shape[-1])) and disp["u"].shape[-1] >= 10
