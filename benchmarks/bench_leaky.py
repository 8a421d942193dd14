"""Throughput of surfwave.solvers.leaky.leaky_wave against stroh.surface_wave in the same run.

Run: OMP_NUM_THREADS=1 PYTHONPATH=src python benchmarks/bench_leaky.py [m]
Prints orientations per second (one core) for Cu(001) (elastic, 6 x 6) and rotated Y-cut
X-propagating LiNbO3 (piezoelectric, 8 x 8, free and metallized), and the ratio to the subsonic
solver stroh.surface_wave on the same elastic tensors.
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests" / "solvers"))

from piezo_data import rotated  # noqa: E402

from surfwave.solvers import orientation, stroh, tensors  # noqa: E402
from surfwave.solvers.leaky import leaky_wave  # noqa: E402


def rate(fn, m: int, repeat: int = 2) -> float:
    """Best of ``repeat`` runs: calls per second of fn() doing m orientations."""
    best = np.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return m / best


def main(m: int = 400) -> None:
    ang = np.linspace(30.0, 45.0, m)
    C = tensors.voigt_to_tensor(tensors.cubic_voigt(168.4e9, 121.4e9, 75.4e9))
    A = tensors.rotate4(C, orientation.lab_axes("(001)", ang))
    r_leaky = rate(lambda: leaky_wave(A, 8960.0), m)
    r_stroh = rate(lambda: stroh.surface_wave(A, 8960.0), m)
    print(f"Cu(001), {m} angles 30..45 deg")
    print(f"  leaky_wave (elastic)      {r_leaky:9.0f} orientations/s")
    print(f"  stroh.surface_wave        {r_stroh:9.0f} orientations/s   (leaky / stroh = {r_leaky / r_stroh:.3f})")
    th = np.linspace(40.0, 80.0, m)
    Ap, e, eps, rho = rotated("LiNbO3", 0 * th, th - 90, 0 * th)
    for el in ("free", "metallized"):
        r = rate(lambda: leaky_wave(Ap, rho, e, eps, electrical=el), m)
        print(f"  LiNbO3 rotated Y-X, {el:10s} {r:9.0f} orientations/s   (/ stroh on Cu = {r / r_stroh:.3f})")


if __name__ == "__main__":
    main(int(sys.argv[1]) if len(sys.argv) > 1 else 400)
