"""Leaky SAW of rotated Y-cut, X-propagating LiNbO3 (Warner 1967 constants, ``LiNbO3``): the points
where the solver said "no leaky wave" (REASON_NOMIN) although a root exists, and the points where
the branch leaves the window through v_L1.

Reference: an independent continuation in the rotation angle (numpy eig of the 8 x 8 Stroh matrix
built here from the generalised blocks of the lab tensors, the four partial waves matched to the nearest roots of the
previous step, an own secant in X at every angle; the electrically free or metallized boundary
determinant written here) from a root the solver found before this change (metallized 3 deg:
4102.16 m/s, 0.717 dB/lambda; free 112 deg, 4293.83 m/s; free 156 deg, 4424.41 m/s; metallized
110 deg, 4259.00 m/s). It gives (docs/physics/leaky-waves.md, "Rotated Y-cut LiNbO3"): metallized
0-2 deg 4080.88-4094.15 m/s with 0.59-0.68 dB/lambda (c_leaky above v_L1 = 4079.18 m/s,
Re X - X_L1 > 0); free 114-122 deg and 140-154 deg, metallized 112-117 deg; beyond these the
root's real speed falls below v_L1 (free ~122.2 and ~139.2 deg, metallized ~117.4 deg), the root
then meets its mirror image on the real X axis below X_L1 (a real root with a growing partial wave;
metallized 130-147 deg a real root just below v_L1 with all four waves decaying).
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.real_crystals.piezo_materials import lab_tensors
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.leaky import REASON_LOW, REASON_NOMIN, leaky_wave
from surfwave.solvers.piezo_stroh import generalised_blocks
from surfwave.solvers.piezo_tensors import EPS0


def _tensors(rot):
    rot = np.atleast_1d(np.asarray(rot, dtype=float))
    return lab_tensors("LiNbO3", euler_lab_axes(0 * rot, rot - 90.0, 0 * rot).reshape(-1, 3, 3))


def _solve(rot, electrical):
    t = _tensors(rot)
    return leaky_wave(t["C"], t["rho"], t["e"], t["eps"], electrical=electrical)


#: Stiffness scale (Pa) of the continuation, fixed for all angles (X = rho v^2 / S).
S = 2.0e11


def _N(rot, X, s=S):
    """8 x 8 Stroh matrix of one rotation at X = rho v^2 / s, from the generalised blocks
    (surfwave.solvers.piezo_stroh.generalised_blocks, C / s, e / sqrt(s EPS0), eps / EPS0)."""
    t = _tensors(rot)
    Q, R, T = (b[0] for b in generalised_blocks(t["C"] / s, t["e"] / np.sqrt(s * EPS0), t["eps"] / EPS0))
    Ti = np.linalg.inv(T)
    M = np.diag([1.0, 1, 1, 0])
    return np.block([[-Ti @ R.T, Ti], [R @ Ti @ R.T - Q + X * M, -R @ Ti]]), s, t["rho"]


def _det(rot, X, p_prev, electrical):
    N, _, _ = _N(rot, X)
    ev, vec = np.linalg.eig(N)
    j = np.abs(ev[None, :] - p_prev[:, None]).argmin(axis=1)
    assert len(set(j)) == 4
    Mi = vec[4:, j] @ np.linalg.inv(vec[:4, j])
    if electrical == "free":
        Mi[3, 3] -= 1j
        return np.linalg.det(Mi), ev[j]
    return np.linalg.det(Mi[:3, :3]), ev[j]


def _continue(rots, electrical):
    """The solver's root at rots[0], followed along ``rots`` (independent secant). Returns
    (len(rots), 2): c_leaky (m/s) and delta per angle."""
    r0 = _solve(rots[0], electrical)
    assert r0["reason"][0] == ""
    _, s, rho = _N(rots[0], 1.0)
    X, p = complex(rho * r0["c_leaky_complex"][0] ** 2 / s), r0["decay"][0]
    out = []
    for a in rots:
        fa, pa = _det(a, X, p, electrical)
        Xb = X * (1 + 1e-6)
        for _ in range(60):
            fb, pb = _det(a, Xb, pa, electrical)
            X, Xb, fa, pa = Xb, Xb - fb * (Xb - X) / (fb - fa), fb, pb
            if abs(Xb - X) < 1e-14 * abs(X):
                break
        p = pa
        v = np.sqrt(X * s / rho)
        out.append((1 / (1 / v).real, (1 / v).imag / (1 / v).real))
    return np.array(out)


def test_metallized_near_0_deg_root_found():
    """Metallized 0-2 deg was REASON_NOMIN ("no leaky wave"); the continuation from 3 deg (0.25-deg
    steps) reaches 0 deg at 4080.877 m/s, 0.590 dB/lambda, still above v_L1 = 4079.176 m/s."""
    rots = np.arange(3.0, -0.01, -0.25)
    ref = _continue(rots, "metallized")
    want = np.array([0.0, 0.5, 1.0, 2.0])
    r = _solve(want, "metallized")
    assert np.all(r["reason"] == ""), r["reason"]
    k = [int(np.argmin(np.abs(rots - a))) for a in want]
    assert np.allclose(r["c_leaky"], ref[k, 0], rtol=1e-9)
    assert np.allclose(r["delta"], ref[k, 1], rtol=1e-6)
    assert r["c_leaky"][0] == pytest.approx(4080.877, abs=0.01)
    assert r["leaky_attenuation"][0] == pytest.approx(0.590, abs=0.001)
    assert np.all(r["c_leaky"] > r["c_limits"][:, 0])


@pytest.mark.parametrize(("electrical", "start", "angles"),
                         [("free", 112.0, [114.0, 118.0, 122.0]), ("free", 156.0, [154.0, 146.0, 140.0]),
                          ("metallized", 110.0, [112.0, 114.0, 117.0])])
def test_rotated_y_gap_roots_found(electrical, start, angles):
    """Free 114-122 and 140-154 deg, metallized 112-117 deg were REASON_NOMIN; the continuation
    from the last converged neighbour (1-degree steps) gives the root the solver now reports."""
    step = 1.0 if angles[-1] > start else -1.0
    rots = np.arange(start, angles[-1] + 0.5 * step, step)
    ref = _continue(rots, electrical)
    r = _solve(angles, electrical)
    assert np.all(r["reason"] == ""), r["reason"]
    k = [int(np.argmin(np.abs(rots - a))) for a in angles]
    assert np.allclose(r["c_leaky"], ref[k, 0], rtol=1e-9)
    assert np.allclose(r["delta"], ref[k, 1], rtol=1e-6)


@pytest.mark.parametrize(("electrical", "start", "angle"), [("free", 122.0, 123.0), ("free", 140.0, 139.0),
                                                            ("metallized", 117.0, 118.0)])
def test_branch_leaving_through_v_l1_is_named(electrical, start, angle):
    """Where the continued root's real speed has fallen below v_L1 (free 123 and 139 deg,
    metallized 118 deg) there is no leaky wave of the window: the reason names it (REASON_LOW),
    and none says REASON_NOMIN ("no interior minimum ... not found") over the old gaps."""
    step = 0.25 if angle > start else -0.25
    ref = _continue(np.arange(start, angle + 0.5 * step, step), electrical)
    r = _solve([angle], electrical)
    assert ref[-1, 0] < r["c_limits"][0, 0]
    assert r["reason"][0] == REASON_LOW and np.isnan(r["c_leaky"][0])
    gap = _solve(np.arange(112.0, 180.0, 2.0), electrical)
    assert not np.any(gap["reason"] == REASON_NOMIN)


def test_nomin_reason_does_not_claim_absence():
    """REASON_NOMIN is returned where no search converged; it must not say "no leaky wave"."""
    assert not REASON_NOMIN.startswith("no leaky wave")
    assert "not found" in REASON_NOMIN


@pytest.mark.parametrize("name", ["LiNbO3", "LiTaO3", "quartz"])
def test_both_conditions_in_one_call_are_bit_identical(name):
    """leaky_wave(..., electrical=("free", "metallized")) shares the limits, the real scan's
    eigen-decompositions and the grid impedance; reference: two separate calls (one per
    condition), every output bit-identical (rotated Y-cuts 0-180 deg in 3-degree steps, gaps and
    their complex starts included)."""
    rot = np.arange(0.0, 180.0, 3.0)
    t = lab_tensors(name, euler_lab_axes(0 * rot, rot - 90.0, 0 * rot).reshape(-1, 3, 3))
    kw = {"A": t["C"], "rho": t["rho"], "e": t["e"], "eps": t["eps"]}
    both = leaky_wave(**kw, electrical=("free", "metallized"))
    assert set(both) == {"free", "metallized"}
    for el in ("free", "metallized"):
        one = leaky_wave(**kw, electrical=el)
        assert set(one) == set(both[el])
        for k, v in one.items():
            if v.dtype == object:
                assert np.array_equal(v, both[el][k]), k
            else:
                assert np.array_equal(v, both[el][k], equal_nan=True), k


def test_both_conditions_elastic_and_bad_input():
    """Without e the condition is ignored: each key gets the single-call answer (own arrays).
    A repeated or unknown condition, or none, is an InputError."""
    from surfwave.errors import InputError
    from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor
    C = voigt_to_tensor(cubic_voigt(168.4e9, 121.4e9, 75.4e9))[None]
    one = leaky_wave(C, 8960.0)
    both = leaky_wave(C, 8960.0, electrical=["metallized", "free"])
    for el in ("free", "metallized"):
        for k, v in one.items():
            assert np.array_equal(v, both[el][k], equal_nan=True) if v.dtype != object else np.array_equal(v, both[el][k])
    assert both["free"]["c_limits"] is not both["metallized"]["c_limits"]
    for bad in (("free", "free"), (), ("free", "shorted")):
        with pytest.raises(InputError):
            leaky_wave(C, 8960.0, electrical=bad)


def test_piezo_saw_conditions_uses_one_leaky_call():
    """piezo_saw_conditions now solves both leaky conditions in one call; reference: the separate
    leaky_wave calls (per condition), c_leaky / attenuation / reason identical."""
    from surfwave.solvers.piezo_saw import piezo_saw_conditions
    rot = np.array([0.0, 41.0, 64.0, 120.0, 128.0, 150.0])
    t = _tensors(rot)
    rho = np.full(rot.size, t["rho"])
    res = piezo_saw_conditions(t["C"], rho, t["e"], t["eps"])
    for el in ("free", "metallized"):
        one = leaky_wave(t["C"], rho, t["e"], t["eps"], electrical=el)
        assert np.array_equal(res[el]["c_leaky"], one["c_leaky"], equal_nan=True)
        assert np.array_equal(res[el]["leaky_attenuation"], one["leaky_attenuation"], equal_nan=True)
        assert np.array_equal(res[el]["leaky_reason"], one["reason"])
