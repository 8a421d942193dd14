"""Throughput of the piezoelectric SAW solver (solvers.piezo) against the elastic one, one core.

Usage: python benchmarks/bench_piezo.py [N]   -> prints one JSON line

Orientations: N (default 2000) random SAW Euler angles of LiNbO3 (Warner, Onoe, Coquin, JASA 42,
1223 (1967) constants, as in tests/solvers/test_piezo.py), lab-frame tensors built once. Timed
(interleaved, REPEATS rounds): solvers.stroh.surface_wave on the same A (elastic, e ignored),
piezo_surface_wave free, metallized (one vectorised call each) and coupling_coefficient (both
conditions in one call, sharing the limiting speed and first step). Reported: orientations per
second (min / median / max over the rounds) and the time ratios to the elastic solver of the
same round. CPU time of this process (time.process_time: single-threaded numpy, so it is
the time on one core; wall time on the shared machine includes waiting for a core).
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
from surfwave.solvers.piezo import EPS0, coupling_coefficient, euler_lab_axes, piezo_surface_wave  # noqa: E402

REPEATS = 7


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

    # interleaved so that the load of the shared machine hits all alike; per round the ratio
    # to the elastic solver's time measured right next to it; CPU and wall time
    cpu, wall = np.zeros((REPEATS, 4)), np.zeros((REPEATS, 4))
    calls = (lambda: stroh.surface_wave(A, rho),
             lambda: piezo_surface_wave(A, el, ep, rho, electrical="free"),
             lambda: piezo_surface_wave(A, el, ep, rho, electrical="metallized"),
             lambda: coupling_coefficient(A, el, ep, rho))
    for i in range(REPEATS):
        out = []
        for j, f in enumerate(calls):
            c0, w0 = time.process_time(), time.perf_counter()
            out.append(f())
            cpu[i, j], wall[i, j] = time.process_time() - c0, time.perf_counter() - w0
    _, rf, rm, k = out
    t_el, t_free, t_met, t_pair = cpu.T
    found = np.isfinite(rf["c"]) & np.isfinite(rm["c"])

    def mmm(x):
        return [float(np.min(x)), float(np.median(x)), float(np.max(x))]

    return {
        "orientations": n,
        "repeats": REPEATS,
        "found_both": int(found.sum()),
        "free_per_s_min_med_max": mmm(n / t_free),
        "metallized_per_s_min_med_max": mmm(n / t_met),
        "coupling_pair_per_s_min_med_max": mmm(n / t_pair),
        "elastic_per_s_min_med_max": mmm(n / t_el),
        "ratio_free_over_elastic_min_med_max": mmm(t_free / t_el),
        "ratio_metallized_over_elastic_min_med_max": mmm(t_met / t_el),
        "ratio_pair_over_elastic_min_med_max": mmm(t_pair / t_el),
        "wall_ratio_free_metallized_pair_over_elastic_median": [float(np.median(wall[:, j] / wall[:, 0]))
                                                                for j in (1, 2, 3)],
        "K2_median": float(np.median(2 * (rf["c"] - rm["c"])[found] / rf["c"][found])),
        "pair_equals_separate": bool(np.allclose(k["c_free"], rf["c"], rtol=1e-13, equal_nan=True)
                                     and np.allclose(k["c_metallized"], rm["c"], rtol=1e-13, equal_nan=True)),
    }


if __name__ == "__main__":
    print(json.dumps(main(int(sys.argv[1]) if len(sys.argv) > 1 else 2000)))
