"""The SLURM profile on a real single-node SLURM cluster on localhost (issue 15).

Opt-in (`make test-slurm`, run by `.ci/run` after `make test`): the test installs Debian's
slurmctld, slurmd, slurm-client and munge when they are missing, starts munged, slurmctld
and slurmd (private key, socket, ports and state under a temporary directory, all traffic on
localhost, no accounting), runs tiny scenes once locally (`-j2`) and once through
`--profile profiles/slurm` exactly as shipped, and checks that every cube is identical
(data variables and coordinates). The daemons are stopped by their PIDs afterwards, also on
failure, on timeout and on SIGTERM. Without the opt-in, without root or without apt the test
skips and says why; with SURFWAVE_SLURM_REQUIRED=1 (CI) a reason to skip is a failure.

Manual use (as root): `python tests/workflow/test_slurm.py -- CMD...` starts a throwaway cluster, runs
CMD against it (e.g. `snakemake --profile profiles/slurm`), and stops the cluster.

Knobs (environment): SURFWAVE_SLURM_TEST=1 opts in, SURFWAVE_SLURM_REQUIRED=1 turns skips
into failures, SURFWAVE_SLURM_BUDGET (seconds, default 600) bounds the whole test.
"""
from __future__ import annotations

import importlib.util
import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import pytest
from test_workflow import make_workdir, scheduled, smk  # the workflow copy with a tiny config

REPO = Path(__file__).resolve().parents[2]
SNAKEMAKE = Path(sys.executable).with_name("snakemake")
PACKAGES = ["slurmctld", "slurmd", "slurm-client", "munge"]
BINARIES = ["slurmctld", "slurmd", "sbatch", "squeue", "sinfo", "scontrol", "munged", "mungekey"]
#: Daemons left behind by a run that was killed hard (SIGKILL) are stopped by the next run.
PIDFILE = Path(tempfile.gettempdir()) / "surfwave-slurm-test.pids"
#: The jobs' nested `srun` (slurm-jobstep plugin) drops SLURM_CONF from its environment, so the
#: test cluster's configuration has to be where SLURM looks by default, as on a real cluster.
#: It is written only when absent (or left by an earlier run of this test) and removed after.
SYSTEM_CONF = Path("/etc/slurm/slurm.conf")
MARKER = "# Single-node test cluster of surfwave's tests/workflow/test_slurm.py"
#: Daemons live in /usr/sbin, which a non-login root shell may not have on PATH.
SEARCH_PATH = os.pathsep.join(p for p in (os.environ.get("PATH"), "/usr/sbin", "/sbin") if p)
CTLD_PORT, SLURMD_PORT = 16817, 16818  # not SLURM's defaults: a real slurmd may be running

# `tiny`: the FCC scene (one grouped SLURM job); `tiny_tri`: the triangular stages,
# which use the parameter cache (three more SLURM jobs running in parallel).
TINY = """\
run: [tiny, tiny_tri]
scenes:
  tiny:
    lattice: fcc
    loading: in_plane_hydrostatic
    potentials: [lj]
    directions: ["[100]"]
    d_over_d0: [0.99, 1.0, 1.01]
    quantities: [elastic, rayleigh]
  tiny_tri:
    lattice: triangular
    loading: uniaxial
    potentials: [harmonic]
    d_over_d0: [0.95, 1.0]
    theta: {n: 4}
    quantities: [dispersion, displacements, entropy]
    accuracy: {displacements: {n_rows: 6}}
"""
CUBES = {"tiny": ["crystal", "elastic", "rayleigh"],
         "tiny_tri": ["crystal", "dispersion", "displacements", "entropy"]}


class Terminated(BaseException):
    """SIGTERM (e.g. from `timeout`) turned into an exception, so `finally` stops the daemons."""


def _on_sigterm(signum, frame):
    raise Terminated(f"signal {signum}")


def _run(cmd, timeout, check=True, **kw) -> subprocess.CompletedProcess:
    return subprocess.run(cmd, capture_output=True, text=True, timeout=max(timeout, 1), check=check, **kw)


def _missing() -> list[str]:
    return [b for b in BINARIES if shutil.which(b, path=SEARCH_PATH) is None]


def why_not_runnable() -> str | None:
    """Why this machine cannot run the test (None: it can, possibly after installing packages)."""
    if not sys.platform.startswith("linux"):
        return "needs Linux (SLURM daemons)"
    if os.geteuid() != 0:
        return "needs root (it starts munged, slurmctld and slurmd and may apt-get install them)"
    if SYSTEM_CONF.exists() and MARKER not in SYSTEM_CONF.read_text(errors="replace"):
        return f"{SYSTEM_CONF} exists (a real SLURM setup?): the test does not touch it"
    if _missing() and shutil.which("apt-get", path=SEARCH_PATH) is None:
        return f"SLURM/munge not installed and no apt-get to install {' '.join(PACKAGES)}"
    return None


def install(deadline: float) -> str | None:
    """apt-get install the Debian packages when a binary is missing; the error text if it fails."""
    if not _missing():
        return None
    env = {**os.environ, "DEBIAN_FRONTEND": "noninteractive", "PATH": SEARCH_PATH}
    cmd = ["apt-get", "install", "-y", "-q", "--no-install-recommends", *PACKAGES]
    proc = _run(cmd, deadline - time.time(), check=False, env=env)
    if proc.returncode != 0:  # a fresh image has no package lists yet
        _run(["apt-get", "update", "-q"], deadline - time.time(), check=False, env=env)
        proc = _run(cmd, deadline - time.time(), check=False, env=env)
    missing = _missing()
    if proc.returncode != 0 or missing:
        return f"apt-get install {' '.join(PACKAGES)} failed (missing {missing}): {proc.stderr[-1500:]}"
    return None


def _stop_pid(pid: int, grace: float = 10.0) -> None:
    """SIGTERM, then SIGKILL after `grace` seconds, a process that is not our child."""
    try:
        os.kill(pid, signal.SIGTERM)
    except ProcessLookupError:
        return
    end = time.time() + grace
    while time.time() < end:
        try:
            os.kill(pid, 0)
        except ProcessLookupError:
            return
        time.sleep(0.1)
    try:
        os.kill(pid, signal.SIGKILL)
    except ProcessLookupError:
        pass


def stop_stale_daemons() -> None:
    """Stop daemons a previous, hard-killed run left behind (PIDs from PIDFILE, names checked)."""
    if SYSTEM_CONF.exists() and MARKER in SYSTEM_CONF.read_text(errors="replace"):
        SYSTEM_CONF.unlink()
    if not PIDFILE.exists():
        return
    for line in PIDFILE.read_text().split():
        pid = int(line)
        try:
            cmdline = Path(f"/proc/{pid}/cmdline").read_bytes().split(b"\0")[0].decode()
        except OSError:
            continue
        if Path(cmdline).name in ("munged", "slurmctld", "slurmd"):
            _stop_pid(pid)
    PIDFILE.unlink(missing_ok=True)


class LocalSlurm:
    """A single-node SLURM cluster on localhost: munged, slurmctld and slurmd under `root`.

    Its slurm.conf is SYSTEM_CONF (clients and the jobs' srun find it there); the munge socket,
    key, ports and state are private, so a munged already running is neither used nor disturbed.
    """

    def __init__(self, root: Path):
        self.root = root
        self.conf = SYSTEM_CONF
        self.host = socket.gethostname().split(".")[0]
        self.procs: list[subprocess.Popen] = []
        self.env = {k: v for k, v in os.environ.items() if k != "SLURM_CONF"}
        self.env["PATH"] = SEARCH_PATH

    def write_config(self) -> None:
        r = self.root
        for d in ("state", "spool", "log"):
            (r / d).mkdir(parents=True, exist_ok=True)
        cpus = len(os.sched_getaffinity(0))
        mem_mb = int(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES") / 2**20 * 0.8)
        if self.conf.exists() and MARKER not in self.conf.read_text(errors="replace"):
            raise FileExistsError(f"{self.conf} exists and is not ours: not touching a real SLURM setup")
        self.conf.parent.mkdir(parents=True, exist_ok=True)
        self.conf.write_text(f"""\
{MARKER} (no accounting, no cgroups); removed when the test ends.
ClusterName=surfwavetest
SlurmctldHost={self.host}(127.0.0.1)
SlurmctldPort={CTLD_PORT}
SlurmdPort={SLURMD_PORT}
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket={r / 'munge.socket'}
CredType=cred/munge
StateSaveLocation={r / 'state'}
SlurmdSpoolDir={r / 'spool'}
SlurmctldPidFile={r / 'slurmctld.pid'}
SlurmdPidFile={r / 'slurmd.pid'}
SlurmctldLogFile={r / 'log' / 'slurmctld.log'}
SlurmdLogFile={r / 'log' / 'slurmd.log'}
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
SlurmdParameters=config_overrides
MpiDefault=none
ReturnToService=2
MailProg=/bin/true
# Finished jobs stay visible to squeue for 300 s (SLURM's default): above 3x the profile's
# initial status wait and above the plugin's longest wait between status checks (180 s).
MinJobAge=300
AccountingStorageType=accounting_storage/none
JobAcctGatherType=jobacct_gather/none
JobCompType=jobcomp/none
NodeName={self.host} NodeAddr=127.0.0.1 CPUs={cpus} RealMemory={mem_mb} State=UNKNOWN
PartitionName=debug Nodes={self.host} Default=YES MaxTime=INFINITE State=UP
""")

    def _spawn(self, name: str, cmd: list[str]) -> None:
        log = open(self.root / "log" / f"{name}.out", "w")
        proc = subprocess.Popen(cmd, stdout=log, stderr=subprocess.STDOUT, env=self.env,
                                stdin=subprocess.DEVNULL, start_new_session=True)
        self.procs.append(proc)
        with open(PIDFILE, "a") as f:
            f.write(f"{proc.pid}\n")

    def start(self, deadline: float) -> None:
        r = self.root
        self.write_config()
        key = r / "munge.key"
        _run(["mungekey", "--create", f"--keyfile={key}"], deadline - time.time(), env=self.env)
        key.chmod(0o600)
        self._spawn("munged", ["munged", "--foreground", "--force", f"--socket={r / 'munge.socket'}",
                               f"--key-file={key}", f"--pid-file={r / 'munged.pid'}",
                               f"--log-file={r / 'log' / 'munged.log'}", f"--seed-file={r / 'munged.seed'}"])
        self._wait(lambda: (r / "munge.socket").exists(), deadline, "munged socket")
        self._spawn("slurmctld", ["slurmctld", "-D", "-c", "-i", "-f", str(self.conf)])
        self._wait(lambda: _run(["scontrol", "ping"], 10, check=False, env=self.env).returncode == 0,
                   deadline, "slurmctld (scontrol ping)")
        self._spawn("slurmd", ["slurmd", "-D", "-f", str(self.conf), "-N", self.host])
        self._wait(lambda: self.node_state() == "idle", deadline, "node idle in sinfo")

    def remove_config(self) -> None:
        if self.conf.exists() and MARKER in self.conf.read_text(errors="replace"):
            self.conf.unlink()

    def node_state(self) -> str:
        proc = _run(["sinfo", "-h", "-N", "-o", "%t"], 10, check=False, env=self.env)
        return proc.stdout.strip()

    def _wait(self, ready, deadline: float, what: str) -> None:
        while time.time() < deadline:
            for p in self.procs:
                if p.poll() is not None:
                    raise RuntimeError(f"{p.args[0]} exited ({p.returncode}) while waiting for {what}:\n"
                                       + self.logs())
            if ready():
                return
            time.sleep(0.2)
        raise TimeoutError(f"timed out waiting for {what}:\n" + self.logs())

    def logs(self) -> str:
        out = []
        for f in sorted((self.root / "log").glob("*")):
            out.append(f"--- {f.name}\n" + f.read_text(errors="replace")[-2000:])
        return "\n".join(out)

    def stop(self) -> None:
        """Cancel every job of this cluster, then stop slurmd, slurmctld and munged by PID."""
        if any(p.args[0] == "slurmctld" and p.poll() is None for p in self.procs):
            try:  # never let a slow or failing scancel keep the daemons running
                _run(["scancel", "--full", "--user", "root"], 15, check=False, env=self.env)
            except (OSError, subprocess.SubprocessError):
                pass
        for p in reversed(self.procs):  # our children: wait() reaps them
            p.terminate()
            try:
                p.wait(timeout=15)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
        PIDFILE.unlink(missing_ok=True)
        self.remove_config()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()


def _mkdir(path: Path) -> Path:
    path.mkdir(parents=True)
    return path


def snakemake(workdir: Path, args: list[str], deadline: float, env: dict) -> tuple[float, str]:
    """Run snakemake in its own process group; kill the group (SIGKILL: the plugin may ignore
    SIGTERM) when the deadline passes. Returns (seconds, output); raises on failure."""
    env = {**env, "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1"}
    log = workdir / "snakemake.out"
    t0 = time.perf_counter()
    with open(log, "w") as out:
        proc = subprocess.Popen([str(SNAKEMAKE), "--directory", str(workdir), *args], cwd=workdir,
                                stdout=out, stderr=subprocess.STDOUT, env=env, start_new_session=True)
        try:
            proc.wait(timeout=max(deadline - time.time(), 1))
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGTERM)
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
            raise AssertionError(f"snakemake {' '.join(args)} did not finish in time:\n"
                                 + log.read_text()[-4000:]) from None
        except BaseException:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait()
            raise
    seconds = time.perf_counter() - t0
    text = log.read_text()
    if proc.returncode != 0:
        raise AssertionError(f"snakemake {' '.join(args)} failed ({proc.returncode}):\n{text[-6000:]}")
    return seconds, text


def compare_cubes(local: Path, cluster: Path) -> list[str]:
    """Differences between two results/ trees: missing cubes, data variables or coordinates."""
    from surfwave.data.cube import open_cube  # complex values as numbers

    problems = []
    names = sorted(p.relative_to(local) for p in local.rglob("*.nc") if "cache" not in p.parts)
    other = sorted(p.relative_to(cluster) for p in cluster.rglob("*.nc") if "cache" not in p.parts)
    if names != other:
        problems.append(f"different cube files: local {names}, cluster {other}")
    for name in sorted(set(names) & set(other)):
        a, b = open_cube(local / name), open_cube(cluster / name)
        a.attrs, b.attrs = {}, {}  # history (time, rule) differs by design
        if not a.identical(b):
            diff = [v for v in set(a.variables) | set(b.variables)
                    if v not in a.variables or v not in b.variables or not a[v].identical(b[v])]
            problems.append(f"{name}: not identical (variables {sorted(diff)})")
    return problems


def test_profiles_keep_cluster_runs_free_of_laptop_settings():
    """Static checks (no cluster, part of `make test`): Snakemake loads profiles/default for
    every run and lets it override --profile, so it may set nothing machine-specific; the
    SLURM profile hard-codes no site value and queries job status in a way that works
    without accounting."""
    import yaml

    default = yaml.safe_load((REPO / "profiles" / "default" / "config.yaml").read_text()) or {}
    slurm = yaml.safe_load((REPO / "profiles" / "slurm" / "config.yaml").read_text())
    machine = {"cores", "jobs", "latency-wait", "executor", "default-resources", "set-resources",
               "resources", "local-cores", "set-threads", "groups", "group-components"}
    assert not machine & set(default), sorted(machine & set(default))
    assert not {k for k in default if k in slurm and slurm[k] != default[k]}
    assert slurm["executor"] == "slurm"
    site = slurm.get("default-resources", {})
    assert not {"slurm_partition", "slurm_account", "cpus_per_task"} & set(site), site
    assert all("cpus_per_task" not in r for r in slurm.get("set-resources", {}).values())
    assert slurm["slurm-status-command"] == "squeue"
    # squeue sees a finished job for MinJobAge (default 300 s); the plugin wants >= 3x this.
    assert 3 * slurm["slurm-init-seconds-before-status-checks"] <= 300


@pytest.mark.workflow
def test_slurm_profile_dry_run(tmp_path):
    """The profile as shipped plans the tiny scenes (no cluster needed). It needs the plugin,
    which only .venv-cluster has (environment-cluster.lock): `make test-slurm` runs it there;
    in the default environment it skips (a failure where the SLURM test is required)."""
    if importlib.util.find_spec("snakemake_executor_plugin_slurm") is None:
        reason = (f"snakemake-executor-plugin-slurm is not installed in {sys.prefix} (it is in "
                  ".venv-cluster: `make test-slurm`)")
        if os.environ.get("SURFWAVE_SLURM_REQUIRED"):
            pytest.fail(reason)
        pytest.skip(reason)
    wd = make_workdir(tmp_path)
    proc = smk(wd, "-n", "--profile", "profiles/slurm")
    jobs = scheduled(proc)
    assert ("rayleigh", "tiny_fcc") in jobs and ("entropy", "tiny_tri") in jobs


def test_slurm_profile_on_local_cluster(tmp_path):
    if not os.environ.get("SURFWAVE_SLURM_TEST"):
        pytest.skip("opt-in: `make test-slurm` (needs root and the Debian archive; runs in CI)")
    budget = float(os.environ.get("SURFWAVE_SLURM_BUDGET", "600"))
    deadline = time.time() + budget

    def cannot(reason: str):
        if os.environ.get("SURFWAVE_SLURM_REQUIRED"):
            pytest.fail(f"SLURM test required but cannot run: {reason}")
        pytest.skip(reason)

    reason = why_not_runnable()
    if reason:
        cannot(reason)
    if importlib.util.find_spec("snakemake_executor_plugin_slurm") is None:
        # checked before any install: the plugin is only in .venv-cluster (environment-cluster.lock)
        cannot(f"snakemake-executor-plugin-slurm is not installed in {sys.prefix}: run "
               "`make test-slurm`, which uses .venv-cluster (`make cluster-env`)")
    previous = signal.signal(signal.SIGTERM, _on_sigterm)
    try:
        stop_stale_daemons()
        t_install = time.perf_counter()
        error = install(deadline)
        if error:
            cannot(error)
        t_install = time.perf_counter() - t_install

        local = make_workdir(_mkdir(tmp_path / "local"), TINY)
        t_local, _ = snakemake(local, ["-j2"], deadline, dict(os.environ))

        cluster = make_workdir(_mkdir(tmp_path / "cluster"), TINY)
        t_start = time.perf_counter()
        with LocalSlurm(tmp_path / "slurm") as slurm:
            slurm.start(deadline)
            t_start = time.perf_counter() - t_start
            try:
                t_slurm, out = snakemake(cluster, ["--profile", "profiles/slurm"], deadline, slurm.env)
            except AssertionError as exc:
                raise AssertionError(f"{exc}\n{slurm.logs()}") from None
        assert re.search(r"submitted with SLURM jobid \d+", out), out[-3000:]
        for scene, cubes in CUBES.items():
            for c in cubes:
                assert (cluster / "results" / scene / f"{c}.nc").exists(), (scene, c)
        assert any((cluster / "results" / "cache").rglob("*.npz")), "parameter cache not written"
        problems = compare_cubes(local / "results", cluster / "results")
        assert not problems, "\n".join(problems)
        print(f"\nSLURM test timings: install {t_install:.1f} s, local -j2 {t_local:.1f} s, "
              f"cluster start {t_start:.1f} s, --profile profiles/slurm {t_slurm:.1f} s")
    finally:
        signal.signal(signal.SIGTERM, previous)


if __name__ == "__main__":  # python tests/workflow/test_slurm.py -- CMD...: CMD against a throwaway cluster
    if "--" not in sys.argv or os.geteuid() != 0:
        sys.exit(__doc__)
    cmd = sys.argv[sys.argv.index("--") + 1:]
    signal.signal(signal.SIGTERM, _on_sigterm)
    stop_stale_daemons()
    with tempfile.TemporaryDirectory(prefix="surfwave-slurm-") as tmp:
        with LocalSlurm(Path(tmp)) as slurm:
            slurm.start(time.time() + 120)
            sys.exit(subprocess.run(cmd, env=slurm.env).returncode)
