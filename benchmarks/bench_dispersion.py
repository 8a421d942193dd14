"""Benchmark of the triangular-lattice dispersion: accuracy against cost of the numerical
semi-infinite solve, and the speed of the analytic path.

Usage: ``python benchmarks/bench_dispersion.py OUTDIR`` writes ``OUTDIR/bench_dispersion.nc``
(xarray Dataset, engine h5netcdf) and ``OUTDIR/bench_dispersion.png``.

Measured:
* ``n_steps`` knob (decimation steps, crystal depth 2^n_steps rows) and ``tol`` knob (default
  mode: decimate until the neglected coupling is below tol): max relative error of
  ``omega_lattice`` against Eq. 15 (exact for every potential with phi'(d0) = 0, see
  surfwave.dynamics.dispersion), the max of the error estimate relative to omega, wall time, per potential.
* wall time of ``dispersion.solve`` on an n x n (strain, theta) grid (n = 1000 by default) and
  of ``lattice_dynamics.surface_mode`` on the accuracy grid.
* max |omega_lattice/((c_R/d_x) sin theta) - 1| (c_R from Eq. 20) per potential: the sine law.
"""
from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

from surfwave import __version__
from surfwave.dynamics import dispersion
from surfwave.dynamics import triangular_surface as lattice_dynamics
from surfwave.plots.dispersion import plt

POTENTIALS = ("harmonic", "lj", "morse")
# Strain grids: from 1% inside the surface instability (c_R^2 = 0) to tension.
EDGES = {"harmonic": (0.70849737787, 1.95), "lj": (0.89361985602, 1.11392551139),
         "morse": (None, None)}


def strain_grid(name: str, n: int) -> np.ndarray:
    lo, hi = EDGES[name]
    if lo is None:  # find the valid range from the analytic c_R^2 > 0
        d = np.linspace(0.5, 1.95, 2901)
        ok = np.isfinite(dispersion.solve(name, d, [1.0])["c2_R"])
        lo, hi = d[ok][0], d[ok][-1]
    return np.linspace(lo * 1.01, hi * (0.99 if hi < 1.9 else 1.0), n)


def theta_grid(m: int) -> np.ndarray:
    return np.concatenate([[1e-3], np.linspace(0.02, np.pi - 0.02, m - 2), [np.pi - 1e-3]])


def timed(fn, *args, repeat: int = 1, **kw):
    best, out = np.inf, None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn(*args, **kw)
        best = min(best, time.perf_counter() - t0)
    return out, best


def run(outdir: Path, n_analytic: int = 1000, quick: bool = False) -> xr.Dataset:
    steps = np.arange(2, 25, 2 if quick else 1)
    tols = 10.0 ** -np.arange(2, 15, 2 if quick else 1)
    ns, mt = (4, 12) if quick else (8, 40)
    shape = (len(POTENTIALS),)
    err_s = np.full(shape + (steps.size,), np.nan)
    est_s, time_s = err_s.copy(), err_s.copy()
    nan_s = np.zeros(shape + (steps.size,), dtype=int)
    err_t, est_t, time_t, depth_t = (np.full(shape + (tols.size,), np.nan) for _ in range(4))
    sine_dev, time_default = np.full(shape, np.nan), np.full(shape, np.nan)
    th = theta_grid(mt)
    for p, name in enumerate(POTENTIALS):
        d = strain_grid(name, ns)
        exact = dispersion.solve(name, d, th)["omega"]
        for k, st in enumerate(steps):
            r, sec = timed(lattice_dynamics.surface_mode, name, d, th, n_steps=int(st))
            rel = np.abs(r["omega_lattice"] / exact - 1)
            nan_s[p, k] = np.isnan(rel).sum()
            err_s[p, k] = np.nanmax(rel, initial=0.0) if nan_s[p, k] < rel.size else np.nan
            est_s[p, k] = np.nanmax(r["omega_lattice_error"] / r["omega_lattice"], initial=0.0)
            time_s[p, k] = sec
        for k, tol in enumerate(tols):
            r, sec = timed(lattice_dynamics.surface_mode, name, d, th, tol=float(tol))
            err_t[p, k] = np.nanmax(np.abs(r["omega_lattice"] / exact - 1))
            est_t[p, k] = np.nanmax(r["omega_lattice_error"] / r["omega_lattice"])
            time_t[p, k], depth_t[p, k] = sec, np.nanmax(r["depth"])
        r, time_default[p] = timed(lattice_dynamics.surface_mode, name, d, th)
        sine_dev[p] = np.nanmax(np.abs(r["sine_law_deviation"]))
    d = np.linspace(0.72, 1.9, n_analytic)
    tha = np.linspace(1e-3, np.pi - 1e-3, n_analytic)
    _, t_analytic = timed(dispersion.solve, "harmonic", d, tha, repeat=3)
    ds = xr.Dataset(
        {
            "error_steps": (("potential", "n_steps"), err_s, {
                "long_name": "max relative error of omega_lattice vs Eq. 15 at fixed decimation steps",
                "units": "1"}),
            "error_estimate_steps": (("potential", "n_steps"), est_s, {
                "long_name": "max relative error estimate omega_lattice_error/omega_lattice", "units": "1"}),
            "nan_points_steps": (("potential", "n_steps"), nan_s, {
                "long_name": "points with no bound mode found (crystal too shallow)", "units": "1"}),
            "time_steps": (("potential", "n_steps"), time_s, {"long_name": "wall time of surface_mode",
                                                              "units": "s"}),
            "error_tol": (("potential", "tol"), err_t, {
                "long_name": "max relative error of omega_lattice vs Eq. 15 at decimation tolerance",
                "units": "1"}),
            "error_estimate_tol": (("potential", "tol"), est_t, {
                "long_name": "max relative error estimate omega_lattice_error/omega_lattice", "units": "1"}),
            "time_tol": (("potential", "tol"), time_t, {"long_name": "wall time of surface_mode", "units": "s"}),
            "depth_tol": (("potential", "tol"), depth_t, {"long_name": "rows coupled (2^steps)", "units": "1"}),
            "time_default": (("potential",), time_default, {
                "long_name": "wall time of surface_mode with defaults (tol = 1e-10)", "units": "s"}),
            "sine_law_max_deviation": (("potential",), sine_dev, {
                "long_name": "max |omega_lattice / ((c_R/d_x) sin theta) - 1|, c_R from Eq. 20",
                "units": "1"}),
            "time_analytic": ((), t_analytic, {
                "long_name": f"wall time of dispersion.solve on a {n_analytic} x {n_analytic} "
                             "(strain, theta) grid (best of 3)", "units": "s"}),
        },
        coords={"potential": list(POTENTIALS), "n_steps": steps, "tol": tols},
        attrs={"Conventions": "CF-1.10", "title": "surfwave triangular dispersion benchmark",
               "source": f"surfwave {__version__}", "history": f"{time.ctime()}: benchmarks/bench_dispersion.py",
               "n_analytic": n_analytic,
               "accuracy_grid": f"{ns} strains x {mt} theta per potential (1% inside the instabilities, "
                                "theta from 1e-3 to pi - 1e-3)"},
    )
    outdir.mkdir(parents=True, exist_ok=True)
    ds.to_netcdf(outdir / "bench_dispersion.nc", engine="h5netcdf")
    plot(ds, outdir / "bench_dispersion.png")
    return ds


def plot(ds: xr.Dataset, path: Path) -> None:
    fig, (a, b) = plt.subplots(1, 2, figsize=(9, 3.6))
    for p in ds.potential.values:
        s = ds.sel(potential=p)
        a.loglog(s.tol, np.maximum(s.error_tol, 1e-17), "o-", ms=3, label=f"{p} actual")
        a.loglog(s.tol, np.maximum(s.error_estimate_tol, 1e-17), ":", label=f"{p} estimate")
        b.semilogy(s.n_steps, np.maximum(s.error_steps, 1e-17), "o-", ms=3, label=f"{p} actual")
        b.semilogy(s.n_steps, np.maximum(s.error_estimate_steps, 1e-17), ":", label=f"{p} estimate")
    a.set_xlabel("decimation tolerance tol (default 1e-10)")
    a.set_ylabel("max relative error of omega_lattice")
    a.invert_xaxis()
    a.legend(fontsize=7)
    b.set_xlabel("decimation steps (depth 2^steps rows)")
    b.set_ylabel("max relative error")
    b.legend(fontsize=7)
    fig.suptitle("numerical surface-wave solve (decimation) vs Eq. 15, max over strain x theta; "
                 f"analytic path {ds.time_analytic.item():.2f} s per {ds.attrs['n_analytic']}^2 points",
                 fontsize=9)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outdir", type=Path)
    ap.add_argument("--n-analytic", type=int, default=1000)
    ap.add_argument("--quick", action="store_true", help="coarser knob grids (for tests)")
    args = ap.parse_args(argv)
    ds = run(args.outdir, args.n_analytic, args.quick)
    print(ds[["time_default", "sine_law_max_deviation"]].to_dataframe().to_string())
    print("time_analytic [s]:", float(ds.time_analytic))
    print(ds[["error_tol", "time_tol", "depth_tol"]].to_dataframe().to_string())
    print(ds[["error_steps", "error_estimate_steps", "time_steps"]].to_dataframe().to_string())
    return 0


if __name__ == "__main__":
    sys.exit(main())
