"""``surfwave fit-film``: fit a film's parameters to measured dispersion points from a CSV file.

:mod:`surfwave.cli` registers the subcommand with :func:`add_parser` and runs it with :func:`run`;
the fit is :func:`surfwave.fit_film`.
"""
from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path
from typing import Any, Literal

import numpy as np

from surfwave.errors import InputError

__all__ = ["EPILOG", "add_parser", "parse_pairs", "read_points", "run"]

EPILOG = """\
The CSV file: a header row, then one measured point per row; '#' lines are comments. Columns:
kh (wavenumber x total film thickness) or frequency_Hz, then c_m_s (phase speed, m/s), and
optionally sigma_m_s (1-sigma uncertainty of c, m/s) and mode (the point's mode: Love mode
number, or a label or column of surfwave.layered; instead of --mode, to fit several modes).
Without sigma the uncertainties come from the scatter of the residuals (covariance scaled by
chi2/dof; --noise says whether the points are equally uncertain in relative terms, the
default, or in m/s).

Stack: --film and --substrate as KEY=VALUE lists. Love model (shear-horizontal guided wave, one
isotropic film on an isotropic substrate, closed form): mu (GPa) or E (GPa) and nu, rho
(kg/m^3), and the film's thickness (m; needed with frequency data). Layered model (any guided
mode, through surfwave.layered, sensitivities by implicit differentiation of its secular
equation): --substrate a material name or KEY=VALUE (E, nu, rho); --film E, nu, rho, thickness,
stress (GPa, equibiaxial) as KEY=VALUE, or a database film NAME:THICKNESS[:STRESS] as for
`surfwave layered` (its constants are the starting values); repeat --film from the top down and
pick the fitted one with --layer. Free parameters (--free): Love mu or E/nu, rho, thickness,
substrate_mu, substrate_rho; layered E, nu, rho, thickness, stress.

examples:
  surfwave fit-film --data points.csv --film mu=30,rho=2200,thickness=1e-6 --substrate mu=66.25,rho=2650 --free mu rho
  surfwave fit-film --data points.csv --film E=70,nu=0.17,rho=2200,thickness=1e-6 --substrate mu=66.25,rho=2650 \\
      --free E thickness --bounds E=40:120 --figure fit.png
  surfwave fit-film --model layered --data points.csv --substrate Si --film SiO2:1um --free E nu --mode R
"""

_UNITS = {"mu": "GPa", "E": "GPa", "substrate_mu": "GPa", "stress": "GPa", "nu": "1", "rho": "kg/m^3",
          "substrate_rho": "kg/m^3", "thickness": "m"}


def add_parser(sub: Any) -> argparse.ArgumentParser:
    """Add the ``fit-film`` subcommand to the subparsers ``sub`` of the ``surfwave`` command."""
    fp = sub.add_parser(
        "fit-film", help="fit a film's parameters (E, nu, rho, thickness, stress) to measured dispersion points",
        description="Least-squares fit of film parameters to measured surface-wave phase speeds (kh or "
        "frequency), with 1-sigma uncertainties, correlations and warnings when parameters are not separable.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter)
    fp.add_argument("--data", required=True, type=Path, metavar="CSV",
                    help="measured points: columns kh or frequency_Hz, c_m_s[, sigma_m_s]")
    fp.add_argument("--film", required=True, action="append", metavar="KEY=VALUE,...|NAME:THICKNESS[:STRESS]",
                    help="the film: starting values of the free parameters, values of the fixed ones (layered: "
                    "also a database film NAME:THICKNESS[:STRESS]; repeat from the top down)")
    fp.add_argument("--substrate", required=True, metavar="KEY=VALUE,...|NAME",
                    help="the substrate: KEY=VALUE list (mu or E, nu; rho), or a material name (layered model)")
    fp.add_argument("--free", required=True, nargs="+", metavar="NAME", help="the parameters to fit")
    fp.add_argument("--model", choices=["love", "layered"], default="love",
                    help="love: closed-form SH guided wave (default); layered: a mode of surfwave.layered")
    fp.add_argument("--mode", default="0",
                    help="the measured mode: Love mode number (0 = fundamental); layered: column or label")
    fp.add_argument("--layer", type=int, default=0, help="layered: which --film is fitted (0 = top)")
    fp.add_argument("--surface", default="(001)", help="layered: substrate surface (hkl) (default (001))")
    fp.add_argument("--direction", default="[100]", help="layered: propagation direction [uvw] or angle, degrees")
    fp.add_argument("--euler", nargs=3, type=float, metavar=("PHI", "THETA", "PSI"),
                    help="layered: SAW Euler angles of the substrate, degrees (instead of --surface/--direction)")
    fp.add_argument("--bounds", nargs="+", default=[], metavar="NAME=LOW:HIGH",
                    help="bounds of free parameters (default: physical limits)")
    fp.add_argument("--noise", choices=["relative", "absolute"], default="relative",
                    help="without sigma_m_s: points equally uncertain in relative terms (default) or in m/s")
    fp.add_argument("--figure", type=Path, metavar="PNG", help="also draw data, fit, residuals and the table")
    fp.add_argument("--json", action="store_true", help="print JSON instead of a table")
    return fp


def parse_pairs(text: str, what: str) -> dict[str, float]:
    """``"mu=31.2,rho=2200"`` -> {"mu": 31.2, "rho": 2200.0}; errors name ``what`` and the item."""
    out: dict[str, float] = {}
    for item in (t.strip() for t in text.split(",")):
        if not item:
            continue
        key, sep, value = item.partition("=")
        if not sep or not key.strip():
            raise InputError(f"{what}: expected KEY=VALUE, got {item!r}")
        try:
            out[key.strip()] = float(value)
        except ValueError:
            raise InputError(f"{what}: {key.strip()} must be a number, got {value!r}") from None
    if not out:
        raise InputError(f"{what}: give at least one KEY=VALUE")
    return out


def read_points(path: Path) -> tuple[Literal["kh", "frequency"], np.ndarray, np.ndarray, np.ndarray | None,
                                     list[int | str] | None]:
    """(variable, x, c, sigma, modes) from a CSV file of measured points (see :data:`EPILOG`)."""
    if not path.is_file():
        raise InputError(f"--data: no such file {str(path)!r}")
    with path.open(newline="") as fh:
        rows = [r for r in csv.reader(line for line in fh if line.strip() and not line.lstrip().startswith("#"))]
    if len(rows) < 2:
        raise InputError(f"--data {path}: needs a header row and at least one point")
    head = [h.strip() for h in rows[0]]
    xs = [h for h in ("kh", "frequency_Hz") if h in head]
    if len(xs) != 1 or "c_m_s" not in head:
        raise InputError(f"--data {path}: the header must hold exactly one of kh, frequency_Hz and c_m_s "
                         f"(optional sigma_m_s), got {head}")
    cols = {h: i for i, h in enumerate(head)}
    wanted = [xs[0], "c_m_s"] + (["sigma_m_s"] if "sigma_m_s" in cols else [])
    table = []
    for n, row in enumerate(rows[1:], start=2):
        try:
            table.append([float(row[cols[h]]) for h in wanted])
        except (ValueError, IndexError):
            raise InputError(f"--data {path}: row {n} is not numbers in columns {wanted}: {row}") from None
    a = np.array(table)
    variable: Literal["kh", "frequency"] = "kh" if xs[0] == "kh" else "frequency"
    modes = None
    if "mode" in cols:
        texts = [row[cols["mode"]].strip() if len(row) > cols["mode"] else "" for row in rows[1:]]
        if any(not t for t in texts):
            raise InputError(f"--data {path}: the mode column has empty entries")
        modes = [int(t) if t.lstrip("-").isdigit() else t for t in texts]
    return variable, a[:, 0], a[:, 1], (a[:, 2] if a.shape[1] == 3 else None), modes


def _film(text: str, layered: bool) -> dict[str, Any]:
    """One --film: KEY=VALUE,... or (layered model) a database film NAME:THICKNESS[:STRESS]."""
    if layered and "=" not in text:
        from surfwave.cli_layered import parse_film

        return parse_film(text)
    return dict(parse_pairs(text, "--film"))


def _bounds(items: list[str]) -> dict[str, tuple[float, float]]:
    out = {}
    for item in items:
        name, sep, rng = item.partition("=")
        lo, sep2, hi = rng.partition(":")
        try:
            if not (sep and sep2):
                raise ValueError
            out[name.strip()] = (float(lo), float(hi))
        except ValueError:
            raise InputError(f"--bounds: expected NAME=LOW:HIGH, got {item!r}") from None
    return out


def _fmt(v: float) -> str:
    return f"{v:.6g}" if math.isfinite(v) else ("inf" if v > 0 else "nan")


def run(args: argparse.Namespace) -> int:
    """Run ``surfwave fit-film``: read, fit, print (and draw)."""
    from surfwave.metrology.film import fit_film

    variable, x, c, sigma, modes = read_points(args.data)
    layered = args.model == "layered"
    films = [_film(text, layered) for text in args.film]
    if not layered and len(films) != 1:
        raise InputError(f"--model love takes one --film, got {len(films)}; use --model layered")
    layered_sub = layered and "=" not in args.substrate
    substrate: Any = args.substrate.strip() if layered_sub else parse_pairs(args.substrate, "--substrate")
    mode: Any = int(args.mode) if args.mode.lstrip("-").isdigit() else args.mode
    if modes is not None:
        mode = modes
    options: dict[str, Any] = {}
    if layered:
        direction: str | float = args.direction
        try:
            direction = float(args.direction)
        except ValueError:
            pass
        options = {"surface": args.surface, "direction": direction, "euler": args.euler}
    r = fit_film(x, c, model=args.model, film=films if layered else films[0], substrate=substrate, free=args.free,
                 sigma=sigma, variable=variable, mode=mode, layer=args.layer, bounds=_bounds(args.bounds),
                 noise=args.noise, layered_options=options)
    if args.figure is not None:
        from surfwave.plots.fit import plot_fit

        plot_fit(r, args.figure)
    if args.json:
        out = {"model": r["model"], "x_name": r["x_name"], "n_points": int(r["x"].size), "names": r["names"],
               "values": r["values"], "uncertainties": {k: (v if math.isfinite(v) else None)
                                                        for k, v in r["uncertainties"].items()},
               "uncertainty_basis": r["uncertainty_basis"],
               "correlation": [[(float(v) if math.isfinite(v) else None) for v in row] for row in r["correlation"]],
               "noise": r["noise"], "chi2": r["chi2"], "dof": r["dof"], "reduced_chi2": r["reduced_chi2"],
               "p_value": r["p_value"] if math.isfinite(r["p_value"]) else None,
               "residuals_m_s": r["residuals"].tolist(), "warnings": r["warnings"], "success": r["success"]}
        print(json.dumps(out, indent=2))
        return 0
    basis = ("from the given sigma" if r["uncertainty_basis"] == "sigma"
             else f"from the scatter (covariance x chi2/dof, {r['noise']} noise)")
    print(f"# {r['model']}; {r['x'].size} points, {r['x_name']} {r['x'].min():.4g} ... {r['x'].max():.4g}")
    print(f"# 1-sigma uncertainties {basis}")
    print(f"{'parameter':>14} {'value':>14} {'1-sigma':>12} {'relative':>10}  unit")
    for k in r["names"]:
        v, s = r["values"][k], r["uncertainties"][k]
        rel = f"{100 * s / abs(v):9.3g}%" if v and math.isfinite(s) else f"{'-':>10}"
        print(f"{k:>14} {_fmt(v):>14} {_fmt(s):>12} {rel}  {_UNITS.get(k, 'GPa' if k.startswith('C') else '')}")
    fixed = {k: v for k, v in r["values"].items() if k not in r["names"]}
    if fixed:
        print("fixed: " + ", ".join(f"{k} = {_fmt(v)} {_UNITS.get(k, '')}".rstrip() for k, v in fixed.items()))
    if len(r["names"]) > 1:
        print("correlation:")
        print(" " * 15 + "".join(f"{k:>14}" for k in r["names"]))
        for k, row in zip(r["names"], r["correlation"]):
            print(f"{k:>15}" + "".join(f"{v:14.4f}" if math.isfinite(v) else f"{'nan':>14}" for v in row))
    rms = float(np.sqrt(np.mean(r["residuals"] ** 2)))
    if r["noise"] == "sigma":
        print(f"chi2 = {r['chi2']:.4g}, dof = {r['dof']}, chi2/dof = {r['reduced_chi2']:.4g}"
              + (f", p = {r['p_value']:.3g}" if math.isfinite(r["p_value"]) else "") + f"; rms residual {rms:.4g} m/s")
    else:
        s = math.sqrt(r["reduced_chi2"])
        est = f"{100 * s:.3g} % of c" if r["noise"] == "relative" else f"{s:.3g} m/s"
        print(f"noise estimated from the scatter: {est} (dof = {r['dof']}); rms residual {rms:.4g} m/s")
    if not r["success"]:
        print(f"solver: {r['message']}")
    for w in r["warnings"]:
        print(f"warning: {w}")
    if args.figure is not None:
        print(f"figure: {args.figure}")
    return 0
