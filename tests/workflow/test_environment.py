"""The locked environments: what is in each, and that a local Snakemake call does not pay for
the cluster path (issue 20, item 11).

References: the plugin's own source (snakemake-executor-plugin-slurm 2.8.0: its package
__init__ runs ``scontrol show config`` via ``shutil.which("sinfo")`` while Snakemake builds its
command line, measured ~10 s per call where no controller answers). The time is not asserted:
the test checks the behaviour (no probe call).
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
from importlib import metadata
from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]
SNAKEMAKE = Path(sys.executable).with_name("snakemake")
PLUGIN = "snakemake-executor-plugin-slurm"


def _pins(lock: Path) -> dict[str, tuple[str, tuple[str, ...]]]:
    """name -> (version, hashes) of a pip-compile lock."""
    pins, name = {}, None
    for line in lock.read_text().splitlines():
        m = re.match(r"^([A-Za-z0-9_.-]+)==(\S+)", line)
        if m:
            name = m.group(1).lower()
            pins[name] = (m.group(2), ())
        h = re.search(r"--hash=(sha256:[0-9a-f]{64})", line)
        if h and name:
            pins[name] = (pins[name][0], pins[name][1] + (h.group(1),))
    return pins


def test_locks_split_the_cluster_plugin_and_agree_on_every_shared_pin():
    """environment.lock: no SLURM plugin; ruff and mypy pinned with hashes (make test's style
    checks). environment-cluster.lock: the plugin (and its jobstep plugin) plus exactly the
    same pins and hashes for everything else."""
    main, cluster = _pins(REPO / "environment.lock"), _pins(REPO / "environment-cluster.lock")
    assert PLUGIN not in main and not any(n.startswith(PLUGIN) for n in main)
    assert PLUGIN in cluster and f"{PLUGIN}-jobstep" in cluster
    for tool in ("ruff", "mypy"):
        assert tool in main and main[tool][1], f"{tool} is not pinned with hashes"
    assert {n: p for n, p in cluster.items() if n in main} == main
    assert set(cluster) - set(main) == {PLUGIN, f"{PLUGIN}-jobstep"}


@pytest.mark.workflow
@pytest.mark.xdist_group("workflow")
def test_noop_snakemake_does_not_probe_slurm(tmp_path):
    """A dry run with a SLURM client on PATH (fake `sinfo`, `scontrol`, `squeue`, `sacct` that
    record each call) calls none of them: a local Snakemake call does not load the cluster
    plugin, whose import probes the controller (~10 s per call without one). Behaviour, not wall
    time: the time it saves is a benchmark's business."""
    from test_workflow import make_workdir

    (tmp_path / "wf").mkdir()
    work = make_workdir(tmp_path / "wf")
    fake = tmp_path / "fakebin"
    fake.mkdir()
    for tool in ("sinfo", "scontrol", "squeue", "sacct"):
        (fake / tool).write_text(f"#!/bin/sh\necho \"{tool} $*\" >> {fake}/calls\n")
        (fake / tool).chmod(0o755)
    path = f"{fake}{os.pathsep}{os.environ['PATH']}"
    assert shutil.which("sinfo", path=path) == str(fake / "sinfo")    # the fake is what a probe finds
    subprocess.run([str(SNAKEMAKE), "-n", "--directory", str(work)], cwd=work, check=True, capture_output=True,
                   env={**os.environ, "OMP_NUM_THREADS": "1", "PATH": path}, timeout=120)
    try:
        where = f"{PLUGIN} {metadata.version(PLUGIN)} is installed in {sys.prefix}"
    except metadata.PackageNotFoundError:
        where = f"{PLUGIN} is not installed"
    calls = (fake / "calls").read_text().splitlines() if (fake / "calls").exists() else []
    assert calls == [], f"snakemake ran {calls}; {where} (it belongs in .venv-cluster: make cluster-env)"
