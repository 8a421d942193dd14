"""The benchmark table of the README: one row per method and knob, in words.

``benchmarks/bench_*.py`` write one cube per method under ``results/benchmarks/<name>/``.
:func:`benchmark_table` turns them into ``results/benchmarks/README_table.md`` with the
columns method, knob, default, error at the default, time at the default, and why that
default. The five benchmarks of the repository have a reader each (:data:`READERS`, keyed
by file name); any other cube following the convention below gets a generic row.

Convention of a generic benchmark cube: global attributes ``method``, ``knob`` (the
swept dimension), ``default`` (the chosen knob value) and ``default_reason``; data
variables ``error`` (with ``units``) and ``time`` (seconds) along the knob dimension. A
cube may instead list its rows itself in the attribute ``readme_rows`` (JSON list of
[method, knob, default, error, time, why]).
"""
from __future__ import annotations

import json
from pathlib import Path
from typing import Callable, Iterable, SupportsFloat

import numpy as np
import xarray as xr

from surfwave.data.cube import open_cube
from surfwave.errors import InputError

HEAD = ["Method", "Knob", "Default", "Error at the default", "Time at the default", "Why this default"]


def _g(x: SupportsFloat) -> str:
    """A number for a reader: 3 significant digits, no trailing zeros."""
    x = float(x)
    if not np.isfinite(x):
        return "n/a"
    return f"{x:.2g}" if abs(x) < 1e-3 or abs(x) >= 1e4 else f"{x:.3g}"


def _ms(seconds: SupportsFloat) -> str:
    s = float(seconds)
    return f"{s * 1e3:.3g} ms" if s < 1 else f"{s:.3g} s"


def _rayleigh(ds: xr.Dataset) -> list[list[str]]:
    rate = ds["points_per_second"]
    default = int(ds.attrs["default"])
    r = float(rate.sel(batch=default))
    return [["Rayleigh speed, Eq. (17) closed-form cubic with root selection (`rayleigh_c2`)",
             "points per vectorised call (batch)", f"{default:,} points",
             f"{_g(float(ds['error'].max()))} K d0^2/m from the closed form Eq. (20) (at every batch size)",
             f"{r / 1e6:.2g} million points/s on one core (best {float(rate.max()) / 1e6:.2g} million)",
             "the smallest batch within 10 % of the best throughput; larger ones only cost memory"]]


def _phonons(ds: xr.Dataset) -> list[list[str]]:
    a = ds.attrs
    sc, amp = int(a["default_supercell"]), float(a["default_displacement"])
    at = ds.sel(supercell=sc, displacement=amp, method="nearest")
    mesh = int(a["default_zone_mesh"])
    rows = [
        ["phonopy bulk sound speeds (finite displacements, force constants from the pair forces)",
         "supercell N x N x N", f"N = {sc}",
         f"{_g(at['max_rel_dev'])} relative to Eq. (A11); larger N change nothing",
         f"{_ms(at['time_per_point'])} per strain point (N = 3: "
         f"{_ms(ds['time_per_point'].sel(supercell=3, displacement=amp, method='nearest'))})"
         if 3 in ds["supercell"].values else f"{_ms(at['time_per_point'])} per strain point",
         "the smallest supercell in which nearest-neighbour images are unambiguous is already exact "
         "for nearest-neighbour forces"],
        ["phonopy bulk sound speeds", "displacement amplitude", f"{amp:g} d0",
         f"{_g(at['max_rel_dev'])} relative (the error grows as amplitude^2)",
         "independent of the amplitude",
         "the error falls as amplitude^2 until roundoff (~1e-16/amplitude) takes over"],
    ]
    if "mesh_time_per_point" in ds and mesh in ds["zone_mesh"].values:
        low = ds["mesh_min_omega2"]
        finest = int(ds["zone_mesh"].values.max())
        same = bool(np.isclose(float(low.sel(zone_mesh=mesh)), float(low.sel(zone_mesh=finest)), rtol=1e-6))
        rows.append(["full-zone stability scan (phonopy dynamical matrix on a mesh)", "zone mesh per axis",
                     f"{mesh}", f"lowest omega^2 {_g(low.sel(zone_mesh=mesh))} K/m on the probe point "
                     f"({'the same' if same else 'differs from'} {_g(low.sel(zone_mesh=finest))} at mesh {finest})",
                     f"{_ms(ds['mesh_time_per_point'].sel(zone_mesh=mesh))} per strain point",
                     "cost grows as mesh^3" + ("; the finest mesh tried finds the same lowest mode" if same
                                               else "; a finer mesh finds a lower mode: consider raising it")])
    if "lw_max_rel_dev" in ds:
        lw = str(a.get("default_long_wave", "curvature"))
        rows.append(["long-wave speeds from the phonopy force constants", "method (curvature or secant)", lw,
                     f"{_g(ds['lw_max_rel_dev'].sel(long_wave_method=lw))} relative",
                     f"{_ms(ds['lw_time_per_point'].sel(long_wave_method=lw))} per strain point",
                     "the curvature at Gamma has no roundoff floor; the secant does"])
    return rows


def _dispersion(ds: xr.Dataset) -> list[list[str]]:
    tol = 1e-10
    sel = ds.sel(tol=tol, method="nearest")
    n = int(ds.attrs.get("n_analytic", 1000))
    above = bool((sel["error_estimate_tol"] >= sel["error_tol"]).all())
    worst = ds["error_tol"].max("potential")
    floor = float(worst.min())
    knee = float(ds["tol"].values[np.flatnonzero(worst.values <= 1.01 * floor)].max())
    return [
        ["triangular-lattice surface mode, numerical (semi-infinite Green's function by decimation)",
         "decimation tolerance tol", f"{tol:g}",
         f"{_g(sel['error_tol'].max())} relative to Eq. (15) (its own estimate "
         f"{_g(sel['error_estimate_tol'].max())}, {'above' if above else 'NOT always above'} the true error)",
         f"{_ms(ds['time_default'].max())} for 8 strains x 40 theta",
         f"the error stops improving at {_g(floor)} from tol = {_g(knee)} on; the default keeps a margin"],
        ["triangular-lattice dispersion, analytic (Eqs. 3a-15)", "none", "-",
         f"sine law holds to {_g(ds['sine_law_max_deviation'].max())}",
         f"{_ms(ds['time_analytic'])} for a {n} x {n} (strain, theta) grid", "closed form"],
    ]


def _entropy(ds: xr.Dataset) -> list[list[str]]:
    i = int(np.argmin(np.abs(np.log10(ds["tol"].values) + 8)))
    err = ds["tol_error_exact"].isel(tol=i)
    rep = ds["tol_reported_error_exact"].isel(tol=i) if "tol_reported_error_exact" in ds else None
    return [["surface entropy: cyclic reduction + Widom term, Gauss-Legendre in theta",
             "quadrature tolerance tol", f"{float(ds['tol'].values[i]):g} k_B",
             f"{_g(err.max())} k_B true" + (f" ({_g(rep.max())} k_B estimated)" if rep is not None else ""),
             f"{_ms(ds['tol_time'].isel(tol=i).max())} per strain point (worst case)",
             "the loosest tolerance whose true error meets the 1e-8 k_B target"
             + ("" if float(ds["tol_time"].isel(tol=i).max()) <= 0.5 else " (slower than the 0.5 s target here)")]]


def _workflow(ds: xr.Dataset) -> list[list[str]]:
    t = {str(k): float(v) for k, v in zip(ds["run"].values, ds["time"].values)}
    full = next((v for k, v in t.items() if k.startswith("full")), np.nan)
    noop = next((v for k, v in t.items() if k.startswith("no-op")), np.nan)
    ok = "prints 'Nothing to be done'" if int(ds.attrs.get("nothing_to_be_done", 0)) else "reran jobs (see log)"
    return [["full reproduction, `snakemake -j2` from an empty `results/`", "none", "-", "-",
             f"{full:.3g} s on the 2 cores", "one measurement in this run; the machine is shared"],
            ["no-op rerun", "none", "-", "-", f"{noop:.3g} s", f"the rerun {ok}"]]


#: File name -> reader of the repository's benchmark cubes.
READERS: dict[str, Callable[[xr.Dataset], list[list[str]]]] = {
    "rayleigh_throughput.nc": _rayleigh,
    "bench_phonons.nc": _phonons,
    "bench_dispersion.nc": _dispersion,
    "entropy_convergence.nc": _entropy,
    "workflow_timing.nc": _workflow,
}


def _generic(ds: xr.Dataset, name: str) -> list[list[str]]:
    a = ds.attrs
    method = str(a.get("method") or a.get("title") or name)
    knob = str(a.get("knob", ""))
    if "error" in ds and "time" in ds and knob in ds["error"].dims:
        values = ds[knob].values
        default = a.get("default", values[0])
        try:
            i = int(np.argmin(np.abs(np.asarray(values, float) - float(default))))
        except (TypeError, ValueError):
            i = 0
        err = ds["error"].isel({knob: i}).max()
        return [[method, knob, f"{default}", f"{_g(err)} {ds['error'].attrs.get('units', '')}".strip(),
                 _ms(ds["time"].isel({knob: i}).max()), str(a.get("default_reason", ""))]]
    return [[method, "", "", "", "", f"see `{name}` (not in the benchmark convention)"]]


def benchmark_rows(path: str | Path) -> list[list[str]]:
    """Table rows [method, knob, default, error, time, why] of one benchmark cube.

    Raises
    ------
    InputError
        A row of the cube's ``readme_rows`` without exactly one cell per column of :data:`HEAD`.
    """
    path = Path(path)
    ds = open_cube(path)
    if "readme_rows" in ds.attrs:
        rows = [[str(c) for c in row] for row in json.loads(ds.attrs["readme_rows"])]
        for i, row in enumerate(rows):
            if len(row) != len(HEAD):  # a cell short would shift every later one into the wrong column
                first = (row or [""])[0][:60]
                raise InputError(f"{path}: readme_rows[{i}] ({first!r}) has {len(row)} cells, the table has "
                                 f"{len(HEAD)}: {', '.join(HEAD)}")
        return rows
    reader = READERS.get(path.name)
    if reader is not None:
        try:
            return reader(ds)
        except (KeyError, ValueError, IndexError):  # an older cube layout: fall back
            pass
    return _generic(ds, path.name)


def benchmark_table(dirs: Iterable[str | Path], out_md: str | Path) -> str:
    """Write the README's benchmark table from every ``*.nc`` in ``dirs``; returns the text."""
    lines = ["| " + " | ".join(HEAD) + " |", "|" + "---|" * len(HEAD)]
    pngs = []
    for d in map(Path, dirs):
        files = sorted(d.glob("*.nc")) if d.is_dir() else []
        if not files:
            lines.append(f"| {d.name} | | | | | not computed |")
        for f in files:
            lines += ["| " + " | ".join(c.replace("|", "/") for c in row) + " |" for row in benchmark_rows(f)]
        pngs += sorted(d.glob("*.png")) if d.is_dir() else []
    text = "\n".join(lines) + "\n"
    if pngs:
        text += "\nPlots: " + ", ".join(f"`{p}`" for p in pngs) + "\n"
    Path(out_md).write_text(text)
    return text
