# Helpers shared by the rules. Logic lives in surfwave.pipeline.scenes; this file only wires it up.
import threading

from surfwave.data import cache
from surfwave.data.provenance import module_closure
from surfwave.pipeline.scenes import job_params, selected, targets
from surfwave.pipeline.targets import report_entry

#: Software of every rule under `--sdm conda` (the default route is the .venv from the lock).
CONDA_ENV = "../envs/surfwave.yaml"
#: The paper's printed numbers (the report's and Table I's only hand-typed values).
PAPER_VALUES = "src/surfwave/data/paper_values.yaml"
#: The materials database (real-crystal scenes read it).
MATERIALS = "src/surfwave/real_crystals/materials.yaml"


def scene_targets():
    """Cubes of the selected scenes (config `run`, default every scene), built by `all`."""
    return targets(SCENES, selected(config, SCENES))


def params_for(stage):
    """Params of a stage's job: exactly the config values it uses (surfwave.pipeline.scenes.job_params)."""
    return lambda wildcards: job_params(SCENES[wildcards.scene], stage)


def code(*modules, shallow=()):
    """Library files a stage runs (transitive surfwave imports), as inputs: code changes rerun it.
    ``shallow`` modules count without their imports (surfwave.data.provenance.module_closure).
    """
    return module_closure(*modules, shallow=shallow)


def report_output(key, path, scene):
    """``path`` wrapped for `snakemake --report` when its output kind has a caption
    (surfwave.pipeline.targets.REPORT_ENTRIES), else ``path``."""
    entry = report_entry(key)
    if entry is None:
        return path
    return report(
        path, caption=f"../report/{entry[0]}", category=entry[1], subcategory=scene
    )


def exit_now():
    """Let the process end when the run has: Snakemake's scheduler leaves a non-daemon
    threading.Timer (its once-a-second re-check of the job rate limit) pending, and Python
    waits up to 1 s for it at exit. Cancelling it after the run changes nothing else."""
    for thread in threading.enumerate():
        if isinstance(thread, threading.Timer):
            thread.cancel()
