"""Wall time and peak memory of a large user scene (issue 13: speed where scenes grow).

Usage: python benchmarks/bench_large_scene.py OUTDIR [REPEATS]
       -> OUTDIR/large_scene_timing.nc, .png

The scene is benchmarks/large_scene.yaml: FCC, 20000 strains x 2 potentials x 2 directions,
quantities [elastic, rayleigh] (80000 cells). The repository is copied (without results/,
.snakemake/, .git/, .venv/) to a temporary directory, where
``snakemake -j2 --configfile benchmarks/large_scene.yaml`` runs REPEATS times (default 3)
from an empty ``results/big/``, then once more with nothing to do: that no-op rerun (the
same DAG, no job) is the yardstick measured in the same run, since the machine is shared.
Reported: wall time and peak resident memory (largest single process of the run, from
``os.wait4``; and the sum over snakemake and its running jobs, sampled every 0.1 s with
psutil) with min/median/max over the repeats, and each job's time from Snakemake's
``.snakemake/metadata`` (starttime, endtime). Targets: < 30 s wall and < 500 MB peak on
the 2-core machine.
"""
from __future__ import annotations

import base64
import json
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
import psutil  # noqa: E402
import xarray as xr  # noqa: E402

import surfwave  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
SCENE_FILE = "benchmarks/large_scene.yaml"
SCENE = "big"
IGNORE = shutil.ignore_patterns("results", ".snakemake", ".git", ".venv", "__pycache__",
                                ".pytest_cache", "*.egg-info")
TARGET_S, TARGET_MB = 30.0, 500.0


def _snakemake() -> str:
    exe = Path(sys.executable).with_name("snakemake")
    return str(exe) if exe.exists() else "snakemake"


def _tree_rss(proc: psutil.Process) -> int:
    """Resident bytes of a process and all its descendants now (0 for those gone meanwhile)."""
    total = 0
    try:
        procs = [proc, *proc.children(recursive=True)]
    except psutil.Error:
        return 0
    for p in procs:
        try:
            total += p.memory_info().rss
        except psutil.Error:
            pass
    return total


def run_once(workdir: Path, log) -> tuple[float, float, float, str]:
    """One ``snakemake -j2`` run: (wall s, peak RSS MB of the largest single process, peak
    of the summed RSS of snakemake and its running jobs sampled every 0.1 s in MB, output)."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(  # the copy's src/ first (see bench_workflow)
        [str(workdir / "src"), *filter(None, [os.environ.get("PYTHONPATH")])]))
    cmd = [_snakemake(), "-j2", "--configfile", SCENE_FILE, "--config", f"run=[{SCENE}]"]
    tree_peak = 0
    with tempfile.TemporaryFile("w+") as out:
        t0 = time.perf_counter()
        proc = subprocess.Popen(cmd, cwd=workdir, stdout=out, stderr=subprocess.STDOUT, env=env)
        watch = psutil.Process(proc.pid)
        while True:
            pid, status, usage = os.wait4(proc.pid, os.WNOHANG)  # rusage: snakemake + reaped jobs
            if pid:
                break
            tree_peak = max(tree_peak, _tree_rss(watch))
            time.sleep(0.1)
        dt = time.perf_counter() - t0
        proc.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0)
        text = out.read()
    log.write(text)
    if proc.returncode != 0:
        raise SystemExit(f"snakemake failed in {workdir} (exit {proc.returncode}):\n{text[-3000:]}")
    return dt, usage.ru_maxrss / 1024.0, tree_peak / 2**20, text


def job_times(workdir: Path) -> dict[str, float]:
    """Seconds per job of the scene (rule name -> endtime - starttime) from the metadata."""
    out = {}
    for f in (workdir / ".snakemake" / "metadata").iterdir():
        try:
            target = base64.b64decode(f.name).decode()
            meta = json.loads(f.read_text())
        except (ValueError, UnicodeDecodeError):
            continue
        if target.startswith(f"results/{SCENE}/") and meta.get("rule"):
            out[meta["rule"]] = float(meta["endtime"]) - float(meta["starttime"])
    return out


def main(outdir: str, repeats: int = 3) -> Path:
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    walls, peaks, trees, jobs = [], [], [], []
    with tempfile.TemporaryDirectory(prefix="surfwave-bench-") as tmp:
        work = Path(tmp, "repo")
        shutil.copytree(ROOT, work, ignore=IGNORE)
        with open(out / "snakemake_output.log", "w") as log:
            for _ in range(repeats):
                shutil.rmtree(work / "results" / SCENE, ignore_errors=True)
                dt, mb, tree, _ = run_once(work, log)
                walls.append(dt)
                peaks.append(mb)
                trees.append(tree)
                jobs.append(job_times(work))
            t_noop, _, _, text = run_once(work, log)
    nothing = "Nothing to be done" in text
    rules = sorted({r for j in jobs for r in j}, key=lambda r: -np.median([j.get(r, 0) for j in jobs]))
    per_job = np.array([[j.get(r, np.nan) for r in rules] for j in jobs])
    walls, peaks, trees = np.array(walls), np.array(peaks), np.array(trees)
    stat = lambda a: f"{np.min(a):.3g} / {np.median(a):.3g} / {np.max(a):.3g}"  # noqa: E731
    jobs_text = ", ".join(f"{r} {np.median(per_job[:, i]):.2g} s" for i, r in enumerate(rules))
    print(f"wall (min/median/max over {repeats}): {stat(walls)} s (target < {TARGET_S:g} s); "
          f"no-op rerun {t_noop:.2f} s; peak RSS {stat(peaks)} MB (largest process; target "
          f"< {TARGET_MB:g} MB), {stat(trees)} MB (snakemake + running jobs, summed)")
    print(f"median per job: {jobs_text}")
    rows = [[f"large scene: FCC 20000 strains x 2 potentials x 2 directions, elastic + rayleigh "
             f"(`{SCENE_FILE}`, `snakemake -j2` from an empty `results/{SCENE}/`)", "none", "-", "-",
             f"{stat(walls)} s (min / median / max of {repeats}) = {np.median(walls) / t_noop:.2g} x "
             f"the no-op rerun ({t_noop:.2g} s); peak memory {stat(peaks)} MB (largest process), "
             f"{stat(trees)} MB (all processes at once)",
             f"targets < {TARGET_S:g} s, < {TARGET_MB:g} MB; median per job: {jobs_text}"]]
    ds = xr.Dataset(
        {"wall_time": ("repeat", walls, {"long_name": "wall time of the clean run", "units": "s"}),
         "peak_memory": ("repeat", peaks, {"long_name": "peak resident memory of the largest "
                                                        "process of the run", "units": "MB"}),
         "peak_memory_total": ("repeat", trees, {"long_name": "peak of the summed resident memory "
                                                              "of snakemake and its running jobs "
                                                              "(sampled every 0.1 s)", "units": "MB"}),
         "job_time": (("repeat", "job"), per_job, {"long_name": "job time (Snakemake metadata "
                                                                "endtime - starttime)", "units": "s"}),
         "noop_time": ((), t_noop, {"long_name": "wall time of the no-op rerun (yardstick)",
                                    "units": "s"})},
        coords={"repeat": ("repeat", np.arange(repeats)), "job": ("job", rules)},
        attrs={"Conventions": "CF-1.10", "title": "surfwave benchmark: large user scene",
               "source": f"surfwave {surfwave.__version__}",
               "history": f"{time.ctime()}: bench_large_scene.py", "kind": "timing",
               "method": f"snakemake -j2 --configfile {SCENE_FILE}, {repeats} clean runs + 1 no-op",
               "default_reason": f"targets < {TARGET_S:g} s, < {TARGET_MB:g} MB; no-op printed "
                                 f"'Nothing to be done': {nothing}",
               "nothing_to_be_done": int(nothing), "readme_rows": json.dumps(rows)},
    )
    nc = out / "large_scene_timing.nc"
    ds.to_netcdf(nc, engine="h5netcdf")
    fig, ax = plt.subplots(figsize=(5.5, 3))
    med = np.nanmedian(per_job, axis=0)
    ax.barh(rules, med, xerr=[med - np.nanmin(per_job, axis=0), np.nanmax(per_job, axis=0) - med],
            color="tab:blue")
    ax.set_xlabel("job time (s): median, min-max of the repeats")
    ax.set_title(f"Large scene: wall {np.median(walls):.3g} s, peak {np.median(peaks):.0f} MB (2 cores)")
    fig.savefig(out / "large_scene_timing.png", dpi=150, bbox_inches="tight")
    return nc


if __name__ == "__main__":
    if len(sys.argv) not in (2, 3):
        raise SystemExit(__doc__.split("\n\n")[1])
    main(sys.argv[1], *(int(a) for a in sys.argv[2:]))
