"""Leaky surface waves (solvers.leaky) against the elastic Stroh solver, one core: speed and tol.

Usage: python benchmarks/bench_leaky.py OUTDIR   -> OUTDIR/leaky_speed_tol.nc, .png

Cases (N_ANGLES orientations each, one vectorised call):

* Cu (001), angles 30-45 deg from [100] (C11, C12, C44 = 168.4, 121.4, 75.4 GPa, rho = 8960
  kg/m^3): the elastic leaky branch (6 x 6 Stroh problem) between the pseudo region and [110];
* rotated Y-cut, X-propagating LiNbO3 (``LiNbO3-Warner1967``: Warner, Onoe, Coquin, JASA 42,
  1223 (1967)), cut angles 40-80 deg (SAW Euler angles (0, angle - 90, 0), which contain 41Y-X
  and 64Y-X), electrically free and metallized (8 x 8);
* the same LiNbO3 cuts, both conditions in one call (``leaky_wave(..., electrical=("free",
  "metallized"))``: limits, real scan and grid impedance shared), one orientation = both conditions.

1. Speed. Each round times the elastic solver stroh.surface_wave on the same A (e ignored; the
   yardstick: in the leaky region it returns `pseudo` NaN, its cost is still the search) and
   leaky_wave, alternating which goes first; per round the ratio of the two; min / median /
   max over REPEATS rounds. CPU time of this process (time.process_time, numpy pinned to one
   thread). Target (issue 19): leaky waves >= 1e3 orientations per second per core. The
   both-conditions row times, in each round and in rotating order, the elastic solver, the one
   call for both conditions and the two separate calls; it reports the rate, the ratio to the
   elastic solver's time in the same round and the speed-up against the two calls, and checks
   that the one call's answers are bit-identical to the two calls'.
2. Accuracy knob ``tol`` (relative accuracy of the complex X = rho v^2 in the secant search):
   at every tol of TOLS, error = max over the orientations of |c_leaky / c_leaky(tol = 1e-15)
   - 1| and of |attenuation - attenuation(1e-15)| (dB per wavelength), the number of
   orientations found at one tol only, CPU time (min over KNOB_REPEATS rounds, tols
   interleaved) and the mean number of secant evaluations per orientation (deterministic cost;
   the SCAN real-speed grid points come on top). The default is the library's (leaky_wave's
   ``tol``), justified by the measured curve in the README row. The leaky root's agreement
   with an independent route is tested in tests/solvers/test_leaky.py.
"""
from __future__ import annotations

import os

for _v in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ[_v] = "1"  # one core, before numpy is imported

import inspect  # noqa: E402
import json  # noqa: E402
import time  # noqa: E402
from pathlib import Path  # noqa: E402

import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402
from surfwave.real_crystals.piezo_materials import lab_tensors  # noqa: E402
from surfwave.solvers import orientation, stroh, tensors  # noqa: E402
from surfwave.solvers.euler import euler_lab_axes  # noqa: E402
from surfwave.solvers.leaky import SCAN, leaky_wave  # noqa: E402

N_ANGLES = 400
REPEATS = 5
KNOB_REPEATS = 2
TOLS = [1e-4, 1e-6, 1e-8, 1e-10, 1e-12, 1e-14]
REF_TOL = 1e-15
DEFAULT_TOL = inspect.signature(leaky_wave).parameters["tol"].default
TARGET = 1e3  # orientations per second per core
CASES = ["Cu (001) 30-45 deg, elastic", "LiNbO3 rotated Y-X 40-80 deg, free",
         "LiNbO3 rotated Y-X 40-80 deg, metallized"]
BOTH_CASE = "LiNbO3 rotated Y-X 40-80 deg, both conditions, one call"
BOTH_SOLVERS = ["elastic", "leaky both conditions, one call", "leaky two calls (free, metallized)"]


def cases(m: int) -> list[dict]:
    """Per case the keyword arguments of leaky_wave (A Pa, rho, e, eps, electrical)."""
    ang = np.linspace(30.0, 45.0, m)
    C = tensors.voigt_to_tensor(tensors.cubic_voigt(168.4e9, 121.4e9, 75.4e9))
    cu = {"A": tensors.rotate4(C, orientation.lab_axes("(001)", ang)), "rho": 8960.0}
    cut = np.linspace(40.0, 80.0, m)
    t = lab_tensors("LiNbO3-Warner1967", euler_lab_axes(0 * cut, cut - 90.0, 0 * cut).reshape(-1, 3, 3))
    ln = {"A": t["C"], "rho": t["rho"], "e": t["e"], "eps": t["eps"]}
    return [cu, dict(ln, electrical="free"), dict(ln, electrical="metallized")]


def mmm(x) -> tuple[float, float, float]:
    """(min, median, max) of x."""
    return float(np.min(x)), float(np.median(x)), float(np.max(x))


def cpu(f) -> tuple[float, object]:
    """CPU seconds of one call of f() and its result."""
    t0 = time.process_time()
    out = f()
    return time.process_time() - t0, out


def speed(kw: list[dict]) -> np.ndarray:
    """CPU seconds (case, solver = [elastic, leaky], round), the pair alternated."""
    secs = np.zeros((len(kw), 2, REPEATS))
    for i, k in enumerate(kw):
        calls = (lambda: stroh.surface_wave(k["A"], k["rho"]), lambda: leaky_wave(**k))
        for f in calls:  # warm-up
            f()
        for r in range(REPEATS):
            for j in ((0, 1) if r % 2 == 0 else (1, 0)):
                secs[i, j, r] = cpu(calls[j])[0]
    return secs


def speed_both(k: dict) -> tuple[np.ndarray, bool]:
    """CPU seconds (solver = BOTH_SOLVERS, round) of the both-conditions case (``k``: the
    piezoelectric keyword arguments without ``electrical``), the order rotated each round; and
    whether the one call's answers are bit-identical to the two calls'."""
    both = ("free", "metallized")
    calls = (lambda: stroh.surface_wave(k["A"], k["rho"]), lambda: leaky_wave(**k, electrical=both),
             lambda: [leaky_wave(**k, electrical=el) for el in both])
    one, two = calls[1](), calls[2]()
    same = all(np.array_equal(one[el][q], r[q], equal_nan=r[q].dtype != object)
               for el, r in zip(both, two) for q in r)
    calls[0]()
    secs = np.zeros((3, REPEATS))
    for r in range(REPEATS):
        for j in np.roll(np.arange(3), r):
            secs[j, r] = cpu(calls[j])[0]
    return secs, same


def knob(kw: list[dict]) -> dict[str, np.ndarray]:
    """Errors, mismatches, CPU time and evaluations (case, tol), tols incl. REF_TOL."""
    tols = TOLS + [REF_TOL]
    n, m = len(kw), kw[0]["A"].shape[0]
    secs = np.zeros((n, len(tols), KNOB_REPEATS))
    c, att, its = (np.zeros((n, len(tols), m)) for _ in range(3))
    for r in range(KNOB_REPEATS):
        for k, tol in enumerate(tols):
            for i, a in enumerate(kw):
                secs[i, k, r], res = cpu(lambda: leaky_wave(**a, tol=tol))
                c[i, k], att[i, k], its[i, k] = res["c_leaky"], res["leaky_attenuation"], res["iterations"]
    ref_c, ref_a = c[:, -1:], att[:, -1:]
    both = np.isfinite(c) & np.isfinite(ref_c)
    with np.errstate(invalid="ignore"):
        err = np.where(both, np.abs(c / ref_c - 1.0), 0.0).max(axis=2)
        err_att = np.where(both, np.abs(att - ref_a), 0.0).max(axis=2)
    return {"error": err, "error_attenuation": err_att,
            "found_mismatch": (np.isfinite(c) != np.isfinite(ref_c)).sum(axis=2),
            "found": np.isfinite(c).sum(axis=2), "time": secs.min(axis=2), "time_median": np.median(secs, axis=2),
            "evaluations": its.mean(axis=2)}


def main(outdir: str) -> Path:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    kw = cases(N_ANGLES)
    secs = speed(kw)
    kb = {key: v for key, v in kw[1].items() if key != "electrical"}
    secs_b, same_b = speed_both(kb)
    kn = knob(kw)
    rate = N_ANGLES / secs                                 # (case, solver, round)
    ratio = secs[:, 1] / secs[:, 0]                        # leaky / elastic, same round
    i = TOLS.index(DEFAULT_TOL)
    lo = int(np.argmax(TOLS))
    rows = []
    for c, name in enumerate(CASES):
        r, q, el = mmm(rate[c, 1]), mmm(ratio[c]), mmm(rate[c, 0])
        ev = kn["evaluations"][c]
        per100 = (ev[TOLS.index(min(TOLS))] - ev[lo]) / (np.log10(max(TOLS) / min(TOLS)) / 2)
        verdict = "met" if r[1] >= TARGET else "NOT met"
        rows.append([
            f"leaky SAW `leaky_wave` (boundary-determinant scan + complex secant), {name} "
            f"({N_ANGLES} orientations, one call)",
            f"tol in [{min(TOLS):g}, {max(TOLS):g}] (relative accuracy of complex rho v^2)", f"{DEFAULT_TOL:g}",
            f"{kn['error'][c, i]:.2g} relative in c_leaky, {kn['error_attenuation'][c, i]:.2g} dB/wavelength "
            f"vs tol {REF_TOL:g} ({int(kn['found_mismatch'][c, i])} of {int(kn['found'][c, -1])} found at one "
            f"tol only)",
            f"{r[1]:.3g} orientations/s (min / median / max {r[0]:.3g} / {r[1]:.3g} / {r[2]:.3g}) = {q[1]:.1f} x "
            f"the elastic solver's time on the same tensors (min / median / max ratio {q[0]:.1f} / {q[1]:.1f} / "
            f"{q[2]:.1f} over {REPEATS} rounds; elastic {el[1]:.3g}/s)",
            f"target >= {TARGET:.0e} orientations/s/core: {verdict} (median); the error follows tol "
            f"({kn['error'][c, lo]:.1g} at tol {max(TOLS):g}, {kn['error'][c, TOLS.index(min(TOLS))]:.1g} at "
            f"{min(TOLS):g}: the stopping test bounds the last secant step) and each factor 100 in tol costs "
            f"{per100:.1f} secant evaluations (of the {ev[i]:.1f}, + {SCAN} scan points, per orientation at the "
            f"default); tol {DEFAULT_TOL:g} saves {ev[TOLS.index(min(TOLS))] - ev[i]:.1f} of them against tol "
            f"{min(TOLS):g} for an error still {kn['error'][c, i]:.0e} in speed"])
    rate_b = N_ANGLES / secs_b                             # (solver, round)
    ratio_b = secs_b[1] / secs_b[0]
    gain_b = secs_b[2] / secs_b[1]
    r, q, g, el = mmm(rate_b[1]), mmm(ratio_b), mmm(gain_b), mmm(rate_b[0])
    rows.append([
        f"leaky SAW `leaky_wave(..., electrical=(\"free\", \"metallized\"))`, {BOTH_CASE} ({N_ANGLES} "
        f"orientations, one orientation = both conditions)",
        "tol (as above)", f"{DEFAULT_TOL:g}",
        f"{'bit-identical' if same_b else 'NOT bit-identical'} to two separate calls (every output)",
        f"{r[1]:.3g} orientations/s (min / median / max {r[0]:.3g} / {r[1]:.3g} / {r[2]:.3g}) = {q[1]:.1f} x "
        f"the elastic solver's time on the same tensors (min / median / max ratio {q[0]:.1f} / {q[1]:.1f} / "
        f"{q[2]:.1f} over {REPEATS} rounds; elastic {el[1]:.3g}/s)",
        f"{g[1]:.2f} x faster than two calls (min / median / max {g[0]:.2f} / {g[1]:.2f} / {g[2]:.2f}, same "
        f"rounds): the limits, the {SCAN}-point real scan's eigen-decompositions and the grid impedance are "
        f"shared; the secant searches and the validation stay per condition"])
    for row in rows:
        print(" | ".join(row))

    tols = TOLS + [REF_TOL]
    dims = ("case", "tol")
    ds = xr.Dataset(
        {
            "cpu_time": (("case", "solver", "round"), secs,
                         {"long_name": f"CPU time of one vectorised call on {N_ANGLES} orientations, one core",
                          "units": "s"}),
            "rate": (("case", "solver", "round"), rate, {"long_name": "orientations per second per core",
                                                         "units": "s-1"}),
            "ratio_to_elastic": (("case", "round"), ratio,
                                 {"long_name": "leaky_wave CPU time / stroh.surface_wave's on the same A, same round",
                                  "units": "1"}),
            "cpu_time_both": (("solver_both", "round"), secs_b,
                              {"long_name": f"CPU time of one call (or two) on {N_ANGLES} orientations, both "
                                            "conditions, one core", "units": "s"}),
            "ratio_to_elastic_both": (("round",), ratio_b,
                                      {"long_name": "one call for both conditions / stroh.surface_wave, same round",
                                       "units": "1"}),
            "speedup_vs_two_calls": (("round",), gain_b,
                                     {"long_name": "two separate calls / one call for both conditions, same round",
                                      "units": "1"}),
            "error": (dims, kn["error"], {"long_name": f"max relative change of c_leaky against tol = {REF_TOL:g}",
                                          "units": "1"}),
            "error_attenuation": (dims, kn["error_attenuation"],
                                  {"long_name": f"max change of the attenuation against tol = {REF_TOL:g}",
                                   "units": "dB per wavelength"}),
            "found_mismatch": (dims, kn["found_mismatch"],
                               {"long_name": f"orientations with a leaky wave at this tol or at {REF_TOL:g}, not both",
                                "units": "1"}),
            "found": (dims, kn["found"], {"long_name": "orientations with a leaky wave", "units": "1"}),
            "time": (dims, kn["time"], {"long_name": f"min CPU time of one call over {KNOB_REPEATS} rounds",
                                        "units": "s"}),
            "time_median": (dims, kn["time_median"],
                            {"long_name": f"median CPU time of one call over {KNOB_REPEATS} rounds", "units": "s"}),
            "evaluations": (dims, kn["evaluations"],
                            {"long_name": f"mean secant evaluations per orientation (+ {SCAN} scan points)",
                             "units": "1"}),
        },
        coords={"case": CASES, "solver": ("solver", ["elastic", "leaky"], {"long_name": "elastic = "
                                                                           "stroh.surface_wave (yardstick)"}),
                "round": np.arange(REPEATS), "solver_both": BOTH_SOLVERS,
                "tol": ("tol", tols, {"long_name": "relative accuracy asked of complex X = rho v^2", "units": "1"})},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: leaky surface-wave solver",
               "source": f"surfwave {surfwave.__version__}", "history": f"{time.ctime()}: bench_leaky.py",
               "method": "solvers.leaky.leaky_wave", "knob": "tol", "default": DEFAULT_TOL,
               "default_reason": rows[0][-1], "n_orientations": N_ANGLES, "repeats": REPEATS,
               "target_per_second": TARGET, "both_bit_identical": int(same_b),
               "readme_rows": json.dumps(rows)},
    )
    nc = out / "leaky_speed_tol.nc"
    ds.to_netcdf(nc, engine="h5netcdf")

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.2), layout="constrained")
    marks = "os^"
    for ax, key, xl in ((axes[0], "time", f"CPU time per orientation (ms, min of {KNOB_REPEATS})"),
                        (axes[1], "evaluations", f"secant evaluations per orientation (+ {SCAN} scan points)")):
        for c, name in enumerate(CASES):
            x = kn[key][c, :-1] * (1e3 / N_ANGLES if key == "time" else 1.0)
            y = np.maximum(kn["error"][c, :-1], 1e-17)
            ax.semilogy(x, y, marks[c] + "-", label=name)
            for xx, yy, tol in zip(x, y, TOLS):
                ax.annotate(f"{tol:g}", (xx, yy), fontsize=7, xytext=(3, 3), textcoords="offset points")
            ax.semilogy(x[i], y[i], marks[c], ms=12, mfc="none", color="tab:red")
        ax.set_xlabel(xl)
        ax.set_ylabel(f"max relative error of c_leaky (vs tol {REF_TOL:g})")
        ax.set_title(f"tol sweep (labels); circled: default {DEFAULT_TOL:g}", fontsize=9)
        ax.legend(fontsize=7)
    ax = axes[2]
    pos = np.arange(len(CASES) + 1)
    ax.boxplot([rate[c, 1] for c in range(len(CASES))] + [rate_b[1]], positions=pos - 0.18, widths=0.3)
    ax.boxplot([rate[c, 0] for c in range(len(CASES))] + [rate_b[0]], positions=pos + 0.18, widths=0.3,
               boxprops={"color": "gray"}, medianprops={"color": "gray"})
    ax.set_yscale("log")
    ax.set_xticks(pos, ["Cu (001)\nelastic", "LiNbO3\nrot. Y-X\nfree", "LiNbO3\nrot. Y-X\nmetallized",
                        "LiNbO3\nrot. Y-X\nboth, one call"])
    ax.axhline(TARGET, color="tab:red", ls="--", label=f"target {TARGET:.0e}/s (leaky)")
    ax.plot([], [], color="gray", label="elastic solver, same tensors")
    ax.set_ylabel("orientations per second, one core (CPU)")
    ax.set_title(f"leaky_wave (black) against stroh.surface_wave (gray), {REPEATS} rounds", fontsize=9)
    ax.legend(fontsize=8)
    for a in axes:
        a.grid(alpha=0.3, which="both")
    fig.suptitle(f"Leaky-wave solver: accuracy knob and speed ({N_ANGLES} orientations per call)")
    fig.savefig(out / "leaky_speed_tol.png", dpi=150, bbox_inches="tight")
    return nc


if __name__ == "__main__":
    import argparse

    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], epilog=__doc__.split("\n\n")[1])
    ap.add_argument("outdir", help="output directory (leaky_speed_tol.nc, .png)")
    ap.add_argument("--repeats", type=int, default=REPEATS, help=f"speed rounds (default {REPEATS})")
    ap.add_argument("--angles", type=int, default=N_ANGLES,
                    help=f"orientations per case and call (default {N_ANGLES})")
    args = ap.parse_args()
    REPEATS, N_ANGLES = args.repeats, args.angles
    main(args.outdir)
