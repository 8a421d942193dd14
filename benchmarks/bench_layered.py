"""Layered stacks: all subsonic modes of one film on a crystal at 200 kh, against material() at 200 angles.

Usage: python benchmarks/bench_layered.py [OUTDIR]   -> prints a table; OUTDIR/bench_layered.json

Cases (one core, CPU time of this process, numpy pinned to one thread):

* ``Si(001)[100] + SiO2``: 1 um fused silica on Si (001) along [100] (mirror: sagittal and SH
  families), surfwave.layered at 200 kh in [0, 5] in one call;
* ``Si(001)20deg + SiO2``: the same at 20 degrees from [100] (no mirror: one coupled family);
* yardstick: surfwave.material("Si", direction=200 angles in [0, 90]) in the same round.

Each round runs all three in a rotating order so the load of the shared machine hits them alike;
reported: min / median / max over REPEATS rounds of the time per call, the ratio to the yardstick
of the same round, full curves per second (one curve = all modes at all 200 kh) and the number of
(kh, mode) points found. Targets (issue 26): >= 10 curves per second per core, <= 10x material().
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import surfwave  # noqa: E402

REPEATS = 7
KH = np.linspace(0.0, 5.0, 200)
ANGLES = np.linspace(0.0, 90.0, 200)
FILM = [{"name": "SiO2", "thickness": 1e-6}]
CASES = {
    "Si(001)[100] + SiO2": lambda: surfwave.layered("Si", FILM, direction="[100]", kh=KH),
    "Si(001)20deg + SiO2": lambda: surfwave.layered("Si", FILM, direction=20.0, kh=KH),
    "material(Si, 200 angles)": lambda: surfwave.material("Si", direction=ANGLES),
}
YARD = "material(Si, 200 angles)"


def run() -> dict:
    """Time every case REPEATS times (rotating order); per-round ratios to the yardstick."""
    names = list(CASES)
    times: dict[str, list[float]] = {n: [] for n in names}
    found: dict[str, int] = {}
    for name in names:                                   # warm-up (imports, caches)
        CASES[name]()
    for r in range(REPEATS):
        order = names[r % len(names):] + names[:r % len(names)]
        for name in order:
            t0 = time.process_time()
            out = CASES[name]()
            times[name].append(time.process_time() - t0)
            if name != YARD:
                found[name] = int(np.isfinite(out["c"]).sum())
    res = {}
    for name in names:
        t = np.array(times[name])
        ratio = t / np.array(times[YARD])
        res[name] = {"seconds": [float(t.min()), float(np.median(t)), float(t.max())],
                     "ratio_to_material": [float(ratio.min()), float(np.median(ratio)), float(ratio.max())],
                     "curves_per_second": float(1.0 / np.median(t)), "points": found.get(name)}
    return res


def main(argv: list[str]) -> int:
    """Run, print the table, write OUTDIR/bench_layered.json when OUTDIR is given."""
    res = run()
    print(f"{'case':28s} {'s/call (min/med/max)':>26s} {'x material (min/med/max)':>28s} {'curves/s':>9s} {'points':>7s}")
    for name, v in res.items():
        s, q = v["seconds"], v["ratio_to_material"]
        print(f"{name:28s} {s[0]:8.4f} {s[1]:8.4f} {s[2]:8.4f} {q[0]:9.2f} {q[1]:9.2f} {q[2]:9.2f} "
              f"{v['curves_per_second']:9.1f} {v['points'] if v['points'] is not None else '':>7}")
    if argv:
        out = Path(argv[0])
        out.mkdir(parents=True, exist_ok=True)
        (out / "bench_layered.json").write_text(json.dumps(res, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
