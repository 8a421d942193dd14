"""Piezoelectric crystals through the one real-crystal path (issue 21 item 2).

References: the API (surfwave.material) and the cube (piezo_sweep.piezo_wave_sweep) must give the
same numbers and the same reasons because both call surfwave.real_crystals.stressed_wave
.surface_wave (an independent-route check: two front ends, one solver); Born stability of the
stressed crystal (Wallace's B, toec.born_lowest) decides "no stressed state" for piezoelectric
crystals as for cubic ones; the architecture rule of docs/architecture.md (real_crystals never
imports model_crystals), checked by parsing the imports.
"""
from __future__ import annotations

import ast
from pathlib import Path

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals import stressed_wave
from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material
from surfwave.real_crystals.piezo_sweep import piezo_wave_sweep
from surfwave.real_crystals.stressed_wave import REASON_NO_STATE, Constants, surface_wave

KEYS = ("c_R", "K2", "c_limit", "c_leaky", "leaky_attenuation", "power_flow_angle",
        "potential_share", "penetration_depth")


def test_api_equals_cube_numbers_and_reasons():
    """ST-X quartz and Y-Z LiNbO3, both conditions, stress 0, -0.2 GPa and -80 GPa along x1: the
    cube and surfwave.material agree exactly in every number and reason. At -80 GPa quartz is not
    Born-stable (lowest eigenvalue of Wallace's B < 0): NaN with the "no stressed state" reason of
    the one path (before, the piezoelectric front solved such points without a Born check)."""
    cuts, mats, stresses = ["ST-X quartz", "Y-Z LiNbO3"], ["quartz", "LiNbO3"], [0.0, -0.2, -80.0]
    with np.errstate(invalid="ignore"):
        ds = piezo_wave_sweep(mats, cuts=cuts, stress=stresses)
        for mat in mats:
            for cut in cuts:
                for el in ("free", "metallized"):
                    for s in stresses:
                        r = surfwave.material(mat, euler=get_cut(cut).euler, stress=s, electrical=el)
                        pt = ds.sel(material=get_piezo_material(mat).name, surface=cut, stress=s, toec=False).isel(angle=0)
                        for key in KEYS:
                            v = pt[key].sel(electrical=el) if "electrical" in pt[key].dims else pt[key]
                            np.testing.assert_array_equal(float(v), r[key], err_msg=f"{mat} {cut} {el} {s} {key}")
                        for key in ("reason", "wave_type", "leaky_reason"):
                            assert str(pt[key].sel(electrical=el).values) == r[key], (mat, cut, el, s, key)
    q = ds.sel(material=get_piezo_material("quartz").name, surface="ST-X quartz", stress=-80.0, toec=False)
    assert np.isnan(q.c_R).all() and all(str(x).startswith(REASON_NO_STATE) for x in q.reason.values.ravel())
    assert not surfwave.material("quartz", cut="ST-X quartz", stress=-80.0)["stable"]


def test_one_path_keys_and_zero_e_is_the_elastic_solver():
    """stressed_wave.surface_wave with piezoelectric constants returns the piezoelectric keys; with
    e = 0 its c_R equals the elastic Stroh solver's (the path without piezo constants) bit for bit
    (the elastic solver is called for e = 0, never the 8 x 8 one), K2 = 0."""
    m = get_piezo_material("quartz")
    R = get_cut("ST-X quartz").lab_axes
    r = surface_wave(Constants.from_piezo_material(m), R, np.zeros((3, 3)), electrical="metallized")
    for key in stressed_wave.PIEZO_KEYS + ("leaky_reason", "electrical", "c_L_par", "stable"):
        assert key in r, key
    assert r["c_R"] == r["c_metallized"] and r["polarisation"].shape[-1] == 4
    zero = Constants(m.voigt, m.rho, piezo=np.zeros((3, 6)), permittivity=m.eps_r)
    el = surface_wave(Constants(m.voigt, m.rho), R, np.zeros((3, 3)))
    z = surface_wave(zero, R, np.zeros((3, 3)))
    np.testing.assert_array_equal(z["c_R"], el["c_R"])
    assert np.all(z["K2"] == 0)


def test_toec_with_piezo_constants_is_refused_naming_what_is_missing():
    """Of the piezoelectric database only GaAs carries third-order constants (Thurston, McSkimin
    and Andreatch 1966 for quartz were not found in a stored source): toec=True on quartz raises an
    InputError that names the 14 class-32 constants and how to give them."""
    with pytest.raises(InputError, match="C444.*and this crystal has none"):
        surfwave.material("quartz", cut="ST-X quartz", stress=0.1, toec=True)
    with pytest.raises(InputError, match="give a set as toec="):
        surfwave.material("LiNbO3", cut="128Y-X", stress=0.1, toec=True)


def test_real_crystals_never_import_model_crystals():
    """docs/architecture.md: model_crystals and real_crystals import solvers, never each other.
    Every import statement of every module under real_crystals is parsed (ast), top level and in
    functions alike."""
    root = Path(surfwave.__file__).parent / "real_crystals"
    bad = []
    for path in sorted(root.glob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            names = ([a.name for a in node.names] if isinstance(node, ast.Import)
                     else [node.module or ""] if isinstance(node, ast.ImportFrom) else [])
            bad += [f"{path.name}: {n}" for n in names if n.startswith("surfwave.model_crystals")]
    assert not bad, bad


def test_toec_state_with_piezo_constants():
    """The third-order model runs for a record with piezoelectric constants once it has C3: Cu with its TOEC and e = 0 gives the elastic TOEC value 2019.06 m/s at
    +0.1 GPa along [100] (docs example of stressed_wave, values from before this change) exactly;
    with a non-zero e (LiNbO3's, on Cu: a synthetic crystal) and zero stress, toec=True equals the
    fixed-C result (F = I), and at 0.1 GPa it differs from it (C* and the deformed axes enter)."""
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.stressed_wave import stress_tensor
    from surfwave.solvers.orientation import lab_axes

    cu = Constants.from_material(get_material("Cu"))
    R = lab_axes("(001)", "[100]")
    s = stress_tensor("along", [0.0, 0.1], R)
    zero = Constants(cu.voigt, cu.rho, cu.toec, np.zeros((3, 6)), np.eye(3))
    el = surface_wave(cu, R, s, toec=True)
    z = surface_wave(zero, R, s, toec=True)
    np.testing.assert_array_equal(z["c_R"], el["c_R"])
    assert np.round(z["c_R"][1], 2) == 2019.06
    ln = get_piezo_material("LiNbO3")
    mixed = Constants(cu.voigt, cu.rho, cu.toec, ln.e, ln.eps_r)
    t = surface_wave(mixed, R, s, toec=True)
    f = surface_wave(mixed, R, s, toec=False)
    np.testing.assert_allclose(t["c_free"][0], f["c_free"][0], rtol=1e-12)
    assert t["K2"][0] > 0 and abs(t["c_free"][1] / f["c_free"][1] - 1) > 1e-5


def test_both_conditions_from_one_solve_equal_two_calls():
    """surface_wave_conditions / piezo_wave_conditions share the stressed state and the solves
    between the free and metallized conditions; each condition's dict equals a separate
    surface_wave call bit for bit (reference: the single-condition path), for rotated Y-cuts of
    LiNbO3 (a leaky range included) under stress, with bulk speeds."""
    from surfwave.real_crystals.piezo_wave import piezo_wave, piezo_wave_conditions
    from surfwave.solvers.euler import euler_lab_axes

    R = euler_lab_axes(np.column_stack([np.zeros(7), np.linspace(-90, 90, 7), np.zeros(7)]))
    mat = get_piezo_material("LiNbO3")
    both = piezo_wave_conditions(mat, R, np.linspace(-0.1, 0.1, 7), bulk=True)
    assert set(both) == {"free", "metallized"}
    for el, r in both.items():
        one = piezo_wave(mat, R, np.linspace(-0.1, 0.1, 7), electrical=el, bulk=True)
        assert set(one) == set(r)
        for key, v in one.items():
            if isinstance(v, np.ndarray) and v.dtype.kind in "fc":
                np.testing.assert_array_equal(r[key], v, err_msg=key)
            elif isinstance(v, np.ndarray):
                assert list(r[key].ravel()) == list(v.ravel()), key
            else:
                assert r[key] == v, key
    assert np.isfinite(both["free"]["c_leaky"]).any()


def test_conditions_are_checked():
    """Repeated, unknown or (for an elastic crystal) any electrical condition: InputError."""
    quartz = Constants.from_piezo_material(get_piezo_material("quartz"))
    R = get_cut("ST-X quartz").lab_axes
    for bad in [("free", "free"), ("open",), ()]:
        with pytest.raises(InputError, match="conditions"):
            stressed_wave.surface_wave_conditions(quartz, R, np.zeros((3, 3)), conditions=bad)
    cu = Constants.from_material(surfwave.real_crystals.materials.get_material("Cu"))
    with pytest.raises(InputError, match="conditions"):
        stressed_wave.surface_wave_conditions(cu, R, np.zeros((3, 3)), conditions=("free",))
    r = stressed_wave.surface_wave_conditions(cu, R, np.zeros((3, 3)), conditions=(None,))[None]
    assert r["c_R"] == surface_wave(cu, R, np.zeros((3, 3)))["c_R"]
