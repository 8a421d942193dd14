"""Cost of ``surfwave.material`` against the bare solver it wraps, per direction, one core.

Usage: python benchmarks/bench_material.py OUTDIR   -> OUTDIR/material_overhead.nc, .png

``material()`` resolves its arguments and calls the one path
(:func:`surfwave.real_crystals.stressed_wave.surface_wave`: stressed state, traction check,
Born stability, the Stroh solve, bulk speeds, long-wave stability); the bare solver is
:func:`surfwave.solvers.stroh.surface_wave` on the same wave-propagation tensors A (Pa, lab
frame), built once outside the timing from the solvers and toec modules only. Both give the
same c_R (checked; the largest relative difference is stored). They run in the same process,
alternating which goes first, so machine load hits both alike; per pair the ratio of the CPU
times (time.process_time, numpy pinned to one thread); min / median / max over the pairs.
Target (issue 21 item 2): the median ratio <= 1.5 in every case.

Cases: Cu (001) unstressed (the default call), at 0.2 GPa along the propagation (fixed
constants), and at 0.2 GPa with third-order constants; each with BATCH angles (0-45 deg) in one
call and with one angle (10 deg) per call.

Piezoelectric rows (issue 25): ``material("LiNbO3-Warner1967", euler=E, leaky=False)`` on BATCH
random SAW Euler angles (seed 0) against its bare solver,
:func:`surfwave.solvers.piezo_saw.piezo_saw_conditions` (the free condition; both conditions'
subsonic searches, as material() runs them for K^2) on the same lab tensors built outside the
timing, and against the elastic ``material("Cu", angle=...)`` on as many directions. Targets:
material / its solver <= 1.3, piezoelectric / elastic material() <= 3.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402
from surfwave.real_crystals.materials import get_material  # noqa: E402
from surfwave.real_crystals.piezo_materials import lab_tensors  # noqa: E402
from surfwave.real_crystals.toec import deformed_axes, stressed_state  # noqa: E402
from surfwave.solvers import stroh  # noqa: E402
from surfwave.solvers.euler import euler_lab_axes  # noqa: E402
from surfwave.solvers.orientation import lab_axes  # noqa: E402
from surfwave.solvers.piezo_saw import piezo_saw_conditions  # noqa: E402
from surfwave.solvers.tensors import rotate2, rotate4  # noqa: E402

BATCH = 200
PAIRS = {BATCH: 15, 1: 100}  # timed pairs per angles-per-call
TARGET = 1.5
STRESS_CASES = [(0.0, False), (0.2, False), (0.2, True)]  # (GPa along the propagation, TOEC)
PIEZO = "LiNbO3-Warner1967"
PIEZO_PAIRS = 9
PIEZO_TARGET, PIEZO_ELASTIC_TARGET = 1.3, 3.0


def _tensors(angles, stress: float, use_toec: bool):
    """A (Pa) and rho of Cu (001) at these angles: the bare solver's input (built from the
    solvers and toec modules only, so the script also times the code before the one path)."""
    cu = get_material("Cu")
    R = lab_axes("(001)", angles).reshape(-1, 3, 3)
    sigma = stress * np.einsum("ai,aj->aij", R[:, 0], R[:, 0])
    st = stressed_state(cu.voigt, cu.toec_voigt if use_toec else None, sigma, cu.rho)
    lab = deformed_axes(st["F"], R)
    s_lab = rotate2(sigma, lab)
    s_lab[:, 1, :] = s_lab[:, :, 1] = 0.0
    A = stroh.wave_propagation_tensor(rotate4(st["C_star"], lab) * 1e9, s_lab * 1e9)
    return A, st["rho"]


def _cpu(f) -> float:
    t0 = time.process_time()
    f()
    return time.process_time() - t0


def bench(n_angles: int, stress: float, use_toec: bool, pairs: int) -> tuple[np.ndarray, np.ndarray, float]:
    """CPU seconds per direction (pairs,) of material() and of the bare solver; max |dc/c|."""
    angles = np.linspace(0.0, 45.0, n_angles) if n_angles > 1 else 10.0
    A, rho = _tensors(angles, stress, use_toec)
    if n_angles == 1:
        A, rho = A[0], rho[0]
    api = lambda: surfwave.material("Cu", angle=angles, stress=stress, toec=use_toec)  # noqa: E731
    bare = lambda: stroh.surface_wave(A, rho)  # noqa: E731
    c_api, c_bare = np.atleast_1d(api()["c_R"]), np.atleast_1d(bare()["c"])   # also the warm-up
    np.testing.assert_allclose(c_api, c_bare, rtol=1e-12)                   # the same answer
    diff = float(np.nanmax(np.abs(c_api / c_bare - 1.0)))
    t = np.zeros((2, pairs))
    for r in range(pairs):   # alternating which goes first: load on the machine hits both alike
        for j in ((0, 1) if r % 2 == 0 else (1, 0)):
            t[j, r] = _cpu((api, bare)[j])
    return t[0] / n_angles, t[1] / n_angles, diff


def bench_piezo(n: int, pairs: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """CPU seconds per orientation (pairs,) of material() on a piezoelectric crystal, of its bare
    solver on the same tensors and of the elastic material() on as many directions; max |dc/c|."""
    rng = np.random.default_rng(0)
    E = np.column_stack([rng.uniform(0, 360, n), rng.uniform(0, 180, n), rng.uniform(0, 360, n)])
    t = lab_tensors(PIEZO, euler_lab_axes(E))
    A = stroh.wave_propagation_tensor(t["C"], np.zeros((n, 3, 3)))
    rho = np.full(n, t["rho"])
    angles = np.linspace(0.0, 45.0, n)
    api = lambda: surfwave.material(PIEZO, euler=E, leaky=False)  # noqa: E731
    bare = lambda: piezo_saw_conditions(A, rho, t["e"], t["eps"], conditions=("free",), leaky=False)  # noqa: E731
    elastic = lambda: surfwave.material("Cu", angle=angles)  # noqa: E731
    c_api, c_bare = api()["c_R"], bare()["free"]["c"]
    elastic()
    np.testing.assert_allclose(c_api, c_bare, rtol=1e-12)
    diff = float(np.nanmax(np.abs(c_api / c_bare - 1.0)))
    tt = np.zeros((3, pairs))
    for r in range(pairs):   # rotating order: load on the machine hits all three alike
        for j in np.roll(np.arange(3), r):
            tt[j, r] = _cpu((api, bare, elastic)[j])
    return tt[0] / n, tt[1] / n, tt[2] / n, diff


def main(outdir: str) -> Path:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    batches = [BATCH, 1]
    names = [f"{s:g} GPa{' TOEC' if toec else ''}" for s, toec in STRESS_CASES]
    npair = max(PAIRS.values())
    t_api = np.full((len(batches), len(STRESS_CASES), npair), np.nan)
    t_bare = np.full_like(t_api, np.nan)
    diff = np.zeros((len(batches), len(STRESS_CASES)))
    for b, n in enumerate(batches):
        for s, (stress, use_toec) in enumerate(STRESS_CASES):
            a, bb, diff[b, s] = bench(n, stress, use_toec, PAIRS[n])
            t_api[b, s, :PAIRS[n]], t_bare[b, s, :PAIRS[n]] = a, bb
    ratio = t_api / t_bare
    q = np.stack([np.nanmin(ratio, -1), np.nanmedian(ratio, -1), np.nanmax(ratio, -1)], -1)  # (batch, case, 3)
    worst = float(q[..., 1].max())
    rows = []
    for b, n in enumerate(batches):
        parts = [f"{names[s]}: {q[b, s, 1]:.2f} ({q[b, s, 0]:.2f} / {q[b, s, 1]:.2f} / {q[b, s, 2]:.2f}; "
                 f"{np.nanmedian(t_api[b, s]) * 1e6:.3g} vs {np.nanmedian(t_bare[b, s]) * 1e6:.3g} us per direction)"
                 for s in range(len(STRESS_CASES))]
        w = float(q[b, :, 1].max())
        rows.append([
            "`surfwave.material` (one path: stressed state, traction and Born checks, Stroh solve, bulk speeds) "
            "against the bare `stroh.surface_wave` on the same tensors, Cu (001)",
            "angles per call", f"{n}",
            "identical c_R (bit for bit)" if diff[b].max() == 0 else f"the same c_R to {diff[b].max():.1g} relative",
            f"time ratio material / bare, median (min / median / max over {PAIRS[n]} pairs, CPU, one core): "
            + "; ".join(parts),
            f"target median <= {TARGET:g} x the bare solver per direction (issue 21): "
            f"{'met' if w <= TARGET else 'NOT met'} (worst case {w:.2f})"])
    p_api, p_bare, p_el, p_diff = bench_piezo(BATCH, PIEZO_PAIRS)
    pq = [np.median(p_api / p_bare), np.median(p_api / p_el)]
    rows.append([
        f"`surfwave.material` on a piezoelectric crystal ({PIEZO}, free surface, leaky=False, {BATCH} random "
        "Euler angles in one call) against its bare solver `piezo_saw_conditions` on the same tensors, and "
        "against the elastic `material(\"Cu\", angle=...)` on as many directions",
        "orientations per call", f"{BATCH}",
        "identical c_R (bit for bit)" if p_diff == 0 else f"the same c_R to {p_diff:.1g} relative",
        f"time ratio, median over {PIEZO_PAIRS} rounds (CPU, one core): material / its solver {pq[0]:.2f} "
        f"(min {np.min(p_api / p_bare):.2f}, max {np.max(p_api / p_bare):.2f}; {np.median(p_api) * 1e6:.3g} vs "
        f"{np.median(p_bare) * 1e6:.3g} us per orientation); piezoelectric / elastic material() {pq[1]:.2f}",
        f"targets <= {PIEZO_TARGET:g} x its solver and <= {PIEZO_ELASTIC_TARGET:g} x the elastic material() "
        f"(issue 25): {'met' if pq[0] <= PIEZO_TARGET and pq[1] <= PIEZO_ELASTIC_TARGET else 'NOT met'}"])
    for row in rows:
        print(" | ".join(row))
    print(f"worst median ratio: {worst:.2f} (target <= {TARGET:g})")

    dims = ("angles_per_call", "case", "pair")
    ds = xr.Dataset(
        {
            "time_material": (dims, t_api, {"long_name": "CPU time of surfwave.material per direction", "units": "s"}),
            "time_bare": (dims, t_bare, {"long_name": "CPU time of stroh.surface_wave per direction, same A",
                                         "units": "s"}),
            "ratio": (dims, ratio, {"long_name": "material / bare CPU time, one pair", "units": "1"}),
            "ratio_stats": (("angles_per_call", "case", "stat"), q,
                            {"long_name": "material / bare CPU time over the pairs", "units": "1"}),
            "c_R_difference": (("angles_per_call", "case"), diff,
                               {"long_name": "max |c_R(material) / c(bare) - 1|", "units": "1"}),
            "piezo_time_material": ("piezo_round", p_api, {"long_name": f"CPU time of surfwave.material on {PIEZO} "
                                                           "per orientation (free, leaky=False)", "units": "s"}),
            "piezo_time_bare": ("piezo_round", p_bare, {"long_name": "CPU time of piezo_saw_conditions per "
                                                        "orientation, same tensors", "units": "s"}),
            "piezo_time_elastic_material": ("piezo_round", p_el, {"long_name": "CPU time of the elastic "
                                                                  "surfwave.material (Cu) per direction",
                                                                  "units": "s"}),
        },
        coords={"angles_per_call": batches, "case": ("case", names, {"long_name": "Cu (001), stress along the "
                                                                     "propagation (GPa), TOEC: deforming crystal"}),
                "pair": np.arange(npair), "stat": ["min", "median", "max"], "piezo_round": np.arange(PIEZO_PAIRS)},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: cost of surfwave.material over the bare solver",
               "source": f"surfwave {surfwave.__version__}", "history": f"{time.ctime()}: bench_material.py",
               "method": "surfwave.material", "knob": "angles_per_call", "default": BATCH,
               "default_reason": rows[0][-1], "target_ratio": TARGET, "worst_median_ratio": worst,
               "readme_rows": json.dumps(rows)},
    )
    nc = out / "material_overhead.nc"
    ds.to_netcdf(nc, engine="h5netcdf")

    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8), layout="constrained")
    x = np.arange(len(STRESS_CASES))
    for b, (n, col) in enumerate(zip(batches, ("tab:blue", "tab:orange"))):
        xb = x + (b - 0.5) * 0.35
        axes[0].bar(xb, q[b, :, 1], 0.35, color=col, label=f"{n} angle(s) per call",
                    yerr=[q[b, :, 1] - q[b, :, 0], q[b, :, 2] - q[b, :, 1]], capsize=3)
        axes[1].bar(xb, np.nanmedian(t_api[b], -1) * 1e6, 0.35, color=col, label=f"material, {n}/call")
        axes[1].scatter(xb, np.nanmedian(t_bare[b], -1) * 1e6, color="k", marker="_", s=300, zorder=3,
                        label="bare solver" if b == 0 else None)
    axes[0].axhline(TARGET, color="tab:red", ls="--", label=f"target {TARGET:g}")
    axes[0].axhline(1.0, color="gray", lw=0.8)
    axes[0].set_ylabel("CPU time material / bare (median, min-max bars)")
    axes[1].set_yscale("log")
    axes[1].set_ylabel("CPU time per direction (us, median)")
    for ax in axes:
        ax.set_xticks(x, [f"Cu (001)\n{nm}" for nm in names])
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y", which="both")
    fig.suptitle("surfwave.material against stroh.surface_wave on the same tensors, one core")
    fig.savefig(out / "material_overhead.png", dpi=150, bbox_inches="tight")
    return nc


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__.split("\n\n")[1])
    main(sys.argv[1])
