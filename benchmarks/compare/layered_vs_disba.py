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
f = 1e9 / T Hz with H = 1e-6 m (isotropic stacks take surfwave's exact isotropic path,
``surfwave.layers.isotropic``).

Timed (one core, CPU time, REPEATS rounds each; min / median / max): disba's four curves
(fundamental and first overtone of Rayleigh and Love) at the 200 periods; surfwave with
``modes=2`` (the same four curves) and with every guided mode, at the 200 frequencies (disba's
question) and at 200 kh (those of disba's fundamental Rayleigh points). Ratios: surfwave's median
over disba's median of the same run. Accuracy: the largest relative difference of the phase speeds
to disba on each curve (disba's root search stops at its step ``dc``), and of every mode to
surfwave's general (Stroh) solver, forced, at the 200 frequencies (labels must agree too).
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
import surfwave.layers.solve as solve  # noqa: E402
from surfwave.layers.stack import isotropic_voigt  # noqa: E402

REPEATS = 7
FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
HALF = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
LABELS = {"rayleigh0": "R", "rayleigh1": "S1", "love0": "L0", "love1": "L1"}


def _speeds(m: dict) -> tuple[float, float]:
    C = isotropic_voigt(m["E"], m["nu"]) * 1e9
    return float(np.sqrt(C[0, 0] / m["rho"])), float(np.sqrt(C[3, 3] / m["rho"]))


def _timed(**kw) -> tuple[list[float], dict]:
    """CPU seconds of REPEATS calls of surfwave.layered (after one warm-up call) and the last result."""
    films = [{**FILM, "thickness": 1e-6}]
    r = surfwave.layered(HALF, films, **kw)
    out = []
    for _ in range(REPEATS):
        t0 = time.process_time()
        r = surfwave.layered(HALF, films, **kw)
        out.append(time.process_time() - t0)
    return out, dict(r)


def _column(r: dict, lab: str) -> np.ndarray:
    return np.array([row[list(lr).index(lab)] if lab in list(lr) else np.nan for row, lr in zip(r["c"], r["mode"])])


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
    f = 1e9 / periods
    kh = np.sort(2 * np.pi / (np.array(disba["rayleigh0"]["c"], dtype=float) * periods))   # the R mode's kh
    runs: dict[str, tuple] = {"disba, 4 curves at 200 periods": (disba["round_seconds"], None)}
    for name, kw in (("surfwave modes=2 at 200 frequencies", {"frequency": f, "modes": 2}),
                     ("surfwave all modes at 200 frequencies", {"frequency": f}),
                     ("surfwave modes=2 at 200 kh", {"kh": kh, "modes": 2}),
                     ("surfwave all modes at 200 kh", {"kh": kh})):
        runs[name] = _timed(**kw)
    t_disba = float(np.median(disba["round_seconds"]))
    out: dict = {"repeats": REPEATS, "timings": {}, "curves": {}}
    print(f"{'case':40s} {'min ms':>8s} {'median':>8s} {'max':>8s} {'/disba':>7s} modes")
    for name, (secs, r) in runs.items():
        s = np.array(secs) * 1e3
        ratio = float(np.median(secs)) / t_disba
        n = "4 curves" if r is None else f"{r['c'].shape[1]} columns"
        print(f"{name:40s} {s.min():8.2f} {np.median(s):8.2f} {s.max():8.2f} {ratio:7.2f} {n}")
        out["timings"][name] = {"ms_min": float(s.min()), "ms_median": float(np.median(s)), "ms_max": float(s.max()),
                                "ratio_to_disba_median": ratio}
    r_f = runs["surfwave all modes at 200 frequencies"][1]
    r_2 = runs["surfwave modes=2 at 200 frequencies"][1]
    for key, lab in LABELS.items():
        cd = np.array([np.nan if v is None else v for v in disba[key]["c"]]) * 1e3
        cs = _column(r_2, lab)
        both = np.isfinite(cd) & np.isfinite(cs)
        diff = float(np.max(np.abs(cd[both] / cs[both] - 1))) if both.any() else float("nan")
        only = int(np.sum(np.isfinite(cd) != np.isfinite(cs)))
        print(f"{key:10s} ({lab:2s}): points {int(both.sum())}, max |c_disba / c_surfwave - 1| = {diff:.2e}, "
              f"points found by one code only: {only}")
        out["curves"][key] = {"max_rel_diff": diff, "one_only": only}
    solve.FAST_ISOTROPIC = False
    try:
        t0 = time.process_time()
        gen = surfwave.layered(HALF, [{**FILM, "thickness": 1e-6}], frequency=f)
        t_gen = time.process_time() - t0
    finally:
        solve.FAST_ISOTROPIC = True
    same = gen["mode"].shape == r_f["mode"].shape and bool((gen["mode"] == r_f["mode"]).all())
    ok = np.isfinite(gen["c"])
    d_c = float(np.max(np.abs(r_f["c"][ok] / gen["c"][ok] - 1))) if same else float("nan")
    d_v = float(np.max(np.abs(r_f["group_velocity"][ok] / gen["group_velocity"][ok] - 1))) if same else float("nan")
    print(f"isotropic path vs the general solver (all modes, 200 frequencies; general {t_gen:.2f} s): labels equal "
          f"{same}, max rel. diff. c {d_c:.1e}, group velocity {d_v:.1e}")
    out["vs_general"] = {"labels_equal": same, "max_rel_diff_c": d_c, "max_rel_diff_vg": d_v, "general_seconds": t_gen}
    if len(sys.argv) > 1:
        Path(sys.argv[1]).mkdir(parents=True, exist_ok=True)
        (Path(sys.argv[1]) / "layered_vs_disba.json").write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
