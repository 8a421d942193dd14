"""Acoustoelastic coefficients of the surface-wave speed from a stressed real-crystal cube.

The coefficient of a material, surface, direction and loading is the relative slope of the
surface-wave speed at zero stress, K = (1/c_R) dc_R/dsigma, in 1/TPa (= 1e-3 / GPa). It is
taken from the cube's stress grid by the central difference over the nearest points
+/- h around zero (error O(h^2)); the central difference over +/- 2h gives the error
estimate by Richardson's rule, |K_2h - K_h| / 3, where the grid has those points.

Examples
--------
>>> from surfwave.data.cube import open_cube
>>> table = coefficients(open_cube("results/acoustoelastic/surface_wave.nc"))  # doctest: +SKIP
>>> table.K.sel(material="Cu", loading="along", toec=True)                    # doctest: +SKIP
"""
from __future__ import annotations

import csv
from pathlib import Path

import numpy as np
import xarray as xr

from surfwave.errors import InputError
from surfwave.vocab import REAL_WAVE_TYPES

#: 1/GPa -> 1/TPa.
PER_TPA = 1.0e3


def _stencil(stress: np.ndarray, k: int) -> tuple[int, int, float] | None:
    """Indices of -k h and +k h around zero on a grid that holds 0 and those points, and h."""
    zeros = np.flatnonzero(stress == 0.0)
    if zeros.size == 0:
        return None
    i0 = int(zeros[0])
    if i0 - k < 0 or i0 + k >= stress.size:
        return None
    lo, hi = stress[i0 - k], stress[i0 + k]
    if not np.isclose(-lo, hi, rtol=1e-9):
        return None
    return i0 - k, i0 + k, float(hi)


def coefficients(ds: xr.Dataset) -> xr.Dataset:
    """Acoustoelastic coefficients (1/c_R) dc_R/dsigma at zero stress and their error estimate.

    Parameters
    ----------
    ds : xarray.Dataset
        ``surface_wave.nc`` with dims (material, surface, angle, loading, toec, stress); the
        stress grid (GPa) must contain 0 and points symmetric about it.

    Returns
    -------
    xarray.Dataset
        Dims (material, surface, angle, loading, toec): ``K`` (1/TPa), ``K_error`` (1/TPa,
        NaN when the grid has no +/- 2h points), ``c_R0`` (m/s, the speed at zero stress),
        ``wave_type0``. K is NaN where any of the three points has no true surface wave.

    Raises
    ------
    InputError
        A cube without a stress grid through zero with a point on each side.
    """
    if "stress" not in ds.dims:
        raise InputError("the cube has no stress grid: acoustoelastic coefficients need one")
    s = ds.stress.values
    first = _stencil(s, 1)
    if first is None:
        raise InputError(f"stress grid {s.tolist()} needs 0 and one point at +/- h on each side")
    i0 = int(np.flatnonzero(s == 0.0)[0])
    wave_ok = ds.wave_type.isin(list(REAL_WAVE_TYPES))
    c = ds.c_R.where(wave_ok)

    def central(st):
        lo, hi, h = st
        return (c.isel(stress=hi) - c.isel(stress=lo)) / (2.0 * h) / c.isel(stress=i0) * PER_TPA

    K = central(first)
    second = _stencil(s, 2)
    err = abs(central(second) - K) / 3.0 if second is not None else xr.full_like(K, np.nan)
    out = xr.Dataset({
        "K": K.drop_vars("stress", errors="ignore").assign_attrs(
            long_name="acoustoelastic coefficient (1/c_R) dc_R/dsigma at zero stress "
            f"(central difference, h = {first[2]:g} GPa)", units="TPa-1"),
        "K_error": err.drop_vars("stress", errors="ignore").assign_attrs(
            long_name="error estimate of K, |K(2h) - K(h)|/3 (Richardson)", units="TPa-1"),
        "c_R0": ds.c_R.isel(stress=i0, drop=True).assign_attrs(
            long_name="surface-wave speed at zero stress", units="m s-1"),
        "wave_type0": ds.wave_type.isel(stress=i0, drop=True).assign_attrs(
            long_name="wave type at zero stress"),
    })
    return out


def _label(ds: xr.Dataset, j: int) -> str:
    if "direction" in ds.coords:
        return f"{ds.direction.values[j]} ({float(ds.angle[j]):g} deg)"
    return f"{float(ds.angle[j]):g} deg"


def rows(ds: xr.Dataset) -> list[dict]:
    """One row per (material, surface, angle, loading): c_R(0) and K without and with TOEC."""
    K = coefficients(ds)
    out = []
    for mat in K.material.values:
        for sf in K.surface.values:
            for j in range(K.sizes["angle"]):
                for ld in K.loading.values:
                    p = K.sel(material=mat, surface=sf, loading=ld).isel(angle=j)
                    row = {"material": str(mat), "surface": str(sf), "direction": _label(ds, j),
                           "loading": str(ld), "c_R0 (m/s)": float(p.c_R0.isel(toec=0)),
                           "wave type": str(p.wave_type0.isel(toec=0).values)}
                    for tv, name in ((False, "fixed C"), (True, "TOEC")):
                        have = tv in p.toec.values
                        row[f"K {name} (1/TPa)"] = float(p.K.sel(toec=tv)) if have else float("nan")
                        row[f"error {name} (1/TPa)"] = float(p.K_error.sel(toec=tv)) if have else float("nan")
                    out.append(row)
    return out


def write_table(ds: xr.Dataset, md_path: str | Path, csv_path: str | Path) -> tuple[Path, Path]:
    """Write the coefficients as a Markdown table (with an explanation) and as CSV.

    Returns
    -------
    (pathlib.Path, pathlib.Path)
        The Markdown and CSV files.
    """
    md_path, csv_path = Path(md_path), Path(csv_path)
    md_path.parent.mkdir(parents=True, exist_ok=True)
    title = f"# Acoustoelastic coefficients of the surface-wave speed ({ds.attrs.get('scene_name', '')})"
    try:
        table = rows(ds)
    except InputError as exc:  # a stress grid without 0 +/- h: say why, write no numbers
        md_path.write_text(f"{title}\n\nNo coefficients: {exc}.\n")
        csv_path.write_text("")
        return md_path, csv_path
    cols = list(table[0])
    with open(csv_path, "w", newline="") as fh:
        w = csv.DictWriter(fh, fieldnames=cols)
        w.writeheader()
        w.writerows(table)

    def fmt(v):  # coefficients to 1e-6 / TPa: a zero by symmetry prints as 0
        if isinstance(v, float):
            return "n/a" if not np.isfinite(v) else (f"{v:.1f}" if abs(v) >= 100 else f"{round(v, 6) + 0.0:.3g}")
        return str(v)

    h = float(np.min(np.abs(ds.stress.values[ds.stress.values != 0])))
    lines = [
        title,
        "",
        "K = (1/c_R) dc_R/dsigma at zero stress, in 1/TPa (a speed change of K x 1e-3 per GPa), "
        f"by central differences over +/- {h:g} GPa of the cube's stress grid; the error is "
        "Richardson's |K(2h) - K(h)|/3. Loadings act in the surface plane: *along* = uniaxial "
        "along the propagation, *across* = uniaxial in-plane perpendicular to it, *biaxial* = "
        "equal in-plane biaxial. *fixed C*: second-order constants of the natural state, stress "
        "only in A = C + sigma (the seed paper's model); *TOEC*: constants and density of the "
        "stressed state from the third-order elastic constants. n/a: no true surface wave at "
        "the three points.",
        "",
        "| " + " | ".join(cols) + " |",
        "|" + "|".join("---" for _ in cols) + "|",
    ]
    lines += ["| " + " | ".join(fmt(r[c]) for c in cols) + " |" for r in table]
    md_path.write_text("\n".join(lines) + "\n")
    return md_path, csv_path
