"""The leaky (pseudo) SAW of non-piezoelectric crystals on the one path, the API and the cube.

References:
- the exact supersonic (mirror-decoupled) wave of Cu (001)[110]: the sagittal root of the
  subsonic solver, ``surfwave.material("Cu", direction="[110]")["c_R"]`` (the closed form Eq. 17,
  an independent solver from the leaky wave's complex root search); mirror symmetry about
  [110] makes delta even in (theta - 45), so the leaky branch meets it with zero attenuation
  (issue 19; tests/solvers/test_leaky.py checks the bare solver the same way);
- the bare leaky solver :func:`surfwave.solvers.leaky.leaky_wave` on the same
  wave-propagation tensors (the one path only routes; it must not change the numbers);
- the cube of main before this change: every existing variable identical (here: the cube
  with the leaky solve switched off, the path main had).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.stressed_wave import REASON_LEAKY_OFF, REASON_LEAKY_SUBSONIC
from surfwave.real_crystals.sweep import VARIABLES, surface_wave_sweep
from surfwave.solvers import stroh
from surfwave.solvers.leaky import REASON_ABOVE as L_REASON_ABOVE
from surfwave.solvers.leaky import leaky_wave
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.tensors import rotate4, voigt_to_tensor

CU = get_material("Cu")


def _cu_A(angles):
    C = rotate4(voigt_to_tensor(CU.voigt)[None], lab_axes("(001)", np.asarray(angles, float))) * 1e9
    return stroh.wave_propagation_tensor(C, np.zeros((len(angles), 3, 3)))


def test_cu_001_leaky_branch_through_the_api_meets_the_mirror_wave():
    """Cu (001), 30 -> 45 deg with leaky=True: one continuous branch (steps shrink with the angle
    step, speed monotone toward [110]), equal at 45 deg to the exact supersonic_decoupled c_R
    (reference: the sagittal root of material('Cu', direction='[110]')) to 1e-8, attenuation
    -> 0 as (45 - theta)^2 (mirror symmetry), and equal to the bare leaky solver."""
    ang = np.array([30.0, 34.0, 38.0, 42.0, 44.0, 44.9, 44.99, 44.995, 45.0])
    r = surfwave.material("Cu", angle=ang, leaky=True)
    assert np.all(r["leaky_reason"] == ""), r["leaky_reason"]
    c45 = surfwave.material("Cu", direction="[110]")
    assert c45["wave_type"] == "supersonic_decoupled"
    assert abs(r["c_leaky"][-1] - c45["c_R"]) <= 1e-8 * c45["c_R"]
    assert r["leaky_attenuation"][-1] == 0.0
    # the branch's own limit (the point before 45) reaches the exact wave too
    assert abs(r["c_leaky"][-2] - c45["c_R"]) < 1e-6 * c45["c_R"]
    assert np.all(np.diff(r["c_leaky"]) > 0)
    att = r["leaky_attenuation"]
    assert np.all(np.diff(att[3:]) < 0) and att[-2] < 1e-6
    assert att[5] / att[6] == pytest.approx(100.0, rel=0.02)     # (0.1 / 0.01)^2
    bare = leaky_wave(_cu_A(ang[:-1]), CU.rho)
    np.testing.assert_allclose(r["c_leaky"][:-1], bare["c_leaky"], rtol=1e-10)
    np.testing.assert_allclose(r["leaky_attenuation"][:-1], bare["leaky_attenuation"], rtol=1e-6, atol=1e-12)


def test_default_solves_only_where_no_subsonic_wave():
    """Default leaky=None: the pseudo points of Cu (001) next to [110] (NaN c_R today) get the
    leaky wave (the bare solver's numbers), the mirror point the exact wave with attenuation 0,
    and points with a subsonic wave keep c_leaky NaN with REASON_LEAKY_SUBSONIC."""
    ang = np.array([10.0, 44.0, 44.97, 44.99, 45.0])
    r = surfwave.material("Cu", angle=ang)
    assert list(r["wave_type"]) == ["surface", "surface", "pseudo", "pseudo", "supersonic_decoupled"]
    assert np.all(np.isnan(r["c_leaky"][:2])) and np.all(np.isnan(r["leaky_attenuation"][:2]))
    assert list(r["leaky_reason"][:2]) == [REASON_LEAKY_SUBSONIC] * 2
    bare = leaky_wave(_cu_A(ang[2:4]), CU.rho)
    np.testing.assert_allclose(r["c_leaky"][2:4], bare["c_leaky"], rtol=1e-10)
    assert np.all(r["leaky_attenuation"][2:4] > 0)
    assert r["c_leaky"][4] == r["c_R"][4] and r["leaky_attenuation"][4] == 0.0
    assert list(r["leaky_reason"][2:]) == [""] * 3
    # existing outputs untouched by the leaky solve
    off = surfwave.material("Cu", angle=ang, leaky=False)
    for key in ("c_R", "c_limit", "polarisation", "decay"):
        np.testing.assert_array_equal(r[key], off[key])
    assert list(off["leaky_reason"]) == [REASON_LEAKY_OFF] * 5 and np.all(np.isnan(off["c_leaky"]))


def test_scalar_call_and_subsonic_point_with_leaky_true():
    """One direction: floats and a str reason. Cu (001) at 10 deg with leaky=True: no leaky
    root on the slowest sheet (the bare solver's reason), NaN, never a number."""
    r = surfwave.material("Cu", angle=10.0, leaky=True)
    assert isinstance(r["leaky_reason"], str) and r["leaky_reason"] != ""
    assert np.isnan(r["c_leaky"]) and np.isnan(r["leaky_attenuation"])
    assert r["leaky_reason"] == leaky_wave(_cu_A([10.0]), CU.rho)["reason"][0]


def test_bad_leaky_argument():
    with pytest.raises(InputError, match="leaky"):
        surfwave.material("Cu", leaky="yes")


def test_cube_equals_api_on_leaky_points_and_keeps_existing_variables():
    """The crystals cube carries c_leaky / leaky_attenuation / leaky_reason (CF attributes as in
    the piezoelectric cube); on its leaky points it equals material(..., leaky=True) (the one
    path), and every variable it had before is identical to the cube without the leaky solve."""
    ang = np.array([0.0, 20.0, 30.0, 40.0, 44.99, 45.0])
    ds = surface_wave_sweep([CU], ["(001)"], ang)
    assert ds.c_leaky.attrs["units"] == "m s-1" and ds.leaky_attenuation.attrs["units"] == "dB"
    assert ds.c_leaky.attrs == VARIABLES["c_leaky"]
    cube = ds.sel(material="Cu", surface="(001)")
    api = surfwave.material("Cu", angle=ang, leaky=True)
    found = np.isfinite(cube.c_leaky.values)
    assert found.sum() >= 4
    np.testing.assert_array_equal(found, np.isfinite(api["c_leaky"]))
    np.testing.assert_allclose(cube.c_leaky.values[found], api["c_leaky"][found], rtol=1e-12)
    np.testing.assert_allclose(cube.leaky_attenuation.values[found], api["leaky_attenuation"][found],
                               rtol=1e-9, atol=1e-15)
    assert list(cube.leaky_reason.values) == list(api["leaky_reason"])
    old = surface_wave_sweep([CU], ["(001)"], ang, leaky=False)
    for name in old.data_vars:
        if not name.startswith(("c_leaky", "leaky_")):
            assert ds[name].equals(old[name]), name


def test_angle_figure_draws_the_leaky_branch(tmp_path):
    """surface_wave_angles.png: with c_leaky in the cube a second row of panels shows the
    attenuation and the top row carries the dashed leaky branch (its data are the cube's);
    a cube without c_leaky (written before) still draws one row."""
    import matplotlib.pyplot as plt

    from surfwave.plots import surface_wave as sw_plots

    ds = surface_wave_sweep([CU], ["(001)", "(111)"], np.arange(0.0, 46.0, 5.0))
    shown = {}
    real_savefig = sw_plots.savefig

    def keep(fig, path):
        shown["axes"] = fig.axes
        return real_savefig(fig, path)

    sw_plots.savefig = keep
    try:
        assert sw_plots.speeds_vs_angle(ds, tmp_path / "a.png").stat().st_size > 0
        axes = shown["axes"]
        assert len(axes) == 4                      # 2 surfaces x (speed, attenuation)
        att = axes[2].lines[0].get_ydata()         # (001) attenuation row, Cu
        x = np.arange(0.0, 46.0, 5.0)
        np.testing.assert_array_equal(att, ds.leaky_attenuation.sel(material="Cu", surface="(001)",
                                                                    angle=x).values)
        assert any(line.get_linestyle() == "--" for line in axes[0].lines)
        sw_plots.speeds_vs_angle(ds.drop_vars(["c_leaky", "leaky_attenuation", "leaky_reason"]),
                                 tmp_path / "b.png")
        assert len(shown["axes"]) == 2
    finally:
        sw_plots.savefig = real_savefig
        plt.close("all")


def _A(name, surface, angles):
    mat = get_material(name)
    C = rotate4(voigt_to_tensor(mat.voigt)[None], lab_axes(surface, np.asarray(angles, float))) * 1e9
    return stroh.wave_propagation_tensor(C, np.zeros((len(angles), 3, 3))), mat.rho


@pytest.mark.parametrize("name", ["Si", "Ni"])
def test_reported_roots_have_decaying_partial_waves(name):
    """Si and Ni (001), 0 to 45 deg in 1-degree steps: every reported leaky root must be a surface
    wave on the slowest sheet, i.e. at its complex X the Stroh roots p it reports are eigenvalues
    of N (recomputed here with numpy from the blocks Q, R, T of A, an independent route) and the
    d - 1 non-radiating ones decay into the crystal (Im p > 0, the definition of a surface
    partial wave; docs/physics/leaky-waves.md). Before this check the solver returned roots at a
    real X whose 'decaying' waves were a complex-conjugate pair (one growing with depth):
    Si (001) 22-23 deg near 5830 m/s and Ni (001) 10-11 deg near 3540 m/s, attenuation ~1e-13."""
    angles = np.arange(0.0, 45.5, 1.0)
    A, rho = _A(name, "(001)", angles)
    r = leaky_wave(A, rho)
    found = r["reason"] == ""
    assert found.any()
    p = r["decay"][found]
    assert np.all(p[:, 1:].imag > 0), angles[found][np.any(p[:, 1:].imag <= 0, axis=1)]
    assert np.all(p[:, 0].imag <= 1e-12)   # radiating: Im p <= 0 (0 at the [110] mirror)
    # the reported p are roots of the 6 x 6 Stroh matrix at the reported X = rho v^2
    X = rho * r["c_leaky_complex"][found] ** 2
    Af = A[found]
    Q, R, T = Af[:, :, 0, :, 0], Af[:, :, 0, :, 1], Af[:, :, 1, :, 1]
    Ti = np.linalg.inv(T)
    N = np.block([[-Ti @ np.swapaxes(R, 1, 2), Ti],
                  [R @ Ti @ np.swapaxes(R, 1, 2) - Q + X[:, None, None] * np.eye(3), -R @ Ti]])
    ev = np.linalg.eigvals(N)
    dist = np.abs(ev[:, None, :] - p[:, :, None]).min(axis=2)
    assert np.all(dist <= 1e-6 * (1 + np.abs(p)))
    # the spurious points of the crystals scene are NaN with the reason
    bad = {"Si": [22.0, 23.0], "Ni": [10.0, 11.0]}[name]
    rb = leaky_wave(*_A(name, "(001)", bad))
    assert np.all(np.isnan(rb["c_leaky"]))
    assert all("Im p <= 0" in s for s in rb["reason"])


def _follow_to_real(A, X0, p0, steps=64):
    """Stroh roots p0 (n, 3) at complex X0 (n,), followed by nearest-root matching along the
    straight path X0 -> Re X0 (numpy eig of the 6 x 6 N at every step; independent of the
    solver's tracking); returns the followed roots (n, 3) and the x2 energy flux Re(a^H b) of each
    at real X."""
    Q, R, T = A[:, :, 0, :, 0], A[:, :, 0, :, 1], A[:, :, 1, :, 1]
    Ti = np.linalg.inv(T)
    Rt = np.swapaxes(R, 1, 2)
    p = p0.copy()
    for s in np.linspace(1, 0, steps + 1)[1:]:
        X = X0.real + 1j * s * X0.imag
        N = np.block([[-Ti @ Rt, Ti], [R @ Ti @ Rt - Q + X[:, None, None] * np.eye(3), -R @ Ti]])
        ev, vec = np.linalg.eig(N)
        j = np.abs(ev[:, None, :] - p[:, :, None]).argmin(axis=2)
        p = np.take_along_axis(ev, j, axis=1)
    sel = np.take_along_axis(vec, j[:, None, :], axis=2)
    flux = np.einsum("mjk,mjk->mk", sel[:, :3].conj(), sel[:, 3:]).real
    return p, flux


def test_pb_111_reports_one_continuous_branch_of_outgoing_plus_decaying_waves():
    """Pb (111), 10 to 21.5 deg: the crystals scene showed the attenuation dropping from 1.7 to
    ~0.2 dB per wavelength with a speed step of ~120 m/s between 16 and 17 deg. That second root
    (882.6 m/s at 17 deg) is a det = 0 of the wrong partial-wave set: followed back to real speed
    (straight path X0 -> Re X0, an independent numpy tracking), its second partial wave is the
    REAL root p = -0.762 with energy flux Re(a^H b) < 0, i.e. the incoming bulk wave of the slowest
    sheet, not a decaying wave (definition of the leaky wave: docs/physics/leaky-waves.md).
    Reference for the reported root: the same real-speed check (outgoing real root with flux > 0,
    two decaying roots with Im p > 0), continuity in angle (steps < 15 m/s per 0.5 deg; the
    branch's slope is ~9 m/s per deg) and the window c_leaky < v_L2 (21.5 deg was reported at
    953.8 m/s with v_L2 = 952.4 m/s before)."""
    angles = np.arange(10.0, 21.51, 0.5)
    A, rho = _A("Pb", "(111)", angles)
    r = leaky_wave(A, rho)
    found = r["reason"] == ""
    assert found[:17].all()                                     # 10 .. 18 deg
    c = r["c_leaky"][found]
    assert np.all(c < r["c_limits"][found, 1])
    assert np.all(np.abs(np.diff(r["c_leaky"][:17])) < 15.0)
    assert np.all(np.diff(r["leaky_attenuation"][:17]) > 0)     # 1.59 -> 1.72 dB, no drop
    s = np.abs(A[found]).max(axis=(1, 2, 3, 4))
    X0 = rho * r["c_leaky_complex"][found] ** 2 / s
    p, flux = _follow_to_real(A[found] / s[:, None, None, None, None], X0, r["decay"][found])
    assert np.all(np.abs(p[:, 0].imag) < 1e-6) and np.all(flux[:, 0] > 0)
    assert np.all(p[:, 1:].imag > 1e-3)
    # the spurious root, followed the same way, holds the incoming wave (the old report at 17 deg)
    A17, _ = _A("Pb", "(111)", [17.0])
    s17 = np.abs(A17).max()
    X = rho * (882.552156 / (1 + 1j * 0.2108529 / 54.575)) ** 2 / s17
    p17, f17 = _follow_to_real(A17 / s17, np.array([X]), np.array([[0.2549 - 0.0033j, -0.7653 + 0.0275j,
                                                                       0.7763 + 1.642j]]))
    assert abs(p17[0, 1].imag) < 1e-6 and f17[0, 1] < 0


def test_al_111_root_next_to_the_v_l2_branch_point_is_verified():
    """Al (111) 28 and 32 deg (mirror copies): the slowest sheet's leaky root lies 2.8e-8 below v_L2
    (3127.9532 m/s, 0.00105 dB per wavelength), 6e-8 X_L2 from the branch point where the second
    sheet's decaying pair turns real. The solver's old check path (8 equal steps back to real
    speed) stepped ~80 times that distance at once and could not match the roots (NaN
    'incoming'); the root-sized steps now verify it. Reference: an independent straight-path
    tracking X0 -> Re X0 in 4096 equal numpy steps (each ~1/6 of the distance to the branch point)
    ends on the outgoing bulk wave (real p, flux > 0) and two decaying waves (Im p = 2.4e-4 and
    1.05 > 0, the second sheet's pair not yet real), and the root is inside the window
    (c_leaky < v_L2, c_limits)."""
    A, rho = _A("Al", "(111)", [28.0, 32.0])
    r = leaky_wave(A, rho)
    assert list(r["reason"]) == ["", ""]
    assert np.all(r["c_leaky"] < r["c_limits"][:, 1])
    assert r["c_leaky"] == pytest.approx(3127.9532, abs=2e-3)
    s = np.abs(A).max(axis=(1, 2, 3, 4))
    X0 = rho * r["c_leaky_complex"] ** 2 / s
    p, flux = _follow_to_real(A / s[:, None, None, None, None], X0, r["decay"], steps=4096)
    assert np.all(np.abs(p[:, 0].imag) < 1e-8) and np.all(flux[:, 0] > 0)
    assert np.all(p[:, 1:].imag > 1e-4)


def _continue_in_angle(name, surface, angles, X, p):
    """The root X (scaled rho v^2 / max|A|) with Stroh roots p (3,) at angles[0], followed along
    ``angles`` by a secant in X at each angle, the three partial waves matched to the nearest
    roots of the previous X (numpy eig of the 6 x 6 N; independent of the solver). Returns the
    root X and its roots p at angles[-1]."""
    def det(Q, R, T, X, p_prev):
        Ti = np.linalg.inv(T)
        N = np.block([[-Ti @ R.T, Ti], [R @ Ti @ R.T - Q + X * np.eye(3), -R @ Ti]])
        ev, vec = np.linalg.eig(N)
        j = np.abs(ev[None, :] - p_prev[:, None]).argmin(axis=1)
        assert len(set(j)) == 3
        return np.linalg.det(vec[3:, j] @ np.linalg.inv(vec[:3, j])), ev[j]
    for a in angles[1:]:
        A, _ = _A(name, surface, [a])
        A = A[0] / np.abs(A).max()
        Q, R, T = A[:, 0, :, 0], A[:, 0, :, 1], A[:, 1, :, 1]
        fa, pa = det(Q, R, T, X, p)
        Xb = X * (1 + 1e-6)
        for _ in range(50):
            fb, pb = det(Q, R, T, Xb, pa)
            X, Xb, fa, pa = Xb, Xb - fb * (Xb - X) / (fb - fa), fb, pb
            if abs(Xb - X) < 1e-14 * abs(X):
                break
        p = pa
    return X, p


@pytest.mark.parametrize("angle", [28.0, 32.0])
def test_cu_111_branch_left_through_v_l2_is_named(angle):
    """Cu (111) 28 and 32 deg (mirror copies about 30 deg) were NaN with 'secant search did not
    converge'. Reference: the branch reported at 24.5 deg (2381 m/s, 1.76 dB per wavelength),
    followed in 0.1-degree steps by an independent secant continuation (numpy, nearest-root
    matching), crosses v_L2 near 25.1 deg and lies above it at 28 deg (2337.7 m/s against
    v_L2 = 2303.1 m/s, delta = 0.0365): a leaky wave radiating into two sheets. The solver now
    finds that root (a search from above v_L2 where none from the real-axis minima converged)
    and names it with REASON_ABOVE; its signed delta is the continuation's."""
    A0, rho = _A("Cu", "(111)", [24.5])
    r0 = leaky_wave(A0, rho)
    assert r0["reason"][0] == ""
    s0 = np.abs(A0).max()
    X0 = rho * r0["c_leaky_complex"][0] ** 2 / s0
    a_end = min(angle, 60.0 - angle)          # 32 deg is the mirror image of 28 deg
    X, p = _continue_in_angle("Cu", "(111)", np.arange(24.5, a_end + 1e-9, 0.1), X0, r0["decay"][0])
    A, _ = _A("Cu", "(111)", [angle])
    r = leaky_wave(A, rho)
    v = np.sqrt(X * np.abs(A).max() / rho)
    c_cont, delta_cont = 1 / (1 / v).real, (1 / v).imag / (1 / v).real
    assert c_cont > r["c_limits"][0, 1]                       # above v_L2
    assert r["reason"][0] == L_REASON_ABOVE and np.isnan(r["c_leaky"][0])
    assert r["delta"][0] == pytest.approx(delta_cont, rel=1e-6)
    assert delta_cont == pytest.approx(0.0365, abs=5e-4)


def test_converged_search_names_the_reason_before_an_unconverged_one():
    """Si (001) 8-12 deg and GaAs (001) 16 deg were NaN with 'secant search did not converge'
    although a second search from another |det| minimum had converged to a root above v_L2 (the
    reason of the first search was reported). Reference: the neighbouring points, Si (001) 14 deg
    and GaAs (001) 18 deg, were already REASON_ABOVE with the same kind of root (X real to
    1e-11: delta ~ 0), and the root followed from there in angle stays above v_L2 (checked
    with the solver's own secant continuation in 0.1-degree steps down to 12.7 deg for Si,
    15.5 deg for GaAs)."""
    for name, angles, ref in (("Si", [8.0, 10.0, 12.0], 14.0), ("GaAs", [16.0], 18.0)):
        A, rho = _A(name, "(001)", angles + [ref])
        r = leaky_wave(A, rho)
        assert all(s == L_REASON_ABOVE for s in r["reason"]), r["reason"]
        assert np.all(np.abs(r["delta"]) < 1e-9)
