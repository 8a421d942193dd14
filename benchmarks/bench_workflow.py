"""Wall time of the full reproduction and of the no-op rerun.

Usage: python benchmarks/bench_workflow.py OUTDIR   -> OUTDIR/workflow_timing.nc, .png

Copies the repository (without results/, .snakemake/, .git/, .venv/) to a temporary
directory and runs ``snakemake -j2`` there from an empty results/ (the parameter cache
starts empty too), then again (must print "Nothing to be done"), then a user scene of
2000 strains x 512 theta with quantities [dispersion] (its lattice-dynamics check on the
default sample of strains, ``accuracy.dispersion.check_points``). Targets:
full reproduction < 15 s, no-op rerun < 2 s, the dispersion scene < 30 s, on the 2-core machine.
"""
from __future__ import annotations

import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
IGNORE = shutil.ignore_patterns("results", ".snakemake", ".git", ".venv", "__pycache__",
                                ".pytest_cache", "*.egg-info")
RUNS = ["full reproduction (empty results, -j2)", "no-op rerun",
        "2000 strain x 512 theta dispersion scene (-j2)"]
TARGETS = np.array([15.0, 2.0, 30.0])

#: The large dispersion scene (a --configfile of the copy).
DISPERSION_SCENE = """run: [big_dispersion]
scenes:
  big_dispersion:
    lattice: triangular
    loading: uniaxial
    potentials: [harmonic, lj]
    d_over_d0: {start: 0.9, stop: 1.0999, step: 0.0001}
    theta: {n: 512}
    quantities: [dispersion]
"""


def _snakemake() -> str:
    exe = Path(sys.executable).with_name("snakemake")
    return str(exe) if exe.exists() else "snakemake"


def run_once(workdir: Path, log, *extra: str) -> tuple[float, str]:
    t0 = time.perf_counter()
    # the copy's own src/ first, so the rules' code inputs are the copy's (not a tree that
    # others may be editing while the benchmark runs)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(
        [str(workdir / "src"), *filter(None, [os.environ.get("PYTHONPATH")])]))
    proc = subprocess.run([_snakemake(), "-j2", *extra], cwd=workdir, capture_output=True, text=True,
                          env=env)
    dt = time.perf_counter() - t0
    log.write(proc.stdout + proc.stderr)
    if proc.returncode != 0:
        raise SystemExit(f"snakemake failed in {workdir} (exit {proc.returncode}):\n"
                         + proc.stderr[-3000:])
    return dt, proc.stdout + proc.stderr


def main(outdir: str) -> Path:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    with tempfile.TemporaryDirectory(prefix="surfwave-bench-") as tmp:
        work = Path(tmp, "repo")
        shutil.copytree(ROOT, work, ignore=IGNORE)
        with open(out / "snakemake_output.log", "w") as log:
            t_full, _ = run_once(work, log)
            t_noop, text = run_once(work, log)
            n_jobs = len(list((work / "results").rglob("*.nc")))
            (work / "big_dispersion.yaml").write_text(DISPERSION_SCENE)
            t_disp, _ = run_once(work, log, "--configfile", "big_dispersion.yaml")
    nothing = "Nothing to be done" in text  # else the log says which jobs reran and why
    times = np.array([t_full, t_noop, t_disp])
    for run, t, target in zip(RUNS, times, TARGETS):
        print(f"{run}: {t:.2f} s (target < {target:g} s)")
    ds = xr.Dataset(
        {"time": ("run", times, {"long_name": "wall time", "units": "s"}),
         "target": ("run", TARGETS, {"long_name": "target wall time", "units": "s"})},
        coords={"run": ("run", RUNS)},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: workflow wall time",
               "source": f"surfwave {surfwave.__version__}",
               "history": f"{time.ctime()}: bench_workflow.py", "kind": "timing",
               "method": "snakemake -j2, default config",
               "default_reason": (f"targets < 15 s (full), < 2 s (no-op), < 30 s (2000 x 512 "
                                  f"dispersion scene); no-op printed "
                                  f"'Nothing to be done': {nothing}; {n_jobs} cubes written"),
               "nothing_to_be_done": int(nothing)},
    )
    nc = out / "workflow_timing.nc"
    ds.to_netcdf(nc, engine="h5netcdf")
    fig, ax = plt.subplots(figsize=(5.5, 3))
    ax.barh(RUNS, times, color=["tab:blue", "tab:green", "tab:purple"])
    ax.scatter(TARGETS, RUNS, marker="|", s=400, color="tab:red", label="target")
    ax.set_xlabel("wall time (s), 2 cores")
    ax.set_title("Full reproduction, no-op rerun, large dispersion scene")
    ax.legend()
    fig.savefig(out / "workflow_timing.png", dpi=150, bbox_inches="tight")
    return nc


if __name__ == "__main__":
    if len(sys.argv) != 2:
        raise SystemExit(__doc__.split("\n\n")[1])
    main(sys.argv[1])
