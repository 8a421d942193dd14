"""surfwave.layered against disba (an established isotropic layered-media code from PyPI): speed at equal accuracy.

Not a `make bench` benchmark: disba (Dunkin's fast delta matrix, numba) is not in the locked
environment (it is no dependency), so its side runs in ``benchmarks/compare/disba_side.py`` under
the interpreter of a throwaway virtual environment given as ``$DISBA_PYTHON``. From the
repository root (``.venv`` is the project's environment, ``make env``)::

    python3 -m venv /tmp/disba-venv
    /tmp/disba-venv/bin/pip install disba==0.7.0
    DISBA_PYTHON=/tmp/disba-venv/bin/python .venv/bin/python benchmarks/compare/layered_vs_disba.py [OUTDIR]

It prints the table (OUTDIR, if given, receives ``layered_vs_disba.json``); then
``rm -rf /tmp/disba-venv``. Stack: a 1 km (disba) = 1 um (surfwave) isotropic layer (E 73 GPa,
nu 0.17, rho 2200 kg/m^3) on an isotropic half-space (E 400 GPa, nu 0.25, rho 3500 kg/m^3);
200 periods. The same dimensionless problem in both: kh = 2 pi H / (c T), so surfwave is asked at
f = 1e9 / T Hz with H = 1e-6 m. Compared: the fundamental Rayleigh and Love modes and their first
overtones; accuracy as the largest relative difference of the phase speeds; surfwave's own
accuracy is ~1e-11 (Love closed form, tests/layers), so the difference measures disba's. CPU time
on one core, min over REPEATS.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ[_v] = "1"

import json  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402

import surfwave  # noqa: E402
from surfwave.layers.stack import isotropic_voigt  # noqa: E402

REPEATS = 5
FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
HALF = {"E": 400.0, "nu": 0.25, "rho": 3500.0}


def _speeds(m: dict) -> tuple[float, float]:
    C = isotropic_voigt(m["E"], m["nu"]) * 1e9
    return float(np.sqrt(C[0, 0] / m["rho"])), float(np.sqrt(C[3, 3] / m["rho"]))


def main() -> int:
    """Run both codes on the same stack and print speed and agreement."""
    py = os.environ.get("DISBA_PYTHON")
    if not py:
        print(__doc__)  # how to make the throwaway environment and run
        return 1
    vp1, vs1 = _speeds(FILM)
    vp2, vs2 = _speeds(HALF)
    periods = np.linspace(0.05, 2.0, 200)                    # s; kh = 2 pi / (c T) with c in km/s, H = 1 km
    job = {"layers": [[1.0, vp1 / 1e3, vs1 / 1e3, FILM["rho"] / 1e3], [0.0, vp2 / 1e3, vs2 / 1e3, HALF["rho"] / 1e3]],
           "periods": periods.tolist(), "modes": [0, 1], "waves": ["rayleigh", "love"], "repeats": REPEATS}
    res = subprocess.run([py, str(Path(__file__).with_name("disba_side.py"))], input=json.dumps(job),
                         capture_output=True, text=True, check=True)
    disba = json.loads(res.stdout)
    films = [{**FILM, "thickness": 1e-6}]
    f = 1e9 / periods
    surfwave.layered(HALF, films, frequency=f[:3])
    best = np.inf
    for _ in range(REPEATS):
        t0 = time.process_time()
        r = surfwave.layered(HALF, films, frequency=f)
        best = min(best, time.process_time() - t0)
    kh = np.sort(2 * np.pi / (np.array(disba["rayleigh0"]["c"], dtype=float) * periods))   # the R mode's kh
    best_kh = np.inf
    for _ in range(REPEATS):
        t0 = time.process_time()
        surfwave.layered(HALF, films, kh=kh)
        best_kh = min(best_kh, time.process_time() - t0)
    print(f"surfwave.layered, all modes at the 200 kh of disba's fundamental Rayleigh points: {best_kh:.3f} s "
          f"(ratio to disba's 4 curves {best_kh / sum(v['seconds'] for v in disba.values()):.1f})")
    label = {"rayleigh0": "R", "rayleigh1": "S1", "love0": "L0", "love1": "L1"}
    t_disba = sum(v["seconds"] for v in disba.values())
    print(f"surfwave.layered, all modes at 200 frequencies: {best:.3f} s; disba, the 4 curves: {t_disba:.3f} s "
          f"(ratio {best / t_disba:.2f})")
    out = {"surfwave_seconds": best, "surfwave_kh_seconds": best_kh, "disba_seconds": t_disba, "curves": {}}
    for key, lab in label.items():
        cd = np.array([np.nan if v is None else v for v in disba[key]["c"]]) * 1e3
        cs = np.array([row[list(lr).index(lab)] if lab in list(lr) else np.nan for row, lr in zip(r["c"], r["mode"])])
        both = np.isfinite(cd) & np.isfinite(cs)
        diff = float(np.max(np.abs(cd[both] / cs[both] - 1))) if both.any() else float("nan")
        only = int(np.sum(np.isfinite(cd) != np.isfinite(cs)))
        print(f"{key:10s} ({lab:2s}): disba {disba[key]['seconds']:.4f} s, points {int(both.sum())}, "
              f"max |c_disba / c_surfwave - 1| = {diff:.2e}, points found by one code only: {only}")
        out["curves"][key] = {"disba_seconds": disba[key]["seconds"], "max_rel_diff": diff, "one_only": only}
    if len(sys.argv) > 1:
        Path(sys.argv[1]).mkdir(parents=True, exist_ok=True)
        (Path(sys.argv[1]) / "layered_vs_disba.json").write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
