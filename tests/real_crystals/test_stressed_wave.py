"""The one path to the surface wave of a stressed real crystal (surfwave.real_crystals.stressed_wave).

References:
- consistency: ``surfwave.material`` (the API), ``acoustoelastic.surface_wave_speed`` and the cube
  solver ``sweep.surface_wave_sweep`` must give the same numbers and the same reasons at shared
  points (issue 21 item 2); they are compared point by point, the API one call per point;
- issue 20 item 1: a sweep with ``toec: [false, true]`` gave points without a stressed state another
  point's c_R labelled ``surface``; by the developers' guide a point without an answer is NaN with
  its reason (docs/architecture.md, "Conventions");
- issue 20 item 8: TOEC off the (001) surface (Cu (111), stress [0, 0.1]) killed the cube job with
  "prestress must lie in the surface plane" while the API gave NaN with a reason;
- the Born criteria of a cubic crystal (C11 - C12 > 0, C11 + 2 C12 > 0, C44 > 0; Born and Huang):
  C11 = 50, C12 = -80 GPa violates the second one;
- Cu (001)[100] unstressed with TOEC: 2012.12 m/s (docs/physics/paper.md), and 2019.06 m/s at
  +0.1 GPa along [100] (the API's docstring example, the value before this refactor).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals import toec
from surfwave.real_crystals.acoustoelastic import loading_stress, surface_wave_speed
from surfwave.real_crystals.materials import Material, get_material
from surfwave.real_crystals.stressed_wave import (
    REASON_NO_STATE,
    REASON_TRACTION,
    Constants,
    stress_tensor,
    surface_wave,
)
from surfwave.real_crystals.sweep import applied_stress, surface_wave_sweep
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor

#: Keys the cube and the API share (floats compared to 1e-12 relative, strings exactly).
SHARED = ("c_R", "c_R_imag", "c_limit", "penetration_depth", "rho", "polarisation", "decay")


def _api_point(material, surface, angle, loading, use_toec, s):
    """One API call for a cube point: scalar stress for ``along``, the 3 x 3 tensor otherwise."""
    R = lab_axes(surface, angle)
    stress = s if loading == "along" else stress_tensor(loading, s, R)
    return surfwave.material(material, surface=surface, angle=angle, stress=stress, toec=use_toec)


def _assert_cube_equals_api(ds):
    for mat in ds.material.values:
        for sf in ds.surface.values:
            for a in ds.angle.values:
                for ld in ds.loading.values:
                    for tc in ds.toec.values:
                        for s in ds.stress.values:
                            pt = ds.sel(material=mat, surface=sf, angle=a, loading=ld, toec=tc, stress=s)
                            r = _api_point(str(mat), str(sf), float(a), str(ld), bool(tc), float(s))
                            where = f"{mat} {sf} {a} {ld} toec={tc} {s} GPa"
                            assert str(pt.reason.values) == r["reason"], where
                            assert str(pt.wave_type.values) == r["wave_type"], where
                            for key in SHARED:
                                np.testing.assert_allclose(pt[key].values, r[key], rtol=1e-12, atol=0,
                                                           equal_nan=True, err_msg=f"{key} at {where}")


def _assert_reasons_mean_nan(ds):
    """Every point with a reason has no speed and is not labelled a surface wave."""
    has_reason = ds.reason.values != ""
    assert np.all(np.isnan(ds.c_R.values[has_reason]))
    assert set(np.unique(ds.wave_type.values[has_reason])) <= {"none", "pseudo"}
    assert np.all(np.isnan(ds.rho.values[np.char.startswith(ds.reason.values.astype(str), REASON_NO_STATE)]))


def test_issue20_item1_no_state_is_nan_and_sweep_equals_api():
    """Issue 20 item 1: Cu and Ag, (001), [100] and [110], stress -3..3 GPa, every loading, toec
    [false, true]. Points without a stressed state must be NaN with wave_type none (not another
    point's c_R labelled surface), and the cube must equal surfwave.material point by point,
    reasons included (failed before: the batch was pre-filled from the first element)."""
    mats = [get_material("Cu"), get_material("Ag")]
    stress = np.arange(-3.0, 3.01, 1.0)
    ds = surface_wave_sweep(mats, ["(001)"], [0.0, 45.0], stress=stress, loadings=["along", "across", "biaxial"],
                            toec=[False, True], directions=["[100]", "[110]"])
    no_state = np.char.startswith(ds.reason.values.astype(str), REASON_NO_STATE)
    assert no_state.sum() > 10 and (~no_state).sum() > 10   # the grid holds both kinds of point
    _assert_reasons_mean_nan(ds)
    _assert_cube_equals_api(ds)


def test_issue20_item8_toec_off_001_gives_nan_not_a_crash():
    """Issue 20 item 8: Cu (111), stress [0, 0.1], toec [false, true] (and Cu, Si, Al at +-1 GPa on
    (001), (110), (111)) killed the cube job ("prestress must lie in the surface plane, sigma_21 =
    ..."); now the points whose deformed surface is loaded are NaN with the traction reason, as in
    the API, and everything else equals the API."""
    ds = surface_wave_sweep([get_material("Cu")], ["(111)"], [0.0, 10.0, 30.0], stress=[0.0, 0.1],
                            loadings=["along", "across", "biaxial"], toec=[False, True])
    loaded = ds.reason.values == REASON_TRACTION
    assert loaded.any() and not loaded[..., 0, :].any()   # fixed-C never turns the surface
    _assert_reasons_mean_nan(ds)
    _assert_cube_equals_api(ds)
    ds = surface_wave_sweep([get_material(m) for m in ("Cu", "Si", "Al")], ["(001)", "(110)", "(111)"],
                            [0.0, 20.0], stress=[-1.0, 1.0], loadings=["along", "biaxial"], toec=[False, True])
    _assert_reasons_mean_nan(ds)
    _assert_cube_equals_api(ds)


def test_born_wording_identical_across_api_acoustoelastic_and_sweep():
    """C11 = 50, C12 = -80, C44 = 30 GPa: C11 + 2 C12 < 0 (Born criteria of a cubic crystal). The
    three callers give the same reason, toec.born_reason of Wallace's lowest eigenvalue (before: the
    API said "the crystal is Born-unstable (the elastic energy is not positive definite)", the
    others "stressed crystal not Born-stable (...)")."""
    C6 = cubic_voigt(50.0, -80.0, 30.0)
    bad = Material(name="bad", symmetry="cubic", rho=5000.0, voigt=C6,
                   constants={"C11": 50.0, "C12": -80.0, "C44": 30.0}, toec=None, sources={})
    lowest = toec.born_lowest(np.asarray(voigt_to_tensor(C6)), np.zeros((3, 3)))
    expected = REASON_NO_STATE + toec.born_reason(lowest)
    api = surfwave.material(voigt=C6, rho=5000.0, direction="[100]")
    ae = surface_wave_speed(C6, None, 5000.0, np.zeros((3, 3)), "(001)", "[100]")
    cube = surface_wave_sweep([bad], ["(001)"], [0.0], stress=[0.0])
    assert api["reason"] == str(ae["reason"]) == str(cube.reason.values.item()) == expected
    assert "Born" in expected and api["stable"] is False
    assert np.isnan(api["c_R"]) and np.isnan(ae["c_R"]) and np.isnan(cube.c_R.values.item())
    assert not toec.born_stable(voigt_to_tensor(C6), np.zeros((3, 3)))


@pytest.mark.parametrize("surface, direction", [("(001)", "[110]"), ("(001)", "[210]"), ("(111)", "[1-10]")])
def test_api_equals_acoustoelastic(surface, direction):
    """The API and acoustoelastic.surface_wave_speed on the same stressed states (Cu, with and
    without TOEC, -40 GPa: no state; a traction-loaded (111) point): same numbers, same reasons."""
    cu = get_material("Cu")
    s = np.array([-40.0, -0.5, 0.0, 0.3, 1.0])
    sig = loading_stress("along", s, surface, direction)
    for c3 in (None, cu.toec_voigt):
        ae = surface_wave_speed(cu.voigt, c3, cu.rho, sig, surface, direction)
        for k, value in enumerate(s):
            r = surfwave.material("Cu", direction=direction, surface=surface, stress=value, toec=c3 is not None)
            assert r["reason"] == ae["reason"][k] and r["wave_type"] == ae["wave_type"][k]
            for key in ("c_R", "c_limit", "rho"):
                np.testing.assert_allclose(r[key], ae[key][k], rtol=1e-12, equal_nan=True)
    assert ae["reason"][0].startswith(REASON_NO_STATE)


def test_stress_tensor_is_the_one_load_to_stress_function():
    """acoustoelastic.loading_stress, sweep.applied_stress and the API's scalar stress are all
    stress_tensor (bitwise); sigma . n = 0; an axis out of the surface is refused by name."""
    R = lab_axes("(110)", np.array([0.0, 30.0, 90.0]))
    s = np.array([-0.5, 0.2])
    for kind in ("along", "across", "biaxial"):
        sig = stress_tensor(kind, s, R)
        assert sig.shape == (3, 2, 3, 3)
        assert np.array_equal(sig, applied_stress(kind, R, s))
        assert np.array_equal(sig[1], loading_stress(kind, s, "(110)", 30.0))
        assert np.abs(np.einsum("aknj,aj->akn", sig, R[:, 1])).max() < 1e-15
    assert np.array_equal(stress_tensor("axis_001", s, R), applied_stress("axis_001", R, s))
    assert np.array_equal(stress_tensor("axis", s, R[0], axis="[001]"),
                          loading_stress("axis", s, "(110)", 0.0, axis="[001]"))
    with pytest.raises(InputError, match="not in the surface plane"):
        stress_tensor("axis_100", s, R)
    with pytest.raises(InputError, match="unknown loading"):
        stress_tensor("shear", s, R)


def test_constants_record_and_values():
    """Cu (001)[100]: 2012.12 m/s unstressed, 2019.06 m/s at +0.1 GPa along [100] with TOEC (values
    before this refactor); the record takes a tensor stiffness too; piezoelectric constants are
    solved (e = 0: the elastic wave, K2 = 0); electrical= without them and toec=True without C3 are
    refused."""
    cu = Constants.from_material(get_material("Cu"))
    R = lab_axes("(001)", "[100]")
    r = surface_wave(cu, R, stress_tensor("along", [0.0, 0.1], R), toec=True)
    assert np.round(r["c_R"], 2).tolist() == [2012.12, 2019.06]
    assert r["ok"].all() and r["stable"].all() and r["reason"].tolist() == ["", ""]
    same = Constants(voigt_to_tensor(cu.voigt), cu.rho, cu.toec)
    assert np.array_equal(same.voigt, cu.voigt)
    piezo = Constants(cu.voigt, cu.rho, piezo=np.zeros((3, 6)), permittivity=np.eye(3))
    z = surface_wave(piezo, R, stress_tensor("along", [0.0, 0.1], R))      # e = 0: the elastic wave
    el = surface_wave(Constants(cu.voigt, cu.rho), R, stress_tensor("along", [0.0, 0.1], R))
    np.testing.assert_allclose(z["c_R"], el["c_R"], rtol=1e-13)
    assert np.round(z["c_R"][0], 2) == 2012.12
    assert z["K2"].tolist() == [0.0, 0.0] and z["polarisation"].shape == (2, 4)
    with pytest.raises(InputError, match="piezoelectric"):
        surface_wave(Constants(cu.voigt, cu.rho), R, np.zeros((3, 3)), electrical="free")
    with pytest.raises(InputError, match="third-order"):
        surface_wave(Constants(cu.voigt, cu.rho), R, np.zeros((3, 3)), toec=True)
