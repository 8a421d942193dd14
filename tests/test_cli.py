"""Command line: help texts, JSON output equal to the library, clean errors."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

import surfwave
from surfwave.cli import main


def test_point_json_matches_library(capsys):
    assert main(["point", "--lattice", "fcc", "--loading", "in_plane_hydrostatic", "--potential", "lj",
                 "--direction", "[110]", "--d-over-d0", "1.02", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    ref = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.02)
    assert out["c2_R"] == pytest.approx(ref["c2_R"][0], rel=1e-15)
    assert round(out["c2_R"], 4) == 0.3043  # Table I
    assert out["wave_type"] == "supersonic_decoupled"


def test_point_table_several_strains(capsys):
    assert main(["point", "--lattice", "triangular", "--loading", "uniaxial", "--potential", "harmonic",
                 "--direction", "[10]", "--d-over-d0", "0.7", "1.0"]) == 0
    out = capsys.readouterr().out
    assert "0.3170" in out  # Eq. (16) at zero stress: (3 - sqrt 3)/4
    assert "note:" in out   # d/d0 = 0.7 has no surface wave; the reason is printed


def test_material_json(capsys):
    """2:1:1 cubic constants (GPa) with rho = 1e9 kg/m^3 -> rho c_R^2/C44 = (3 - sqrt 3)/2 along [100]."""
    assert main(["material", "--C11", "2", "--C12", "1", "--C44", "1", "--rho", "1e9",
                 "--direction", "[100]", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["c_R"] ** 2 == pytest.approx((3 - np.sqrt(3)) / 2)


def test_bad_input_is_a_one_line_error(capsys):
    assert main(["point", "--lattice", "fcc", "--loading", "in_plane_hydrostatic", "--potential", "lj",
                 "--direction", "[100]", "--d-over-d0", "1.5"]) == 2
    err = capsys.readouterr().err
    assert "d/d0 = 1.5" in err and "Traceback" not in err
    assert main(["point", "--lattice", "fcc", "--loading", "uniaxial", "--potential", "nope",
                 "--direction", "[100]", "--d-over-d0", "1"]) == 2
    assert "unknown potential 'nope'" in capsys.readouterr().err
    assert main(["material", "--C11", "2", "--C12", "1", "--C44", "1", "--rho", "-5",
                 "--direction", "[100]"]) == 2


@pytest.mark.parametrize("cmd", [[], ["point"], ["material"], ["cache"]])
def test_help_is_helpful(cmd):
    r = subprocess.run([sys.executable, "-m", "surfwave.cli", *cmd, "--help"], capture_output=True, text=True)
    assert r.returncode == 0
    assert "usage: surfwave" in r.stdout
    if cmd == ["point"]:
        assert "Reduced units" in r.stdout and "examples:" in r.stdout


def test_cache_info_and_clear(tmp_path, capsys):
    """`surfwave cache info|clear` on a cache with two entries written through the cache API."""
    from surfwave.data import cache

    cache.cached_points("demo", {"what": "cli-test"}, np.array([1.0, 1.1]),
                        lambda d: {"x": 2 * d}, tmp_path)
    assert main(["cache", "info", "--root", str(tmp_path)]) == 0
    out = capsys.readouterr().out
    assert "entries: 2" in out and "bytes" in out
    assert main(["cache", "clear", "--root", str(tmp_path)]) == 0
    assert "removed 2" in capsys.readouterr().out
    assert main(["cache", "info", "--root", str(tmp_path)]) == 0
    assert "entries: 0" in capsys.readouterr().out


def test_cache_clear_refuses_results_and_user_data(tmp_path, capsys):
    """`surfwave cache clear --root results` once deleted every cube and figure and said
    "removed 0 cache entries"; now: exit 2, a message naming foreign files, nothing deleted.
    `cache info` on such a directory says it is not a surfwave cache."""
    from surfwave.data import cache

    results = tmp_path / "results"
    cache.cached_points("demo", {"what": "cli-test"}, np.array([1.0]), lambda d: {"x": d},
                        results / "cache")
    cube = results / "table1" / "bulk.nc"
    cube.parent.mkdir()
    cube.write_bytes(b"CDF")
    tex = tmp_path / "mydata" / "paper" / "main.tex"
    tex.parent.mkdir(parents=True)
    tex.write_text("x")
    for root in (results, tmp_path / "mydata"):
        assert main(["cache", "clear", "--root", str(root)]) == 2
        err = capsys.readouterr().err
        assert "not a surfwave cache" in err and "removed" not in err
        assert main(["cache", "info", "--root", str(root)]) == 2
        assert "not a surfwave cache" in capsys.readouterr().err
    assert cube.exists() and tex.exists()
    assert main(["cache", "clear", "--results", str(results)]) == 0
    assert "removed 1 cache entries" in capsys.readouterr().out
    assert cube.exists()
