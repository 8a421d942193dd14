# Helpers shared by the rules. Logic lives in surfwave.pipeline.scenes; this file only wires it up.
from surfwave.data import cache
from surfwave.data.provenance import module_closure
from surfwave.pipeline.scenes import job_params, selected, targets

#: Software of every rule under `--sdm conda` (the default route is the .venv from the lock).
CONDA_ENV = "../envs/surfwave.yaml"
#: The paper's printed numbers (the report's and Table I's only hand-typed values).
PAPER_VALUES = "src/surfwave/data/paper_values.yaml"
#: The materials database (real-crystal scenes read it).
MATERIALS = "src/surfwave/data/materials.yaml"


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
