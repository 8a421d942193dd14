"""The command line shows the leaky wave's pair and coupling, the bulk waves and the grazing and
constants notes (values against surfwave.material, the library route they come from)."""
from __future__ import annotations

import json
import warnings

import pytest

import surfwave
from surfwave.cli import main
from surfwave.errors import ConstantsNote


def test_piezo_json_and_list_carry_the_leaky_pair(capsys):
    """JSON: c_leaky_free, c_leaky_metallized, K2_leaky and the bulk polarisations (lists) as
    the library gives them; the printed list shows K2_leaky in percent."""
    assert main(["material", "--cut", "64Y-X", "--json"]) == 0
    row = json.loads(capsys.readouterr().out)
    lib = surfwave.material(cut="64Y-X")
    for key in ("c_leaky_free", "c_leaky_metallized", "K2_leaky", "c_T_par", "c_SH_perp"):
        assert row[key] == pytest.approx(lib[key], rel=1e-12), key
    assert row["polarisation_L_par"] == pytest.approx(list(lib["polarisation_L_par"]), abs=1e-12)
    assert main(["material", "--cut", "64Y-X"]) == 0
    out = capsys.readouterr().out
    assert f"{100 * lib['K2_leaky']:.4f} %" in out and "c_leaky_metallized" in out


def test_piezo_table_has_k2_leaky_and_marks_grazing_waves(capsys):
    """Rotated Y LiTaO3 around 128 degrees (Euler theta 36..40): a K2_leaky column, the grazing
    rows (theta 37-39, deeper than 50 wavelengths) starred with the note below the table, and
    the one-line note of the unverified constant set on stderr."""
    assert main(["material", "--material", "LiTaO3", "--euler", "0", "36:40:1", "0"]) == 0
    cap = capsys.readouterr()
    lines = cap.out.strip().splitlines()
    assert "K2_leaky(%)" in lines[1]
    starred = [float(line.split()[0]) for line in lines[2:] if line.rstrip().endswith("*")]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ConstantsNote)
        lib = surfwave.material("LiTaO3", euler=[[0, t, 0] for t in range(36, 41)], leaky=False)
    assert starred == [36.0 + i for i in range(5) if lib["grazing"][i]] and starred
    assert lines[-1].startswith("* grazing")
    notes = [line for line in cap.err.splitlines() if line.startswith("note: constant set LiTaO3-Kovacs1990")]
    assert len(notes) == 1, cap.err
