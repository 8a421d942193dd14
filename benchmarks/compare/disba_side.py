"""The disba side of benchmarks/compare/layered_vs_disba.py (run by it under $DISBA_PYTHON, which has disba).

Reads a JSON job on stdin: layers (thickness km, vp, vs km/s, density g/cm^3; last = half-space),
periods (s), modes, waves, repeats; prints JSON: per (wave, mode) the phase speeds (km/s, NaN where
the mode does not exist), and the CPU seconds of each round (one round = every requested curve,
``round_seconds``, one entry per repeat).
"""
from __future__ import annotations

import json
import sys
import time

import numpy as np
from disba import PhaseDispersion


def main() -> int:
    """Run the job of stdin."""
    job = json.load(sys.stdin)
    lay = np.array(job["layers"], dtype=float)
    t = np.array(job["periods"], dtype=float)
    pd = PhaseDispersion(*lay.T, dc=job.get("dc", 0.005))
    curves = [(wave, mode) for wave in job["waves"] for mode in job["modes"]]
    out: dict = {}
    for wave, mode in curves:                                    # compile (numba) outside the timing
        r = pd(t, mode=mode, wave=wave)
        c = np.full(t.size, np.nan)
        c[np.searchsorted(t, r.period)] = r.velocity
        out[f"{wave}{mode}"] = {"c": [None if not np.isfinite(x) else float(x) for x in c]}
    rounds = []
    for _ in range(job["repeats"]):
        t0 = time.process_time()
        for wave, mode in curves:
            pd(t, mode=mode, wave=wave)
        rounds.append(time.process_time() - t0)
    out["round_seconds"] = rounds
    json.dump(out, sys.stdout)
    return 0


if __name__ == "__main__":
    sys.exit(main())
