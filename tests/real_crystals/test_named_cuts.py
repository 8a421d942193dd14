"""Named SAW cuts through the database (get_cut, lab_tensors) and the solvers, against published values.

Every number compared here is a published speed or coupling; the constant set is the cut's
``material`` in piezoelectric.yaml. Sources of the published values (cut_references there):
Slobodnik, Conway and Delmonico, Microwave Acoustics Handbook 1A (1973), computed with Warner et al.
1967 (LiNbO3) / Bechmann 1958 (quartz); Morgan, Surface Acoustic Wave Devices (2007), Table 8.1;
leaky-wave values as quoted in the project's leaky-wave brief (set not named there; which set
reproduces them is itself a finding recorded in the yaml notes).

Tolerances are stated per test and are the measured gap plus a margin, not a blanket per cent:
the largest gaps are 128Y-X (15 m/s: the published set is not named) and 36Y-X metallized
(10.5 m/s: the LiTaO3 set is unverified), both explained in the yaml notes.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.real_crystals.piezo_materials import get_cut, lab_tensors
from surfwave.solvers import leaky, piezo


def _subsonic(cut_name, material=None):
    cut = get_cut(cut_name)
    t = lab_tensors(material or cut.material, cut.lab_axes)
    r = piezo.coupling_coefficient(t["C"][None], t["e"][None], t["eps"][None], t["rho"])
    return cut, r["c_free"][0], r["c_metallized"][0], 100 * r["K2"][0]


def _leaky(cut_name, material=None):
    cut = get_cut(cut_name)
    t = lab_tensors(material or cut.material, cut.lab_axes)
    out = {}
    for el in ("free", "metallized"):
        r = leaky.leaky_wave(t["C"][None], t["rho"], t["e"][None], t["eps"][None], electrical=el)
        assert r["reason"][0] == "", r["reason"][0]
        out[el] = (r["c_leaky"][0], r["leaky_attenuation"][0], r["c_limits"][0])
    return cut, out


def test_y_z_linbo3_warner():
    """Y-Z LiNbO3, Warner 1967 set (the set of the publication): 3488 / 3404 m/s, K^2 4.8 %
    (Slobodnik et al. 1973). Measured: 3487.8 / 3403.7, 4.82 %; tolerance 1 m/s, 0.05 % K^2."""
    cut, vf, vm, k2 = _subsonic("Y-Z")
    assert cut.material == "LiNbO3-Warner1967"
    p = cut.published
    assert vf == pytest.approx(p["v_free"], abs=1.0) and vm == pytest.approx(p["v_metallized"], abs=1.0)
    assert k2 == pytest.approx(p["K2_percent"], abs=0.05)


def test_st_x_quartz_bechmann():
    """ST-X quartz, Bechmann 1958 set: 3158 m/s free, K^2 0.11 % (Morgan 2007; Slobodnik 1973).
    Measured 3159.8 / 3158.0, 0.1135 %; tolerance 2.5 m/s: the 1.8 m/s gap is the density
    (2648 held vs 2651, which gives 3158.07; quartz note in the yaml)."""
    cut, vf, vm, k2 = _subsonic("ST-X")
    assert vf == pytest.approx(cut.published["v_free"], abs=2.5)
    assert k2 == pytest.approx(cut.published["K2_percent"], abs=0.01)


def test_128_y_x_linbo3():
    """128Y-X LiNbO3: 3979 m/s free, K^2 5.3 % (Morgan 2007, set not named). Warner 1967 set:
    3994.2 m/s (+0.38 %), K^2 5.34 %. Tolerance 0.5 % on the speed (the published 3979-3997
    spread between sets) and 0.1 % on K^2. The Kovacs set held here (3989.6, 5.59 %) fails the
    K^2 test, which is why the cut uses Warner. Second route: the independent brute force of
    tests/piezo_saw_brute.py gives the same two speeds to 0.05 m/s."""
    import sys
    from pathlib import Path

    sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
    from piezo_saw_brute import saw_speed

    cut, vf, vm, k2 = _subsonic("128Y-X")
    t = lab_tensors(cut.material, cut.lab_axes)
    for v, free in ((vf, True), (vm, False)):
        assert saw_speed(t["C"], t["e"], t["eps"], t["rho"], 3700, 4020, free=free) == pytest.approx(v, abs=0.05)
    assert vf == pytest.approx(cut.published["v_free"], rel=5e-3)
    assert k2 == pytest.approx(cut.published["K2_percent"], abs=0.1)
    k2_kovacs = _subsonic("128Y-X", "LiNbO3-Kovacs1990")[3]
    assert abs(k2_kovacs - cut.published["K2_percent"]) > 0.2


@pytest.mark.parametrize("name", ["64Y-X", "41Y-X"])
def test_rotated_y_x_linbo3_leaky_warner(name):
    """64Y-X 4742 / 4478 and 41Y-X 4792 / 4379 m/s free / metallized (leaky-wave brief). The
    Warner 1967 set reproduces them: 4742.3 / 4474.8 and 4792.2 / 4379.7 m/s; tolerance 4 m/s
    (the largest gap, 64Y-X metallized, is 3.2 m/s). The Kovacs set held here misses the free
    64Y-X speed by 25 m/s, so the quotes are not from it."""
    cut, r = _leaky(name)
    assert cut.wave == "leaky" and cut.material == "LiNbO3-Warner1967"
    assert r["free"][0] == pytest.approx(cut.published["v_free"], abs=4.0)
    assert r["metallized"][0] == pytest.approx(cut.published["v_metallized"], abs=4.0)
    assert r["metallized"][0] < r["free"][0] < r["free"][2][1]            # below the slow-shear limit
    if name == "64Y-X":
        other = _leaky(name, "LiNbO3-Kovacs1990")[1]
        assert abs(other["free"][0] - cut.published["v_free"]) > 15.0


def test_64_y_x_attenuation_and_coupling_warner():
    """64Y-X LiNbO3 (Yamanouchi and Shibayama, J. Appl. Phys. 43, 856 (1972), as cited in
    tests/solvers/test_leaky.py; their constants are Warner-type): K^2 = 0.113, attenuation
    0.036 dB per wavelength free and ~0 metallized. Measured 0.1128, 0.0359 and < 1e-4 dB/λ;
    tolerances 0.003 on K^2 and 0.003 dB/λ."""
    cut, r = _leaky("64Y-X")
    K2 = 2 * (r["free"][0] - r["metallized"][0]) / r["free"][0]
    assert K2 == pytest.approx(0.113, abs=0.003)
    assert r["free"][1] == pytest.approx(0.036, abs=0.003)
    assert r["metallized"][1] < 1e-3


def test_36_y_x_litao3_leaky():
    """36Y-X LiTaO3, Kovacs 1990 set as held (unverified): 4212 m/s free / 4112 m/s metallized
    (leaky-wave brief; 4112 is the metallized speed). Measured 4211.0 / 4101.5 m/s: tolerance
    2 m/s free and 0.3 % (12 m/s) metallized, the 10.5 m/s gap is the largest of the LiTaO3
    cuts (e and eps digits of the unverified set). Low-loss cut: both attenuations < 0.01 dB/λ.
    The previously held set (LiTaO3-unattributed) gives 4229.0 free, outside 2 m/s."""
    cut, r = _leaky("36Y-X")
    assert r["free"][0] == pytest.approx(cut.published["v_free"], abs=2.0)
    assert r["metallized"][0] == pytest.approx(cut.published["v_metallized"], rel=3e-3)
    assert r["free"][1] < 0.01 and r["metallized"][1] < 0.01
    other = _leaky("36Y-X", "LiTaO3-unattributed")[1]
    assert abs(other["free"][0] - cut.published["v_free"]) > 10.0


def test_42_y_x_litao3_is_a_leaky_wave_but_4022_is_not_a_half_space_speed():
    """42Y-X LiTaO3: the quoted 4022 m/s (leaky-wave brief) is not reproduced by any set we hold
    (yaml note); only the half-space facts are tested: a leaky wave exists for both boundary
    conditions with metallized < free <= slow-shear limit, low loss (< 0.05 dB/λ), and the
    metallized speed is within 1 % of 36Y-X's (the two cuts differ by 6 degrees; Kovacs set:
    4107.5 vs 4101.5 m/s). The published value is asserted to be more than 1 % below both
    computed speeds, so a future set or boundary condition that reproduces it will be noticed."""
    cut, r = _leaky("42Y-X")
    assert r["metallized"][0] < r["free"][0] <= r["free"][2][1] * (1 + 1e-9)
    assert r["free"][1] < 0.05 and r["metallized"][1] < 0.05
    assert r["metallized"][0] == pytest.approx(_leaky("36Y-X")[1]["metallized"][0], rel=1e-2)
    assert cut.published["v"] < 0.99 * min(r["free"][0], r["metallized"][0])


def test_every_cut_is_covered():
    """Each named cut of the database has a test above (a new cut must get one)."""
    from surfwave.real_crystals.piezo_materials import available_cuts

    assert set(available_cuts()) == {"Y-Z LiNbO3", "128Y-X LiNbO3", "64Y-X LiNbO3", "41Y-X LiNbO3",
                                     "36Y-X LiTaO3", "42Y-X LiTaO3", "ST-X quartz"}


def test_recorded_computed_values_match_the_solvers():
    """The ``computed`` blocks of piezoelectric.yaml (a record for readers) are what the solvers
    give now, to their printed digits (0.1 m/s, 0.01 % K^2 rounded; 0.001 dB/λ)."""
    from importlib import resources

    import yaml

    raw = yaml.safe_load(resources.files("surfwave.real_crystals").joinpath("piezoelectric.yaml").read_text())
    for name, entry in raw["cuts"].items():
        rec = entry["computed"]
        if entry["wave"] == "rayleigh":
            _, vf, vm, k2 = _subsonic(name)
            np.testing.assert_allclose([vf, vm], [rec["v_free"], rec["v_metallized"]], atol=0.06)
        else:
            _, r = _leaky(name)
            vf, vm = r["free"][0], r["metallized"][0]
            np.testing.assert_allclose([vf, vm], [rec["v_free"], rec["v_metallized"]], atol=0.06)
            np.testing.assert_allclose([r["free"][1], r["metallized"][1]], [rec["att_free"], rec["att_metallized"]],
                                       atol=6e-5)
            k2 = 200 * (vf - vm) / vf
        assert k2 == pytest.approx(rec["K2_percent"], abs=6e-3)
