"""Throughput of the piezoelectric SAW solver (solvers.piezo) against the elastic one, one core.

Usage: python benchmarks/bench_piezo.py [N]   -> prints one JSON line

Orientations: N (default 2000) random SAW Euler angles of LiNbO3 (Warner, Onoe, Coquin, JASA 42,
1223 (1967) constants, as in tests/solvers/test_piezo.py), lab-frame tensors built once. Timed:
piezo_surface_wave free + metallized (one call each, vectorised), and
solvers.stroh.surface_wave on the same A (elastic, e ignored) in the same run. Reported:
orientations per second for the pair (free + metallized), per condition, the elastic solver's,
and the time ratio piezo (one condition) / elastic. Median of REPEATS; the machine is shared.
Target (brief): >= 1e4 orientations/s/core.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from surfwave.solvers import stroh  # noqa: E402
from surfwave.solvers.tensors import VOIGT_INDEX, rotate2, rotate4, voigt_to_tensor  # noqa: E402
from surfwave.solvers.piezo import EPS0, euler_lab_axes, piezo_surface_wave  # noqa: E402

REPEATS = 3


def linbo3():
    """(C Pa, e_kij C/m^2, eps F/m, rho kg/m^3) of LiNbO3, crystal axes (3m standard forms)."""
    C11, C12, C13, C14, C33, C44 = 203.0, 53.0, 75.0, 9.0, 245.0, 60.0
    C = np.zeros((6, 6))
    C[0, 0] = C[1, 1] = C11
    C[0, 1] = C[1, 0] = C12
    C[0, 2] = C[2, 0] = C[1, 2] = C[2, 1] = C13
    C[2, 2], C[3, 3], C[4, 4], C[5, 5] = C33, C44, C44, 0.5 * (C11 - C12)
    C[0, 3] = C[3, 0] = C[4, 5] = C[5, 4] = C14
    C[1, 3] = C[3, 1] = -C14
    e15, e22, e31, e33 = 3.7, 2.5, 0.2, 1.3
    e6 = np.array([[0, 0, 0, 0, e15, -e22], [-e22, e22, 0, e15, 0, 0], [e31, e31, e33, 0, 0, 0]])
    return voigt_to_tensor(C * 1e9), e6[:, VOIGT_INDEX], np.diag([44.0, 44.0, 29.0]) * EPS0, 4700.0


def main(n: int = 2000) -> dict:
    rng = np.random.default_rng(0)
    R = euler_lab_axes(rng.uniform(0, 360, n), rng.uniform(0, 180, n), rng.uniform(0, 360, n))
    C, e, eps, rho = linbo3()
    A = rotate4(C, R)
    el = np.einsum("mai,mbj,mck,ijk->mabc", R, R, R, e)
    ep = rotate2(eps, R)

    def timed(f):
        ts = []
        for _ in range(REPEATS):
            t0 = time.perf_counter()
            out = f()
            ts.append(time.perf_counter() - t0)
        return float(np.median(ts)), out

    t_free, rf = timed(lambda: piezo_surface_wave(A, el, ep, rho, electrical="free"))
    t_met, rm = timed(lambda: piezo_surface_wave(A, el, ep, rho, electrical="metallized"))
    t_el, _ = timed(lambda: stroh.surface_wave(A, rho))
    found = np.isfinite(rf["c"]) & np.isfinite(rm["c"])
    return {
        "orientations": n,
        "found_both": int(found.sum()),
        "pairs_per_s": n / (t_free + t_met),
        "free_per_s": n / t_free,
        "metallized_per_s": n / t_met,
        "elastic_per_s": n / t_el,
        "ratio_piezo_one_condition_over_elastic": 0.5 * (t_free + t_met) / t_el,
        "K2_median": float(np.median(2 * (rf["c"] - rm["c"])[found] / rf["c"][found])),
    }


if __name__ == "__main__":
    print(json.dumps(main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)))
