"""Third-order constants in the piezoelectric sweep (the cube of a piezoelectric scene).

References: the per-point call the sweep made before it had a ``toec`` option
(surfwave.real_crystals.piezo_wave.piezo_wave_conditions with toec=False, the fixed-constants
model; bit for bit), and the front door surfwave.material("GaAs", euler=..., stress=...,
toec=True or a caller's mapping) point by point: two front ends of the one path
(surfwave.real_crystals.stressed_wave.surface_wave). GaAs's set is the elastic database's
(McSkimin and Andreatch 1967, checked against measured pressure derivatives in
tests/real_crystals/test_toec_measurements.py).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.piezo_materials import get_piezo_material
from surfwave.real_crystals.piezo_sweep import VARIABLES, piezo_wave_sweep
from surfwave.real_crystals.piezo_wave import piezo_wave_conditions
from surfwave.solvers.euler import euler_lab_axes

#: GaAs plates: (001) with propagation along [100] and 45 degrees off it (K^2 = 0 and K^2 > 0),
#: and a (110)-like plate, under compression, nothing and tension (GPa).
EULER = {"phi": 0.0, "theta": [0.0, -90.0], "psi": [0.0, 45.0]}
STRESS = [-0.5, 0.0, 0.5]
KEYS = ("c_R", "c_leaky", "leaky_attenuation", "power_flow_angle", "potential_share")


def _points():
    """Euler angles of the cube's (surface, angle) points in cube order, (n, 3)."""
    return np.array([[EULER["phi"], t, p] for t in EULER["theta"] for p in EULER["psi"]])


def test_toec_false_is_the_fixed_constants_cube_bit_for_bit():
    """toec=(False,) (and the False slice of (False, True)) equals, bit for bit, the per-point
    call the sweep made before it had a toec option (piezo_wave_conditions, fixed constants);
    the unstressed cube has neither a toec nor a stress dim."""
    only = piezo_wave_sweep(["GaAs"], euler=EULER, stress=STRESS, toec=(False,))
    both = piezo_wave_sweep(["GaAs"], euler=EULER, stress=STRESS, toec=(False, True))
    assert only.c_R.dims == ("material", "surface", "angle", "electrical", "toec", "stress")
    assert only.toec.values.tolist() == [False] and both.toec.values.tolist() == [False, True]
    e = _points()
    R = np.repeat(euler_lab_axes(e).reshape(-1, 3, 3), len(STRESS), axis=0)
    S = np.tile(STRESS, len(e))
    ref = piezo_wave_conditions(get_piezo_material("GaAs"), R, S, toec=False)
    for el in ("free", "metallized"):
        for key in VARIABLES:
            want = np.asarray(ref[el][key]).reshape((2, 2, len(STRESS)) + np.shape(ref[el][key])[1:])
            for ds in (only, both):
                got = ds[key].isel(material=0).sel(toec=False)
                got = got.sel(electrical=el) if "electrical" in got.dims else got
                if want.dtype.kind in "fc":
                    assert np.array_equal(got.values, want, equal_nan=True), (key, el)
                else:
                    assert got.values.astype(str).tolist() == want.astype(str).tolist(), (key, el)
    bare = piezo_wave_sweep(["GaAs"], euler=EULER)
    assert "toec" not in bare.dims and "stress" not in bare.dims


def test_toec_true_equals_the_front_door_point_by_point():
    """toec=True for GaAs (the database's set) equals surfwave.material("GaAs", euler=...,
    stress=..., toec=True) at every point and both conditions; the third-order model moves the
    speeds (the cube does not repeat the fixed-constants values)."""
    ds = piezo_wave_sweep(["GaAs"], euler=EULER, stress=STRESS, toec=(False, True))
    for (i, j), e in zip(np.ndindex(2, 2), _points()):
        for el in ("free", "metallized"):
            r = surfwave.material("GaAs", euler=np.repeat(e[None], len(STRESS), 0), stress=np.array(STRESS),
                                  toec=True, electrical=el)
            got = ds.isel(material=0, surface=i, angle=j).sel(electrical=el, toec=True)
            for key in KEYS:
                np.testing.assert_allclose(got[key].values, r[key], rtol=1e-12, atol=1e-12, err_msg=key)
            np.testing.assert_allclose(got.K2.values, r["K2"], rtol=1e-12, atol=1e-15)
    moved = np.abs(ds.c_R.sel(toec=True) - ds.c_R.sel(toec=False)).sel(stress=0.5)
    assert float(moved.min()) > 1.0                                  # m/s at 0.5 GPa


def test_a_callers_set_equals_the_front_door_with_the_same_mapping():
    """toec_constants (a mapping of the -43m names, with a source key as a YAML file has it) is
    the set of every point: equal to surfwave.material("GaAs", ..., toec=mapping), and different
    from the database's set it replaces (scaled by 0.8)."""
    named = {k: 0.8 * v for k, v in get_material("GaAs").toec.items()}
    ds = piezo_wave_sweep(["GaAs"], euler={"phi": 0, "theta": 0, "psi": 45}, electrical=["free"], stress=STRESS,
                          toec=(True,), toec_constants={**named, "source": "scaled for a test"})
    r = surfwave.material("GaAs", euler=np.repeat([[0.0, 0.0, 45.0]], 3, 0), stress=np.array(STRESS), toec=named)
    got = ds.isel(material=0, surface=0, angle=0, electrical=0, toec=0)
    np.testing.assert_allclose(got.c_R.values, r["c_R"], rtol=1e-12)
    db = piezo_wave_sweep(["GaAs"], euler={"phi": 0, "theta": 0, "psi": 45}, electrical=["free"], stress=[0.5],
                          toec=(True,))
    assert abs(float(db.c_R.squeeze()) - float(got.c_R.sel(stress=0.5))) > 0.1


def test_toec_true_without_a_set_is_refused():
    """LiNbO3 has no third-order set in the database: toec=True names the material; a wrong
    mapping is refused with toec_classes.toec_from_named's message."""
    with pytest.raises(InputError, match="'LiNbO3-Warner1967' has no third-order"):
        piezo_wave_sweep(["LiNbO3"], cuts=["Y-Z LiNbO3"], stress=[0.1], toec=(True,))
    with pytest.raises(InputError, match=r"missing \['C456'\]"):
        piezo_wave_sweep(["GaAs"], euler={"phi": 0, "theta": 0, "psi": 0}, stress=[0.1], toec=(True,),
                         toec_constants={k: v for k, v in get_material("GaAs").toec.items() if k != "C456"})
