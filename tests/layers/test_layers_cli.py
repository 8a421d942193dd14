"""The ``surfwave layered`` command: the table holds the API's numbers; bad input is one error line."""
from __future__ import annotations

import json

import numpy as np
import pytest

import surfwave
from surfwave.cli import main
from surfwave.cli_layered import parse_film, parse_frequency, parse_kh


def test_table_matches_the_api(capsys):
    """The CLI table prints surfwave.layered's speeds (to the printed 3 decimals) for each label."""
    assert main(["layered", "--substrate", "Si", "--film", "SiO2:1um", "--kh", "0:2:1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].split() == ["kh", "c_R", "c_L0", "c_S1"]
    r = surfwave.layered("Si", [{"name": "SiO2", "thickness": 1e-6}], kh=[0.0, 1.0, 2.0])
    row = out[4].split()
    assert float(row[0]) == 2.0
    assert [float(v) for v in row[1:]] == pytest.approx(list(r["c"][2]), abs=6e-4)


def test_header_names_each_family_limit(capsys):
    """Si (001)[100] decouples: the header gives the sagittal and SH limits, the record's mode_limit values
    (material()'s c_limit 5648.503 and sqrt(C44/rho) 5844.920 m/s); gold on fused silica (isotropic) one c_limit."""
    assert main(["layered", "--substrate", "Si", "--film", "SiO2:1um", "--kh", "1:3:1"]) == 0
    head = capsys.readouterr().out.splitlines()[0]
    assert head.startswith("# limits 5648.503 m/s (R, S modes), 5844.920 m/s (L modes)")
    assert main(["layered", "--substrate", "fused-SiO2", "--film", "Au-poly:100nm", "--kh", "1"]) == 0
    c_lim = surfwave.layered("fused-SiO2", [{"name": "Au-poly", "thickness": 1e-7}], kh=[1.0])["c_limit"]
    assert capsys.readouterr().out.startswith(f"# c_limit = {c_lim:.3f} m/s; ")


def test_json_and_frequency(capsys):
    """--json gives the record; --frequency gives each mode its own kh (kh c = 2 pi f H)."""
    assert main(["layered", "--substrate", "Si", "--film", "SiO2:500nm", "--frequency", "1e9", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    c, kh = np.array(r["c"][0], dtype=float), np.array(r["kh"][0], dtype=float)
    assert c * kh / (2 * np.pi * 5e-7) == pytest.approx(1e9, rel=1e-9)


@pytest.mark.parametrize(("argv", "words"), [
    (["--film", "SiO2:1", "--kh", "1"], "needs a unit"),
    (["--film", "SiO2:-1um", "--kh", "1"], ">= 0"),
    (["--film", "SiO2:1um", "--kh", "3:1:0.5"], "STOP >= START"),
    (["--film", "unobtainium:1um", "--kh", "1"], "unknown material"),
    (["--film", "SiO2:1um", "--frequency", "1THz"], "units: Hz, kHz, MHz, GHz"),
    (["--film", "SiO2:1um", "--frequency", "2GHz:1GHz:1MHz"], "STOP >= START"),
    (["--film", "SiO2:1um", "--kh", "1MHz"], "--kh must be numbers"),
])
def test_errors_are_one_line(capsys, argv, words):
    """Bad input: exit code 2 and one line on stderr naming the problem."""
    assert main(["layered", "--substrate", "Si", *argv]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and "\n" not in err


def test_parsers():
    """Film and kh parsing: units and the inclusive sweep."""
    assert parse_film("Au-poly:50nm:-0.5") == {"name": "Au-poly", "thickness": pytest.approx(5e-8), "stress": -0.5}
    assert parse_kh(["0:5:0.05"]).size == 101


def test_frequency_units_and_sweep():
    """--frequency words: plain Hz, a unit on each number, and an inclusive sweep whose ends carry units
    (reference: the values written out by hand)."""
    assert parse_frequency(["1e8", "0.5GHz", "250 MHz", "3kHz", "7Hz"]).tolist() == pytest.approx([1e8, 5e8, 2.5e8, 3e3, 7.0])
    sweep = parse_frequency(["100MHz:1GHz:300MHz"])
    assert sweep.tolist() == pytest.approx([1e8, 4e8, 7e8, 1e9])
    assert parse_frequency(["1e8:1e9:3e8"]).tolist() == pytest.approx(sweep.tolist())


def test_frequency_sweep_matches_the_api(capsys):
    """A --frequency sweep with units prints the rows of surfwave.layered at those frequencies."""
    assert main(["layered", "--substrate", "Si", "--film", "SiO2:1um", "--frequency", "0.2GHz:0.6GHz:0.2GHz",
                 "--modes", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.layered("Si", [{"name": "SiO2", "thickness": 1e-6}], frequency=[2e8, 4e8, 6e8], modes=1)
    assert np.array(out["c"], dtype=float) == pytest.approx(ref["c"], rel=1e-12)
