"""`surfwave fit-film`: a CSV of measured points in, the parameter table out.

Reference: synthetic points from the closed-form Love wave (surfwave.metrology.love) at known
parameters; the fitted values must come back within their printed uncertainties' reach.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

from surfwave.cli import main
from surfwave.metrology.love import love_speed

P = {"mu": 31.2, "rho": 2200.0, "thickness": 1.0e-6, "substrate_mu": 66.25, "substrate_rho": 2650.0}


def _csv(tmp_path, variable="kh", sigma=False, noise=1e-3, n=20):
    x = np.linspace(0.2, 5.0, n) if variable == "kh" else np.linspace(5e7, 2.5e9, n)
    c = love_speed(x, P, variable="kh" if variable == "kh" else "frequency")
    c = c * (1 + noise * np.random.default_rng(2).standard_normal(n))
    head = ("kh" if variable == "kh" else "frequency_Hz") + ",c_m_s" + (",sigma_m_s" if sigma else "")
    lines = ["# synthetic points", head] + [f"{a:.8g},{b:.6f}" + (f",{noise * b:.4f}" if sigma else "")
                                              for a, b in zip(x, c)]
    path = tmp_path / "points.csv"
    path.write_text("\n".join(lines) + "\n")
    return path


def test_table_and_json(tmp_path, capsys):
    data = _csv(tmp_path, "frequency", sigma=True)
    args = ["fit-film", "--data", str(data), "--film", "mu=28,rho=2200,thickness=1.1e-6",
            "--substrate", "mu=66.25,rho=2650", "--free", "mu", "thickness"]
    assert main(args) == 0
    out = capsys.readouterr().out
    assert "1-sigma uncertainties from the given sigma" in out and "correlation:" in out and "chi2 =" in out
    row = next(line.split() for line in out.splitlines() if line.split()[:1] == ["mu"])
    assert abs(float(row[1]) - 31.2) < 3 * float(row[2])
    assert main(args + ["--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["names"] == ["mu", "thickness"] and r["noise"] == "sigma" and len(r["correlation"]) == 2
    assert abs(r["values"]["thickness"] - 1e-6) < 3 * r["uncertainties"]["thickness"]


def test_figure_and_scatter_basis(tmp_path, capsys):
    data = _csv(tmp_path, "kh")
    png = tmp_path / "fit.png"
    assert main(["fit-film", "--data", str(data), "--film", "mu=28,rho=2000", "--substrate", "mu=66.25,rho=2650",
                 "--free", "mu", "rho", "--bounds", "rho=1000:4000", "--figure", str(png)]) == 0
    out = capsys.readouterr().out
    assert "noise estimated from the scatter" in out and "% of c" in out and "warning: mu and rho" in out
    assert png.stat().st_size > 10_000


@pytest.mark.parametrize("change, text", [
    ({"--data": "missing.csv"}, "no such file"),
    ({"--film": "mu=abc"}, "must be a number"),
    ({"--film": "mu"}, "KEY=VALUE"),
    ({"--bounds": "mu=1"}, "NAME=LOW:HIGH"),
    ({"--free": "C11"}, "not in the Love model"),
])
def test_bad_input_is_one_line(tmp_path, capsys, change, text):
    data = _csv(tmp_path)
    opts = {"--data": str(data), "--film": "mu=28,rho=2200", "--substrate": "mu=66.25,rho=2650", "--free": "mu"}
    opts.update({k: (str(tmp_path / v) if k == "--data" else v) for k, v in change.items()})
    argv = ["fit-film"] + [t for k, v in opts.items() for t in (k, v)]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert text in err and err.count("\n") == 1


def test_bad_csv(tmp_path, capsys):
    bad = tmp_path / "bad.csv"
    bad.write_text("wavelength,c_m_s\n1,2\n")
    assert main(["fit-film", "--data", str(bad), "--film", "mu=28,rho=2200", "--substrate", "mu=66,rho=2650",
                 "--free", "mu"]) == 2
    assert "kh, frequency_Hz" in capsys.readouterr().err
    bad.write_text("kh,c_m_s\n1,abc\n")
    assert main(["fit-film", "--data", str(bad), "--film", "mu=28,rho=2200", "--substrate", "mu=66,rho=2650",
                 "--free", "mu"]) == 2
    assert "row 2" in capsys.readouterr().err


def test_layered_model_through_the_cli(tmp_path, capsys, monkeypatch):
    """--model layered with a substrate by name reaches surfwave.layered (a closed-form stand-in here: the
    Love mode of the film on an isotropic substrate named "iso"), mode by label."""
    import surfwave

    seen = []

    def layered(substrate, films, *, kh=None, frequency=None, **options):
        seen.append(substrate)
        f = films[0]
        p = {"E": f["E"], "nu": f["nu"], "rho": f["rho"], "substrate_mu": 66.25, "substrate_rho": 2650.0}
        c = love_speed(kh, p)
        return {"c": c[:, None], "mode": np.full((c.size, 1), "L0", dtype=object)}

    monkeypatch.setattr(surfwave, "layered", layered, raising=False)
    kh = np.linspace(0.3, 5, 15)
    c = love_speed(kh, {"E": 73.0, "nu": 0.17, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0})
    data = tmp_path / "p.csv"
    data.write_text("kh,c_m_s,sigma_m_s\n" + "".join(f"{a},{b},1.0\n" for a, b in zip(kh, c)))
    assert main(["fit-film", "--data", str(data), "--model", "layered", "--substrate", "iso", "--film",
                 "E=65,nu=0.17,rho=2200,thickness=1e-6", "--free", "E", "--mode", "L0", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert seen[0] == "iso" and abs(r["values"]["E"] - 73.0) < 1e-6


def test_layered_database_film_through_the_cli(tmp_path, capsys):
    """--model layered --film SiO2:1um (a database film, as `surfwave layered` takes it) recovers E and nu of
    fused silica on Si from exact Rayleigh speeds that surfwave.layered computed (to 1e-4), with the
    sensitivities by implicit differentiation; a bad second film, or two films for the Love model, is one error
    line."""
    import surfwave

    kh = np.linspace(0.5, 5.0, 6)
    c = surfwave.layered("Si", [{"name": "SiO2", "thickness": 1e-6}], kh=kh)["c"][:, 0]
    data = tmp_path / "points.csv"
    data.write_text("kh,c_m_s\n" + "".join(f"{float(k)!r},{float(v)!r}\n" for k, v in zip(kh, c)))
    assert main(["fit-film", "--model", "layered", "--substrate", "Si", "--film", "SiO2:1um", "--data", str(data),
                 "--free", "E", "nu", "--mode", "R", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert r["values"]["E"] == pytest.approx(73.0, rel=1e-4) and r["values"]["nu"] == pytest.approx(0.17, rel=1e-4)
    assert r["success"]
    assert main(["fit-film", "--model", "layered", "--substrate", "Si", "--film", "SiO2:1um", "--film", "SiO2:1",
                 "--data", str(data), "--free", "E"]) == 2
    assert "needs a unit" in capsys.readouterr().err
    assert main(["fit-film", "--model", "love", "--substrate", "mu=66,rho=2650", "--film", "mu=28,rho=2200",
                 "--film", "mu=28,rho=2200", "--data", str(data), "--free", "mu"]) == 2
    assert "takes one --film" in capsys.readouterr().err


def test_mode_column(tmp_path, capsys):
    """A mode column fits points of Love modes 0 and 1 together."""
    kh0, kh1 = np.linspace(0.3, 8, 12), np.linspace(4.0, 8, 8)
    p = {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0}
    rows = [f"{a},{b},0" for a, b in zip(kh0, love_speed(kh0, p))] + [f"{a},{b},1" for a, b in zip(kh1, love_speed(kh1, p, mode=1))]
    data = tmp_path / "two.csv"
    data.write_text("kh,c_m_s,mode\n" + "\n".join(rows) + "\n")
    assert main(["fit-film", "--data", str(data), "--film", "mu=28,rho=2200", "--substrate", "mu=66.25,rho=2650",
                 "--free", "mu", "--json"]) == 0
    r = json.loads(capsys.readouterr().out)
    assert abs(r["values"]["mu"] - 31.2) < 1e-6 and r["model"].startswith("Love modes 0, 1")
