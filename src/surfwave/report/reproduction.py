"""Reproduction report: the paper's printed numbers and claims beside ours.

Everything here is computed from the result cubes (``results/<scene>/<cube>.nc``) and the
paper's printed values in ``surfwave/data/paper_values.yaml`` (the only hand-typed numbers,
each with its source and tolerance). A cube that is missing makes its lines read
"not computed"; nothing here raises on missing data.

Verdicts: ``PASS``, ``FAIL``, ``INCONCLUSIVE`` (the cube exists but its grid does not reach
what the claim needs) and ``not computed``.

Examples
--------
>>> from surfwave.report.reproduction import write_report
>>> write_report(["results/table1/elastic.nc", "results/table1/rayleigh.nc"],
...              "results/report.md")  # doctest: +SKIP
"""
from __future__ import annotations

import argparse
import csv
import json
import math
from pathlib import Path
from typing import Iterable

import numpy as np
import xarray as xr

from surfwave.report import checks as _values
from surfwave.report import claims as _claims
from surfwave.data.cube import open_cube as _open_cube
from surfwave.data.paper import load_paper_values  # noqa: F401 (re-exported)
from surfwave.pipeline.targets import CUBE_NAMES, report_inputs  # noqa: F401 (re-exported)
from surfwave.report.checks import (
    FAIL,
    INCONCLUSIVE,
    NOT_COMPUTED,
    PASS,
    Check,
    fmt,
    pick as _pick,
    sel_strain,
)

# --------------------------------------------------------------------------- I/O helpers
def open_cube(path: str | Path) -> xr.Dataset | None:
    """Load a result cube into memory (:func:`surfwave.data.cube.open_cube`), or None when the
    file does not exist."""
    path = Path(path)
    return _open_cube(path) if path.is_file() else None


class Cubes:
    """Lazy access to ``<scene>/<cube>`` result files; missing ones give None."""

    def __init__(self, paths: Iterable[str | Path]):
        self.paths = {f"{Path(p).parent.name}/{Path(p).stem}": Path(p) for p in paths}
        self._cache: dict[str, xr.Dataset | None] = {}

    @classmethod
    def from_dir(cls, results: str | Path) -> "Cubes":
        root = Path(results)
        return cls(p for p in sorted(root.glob("*/*.nc")) if p.stem in CUBE_NAMES)

    def get(self, scene: str, cube: str) -> xr.Dataset | None:
        key = f"{scene}/{cube}"
        if key not in self._cache:
            path = self.paths.get(key)
            self._cache[key] = open_cube(path) if path is not None else None
        return self._cache[key]

    def listing(self) -> list[tuple[str, str]]:
        return [(k, str(p) if p.is_file() else f"{p} (missing)") for k, p in self.paths.items()]


# --------------------------------------------------------------------------- Table I
def table1_entries(elastic: xr.Dataset | None, rayleigh: xr.Dataset | None,
                   paper_values: dict | None = None) -> list[dict]:
    """Every printed entry of Table I beside ours.

    Returns
    -------
    list of dict
        One per printed number: ``d_over_d0``, ``key``, ``label``, ``paper``, ``ours``
        (our [100] value, or the only direction compared), ``ours_by_direction``,
        ``difference`` (ours - paper, the direction with the largest |difference|),
        ``tolerance`` and ``verdict``.
    """
    pv = paper_values or load_paper_values()
    spec = pv["table1"]
    tol = float(spec["tolerance"]) + float(spec.get("slack", 0.0))
    cubes = {"elastic": elastic, "rayleigh": rayleigh}
    out = []
    for row in spec["rows"]:
        d = float(row[0])
        for col, paper in zip(spec["columns"], row[1:]):
            entry = {"d_over_d0": d, "key": col["key"], "label": col["label"],
                     "paper": float(paper), "ours": None, "ours_by_direction": {},
                     "difference": None, "tolerance": tol, "verdict": NOT_COMPUTED}
            ds = cubes[col["cube"]]
            if ds is not None and col["variable"] in ds:
                da = _pick(ds[col["variable"]], "potential", spec["potential"])
                for direction in col["directions"]:
                    sub = None if da is None else _pick(da, "direction", direction)
                    sub = None if sub is None else sel_strain(sub, d)
                    if sub is not None:
                        entry["ours_by_direction"][direction] = float(sub.values)
            values = entry["ours_by_direction"]
            if len(values) == len(col["directions"]):
                diffs = [v - entry["paper"] for v in values.values()]
                worst = max(diffs, key=lambda x: abs(x) if np.isfinite(x) else np.inf)
                entry["ours"] = values[col["directions"][0]]
                entry["difference"] = worst
                ok = all(np.isfinite(x) and abs(x) <= tol for x in diffs)
                entry["verdict"] = PASS if ok else FAIL
            out.append(entry)
    return out


def table1_markdown(entries: list[dict], paper_values: dict | None = None) -> str:
    """Table I as Markdown: paper beside ours, then ours - paper in units of 1e-4."""
    pv = paper_values or load_paper_values()
    cols = pv["table1"]["columns"]
    by_row: dict[float, dict[str, dict]] = {}
    for e in entries:
        by_row.setdefault(e["d_over_d0"], {})[e["key"]] = e
    head = "| d/d0 | " + " | ".join(f"{c['label']} paper | ours" for c in cols) + " |"
    lines = ["Paper (printed) beside ours:", "", head,
             "|" + "---|" * (1 + 2 * len(cols))]
    for d, row in by_row.items():
        cells = []
        for c in cols:
            e = row[c["key"]]
            ours = "n/a" if e["ours"] is None else f"{e['ours']:.6f}"
            cells += [f"{e['paper']:.4f}", ours]
        lines.append(f"| {d:.2f} | " + " | ".join(cells) + " |")
    lines += ["", "Ours - paper, in units of 1e-4 (a printed 4-decimal number is matched "
              "within 0.5); failures in bold:", "",
              "| d/d0 | " + " | ".join(c["label"] for c in cols) + " |",
              "|" + "---|" * (1 + len(cols))]
    for d, row in by_row.items():
        cells = []
        for c in cols:
            e = row[c["key"]]
            if e["difference"] is None:
                cells.append("not computed")
            else:
                s = f"{e['difference'] * 1e4:+.2f}"
                cells.append(f"**{s} FAIL**" if e["verdict"] == FAIL else s)
        lines.append(f"| {d:.2f} | " + " | ".join(cells) + " |")
    return "\n".join(lines) + "\n"


def table1(elastic_path, rayleigh_path, out_md, out_csv,
           paper_values_path: str | Path | None = None) -> list[dict]:
    """Write Table I (paper beside ours, difference, verdict) as Markdown and CSV.

    Parameters
    ----------
    elastic_path, rayleigh_path : path
        ``results/table1/elastic.nc`` and ``rayleigh.nc`` (missing -> "not computed").
    out_md, out_csv : path
        Outputs. The CSV is long-format, one printed number per line.

    Returns
    -------
    list of dict
        The entries (see `table1_entries`).
    """
    pv = load_paper_values(paper_values_path)
    entries = table1_entries(open_cube(elastic_path), open_cube(rayleigh_path), pv)
    n_fail = sum(e["verdict"] == FAIL for e in entries)
    n_nc = sum(e["verdict"] == NOT_COMPUTED for e in entries)
    title = (f"# Table I: {pv['table1']['source']}\n\n"
             f"{len(entries)} printed numbers: {len(entries) - n_fail - n_nc} PASS, "
             f"{n_fail} FAIL, {n_nc} not computed.\n\n")
    Path(out_md).write_text(title + table1_markdown(entries, pv))
    with open(out_csv, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(["d_over_d0", "quantity", "label", "paper", "ours_100", "ours_110",
                    "difference", "tolerance", "verdict"])
        for e in entries:
            by = e["ours_by_direction"]
            w.writerow([f"{e['d_over_d0']:.2f}", e["key"], e["label"], f"{e['paper']:.4f}",
                        "" if "[100]" not in by else repr(by["[100]"]),
                        "" if "[110]" not in by else repr(by["[110]"]),
                        "" if e["difference"] is None else repr(e["difference"]),
                        repr(e["tolerance"]), e["verdict"]])
    return entries


def _table1_check(entries: list[dict], source: str) -> Check:
    fails = [e for e in entries if e["verdict"] == FAIL]
    done = [e for e in entries if e["difference"] is not None]
    if not done:
        verdict = NOT_COMPUTED
    else:
        verdict = FAIL if fails else (PASS if len(done) == len(entries) else INCONCLUSIVE)
    worst = max((abs(e["difference"]) for e in done if np.isfinite(e["difference"])),
                default=None)
    evidence = "; ".join(f"d/d0={e['d_over_d0']:.2f} {e['label']}: paper {e['paper']:.4f}, "
                         f"ours {fmt(e['ours'])}" for e in fails)
    return Check("Table I (all entries)", source, f"{len(entries)} numbers",
                 f"{len(done)} computed, {len(fails)} outside tolerance",
                 "" if worst is None else f"max abs {worst:.2e}",
                 f"{entries[0]['tolerance']:.2e}" if entries else "", verdict, evidence)


# --------------------------------------------------------------------------- report
def build_checks(cubes: Cubes, paper_values: dict | None = None) -> tuple[list[Check], list[Check], list[dict]]:
    """All checks: (printed-number checks, claim checks, Table I entries)."""
    pv = paper_values or load_paper_values()
    spec = pv["table1"]
    entries = table1_entries(cubes.get(spec["scene"], "elastic"),
                             cubes.get(spec["scene"], "rayleigh"), pv)
    numbers = [_table1_check(entries, spec["source"])]
    for name, vspec in pv["values"].items():
        numbers += _values.value_checks(name, vspec, cubes)
    claims = []
    for name, cspec in pv["claims"].items():
        claims += _claims.claim_checks(name, cspec, cubes)
    return numbers, claims, entries


# --------------------------------------------------------------------------- bulk stage
BULK_SPEEDS = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH")


def _unstable_edges(strain: np.ndarray, ok: np.ndarray) -> str:
    """'compression edge / tension edge': the least-strained unstable points on each side."""
    comp = strain[(strain < 0) & ~ok]
    tens = strain[(strain > 0) & ~ok]
    return (f"{comp.max():+.3f}" if comp.size else "none") + " / " + (f"{tens.min():+.3f}" if tens.size else "none")


def bulk_section(cubes: Cubes) -> list[str]:
    """Markdown lines comparing the phonopy stage (bulk.nc) with the analytic one (elastic.nc).

    For every scene with a bulk cube: the largest relative deviation of the phonopy sound
    speeds from the analytic ones over the long-wave stable points, and where each stability
    criterion first fails in compression and in tension (long-wave: acoustic tensor in every
    direction; full zone: phonopy frequencies on the zone mesh).
    """
    scenes = sorted(k.split("/")[0] for k in cubes.paths if k.endswith("/bulk"))
    if not scenes:
        return ["No scene asks for `bulk`: not computed.", ""]
    lines = ["| Scene | Potential | Direction | Max relative deviation of phonopy speeds "
             "(long-wave stable points) | Long-wave unstable at strain (compression / tension) "
             "| Full-zone unstable at strain (compression / tension) | Points where they disagree |",
             "|---|---|---|---|---|---|---|"]
    for scene in scenes:
        bulk, el = cubes.get(scene, "bulk"), cubes.get(scene, "elastic")
        if bulk is None or el is None:
            lines.append(f"| {scene} | not computed | | | | | |")
            continue
        for pot in bulk["potential"].values:
            for d in bulk["direction"].values:
                b, e = bulk.sel(potential=pot, direction=d), el.sel(potential=pot, direction=d)
                long_wave = e["stable"].values.astype(bool)
                full_zone = b["stable_phonon"].values.astype(bool)
                rel = [np.abs(b[f"{n}_deviation"].values / e[n].values)[long_wave]
                       for n in BULK_SPEEDS if f"{n}_deviation" in b]
                finite = np.concatenate(rel)[np.isfinite(np.concatenate(rel))] if rel else np.array([])
                worst = f"{finite.max():.1e} ({int(long_wave.sum())} points)" if finite.size else "no stable point"
                strain = b["strain"].values
                lines.append(f"| {scene} | {pot} | {d} | {worst} | {_unstable_edges(strain, long_wave)} | "
                             f"{_unstable_edges(strain, full_zone)} | {int((long_wave != full_zone).sum())} |")
    return lines + [""]


def _title(c: Check) -> str:
    return f"{c.name} [{c.label}]" if c.label else c.name


def render(numbers: list[Check], claims: list[Check], entries: list[dict], cubes: Cubes,
           paper_values: dict) -> str:
    """The report as Markdown."""
    every = numbers + claims
    verdicts = (PASS, FAIL, INCONCLUSIVE, NOT_COMPUTED)
    counts = {v: sum(c.verdict == v for c in every) for v in verdicts}
    out = ["# Reproduction report", "",
           f"Paper: {paper_values['paper'].strip()}.", "",
           "Built by `surfwave.report.reproduction` from the result cubes and the paper's printed numbers "
           "(`src/surfwave/data/paper_values.yaml`, each with its source and tolerance); "
           "no other number is typed in. INCONCLUSIVE: the cube exists but its grid does not "
           "reach what the check needs.", "",
           "Summary: " + ", ".join(f"{n} {v}" for v, n in counts.items()) + ".", "",
           "## Printed numbers", "",
           "| Check | Paper | Ours | Ours - paper | Tolerance | Verdict |",
           "|---|---|---|---|---|---|"]
    for c in numbers:
        out.append(f"| {_title(c)} | {c.paper} | {c.ours} | {c.difference} | "
                   f"{c.tolerance} | {c.verdict} |")
    out += ["", "Sources and evidence:", ""]
    seen = set()
    for c in numbers:
        if c.name not in seen:
            seen.add(c.name)
            out.append(f"- {c.name}: {c.source}")
        if c.evidence:
            out.append(f"  - {_title(c)}: {c.evidence}")
    out += ["", "## Table I", "", table1_markdown(entries, paper_values),
            "## Claims of the paper", ""]
    groups: dict[str, list[Check]] = {}
    for c in claims:
        groups.setdefault(c.name, []).append(c)
    for name, items in groups.items():
        out += [f"### {name}", "", f"Paper: {items[0].source}", "",
                f"Criterion: {items[0].tolerance}", "",
                "| Case | Verdict | Evidence |", "|---|---|---|"]
        out += [f"| {c.label or '-'} | {c.verdict} | {c.evidence} |" for c in items] + [""]
    out += ["## Bulk stability: long-wave (analytic) and full-zone (phonopy)", "",
            "The paper checks only c_T,par; we check every bulk acoustic wave in every direction "
            "(elastic.nc `stable`) and, with phonopy, every phonon of the zone mesh "
            "(bulk.nc `stable_phonon`).", ""] + bulk_section(cubes)
    out += ["## Where we disagree with the paper", ""]
    fails = [c for c in every if c.verdict == FAIL]
    out += [f"- **{_title(c)}** ({c.source}): {c.evidence or c.ours}" for c in fails] or ["None."]
    out += ["", "## Cubes read", ""] + [f"- `{k}`: {p}" for k, p in cubes.listing()]
    return "\n".join(out) + "\n"


def write_report(cube_paths: Iterable[str | Path], out_md: str | Path,
                 paper_values_path: str | Path | None = None) -> list[Check]:
    """Write ``results/report.md`` from the given cubes; returns every check made."""
    pv = load_paper_values(paper_values_path)
    cubes = Cubes(cube_paths)
    numbers, claims, entries = build_checks(cubes, pv)
    Path(out_md).write_text(render(numbers, claims, entries, cubes, pv))
    return numbers + claims


# --------------------------------------------------------------------------- benchmarks
BENCH_CONVENTION = """\
Benchmark cube convention (benchmarks/bench_*.py OUTDIR -> OUTDIR/<name>.nc + PNG):
global attributes `method`, `knob` (name of the swept dimension), `default` (the chosen
knob value), `default_reason` (why); data variables `error` (with `units`) and `time`
(seconds) along the knob dimension. Pure timings: attribute `kind = "timing"` and a
variable `time` along any one dimension, one table row per label. A cube may instead give
its rows itself: attribute `readme_rows`, a JSON list of [method, knob, error, time, default
and why]. Anything else is summarised generically (per dimension: the ranges of variables
named *error*/*dev* and *time*, and the `default*` attributes)."""


def _span(values) -> str:
    values = np.asarray(values)
    if values.dtype.kind in "iuf" and values.size > 1:
        return f"[{_fmt_cell(values.min())}, {_fmt_cell(values.max())}]"
    labels = [str(v) for v in values]
    return ", ".join(labels[:4]) + (", ..." if len(labels) > 4 else "")


def _generic_rows(ds: xr.Dataset, name: str) -> list[list[str]]:
    a = ds.attrs
    method = str(a.get("method") or a.get("title") or name)
    defaults = "; ".join(f"{k}: {v}" for k, v in a.items() if k.startswith("default") or k == "target")
    rows = []
    for dim in ds.dims:
        errs = [v for v in ds.data_vars if dim in ds[v].dims and ("error" in v or "dev" in v)
                and "reported" not in v]
        times = [v for v in ds.data_vars if dim in ds[v].dims and "time" in v]
        if not errs and not times:
            continue

        def rng(names, unit_default=""):
            return "; ".join(f"{v}: {_fmt_cell(float(ds[v].min()))} .. {_fmt_cell(float(ds[v].max()))}"
                             f" {ds[v].attrs.get('units', unit_default)}".strip() for v in names)

        rows.append([method, f"{dim} in {_span(ds[dim].values) if dim in ds.coords else ds.sizes[dim]}",
                     rng(errs), rng(times, "s"), defaults if not rows else "(see above)"])
    return rows or [[method, "?", "see " + name, "see " + name, defaults]]


def _fmt_cell(x) -> str:
    try:
        return fmt(float(x), 3)
    except (TypeError, ValueError):
        return str(x)


def benchmark_rows(path: str | Path) -> list[list[str]]:
    """Table rows [method, knob, error, time, default and why] of one benchmark cube."""
    ds = open_cube(path)
    name = Path(path).name
    if ds is None:
        return [[name, "", "", "", "not computed"]]
    a = ds.attrs
    method = str(a.get("method", Path(path).stem))
    if "readme_rows" in a:
        return [[str(c) for c in row] for row in json.loads(a["readme_rows"])]
    if a.get("kind") == "timing" and "time" in ds:
        t = ds["time"]
        dim = t.dims[0] if t.dims else None
        if dim is None:
            return [[method, "", "", f"{float(t):.3g} s", str(a.get("default_reason", ""))]]
        return [[method, f"{dim} = {lab}", "", f"{float(v):.3g} s", str(a.get("default_reason", ""))]
                for lab, v in zip(t[dim].values, t.values)]
    knob = str(a.get("knob", ""))
    if "error" not in ds or "time" not in ds or knob not in ds["error"].dims:
        return _generic_rows(ds, name)
    err, tim = ds["error"], ds["time"]
    values = ds[knob].values
    default = a.get("default")
    i = 0
    if default is not None:
        try:
            i = int(np.argmin(np.abs(np.asarray(values, float) - float(default))))
        except (TypeError, ValueError):
            labels = [str(v) for v in values]
            i = labels.index(str(default)) if str(default) in labels else 0
    others = [d for d in err.dims if d != knob]
    e_def = err.isel({knob: i}).max(others) if others else err.isel({knob: i})
    t_def = tim.isel({knob: i}).max([d for d in tim.dims if d != knob]) if tim.ndim > 1 else tim.isel({knob: i})
    units = err.attrs.get("units", "")
    span = f"{knob} in [{_fmt_cell(values.min())}, {_fmt_cell(values.max())}]" if values.dtype.kind in "iuf" else knob
    why = f"{knob} = {_fmt_cell(values[i])}: {a.get('default_reason', '')}".strip(": ")
    return [[method, span, f"{_fmt_cell(float(e_def))} {units}".strip() +
             f" (range {_fmt_cell(float(err.min()))} .. {_fmt_cell(float(err.max()))})",
             f"{float(t_def):.3g} s (range {float(tim.min()):.3g} .. {float(tim.max()):.3g} s)", why]]


def benchmark_table(dirs: Iterable[str | Path], out_md: str | Path) -> str:
    """Write the README's benchmark table from every ``*.nc`` in ``dirs``; returns the text."""
    lines = ["| Method | Knob | Error at default (range) | Time at default (range) | Default chosen and why |",
             "|---|---|---|---|---|"]
    pngs = []
    for d in dirs:
        d = Path(d)
        files = sorted(d.glob("*.nc")) if d.is_dir() else []
        if not files:
            lines.append(f"| {d.name} | | | | not computed |")
        for f in files:
            lines += ["| " + " | ".join(c.replace("|", "/") for c in row) + " |"
                      for row in benchmark_rows(f)]
        pngs += sorted(d.glob("*.png")) if d.is_dir() else []
    text = "\n".join(lines) + "\n"
    if pngs:
        text += "\nPlots: " + ", ".join(f"`{p}`" for p in pngs) + "\n"
    Path(out_md).write_text(text)
    return text


def main(argv: list[str] | None = None) -> int:
    """``python -m surfwave.report.reproduction [RESULTS] [--out results/report.md]``."""
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("results", nargs="?", default="results")
    p.add_argument("--out", default=None)
    a = p.parse_args(argv)
    cubes = Cubes.from_dir(a.results)
    out = a.out or str(Path(a.results) / "report.md")
    write_report(cubes.paths.values(), out)
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
