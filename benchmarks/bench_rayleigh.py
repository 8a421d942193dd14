"""Throughput of surfwave.rayleigh_c2 on 10^6 prestressed S tensors, one core.

Usage: python benchmarks/bench_rayleigh.py OUTDIR   -> OUTDIR/rayleigh_throughput.nc, .png

The S tensors are realistic: surfwave.point over FCC (001), in-plane hydrostatic stress,
both potentials and both directions on a strain grid spanning each stable range, tiled to
10^6 points. Knob: the batch size of the vectorised call (the method is a closed-form cubic
with root selection, so it has no accuracy knob). Error: max |c_R^2 - Eq. (20)| (the Cauchy
closed form, exact for pair forces with sigma_yy = 0) over the distinct points.
Target: >= 10^6 points per second.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402
from surfwave.continuum.rayleigh import cauchy_c2  # noqa: E402

N_POINTS = 10**6
BATCHES = [10**3, 10**4, 10**5]
TARGET = 1e6  # points per second
GRIDS = {"harmonic": (0.56, 1.30), "lj": (0.875, 1.11)}  # d/d0 ranges (stable, surface wave)


def realistic_S(n_per_case: int = 250) -> tuple[np.ndarray, np.ndarray]:
    """S tensors (times V, rho = 1) and the Eq. (20) reference, shape (n, 3, 3, 3, 3), (n,)."""
    S, ref = [], []
    for pot, (lo, hi) in GRIDS.items():
        grid = np.linspace(lo, hi, n_per_case)
        for direction in ("[100]", "[110]"):
            p = surfwave.point("fcc", "in_plane_hydrostatic", pot, direction, grid)
            S.append(p["S"])
            ref.append(cauchy_c2(p["c2_L_par"], p["c2_T_par"], p["c2_L_perp"], p["c2_T_perp"]))
    return np.concatenate(S), np.concatenate(ref)


def main(outdir: str) -> Path:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    S0, ref = realistic_S()
    c2 = surfwave.rayleigh_c2(S0)
    ok = np.isfinite(c2) & np.isfinite(ref)
    error = float(np.max(np.abs(c2[ok] - ref[ok])))
    print(f"{S0.shape[0]} distinct points, {ok.sum()} with a surface wave; "
          f"max |c_R^2 - Eq.(20)| = {error:.2e}")
    seconds = []
    for batch in BATCHES:
        S = np.ascontiguousarray(np.resize(S0, (batch,) + S0.shape[1:]))
        surfwave.rayleigh_c2(S[: min(batch, 100)])  # warm-up
        calls = N_POINTS // batch
        t0 = time.perf_counter()
        for _ in range(calls):
            surfwave.rayleigh_c2(S)
        seconds.append(time.perf_counter() - t0)
        print(f"batch {batch:>7}: {N_POINTS / seconds[-1]:.3g} points/s")
    seconds = np.array(seconds)
    rate = N_POINTS / seconds
    best = rate.max()
    i_def = int(np.flatnonzero(rate >= 0.9 * best)[0])  # smallest batch within 10 % of the best
    reason = (f"smallest batch within 10 % of the best throughput ({best:.3g} points/s); "
              f"larger batches only cost memory ({BATCHES[i_def] * 81 * 8 / 1e6:.0f} MB of S per batch). "
              f"Target 1e6 points/s {'met' if best >= TARGET else 'NOT met'}.")
    ds = xr.Dataset(
        {
            "time": ("batch", seconds, {"long_name": f"wall time for {N_POINTS} points, one core",
                                         "units": "s"}),
            "points_per_second": ("batch", rate, {"long_name": "throughput", "units": "s-1"}),
            "error": ("batch", np.full(len(BATCHES), error),
                      {"long_name": "max |c_R^2 - Eq. (20) Cauchy closed form| over the distinct points",
                       "units": "K d0^2/m"}),
        },
        coords={"batch": ("batch", BATCHES, {"long_name": "points per vectorised call",
                                              "units": "1"})},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: rayleigh_c2 throughput",
               "source": f"surfwave {surfwave.__version__}", "history": f"{time.ctime()}: bench_rayleigh.py",
               "method": "rayleigh_c2 (Eq. 17, closed-form cubic + root selection)",
               "knob": "batch", "default": BATCHES[i_def], "default_reason": reason,
               "n_points": N_POINTS, "n_distinct": int(S0.shape[0]), "target_points_per_second": TARGET},
    )
    nc = out / "rayleigh_throughput.nc"
    ds.to_netcdf(nc, engine="h5netcdf")
    fig, ax = plt.subplots(figsize=(5, 3.5))
    ax.semilogx(BATCHES, rate, "o-", label="rayleigh_c2, one core")
    ax.axhline(TARGET, color="tab:red", ls="--", label="target 10$^6$ points/s")
    ax.set_xlabel("batch size (points per call)")
    ax.set_ylabel("throughput (points/s)")
    ax.set_title(f"Rayleigh speed throughput on {N_POINTS:.0e} points")
    ax.set_ylim(0, max(best, TARGET) * 1.2)
    ax.legend()
    ax.grid(alpha=0.3)
    fig.savefig(out / "rayleigh_throughput.png", dpi=150, bbox_inches="tight")
    return nc


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__.split("\n\n")[1])
    main(sys.argv[1])
