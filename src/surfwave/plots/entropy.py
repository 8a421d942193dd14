"""Figures of the surface entropy: entropy against strain, convergence with the knobs.

Matplotlib with the Agg backend; every function takes data and an output path and returns
the path written.
"""
from __future__ import annotations

from pathlib import Path
from typing import Mapping

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from numpy.typing import ArrayLike  # noqa: E402

from surfwave.data.paper import load_paper_values  # noqa: E402
from surfwave.data.variables import CUBES  # noqa: E402
from surfwave.plots.labels import potential_label  # noqa: E402
from surfwave.plots.output import savefig  # noqa: E402
from surfwave.validate import as_1d  # noqa: E402

#: The paper's zero-stress values (section III.C) drawn as markers: label -> key in
#: src/surfwave/data/paper_values.yaml (the one copy of the paper's numbers).
PAPER_ZERO_STRESS = {"Eq. (26) estimate": "eq26_entropy_estimate",
                     "lattice dynamics (Ref. 23)": "entropy_lattice_dynamics",
                     "cell cluster (Ref. 24)": "entropy_cell_cluster"}


def _paper_value(key: str) -> float:
    return float(load_paper_values()["values"][key]["value"])

#: Knobs of the benchmark cube: (prefix, coordinate, label, the quantity whose error is shown).
KNOBS = (
    ("theta", "n_theta", "theta quadrature (Gauss nodes)", "exact"),
    ("depth", "levels", "semi-infinite depth 2^levels rows", "exact"),
    ("slab", "slab_rows", "finite slab, N rows (naive)", "exact"),
    ("zone", "zone_grid", "bulk: naive zone grid n x n", "bulk"),
    ("theta", "n_theta", "bulk: theta quadrature", "bulk"),
    ("tol", "tol", "surface_entropy(tol)", "exact"),
)


def to_dataset(result: Mapping[str, np.ndarray], d_over_d0: ArrayLike, potential: str) -> xr.Dataset:
    """Wrap one :func:`surfwave.dynamics.entropy.surface_entropy` result as a (potential, strain) cube.

    Parameters
    ----------
    result : dict of ndarray, shape (n,)
    d_over_d0 : array_like, shape (n,)
    potential : str

    Returns
    -------
    xarray.Dataset
        Dims (potential, strain); coordinates ``strain`` = d/d0 - 1 and ``d_over_d0``.
    """
    d = as_1d(d_over_d0)
    data = {}
    for name, arr in result.items():
        attrs = {k: v for k, v in CUBES["entropy"].get(name, {}).items() if k != "dims"}
        data[name] = (("potential", "strain"), np.asarray(arr)[None], attrs)
    return xr.Dataset(data, coords={"potential": [potential], "strain": d - 1.0,
                                    "d_over_d0": ("strain", d)})


def entropy_vs_strain(ds: xr.Dataset, path: str | Path, title: str | None = None) -> Path:
    """S_surface_estimate and S_surface_exact (and the bulk mean ln omega) against strain.

    Parameters
    ----------
    ds : xarray.Dataset
        Dims (potential, strain) (``potential`` optional), variables of
        ``surfwave.data.variables.CUBES["entropy"]``, coordinate ``strain`` = d/d0 - 1.
    path : str or Path
        PNG to write.

    Returns
    -------
    Path
    """
    path = Path(path)
    if "potential" not in ds.dims:
        ds = ds.expand_dims(potential=["?"])
    fig, (ax, axb) = plt.subplots(1, 2, figsize=(10, 4), layout="constrained")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for i, pot in enumerate(ds["potential"].values):
        sub = ds.sel(potential=pot)
        x = sub["strain"].values
        c = colors[i % len(colors)]
        name = potential_label(pot)
        ax.plot(x, sub["S_surface_exact"].values, "-", color=c, label=f"{name}: exact (lattice dynamics)")
        ax.plot(x, sub["S_surface_estimate"].values, "--", color=c, label=f"{name}: estimate, Eq. (25)")
        axb.plot(x, sub["bulk_mean_log_omega"].values, "-", color=c, label=name)
    markers = iter("o^s")
    for label, key in PAPER_ZERO_STRESS.items():
        ax.plot([0.0], [_paper_value(key)], next(markers), color="k", mfc="none", label=f"paper: {label}")
    ax.set_xlabel(r"strain $d/d_0 - 1$")
    ax.set_ylabel(r"surface entropy per surface atom ($k_B$)")
    ax.set_title(title or "Surface entropy, triangular lattice, uniaxial stress")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    axb.axhline(_paper_value("huckaby_bulk_mean_log_omega"), color="k", lw=0.5, ls=":", label="Huckaby, zero stress")
    axb.set_xlabel(r"strain $d/d_0 - 1$")
    for a in (ax, axb):  # few enough ticks that the labels never overlap
        a.xaxis.set_major_locator(plt.MaxNLocator(5))
    axb.set_ylabel(r"$\langle \ln(\omega/\omega_0) \rangle$ over bulk modes")
    axb.set_title("Bulk mean log frequency")
    axb.legend(fontsize=7)
    axb.grid(alpha=0.3)
    return savefig(fig, path)


def convergence(ds: xr.Dataset, path: str | Path) -> Path:
    """Error against wall time and against knob value, for every knob of the benchmark cube.

    Parameters
    ----------
    ds : xarray.Dataset
        Written by ``benchmarks/bench_entropy.py``: dim ``case`` and one dim per knob
        (``n_theta``, ``levels``, ``slab_rows``, ``zone_grid``, ``tol``) with variables
        ``<prefix>_error_exact`` / ``<prefix>_error_bulk`` and ``<prefix>_time`` (s).
    path : str or Path
        PNG to write.

    Returns
    -------
    Path
    """
    path = Path(path)
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.4), layout="constrained")
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    styles = ["-", "--", ":", "-."]
    floor = 1e-17  # errors that are exactly 0 are drawn here
    for j, case in enumerate(ds["case"].values):
        ls = styles[j % len(styles)]
        for i, (prefix, dim, label, what) in enumerate(KNOBS):
            err_name = f"{prefix}_error_{what}"
            if err_name not in ds:
                continue
            err = np.maximum(ds[err_name].sel(case=case).values, floor)
            t = ds[f"{prefix}_time"].sel(case=case).values
            lab = f"{label} [{what}]" if j == 0 else None
            axes[0].loglog(t, err, ls, marker=".", color=colors[i], label=lab)
            if dim != "tol":
                axes[1].loglog(ds[dim].values.astype(float), err, ls, marker=".", color=colors[i],
                               label=lab)
            else:
                axes[2].loglog(ds["tol"].values, err, ls, marker="o", color=colors[i],
                               label="actual error" if j == 0 else None)
        if "tol_reported_error_exact" in ds:
            rep = ds["tol_reported_error_exact"].sel(case=case).values
            axes[2].loglog(ds["tol"].values, rep, ls, marker="x", color="k",
                           label="reported error estimate" if j == 0 else None)
    tol = ds["tol"].values if "tol" in ds.coords else np.array([1e-12, 1e-2])
    axes[2].loglog(tol, tol, color="0.6", lw=0.8, label="error = tol")
    axes[0].set_xlabel("wall time per strain point (s, one core)")
    axes[0].set_ylabel("absolute error (k_B per surface atom; ln omega0 for the bulk)")
    axes[0].axvline(0.5, color="tab:red", lw=0.8, ls="--")
    axes[0].axhline(1e-8, color="tab:red", lw=0.8, ls="--")
    axes[0].set_title("error against cost (red: target 1e-8 in 0.5 s)")
    axes[1].set_xlabel("knob value (Gauss nodes, levels, slab rows, zone grid n)")
    axes[1].set_title("error against knob")
    axes[1].legend(fontsize=6, loc="lower left")
    axes[2].set_xlabel("tol")
    axes[2].set_title("surface_entropy(tol): S_surface_exact")
    axes[2].legend(fontsize=7)
    cases = "; ".join(f"{styles[j % len(styles)]} {c}" for j, c in enumerate(ds["case"].values))
    fig.suptitle(f"Surface entropy convergence (cases: {cases})", fontsize=10)
    for ax in axes:
        ax.grid(alpha=0.3, which="both")
    return savefig(fig, path)
