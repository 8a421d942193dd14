"""Summary of a user's own scene: what was computed, over which ranges, what has no answer.

``results/<scene>/summary.md`` is to a user scene what ``results/report.md`` is to the
paper's scenes, without the paper: the cubes written, their coordinates' ranges, and per
variable how many points are NaN (no answer, with the most frequent ``reason``) and how
many strains are unstable.
"""
from __future__ import annotations

from collections import Counter
from pathlib import Path
from typing import Iterable

import numpy as np

from surfwave.data.cube import open_cube
from surfwave.report.soft_modes import soft_mode_lines


def _range(values) -> str:
    v = np.asarray(values)
    if v.dtype.kind in "iuf" and v.size:
        return f"{v.min():.6g} .. {v.max():.6g} ({v.size} values)"
    return ", ".join(str(x) for x in v)


def cube_lines(path: str | Path) -> list[str]:
    """Markdown lines describing one cube (dims, ranges, NaN and instability counts)."""
    path = Path(path)
    ds = open_cube(path, load=False)  # one variable in memory at a time (large scenes)
    out = [f"### `{path.name}`", "", f"File: `{path}`. {ds.attrs.get('method', '')}".rstrip(), ""]
    for dim in ds.dims:
        if dim in ds.coords and dim != "complex":
            out.append(f"- {dim}: {_range(ds[dim].values)}")
    if "d_over_d0" in ds.coords:
        out.append(f"- d/d0: {_range(ds['d_over_d0'].values)}")
    out.append("")
    rows = []
    for name, var in ds.data_vars.items():
        v = var.values
        if v.dtype.kind in "fc":
            n_nan = int(np.isnan(v).sum())
            rows.append(f"| `{name}` | {var.attrs.get('long_name', '')} | {v.size} | {n_nan} |")
    if rows:
        out += ["| variable | meaning | values | NaN (no answer) |", "|---|---|---|---|"] + rows + [""]
    for flag in ("stable", "stable_phonon"):
        if flag in ds:
            bad = int((~ds[flag].values.astype(bool)).sum())
            out.append(f"- `{flag}` False (unstable) at {bad} of {ds[flag].size} points")
    if "reason" in ds:
        reasons = Counter(str(r) for r in np.ravel(ds["reason"].values) if str(r))
        for reason, n in reasons.most_common(3):
            out.append(f"- {n} points: {reason}")
    soft = soft_mode_lines(ds)   # surface_phonons.nc: the soft-surface-mode claim
    ds.close()
    return out + [""] + soft


def scene_summary(cube_paths: Iterable[str | Path], scene: str) -> str:
    """Markdown summary of one scene from its cubes (missing files are listed as such)."""
    paths = [Path(p) for p in cube_paths]
    out = [f"# Scene `{scene}`", "",
           f"Cubes under `{paths[0].parent if paths else 'results/' + scene}/` "
           "(open with `xarray.open_dataset` or `surfwave.data.cube.open_cube`).", ""]
    for p in paths:
        out += cube_lines(p) if p.is_file() else [f"### `{p.name}`", "", "not computed", ""]
    return "\n".join(out)


def write_summary(cube_paths: Iterable[str | Path], out_md: str | Path, scene: str) -> Path:
    """Write :func:`scene_summary` to ``out_md``."""
    out_md = Path(out_md)
    out_md.write_text(scene_summary(cube_paths, scene))
    return out_md
