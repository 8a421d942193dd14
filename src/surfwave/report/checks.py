"""The checks behind the reproduction report (`surfwave.report.reproduction`).

Each check reads the cubes through a ``Cubes`` object (``.get(scene, cube)`` -> Dataset or
None) and a spec from ``paper_values.yaml`` and returns `Check` lines; missing data gives
"not computed", never an exception. Criteria are stated in the YAML and repeated in the
report.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, SupportsFloat

import numpy as np
import xarray as xr

if TYPE_CHECKING:
    from surfwave.report.reproduction import Cubes

PASS, FAIL, INCONCLUSIVE, NOT_COMPUTED = "PASS", "FAIL", "INCONCLUSIVE", "not computed"
#: Verdict of a claim that fails our full check but holds under the paper's own approximation
#: (bulk stability judged by c_T,par alone), which our check shows to be off there: not a
#: breakage of this code, a finding about the paper (README, "What we found").
PAPER_APPROX = "PAPER-APPROX"
#: Every verdict, in the order the report counts them.
VERDICTS = (PASS, PAPER_APPROX, FAIL, INCONCLUSIVE, NOT_COMPUTED)
STRAIN_MATCH = 1e-6  # |d/d0 - wanted| below which a grid point is "the" point
FCC_DIRECTIONS = ("[100]", "[110]")


@dataclass
class Check:
    """One line of the report; ``paper``/``ours``/``difference`` are formatted strings."""

    name: str
    source: str
    paper: str
    ours: str
    difference: str
    tolerance: str
    verdict: str
    evidence: str = ""
    label: str = ""


def fmt(x: SupportsFloat | None, digits: int = 6) -> str:
    """Format a number for the report ("n/a" for None/NaN)."""
    if x is None or (isinstance(x, float) and math.isnan(x)):
        return "n/a"
    x = float(x)
    return f"{x:.{digits}g}" if abs(x) >= 1e-3 or x == 0 else f"{x:.3e}"


def d_over_d0(da: xr.DataArray) -> np.ndarray:
    """The d/d0 values of ``da``'s strain axis."""
    if "d_over_d0" in da.coords:
        return np.asarray(da["d_over_d0"].values, dtype=float)
    return np.asarray(da["strain"].values, dtype=float) + 1.0


def sel_strain(da: xr.DataArray, value: float) -> xr.DataArray | None:
    """The slice of ``da`` at d/d0 == ``value`` (within 1e-6), or None if not on the grid."""
    hits = np.flatnonzero(np.abs(d_over_d0(da) - value) < STRAIN_MATCH)
    return None if hits.size == 0 else da.isel(strain=int(hits[0]))


def pick(da: xr.DataArray, dim: str, label: str) -> xr.DataArray | None:
    """``da`` at the string label ``label`` of ``dim`` (None when absent)."""
    if dim not in da.dims:
        return da
    labels = [str(v) for v in da[dim].values]
    return da.isel({dim: labels.index(label)}) if label in labels else None


def _potentials(ds: xr.Dataset) -> list[str]:
    return [str(p) for p in ds["potential"].values] if "potential" in ds.dims else [""]


def _nc(name: str, spec: dict, why: str = "") -> Check:
    paper = fmt(spec["value"], 10) if "value" in spec and not isinstance(spec["value"], dict) else ""
    return Check(name, spec.get("source", ""), paper, NOT_COMPUTED, "", "", NOT_COMPUTED, why)


def _compare(name, spec, ours, evidence="", label="") -> Check:
    paper = float(spec["value"])
    tol = float(spec.get("tolerance", 0.0)) + float(spec.get("slack", 1e-12))
    title = name
    if ours is None or not np.isfinite(ours):
        return Check(title, spec["source"], fmt(paper, 10), "n/a", "", f"{tol:.3g}", NOT_COMPUTED,
                     evidence or "no finite value in the cube", label)
    diff = float(ours) - paper
    ok = ours >= paper - tol if spec.get("comparison") == "at_least" else abs(diff) <= tol
    tol_s = (f">= {fmt(paper)}" if spec.get("comparison") == "at_least" else f"{tol:.3g}")
    if spec.get("tolerance_reason"):
        tol_s += f" ({spec['tolerance_reason'].strip()})"
    return Check(title, spec["source"], fmt(paper, 10), fmt(ours, 10), f"{diff:+.3e}", tol_s,
                 PASS if ok else FAIL, evidence, label)


# --------------------------------------------------------------------------- printed values
def _theta_c(ds: xr.Dataset) -> xr.DataArray | None:
    """theta_c(potential, strain): from the cube, else the first theta where q is complex."""
    if "theta_c" in ds:
        return ds["theta_c"]
    if "q1" not in ds or "q2" not in ds:
        return None
    cplx = (np.abs(ds["q1"].imag) > 1e-9) | (np.abs(ds["q2"].imag) > 1e-9)
    theta = ds["theta"]
    return theta.where(cplx).min("theta")


def value_checks(name: str, spec: dict, cubes: Cubes) -> list[Check]:
    """Checks of one printed value (``values:`` in paper_values.yaml), one per potential."""
    ds = cubes.get(spec["scene"], spec["cube"])
    if ds is None:
        return [_nc(name, spec, f"cube {spec['scene']}/{spec['cube']}.nc not computed")]
    out = []
    for pot in _potentials(ds):
        if pot and "potentials" in spec and pot not in spec["potentials"]:
            continue
        sub = ds.sel(potential=pot) if pot else ds
        try:
            ours, evidence = _VALUE_GETTERS.get(name, _plain_value)(sub, spec)
        except KeyError as exc:  # a variable or label the cube lacks
            ours, evidence = None, f"not in the cube: {exc}"
        out.append(_compare(name, spec, ours, evidence, pot))
    return out


def _plain_value(ds: xr.Dataset, spec: dict):
    var = ds[spec["variable"]]
    for dim, label in spec.get("select", {}).items():
        if dim == "strain":
            var = sel_strain(var, 1.0 + float(label))
        else:
            var = pick(var, dim, label)
        if var is None:
            raise KeyError(f"{dim}={label}")
    ev = ""
    err = f"{spec['variable']}_error"
    if err in ds:
        e = ds[err]
        at = sel_strain(e, 1.0 + float(spec.get("select", {}).get("strain", 0.0))) if "strain" in e.dims else e
        if at is not None:
            ev = f"our error estimate {fmt(float(at.values))}"
    return float(var.values), ev


def _eq16_all(ds: xr.Dataset, spec: dict):
    c2 = pick(ds[spec["variable"]], "direction", "[10]")
    if c2 is None:
        raise KeyError("direction=[10]")
    x = d_over_d0(c2) / 2.0
    eq16 = 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)
    dev = np.abs(np.asarray(c2.values, dtype=float) - eq16)
    ok = np.isfinite(dev)
    if not ok.any():
        return None, "no finite c_R^2"
    i = int(np.nanargmax(np.where(ok, dev, -1)))
    return float(dev[ok].max()), (f"{ok.sum()} strain points; worst at d/d0 = "
                                  f"{d_over_d0(c2)[i]:.4g}")


def _theta_c_value(ds: xr.Dataset, spec: dict):
    tc = _theta_c(ds)
    if tc is None:
        raise KeyError("theta_c (or q1, q2)")
    tc0 = sel_strain(tc, 1.0)
    if tc0 is None:
        raise KeyError("strain=0")
    ev = ""
    if "theta" in ds.dims:
        th = np.sort(np.asarray(ds["theta"].values, dtype=float))
        ev = f"theta grid step {fmt(float(np.diff(th).max()), 3)} rad" if th.size > 1 else ""
    val = float(tc0.values)
    return val, f"theta_c = {val / math.pi:.4f} pi; {ev}".strip("; ")


def _nine_layers(ds: xr.Dataset, spec: dict):
    if "u" not in ds or "v" not in ds:
        raise KeyError("u, v")
    amp = np.sqrt(np.abs(ds["u"]) ** 2 + np.abs(ds["v"]) ** 2)
    amp = sel_strain(amp, 1.0)
    if amp is None:
        raise KeyError("strain=0")
    theta = np.asarray(amp["theta"].values, dtype=float)
    it = int(np.argmin(np.abs(theta - float(spec["theta"]))))
    rows = np.asarray(amp["row"].values)
    row = int(spec["row"])
    if row not in rows or 0 not in rows:
        raise KeyError(f"row={row}")
    a = amp.isel(theta=it)
    ratio = float(a.sel(row=row).values / a.sel(row=0).values)
    return ratio, (f"at theta = {theta[it] / math.pi:.4f} pi (nearest grid point to pi/20), "
                   f"row {row} amplitude / surface amplitude")


_VALUE_GETTERS = {
    "eq16_all_strains": _eq16_all,
    "theta_c_zero_stress": _theta_c_value,
    "nine_layers_pi_over_20": _nine_layers,
}
