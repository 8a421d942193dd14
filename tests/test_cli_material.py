"""`surfwave material`: any surface, direction or angle sweep, Voigt input, stress tensor.

References: the library call with the same arguments (surfwave.material), which
tests/solvers/test_stroh.py checks against closed forms and Eq. (17).
"""
from __future__ import annotations

import json

import numpy as np
import pytest

import surfwave
from surfwave.cli import main

CU = ["--C11", "168.4", "--C12", "121.4", "--C44", "75.4", "--rho", "8960"]   # docs/physics/general-solver.md, copper


def test_surface_and_direction_json_equals_library(capsys):
    assert main(["material", *CU, "--surface", "(111)", "--direction", "[1-10]", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.material(168.4, 121.4, 75.4, 8960.0, "[1-10]", surface="(111)")
    assert out["c_R"] == pytest.approx(ref["c_R"], rel=1e-15)
    assert out["c_limit"] == pytest.approx(ref["c_limit"], rel=1e-15)
    assert out["wave_type"] == ref["wave_type"]
    pol = np.array(out["polarisation"]["re"]) + 1j * np.array(out["polarisation"]["im"])
    np.testing.assert_allclose(pol, ref["polarisation"], atol=1e-15)


def test_angle_sweep_prints_a_table(capsys):
    assert main(["material", *CU, "--surface", "(110)", "--angle", "0:90:15"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    rows = [ln.split() for ln in lines[2:]]
    assert [float(r[0]) for r in rows] == [0, 15, 30, 45, 60, 75, 90]
    ref = surfwave.material(168.4, 121.4, 75.4, 8960.0, angle=np.arange(0, 91, 15.0), surface="(110)")
    np.testing.assert_allclose([float(r[1]) for r in rows], ref["c_R"], atol=0.006)


def test_voigt_and_stress_tensor(capsys):
    C6 = np.zeros((6, 6))
    C6[:3, :3] = 121.4
    C6[np.arange(3), np.arange(3)] = 168.4
    C6[np.arange(3, 6), np.arange(3, 6)] = 75.4
    stress = ["-1", "0", "0", "0", "0", "0", "0", "0", "0"]
    assert main(["material", "--voigt", *map(str, C6.ravel()), "--rho", "8960", "--angle", "20",
                 "--stress", *stress, "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.material(168.4, 121.4, 75.4, 8960.0, angle=20.0, stress=np.diag([-1.0, 0, 0]))
    assert out["c_R"] == pytest.approx(ref["c_R"], rel=1e-14)


@pytest.mark.parametrize("args, message", [
    (["--C11", "168.4e9", "--C12", "121.4", "--C44", "75.4", "--rho", "8960"], "looks like Pa"),
    ([*CU, "--direction", "[111]"], "does not lie in the surface"),
    ([*CU, "--stress", "0", "0", "0", "0", "0", "0", "0", "0", "1"], "traction"),
    ([*CU, "--angle", "0:90"], "START:STOP:STEP"),
    (["--C11", "168.4", "--rho", "8960"], "--C12"),
])
def test_errors_are_one_line(capsys, args, message):
    assert main(["material", *args]) == 2
    err = capsys.readouterr().err
    assert message in err and "Traceback" not in err



def _json(capsys, *args):
    assert main(["material", *args, "--json"]) == 0
    return json.loads(capsys.readouterr().out)


def test_material_by_name_and_third_order_model(capsys):
    """--material takes the database's constants and density (Cu: the README's 2012.12 m/s);
    --toec alone takes the database's third-order constants and agrees with the library call
    surfwave.material("Cu", ..., toec=True); six values equal to the database's give the same."""
    from surfwave.real_crystals.materials import get_material

    assert _json(capsys, "--material", "Cu", "--direction", "[100]")["c_R"] == pytest.approx(2012.12, abs=0.01)
    lib = surfwave.material("Cu", direction="[100]", stress=0.1, toec=True)["c_R"]
    got = _json(capsys, "--material", "Cu", "--direction", "[100]", "--stress", "0.1", "--toec")["c_R"]
    assert got == pytest.approx(lib, rel=1e-12) and abs(got - 2012.12) > 1.0   # the stress matters
    t = get_material("Cu").toec
    six = [repr(float(t[k])) for k in ("C111", "C112", "C123", "C144", "C155", "C456")]
    explicit = _json(capsys, "--material", "Cu", "--direction", "[100]", "--stress", "0.1", "--toec", *six)
    assert explicit["c_R"] == pytest.approx(got, rel=1e-12)


@pytest.mark.parametrize("args, words", [
    (["--material", "Cu", "--C11", "1"], "either --material or constants"),
    (["--C11", "168.4", "--C12", "121.4", "--C44", "75.4"], "missing --rho"),
    (["--material", "Pb", "--stress", "0.1", "--toec"], "Pb"),
    (["--material", "Cu", "--toec", "1", "2"], "six"),
])
def test_material_cli_refuses_ambiguous_or_missing_input(capsys, args, words):
    """Named material plus constants, no density for constants, a TOEC request for a crystal
    without third-order constants (named), a wrong count of --toec values: one clear line each."""
    assert main(["material", *args]) == 2
    err = capsys.readouterr().err
    assert words in err and len(err.strip().splitlines()) == 1


def test_piezo_cut_json_equals_library(capsys):
    """`--material LiNbO3 --cut 128Y-X --json` = surfwave.material("LiNbO3", cut="128Y-X") (free and
    metallized speeds, K2, power flow, the 4-component polarisation)."""
    assert main(["material", "--material", "LiNbO3", "--cut", "128Y-X", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.material("LiNbO3", cut="128Y-X")
    for key in ("c_R", "c_free", "c_metallized", "K2", "power_flow_angle"):
        assert out[key] == pytest.approx(ref[key], rel=1e-15, abs=1e-15), key
    assert out["euler"] == [0.0, 38.0, 0.0] and len(out["polarisation"]["re"]) == 4


def test_euler_sweep_table_with_a_negative_start(capsys):
    """`--euler 0 -90:90:45 0` (a sweep starting negative is a value, not an option) prints one row per
    angle whose v_free, v_met and K2 (%) equal the library's to the printed digits."""
    assert main(["material", "--material", "LiNbO3", "--euler", "0", "-90:90:45", "0"]) == 0
    lines = capsys.readouterr().out.strip().splitlines()
    assert lines[1].split()[:4] == ["theta", "v_free", "v_met", "K2"]
    rows = [line.split() for line in lines[2:]]
    theta = np.array([-90.0, -45.0, 0.0, 45.0, 90.0])
    ref = surfwave.material("LiNbO3", euler=np.column_stack([0 * theta, theta, 0 * theta]))
    assert [float(r[0]) for r in rows] == list(theta)
    np.testing.assert_allclose([float(r[1]) for r in rows], ref["c_free"], atol=0.006)
    np.testing.assert_allclose([float(r[2]) for r in rows], ref["c_metallized"], atol=0.006)
    np.testing.assert_allclose([float(r[3]) for r in rows], 100 * ref["K2"], atol=6e-5)


def test_list_cuts_and_bad_euler(capsys):
    """--list-cuts names every cut of the database; two swept Euler angles and --cut with --euler are
    refused with exit status 2 and a message naming the problem."""
    from surfwave.real_crystals.piezo_materials import available_cuts

    assert main(["material", "--list-cuts"]) == 0
    out = capsys.readouterr().out
    assert all(name in out for name in available_cuts())
    assert main(["material", "--material", "quartz", "--euler", "0:10:5", "0:10:5", "0"]) == 2
    assert "only one Euler angle" in capsys.readouterr().err
    assert main(["material", "--material", "quartz", "--cut", "ST-X", "--euler", "0", "0", "0"]) == 2
    assert "either --cut or --euler" in capsys.readouterr().err


def test_toec_file_equals_the_library_with_the_same_constants(tmp_path, capsys):
    """--toec-file (YAML, named constants, a source key allowed): Cu with the database's six gives
    the library's toec=True value; a quartz file with the wrong names, a missing file and text
    values are one-line errors (exit 2). Reference: surfwave.material with toec=True."""
    import yaml

    from surfwave.real_crystals.materials import get_material

    f = tmp_path / "cu.yaml"
    f.write_text(yaml.safe_dump({"source": "the database's Cu set", **get_material("Cu").toec}))
    assert main(["material", "--material", "Cu", "--direction", "[100]", "--stress", "0.1", "--toec-file", str(f),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.material("Cu", direction="[100]", stress=0.1, toec=True)
    assert out["c_R"] == pytest.approx(ref["c_R"], rel=1e-15)
    assert main(["material", "--material", "quartz", "--cut", "ST-X", "--stress", "0.1", "--toec-file", str(f)]) == 2
    assert "class-32 third-order constants: missing" in capsys.readouterr().err
    assert main(["material", "--material", "Cu", "--toec-file", str(tmp_path / "none.yaml")]) == 2
    assert "cannot read" in capsys.readouterr().err
    bad = tmp_path / "bad.yaml"
    bad.write_text("C111: minus twelve\n")
    assert main(["material", "--material", "Cu", "--toec-file", str(bad)]) == 2
    assert "not numbers" in capsys.readouterr().err
