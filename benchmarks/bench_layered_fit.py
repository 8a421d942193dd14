"""Thin-film metrology: coverage of the fitted uncertainties and the time of a fit.

Usage: python benchmarks/bench_layered_fit.py [N_SEEDS] [OUTDIR]   -> table; OUTDIR/bench_layered_fit.json

1. Coverage: N_SEEDS (default 200) synthetic data sets, 1 um fused silica on Si (001)[100], 8 Rayleigh
   speeds at kh 0.5 ... 5 with 0.1 % Gaussian noise (seeds 0 ... N-1); E and nu fitted from
   (62 GPa, 0.25). Reported: the fraction of fits with the truth within 2 sigma in both parameters
   (target: >= 90 %; 95.4 % expected for a linear model), and of each parameter alone.
2. Speed: a 5-parameter fit (E, nu, rho, thickness of the top film and E of a second film) to 50
   points at kh 0.2 ... 5 of a two-film stack, from 5 % off, CPU time (target: < 2 s), against one
   call of surfwave.material("Si", 200 angles) in the same run.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"

import json  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import surfwave  # noqa: E402
from surfwave.layers.fit import fit_film  # noqa: E402

FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}


def coverage(n: int) -> dict:
    """Fraction of seeded fits whose truth lies within 2 sigma."""
    kh = np.linspace(0.5, 5.0, 8)
    truth = surfwave.layered("Si", [FILM], kh=kh)["c"][:, 0]
    both = e_in = nu_in = 0
    t0 = time.process_time()
    for seed in range(n):
        rng = np.random.default_rng(seed)
        data = {"kh": kh, "c": truth * (1 + 1e-3 * rng.standard_normal(kh.size)), "sigma": 1e-3 * truth}
        r = fit_film("Si", [{**FILM, "E": 62.0, "nu": 0.25}], data, ["E", "nu"])
        z = np.abs(r["values"] - [73.0, 0.17]) / r["uncertainty"]
        both += bool(np.all(z < 2))
        e_in += bool(z[0] < 2)
        nu_in += bool(z[1] < 2)
    return {"fits": n, "within_2_sigma_both": both / n, "within_2_sigma_E": e_in / n, "within_2_sigma_nu": nu_in / n,
            "seconds_per_fit": (time.process_time() - t0) / n}


def five_parameter_fit() -> dict:
    """A 5-parameter fit to 50 points: CPU seconds and the ratio to material() at 200 angles."""
    films = [dict(FILM), {"E": 200.0, "nu": 0.24, "rho": 3200.0, "thickness": 3e-7}]
    kh = np.linspace(0.2, 5.0, 50)
    truth = surfwave.layered("Si", films, kh=kh)["c"][:, 0]
    rng = np.random.default_rng(1)
    data = {"kh": kh, "c": truth * (1 + 1e-3 * rng.standard_normal(kh.size)), "sigma": 1e-3 * truth}
    start = [{**films[0], "E": 73.0 * 1.05, "nu": 0.18, "rho": 2200 * 0.95, "thickness": 1.05e-6},
             {**films[1], "E": 190.0}]
    t0 = time.process_time()
    r = fit_film("Si", start, data, ["E", "nu", "rho", "thickness", "1.E"])
    t_fit = time.process_time() - t0
    t0 = time.process_time()
    surfwave.material("Si", direction=np.linspace(0, 90, 200))
    t_mat = time.process_time() - t0
    return {"seconds": t_fit, "ratio_to_material": t_fit / t_mat, "values": r["values"].tolist(),
            "uncertainty": r["uncertainty"].tolist(), "message": r["message"], "converged": r["converged"]}


def main(argv: list[str]) -> int:
    """Run both parts, print them, write JSON when OUTDIR is given."""
    n = int(argv[0]) if argv else 200
    res = {"coverage": coverage(n), "five_parameter_fit": five_parameter_fit()}
    print(json.dumps(res, indent=1))
    if len(argv) > 1:
        out = Path(argv[1])
        out.mkdir(parents=True, exist_ok=True)
        (out / "bench_layered_fit.json").write_text(json.dumps(res, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
