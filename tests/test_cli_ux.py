"""Command line for a new user: python -m surfwave, --version, did-you-mean, potentials with
help, scenes, cache info/clear subcommands (--results, --json).

References: the library's registries (available_potentials, the default config's scenes)
and the cache module's own info() on the same directory.
"""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import surfwave
from surfwave.cli import main
from surfwave.data import cache
from surfwave.model_crystals.potentials import available_potentials


def test_python_dash_m_and_version():
    proc = subprocess.run([sys.executable, "-m", "surfwave", "--version"], capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout.strip() == f"surfwave {surfwave.__version__}"


@pytest.mark.parametrize("argv, hint", [
    (["potentails"], "'potentials'"),
    (["cache", "inf"], "'info'"),
    (["point", "--latice", "fcc"], "'--lattice'"),
    (["cache", "info", "--result", "x"], "'--results'"),
])
def test_did_you_mean(capsys, argv, hint):
    with pytest.raises(SystemExit) as exc:
        main(argv)
    assert exc.value.code == 2
    assert f"did you mean {hint}?" in capsys.readouterr().err


def test_potentials_lists_registry_with_help(capsys):
    assert main(["potentials"]) == 0
    out = capsys.readouterr().out
    assert [line.split()[0] for line in out.splitlines()] == available_potentials()
    with pytest.raises(SystemExit):
        main(["potentials", "--help"])
    assert "register" in capsys.readouterr().out


def test_cache_info_results_dir_and_json(tmp_path, capsys, monkeypatch):
    """From another directory: the cache read is named, and --results DIR finds the entries."""
    results = tmp_path / "res"
    cache.cached_points("demo", {"a": 1}, np.array([1.0, 2.0]), lambda d: {"y": d}, results / "cache")
    monkeypatch.chdir(tmp_path)
    assert main(["cache", "info"]) == 0
    text = capsys.readouterr().out
    assert str(tmp_path / "results" / "cache") in text and "no such directory" in text
    assert main(["cache", "info", "--results", str(results), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert info["entries"] == 2 == cache.info(results / "cache")["entries"]
    assert info["root"] == str((results / "cache").resolve()) and info["exists"] is True
    with pytest.raises(SystemExit):
        main(["cache", "clear", "--help"])
    assert "Delete every cache entry" in capsys.readouterr().out
    assert main(["cache", "clear", "--results", str(results)]) == 0
    assert cache.info(results / "cache")["entries"] == 0


def test_scenes_lists_configured_scenes(tmp_path, capsys):
    """Default scenes from config/config.yaml, plus a user's scene from --configfile."""
    mine = tmp_path / "my.yaml"
    mine.write_text("run: [mine]\nscenes:\n  mine: {lattice: fcc, loading: uniaxial, potentials: [morse],"
                    " d_over_d0: [1.0], quantities: [elastic]}\n")
    assert main(["scenes", "--configfile", str(mine), "--json"]) == 0
    rows = {r["scene"]: r for r in json.loads(capsys.readouterr().out)}
    assert {"table1", "fig2", "fig2_uniaxial", "triangular", "entropy", "mine"} <= set(rows)
    assert rows["table1"]["quantities"] == ["elastic", "rayleigh", "bulk"]
    from surfwave.model_crystals import phonons  # defaults filled in from the library
    assert rows["table1"]["accuracy"]["bulk"]["supercell"] == phonons.DEFAULT_SUPERCELL
    assert "entropy" not in rows["table1"]["accuracy"]
    assert rows["mine"]["built_by_all"] and not rows["table1"]["built_by_all"]
    assert rows["table1"]["paper"] and not rows["mine"]["paper"]
    # what the scene's figures job writes (pipeline.targets.scene_outputs): no Fig. 2 without
    # a rayleigh cube, but the summary of a user scene
    assert rows["table1"]["outputs"][:2] == ["speeds_vs_stress.png", "table1.md"]
    assert rows["mine"]["outputs"] == ["summary.md"]
    assert main(["scenes"]) == 0
    text = capsys.readouterr().out
    assert "table1" in text and "figures and tables: speeds_vs_stress.png, table1.md" in text
