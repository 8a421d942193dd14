"""Layered stacks: all subsonic modes of one film on a crystal at 200 kh, against material() at 200 angles.

Usage: python benchmarks/bench_layered.py OUTDIR   -> OUTDIR/layered_speed.nc, .png

Cases (one core, CPU time of this process, numpy pinned to one thread):

* ``Si(001)[100] + SiO2``: 1 um fused silica on Si (001) along [100] (mirror: sagittal and SH
  families), ``surfwave.layered`` at N_KH kh in [0, 5] in one call;
* ``Si(001)20deg + SiO2``: the same at 20 degrees from [100] (no mirror: one coupled family);
* ``isotropic film, modes=2``: the isotropic stack of ``benchmarks/compare/layered_vs_disba.py``
  (1 um of E 73 GPa, nu 0.17, rho 2200 on E 400 GPa, nu 0.25, rho 3500; the exact isotropic path)
  at N_FREQ frequencies (disba's 200 periods 0.05 ... 2 s as 1e9 / T Hz), ``modes=2`` (R, S1, L0,
  L1): the question that comparison times, here against the same-run yardstick (no target of its
  own: issue 26 asks "as fast or faster" than disba, measured there);
* yardstick: ``surfwave.material("Si", direction=N_ANGLES angles in [0, 90])`` (the bare
  substrate) in the same round.

Each round runs all three in a rotating order so the load of the shared machine hits them alike;
reported: min / median / max over REPEATS rounds of the time per call, the ratio to the yardstick
of the same round, full curves per second (one curve = all modes at all kh, from the median time)
and the number of (kh, mode) points found (the same in every round: checked). Targets (issue 26):
>= 10 curves per second per core and <= 10 x material() (median ratio).
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from collections.abc import Callable  # noqa: E402
from pathlib import Path  # noqa: E402
from typing import Any  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402

REPEATS = 7
N_KH = 200
N_ANGLES = 200
N_FREQ = 200
KH_MAX = 5.0
FILM = [{"name": "SiO2", "thickness": 1e-6}]
TARGET_CURVES, TARGET_RATIO = 10.0, 10.0
CASES: dict[str, tuple[str | float, str]] = {  # name -> (direction, description)
    "Si(001)[100] + SiO2": ("[100]", "along [100] (mirror: sagittal and SH families)"),
    "Si(001)20deg + SiO2": (20.0, "at 20 degrees from [100] (no mirror: one coupled family)"),
}
#: The isotropic case (the stack of benchmarks/compare/layered_vs_disba.py).
ISO_CASE = "isotropic film, modes=2"
ISO_FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}
ISO_HALF = {"E": 400.0, "nu": 0.25, "rho": 3500.0}


def _calls() -> dict[str, Callable[[], Any]]:
    """The timed calls at the current sizes; the yardstick last."""
    kh = np.linspace(0.0, KH_MAX, N_KH)
    angles = np.linspace(0.0, 90.0, N_ANGLES)

    def stack(direction: str | float) -> Callable[[], Any]:
        return lambda: surfwave.layered("Si", FILM, direction=direction, kh=kh)

    calls = {name: stack(d) for name, (d, _) in CASES.items()}
    freq = 1e9 / np.linspace(0.05, 2.0, N_FREQ)
    calls[ISO_CASE] = lambda: surfwave.layered(ISO_HALF, [ISO_FILM], frequency=freq, modes=2)
    calls["yardstick"] = lambda: surfwave.material("Si", direction=angles)
    return calls


def run() -> tuple[np.ndarray, np.ndarray]:
    """CPU seconds per call (case + yardstick, REPEATS) in rotating order; (kh, mode) points per case."""
    calls = _calls()
    names = list(calls)
    points = np.array([np.isfinite(calls[n]()["c"]).sum() for n in names[:-1]])  # also the warm-up
    t = np.zeros((len(names), REPEATS))
    for r in range(REPEATS):
        for j in np.roll(np.arange(len(names)), r):
            t0 = time.process_time()
            out = calls[names[j]]()
            t[j, r] = time.process_time() - t0
            if j < len(names) - 1 and np.isfinite(out["c"]).sum() != points[j]:
                raise RuntimeError(f"{names[j]}: a different number of (kh, mode) points in round {r}")
    return t, points


def _stats(x: np.ndarray) -> np.ndarray:
    return np.stack([x.min(-1), np.median(x, -1), x.max(-1)], -1)


def main(outdir: str) -> Path:
    """Run, write OUTDIR/layered_speed.nc (with readme_rows) and the PNG; returns the cube's path."""
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    t, points = run()
    ratio = t[:-1] / t[-1]
    ts, qs = _stats(t), _stats(ratio)                    # (case + yard, 3), (case, 3)
    curves = 1.0 / ts[:-1, 1]
    yard_ms = ts[-1, 1] * 1e3
    rows = []
    names = list(CASES) + [ISO_CASE]
    for i, (_, where) in enumerate(CASES.values()):
        met = curves[i] >= TARGET_CURVES and qs[i, 1] <= TARGET_RATIO
        verdict = "met" if met else "NOT met" + (
            f" (curves/s {'met' if curves[i] >= TARGET_CURVES else 'missed'}, "
            f"ratio {'met' if qs[i, 1] <= TARGET_RATIO else 'missed'})")
        rows.append([
            f"`surfwave.layered`, every subsonic mode of 1 um SiO2 on Si (001) {where}: speeds, labels, "
            f"group velocities, power-flow angles, {N_KH} kh in [0, {KH_MAX:g}] in one call",
            "kh per call", f"{N_KH}",
            f"{int(points[i])} (kh, mode) points found, the same in every round (accuracy: tests/layers, "
            "docs/physics/layered.md)",
            f"{ts[i, 1]:.3g} s per call (min / median / max {ts[i, 0]:.3g} / {ts[i, 1]:.3g} / {ts[i, 2]:.3g} "
            f"over {REPEATS} rounds, CPU, one core) = {curves[i]:.3g} curves/s; {qs[i, 0]:.3g} / {qs[i, 1]:.3g} / "
            f"{qs[i, 2]:.3g} x `material(\"Si\")` at {N_ANGLES} angles timed in the same rounds "
            f"(median {yard_ms:.3g} ms)",
            f"targets >= {TARGET_CURVES:g} curves/s/core and <= {TARGET_RATIO:g} x material() (issue 26): "
            f"{verdict}"])
    i = names.index(ISO_CASE)
    rows.append([
        "`surfwave.layered`, isotropic 1 um film (E 73 GPa, nu 0.17) on an isotropic half-space (E 400 GPa, "
        f"nu 0.25), `modes=2` (R, S1, L0, L1) at {N_FREQ} frequencies in one call (the exact isotropic path; "
        "the question of benchmarks/compare/layered_vs_disba.py)",
        "frequencies per call", f"{N_FREQ}",
        f"{int(points[i])} (frequency, mode) points found, the same in every round (accuracy: tests/layers, "
        "benchmarks/compare/layered_vs_disba.py)",
        f"{ts[i, 1] * 1e3:.3g} ms per call (min / median / max {ts[i, 0] * 1e3:.3g} / {ts[i, 1] * 1e3:.3g} / "
        f"{ts[i, 2] * 1e3:.3g} over {REPEATS} rounds, CPU, one core); {qs[i, 0]:.3g} / {qs[i, 1]:.3g} / "
        f"{qs[i, 2]:.3g} x `material(\"Si\")` at {N_ANGLES} angles timed in the same rounds "
        f"(median {yard_ms:.3g} ms)",
        "no target of its own (issue 26: as fast as disba at equal accuracy, timed side by side in "
        "benchmarks/compare/layered_vs_disba.py)"])
    for row in rows:
        print(" | ".join(row))

    ds = xr.Dataset(
        {
            "time": (("case", "round"), t[:-1], {"long_name": "CPU time of one surfwave.layered call", "units": "s"}),
            "time_yardstick": ("round", t[-1], {"long_name": f"CPU time of surfwave.material('Si') at {N_ANGLES} "
                                                "angles, same round", "units": "s"}),
            "ratio": (("case", "round"), ratio, {"long_name": "layered / material() CPU time, one round",
                                                 "units": "1"}),
            "ratio_stats": (("case", "stat"), qs, {"long_name": "layered / material() CPU time over the rounds",
                                                   "units": "1"}),
            "curves_per_second": ("case", curves, {"long_name": "full curves (all modes at all kh) per second, "
                                                   "median time", "units": "s-1"}),
            "points": ("case", points, {"long_name": "(kh, mode) points found per call", "units": "1"}),
        },
        coords={"case": ("case", names, {"long_name": "stack and propagation direction"}),
                "round": np.arange(REPEATS), "stat": ["min", "median", "max"]},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: layered stacks against material()",
               "source": f"surfwave {surfwave.__version__}", "history": f"{time.ctime()}: bench_layered.py",
               "method": "surfwave.layered", "knob": "kh per call", "default": N_KH,
               "n_angles_yardstick": N_ANGLES, "target_curves_per_second": TARGET_CURVES,
               "target_ratio": TARGET_RATIO, "readme_rows": json.dumps(rows)},
    )
    nc = out / "layered_speed.nc"
    ds.to_netcdf(nc, engine="h5netcdf")

    fig, axes = plt.subplots(1, 2, figsize=(9, 3.6), layout="constrained")
    x = np.arange(len(names))
    axes[0].bar(x, qs[:, 1], 0.5, yerr=[qs[:, 1] - qs[:, 0], qs[:, 2] - qs[:, 1]], capsize=3)
    axes[0].axhline(TARGET_RATIO, color="tab:red", ls="--", label=f"target {TARGET_RATIO:g}")
    axes[0].set_ylabel("CPU time / material() (median, min-max)")
    axes[1].bar(x, curves, 0.5, color="tab:orange")
    axes[1].axhline(TARGET_CURVES, color="tab:red", ls="--", label=f"target {TARGET_CURVES:g}")
    axes[1].set_ylabel("curves per second (one core)")
    for ax in axes:
        ax.set_xticks(x, names)
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3, axis="y")
    fig.suptitle(f"surfwave.layered, all modes at {N_KH} kh, against material() at {N_ANGLES} angles")
    fig.savefig(out / "layered_speed.png", dpi=150, bbox_inches="tight")
    plt.close(fig)
    return nc


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__.split("\n\n")[1])
    main(sys.argv[1])
