"""One question, every door: the same answer or the same refusal (issue 25).

The doors: the API with a surface and a direction, the API with SAW Euler angles (the
piezoelectric part on, e = 0 for copper), the command line, and the scene check that runs
before any job (real-crystal and piezoelectric scenes), plus the cube's sweep for the answers.
References: the API with a surface and a direction, itself checked against closed forms and
Eq. (17) (tests/solvers/test_stroh.py) and the Cu third-order data (tests/real_crystals/
test_toec.py); for refusals the wording of :func:`surfwave.case.make_case` (each door must show
the same line). Euler (0, 0, 0) is the (001) surface with propagation along [100] and normal
-[001] (tests/solvers/test_euler*.py), so it asks the same question as ("(001)", "[100]").
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import surfwave
from surfwave.cli import main
from surfwave.errors import InputError
from surfwave.pipeline.crystal_scenes import check_crystal_scene
from surfwave.pipeline.piezo_scenes import check_piezo_scene
from surfwave.real_crystals.sweep import surface_wave_sweep

CU = ["--C11", "168.4", "--C12", "121.4", "--C44", "75.4", "--rho", "8960"]
CU_ARGS = (168.4, 121.4, 75.4, 8960.0)


def _api_surface(**kw):
    return surfwave.material(*CU_ARGS, direction="[100]", surface="(001)", **kw)


def _api_euler(**kw):
    return surfwave.material(*CU_ARGS, euler=(0.0, 0.0, 0.0), **kw)


def _cli(capsys, *extra) -> tuple[int, str, str]:
    code = main(["material", *CU, *extra])
    out = capsys.readouterr()
    return code, out.out, out.err


def _crystal_scene(**kw):
    raw = {"materials": ["Cu"], "surfaces": ["(001)"], "angles": [0.0], "loading": ["along"], "toec": [False],
           "quantities": ["surface_wave"], "accuracy": {}, **kw}
    return check_crystal_scene("s", raw)


def _piezo_scene(**kw):
    raw = {"materials": ["GaAs"], "euler": {"phi": 0, "theta": 0, "psi": 0}, "quantities": ["surface_wave"],
           "accuracy": {}, **kw}
    return check_piezo_scene("s", raw)


def _refusal(call) -> str:
    with pytest.raises(InputError) as exc:
        call()
    return str(exc.value)


def test_a_loaded_surface_is_the_same_refusal_at_every_door(capsys):
    """sigma33 = 0.1 GPa loads the (001) surface: before, the surface/direction door raised
    ("prestress must lie in the surface plane") and the Euler door returned NaN with another
    reason. Now both API doors and the CLI refuse with the same line (the surface named in the
    words of each orientation)."""
    s33 = np.diag([0.0, 0.0, 0.1])
    a = _refusal(lambda: _api_surface(stress=s33))
    b = _refusal(lambda: _api_euler(stress=s33))
    code, _, err = _cli(capsys, "--stress", *(str(v) for v in s33.ravel()))
    for text in (a, b, err):
        assert "prestress must lie in the surface plane" in text and "sigma . n" in text
    assert a.split(": its")[1] == b.split(": its")[1].replace("-0.1", "0.1")   # n = -[001] for Euler (0, 0, 0)
    assert code == 2 and a in err


@pytest.mark.parametrize("door", ["api surface", "api euler", "cli", "crystal scene", "piezo scene"])
def test_stress_in_pa_is_the_same_refusal_at_every_door(door, capsys):
    """2000 GPa: beyond the one bound (surfwave.validate.MAX_STRESS_GPA), refused with the same
    words by the API (both routes), the CLI and both scene checks (before, the elastic API took
    it, the piezoelectric API refused with other words, a piezoelectric scene passed
    validation and failed inside its job)."""
    words = "must be in GPa; got 2000.0, beyond 1000 GPa, which looks like Pa (divide by 1e9: 2e-06 GPa)"
    if door == "api surface":
        text = _refusal(lambda: _api_surface(stress=2000.0))
    elif door == "api euler":
        text = _refusal(lambda: _api_euler(stress=2000.0))
    elif door == "cli":
        code, _, text = _cli(capsys, "--stress", "2000")
        assert code == 2
    else:
        scene, problems = (_crystal_scene if door == "crystal scene" else _piezo_scene)(stress=[2000])
        assert scene is None and len(problems) == 1
        text = problems[0]
        assert text.startswith("scene 's', key 'stress'")
    assert words in text


@pytest.mark.parametrize("door", ["api surface", "api euler", "cli"])
def test_density_out_of_bounds_is_the_same_refusal(door, capsys):
    """rho = 1e-3 kg/m^3 (g/cm^3 mistaken for kg/m^3 would be 8.96): refused by every door
    with the wording of surfwave.validate.density (before, the Euler door returned 8.66e6 m/s
    speeds)."""
    words = "rho = 0.001 kg/m^3 lies outside [1, 1e+12] kg/m^3"
    if door == "cli":
        code = main(["material", *CU[:-2], "--rho", "1e-3", "--euler", "0", "0", "0"])
        text = capsys.readouterr().err
        assert code == 2
    else:
        args = (168.4, 121.4, 75.4, 1e-3)
        kw = {"euler": (0, 0, 0)} if door == "api euler" else {"direction": "[100]"}
        text = _refusal(lambda: surfwave.material(*args, **kw))
    assert words in text


def test_the_same_answer_at_every_door(capsys):
    """Cu (001)[100] under 0.1 GPa along the propagation, third-order constants of the
    database: the API (both orientations), the CLI (--json) and the cube's sweep agree; the
    surface/direction API is the reference (2019.06 m/s, tests/real_crystals/test_toec.py). The
    Euler door runs the piezoelectric solver with e = 0, which hands the point to the elastic
    solver: equal to 1e-12 (C rotated in Pa there, in GPa here)."""
    from surfwave.real_crystals.materials import get_material

    ref = surfwave.material("Cu", direction="[100]", stress=0.1, toec=True)
    eul = surfwave.material("Cu", euler=(0, 0, 0), stress=0.1, toec=True)
    assert main(["material", "--material", "Cu", "--direction", "[100]", "--stress", "0.1", "--toec", "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    ds = surface_wave_sweep([get_material("Cu")], ["(001)"], [0.0], stress=[0.1], toec=[True])
    cube = float(ds.c_R.sel(material="Cu", surface="(001)", angle=0.0, loading="along", toec=True, stress=0.1))
    assert round(ref["c_R"], 2) == 2019.06
    assert cli["c_R"] == ref["c_R"] and cube == ref["c_R"]
    assert eul["c_R"] == pytest.approx(ref["c_R"], rel=1e-12)
    assert eul["wave_type"] == ref["wave_type"] == cli["wave_type"] == "surface"
    assert eul["K2"] == 0.0


@pytest.mark.parametrize("door", ["api surface", "api euler", "cli"])
def test_stress_true_is_not_one_gigapascal(door, capsys):
    """``stress=True`` was taken as 1 GPa by the API (issue 28, item 10); a boolean is refused
    at every door that can carry one (the CLI parses numbers: "True" is refused with one line)."""
    if door == "cli":
        code, _, err = _cli(capsys, "--stress", "True")
        assert code == 2 and "--stress" in err and "'True'" in err
        return
    call = _api_surface if door == "api surface" else _api_euler
    assert "not True/False" in _refusal(lambda: call(stress=True))


def test_born_unstable_constants_are_the_same_answer_at_both_api_doors():
    """C11 = 50, C12 = -80, C44 = 30 GPa: C11 + 2 C12 = -110 GPa < 0 (Born and Huang's cubic
    criterion; the lowest eigenvalue of the Voigt matrix is C11 + 2 C12). Not an input error: both
    doors answer NaN with the same Born reason naming -110 GPa (before, the Euler door refused
    such constants with another message)."""
    a = surfwave.material(50.0, -80.0, 30.0, 5000.0, direction="[100]")
    b = surfwave.material(50.0, -80.0, 30.0, 5000.0, euler=(0, 0, 0))
    assert np.isnan(a["c_R"]) and np.isnan(b["c_R"]) and a["reason"] == b["reason"]
    assert "not Born-stable" in a["reason"] and "-110 GPa" in a["reason"]


#: Bad inputs every door of the API and the CLI must refuse with one line (the fragment), each
#: answered within seconds: (API keyword arguments, CLI arguments, fragment of the refusal).
BAD = [
    ({"stress": float("nan")}, ["--stress", "nan"], "stress must be finite"),
    ({"stress": -5000.0}, ["--stress", "-5000"], "looks like Pa"),
    ({"stress": np.diag([0.0, 0.0, 0.1])}, ["--stress", "0", "0", "0", "0", "0", "0", "0", "0", "0.1"],
     "prestress must lie in the surface plane"),
    ({"stress": np.array([[0.0, 0.1, 0.0], [0.0, 0.0, 0.0], [0.0, 0.0, 0.0]])},
     ["--stress", "0", "0.1", "0", "0", "0", "0", "0", "0", "0"], "symmetric"),
    ({"rho": 0.0}, ["--rho", "0"], "rho"),
    ({"C11": 168.4e9}, ["--C11", "168.4e9"], "looks like Pa"),
    ({"stress": 0.1, "toec": (1271e9, 814e9, 50e9, 3e9, 780e9, 95e9)},     # magnitudes of Cu's set, in Pa
     ["--stress", "0.1", "--toec", "1271e9", "814e9", "50e9", "3e9", "780e9", "95e9"], "looks like Pa"),
]


@pytest.mark.parametrize("door", ["api surface", "api euler", "cli"])
@pytest.mark.parametrize("kw, cli_args, fragment", BAD)
def test_bad_input_table(door, kw, cli_args, fragment, capsys):
    """The same refusal by every door (a new door must pass this table), in seconds."""
    import time

    t0 = time.perf_counter()
    if door == "cli":
        given = dict(zip(CU[::2], CU[1::2]))
        given.update(dict(zip(cli_args[::2], cli_args[1::2])) if len(cli_args) == 2 else {})
        args = [x for k, v in given.items() for x in (k, v)] + ([] if len(cli_args) == 2 else cli_args)
        assert main(["material", *args, "--direction", "[100]"]) == 2
        text = capsys.readouterr().err
    else:
        base = dict(zip(("C11", "C12", "C44", "rho"), CU_ARGS))
        where = {"euler": (0.0, 0.0, 0.0)} if door == "api euler" else {"direction": "[100]"}
        text = _refusal(lambda: surfwave.material(**{**base, **where, **kw}))
    assert fragment in text and "\n" not in text.strip()
    assert time.perf_counter() - t0 < 5.0


#: Bad scene inputs: each refused by the scene check (before any job) with the API's words
#: after the scene, key and value.
SCENE_BAD = [
    ("crystal", {"stress": [-5000]}, "key 'stress': value -5000.0: stress must be in GPa; got -5000.0"),
    ("piezo", {"stress": [-5000]}, "key 'stress': value -5000.0: stress must be in GPa; got -5000.0"),
    ("crystal", {"stress": [0.1], "loading": ["axis_001"]}, "the axis is not in the surface plane"),
    ("piezo", {"euler": {"phi": float("inf")}}, "key 'euler.phi': value inf degrees: Euler angles must be finite"),
]


@pytest.mark.parametrize("kind, kw, fragment", SCENE_BAD)
def test_bad_scene_table(kind, kw, fragment):
    """The scene door of the same table: one line naming the scene and key, the API's words."""
    scene, problems = (_crystal_scene if kind == "crystal" else _piezo_scene)(**kw)
    assert scene is None and len(problems) == 1 and fragment in problems[0]
    assert problems[0].startswith("scene 's', key ")
    if "stress must be in GPa" in fragment:      # the same words as surfwave.material
        assert problems[0].split(": ", 2)[2] == _refusal(lambda: _api_surface(stress=-5000.0))
