# surfwave: Rayleigh waves in prestressed crystals.
#   snakemake -j2                          every scene of config/config.yaml (or those in `run:`)
#   snakemake -j2 --configfile my.yaml     add your scenes (merged with the defaults)
#   snakemake -j2 --config 'run=[my_scene]' --configfile my.yaml   only your scene
import os
import re
import sys
from pathlib import Path

from snakemake.exceptions import WorkflowError
from snakemake.utils import min_version

# This checkout's library, even when another surfwave is installed in the environment
# (the module paths below become rule inputs, so they must be this checkout's files).
sys.path.insert(0, str(Path(workflow.basedir, "src")))

from surfwave.data import cache
from surfwave.data.integrity import set_aside_damaged
from surfwave.pipeline.knobs import expected_cost
from surfwave.pipeline.scenes import (
    SceneError,
    config_sources,
    scene_notes,
    selected,
    validate_config,
)

min_version("9.13.1")

# Jobs (also under --sdm conda or on a cluster) import this checkout's library.
os.environ.update(
    PYTHONPATH=os.pathsep.join(
        p
        for p in (str(Path(workflow.basedir, "src")), os.environ.get("PYTHONPATH"))
        if p
    )
)


configfile: "config/config.yaml"


# Front page of `snakemake --report report.html`: what the workflow is.
report: "workflow/report/workflow.rst"


# Schema (with defaults) and physical ranges, before any job runs; errors name scene, key, value.
# The config files are read once more to refuse duplicate keys (file, key, lines) and to
# know which scenes were defined in more than one file (merged by Snakemake).
try:
    SCENES = validate_config(
        config,
        Path(workflow.basedir, "workflow", "schemas", "config.schema.yaml"),
        sources=config_sources(
            f
            for f in ["config/config.yaml", *workflow.configfiles]
            if os.path.exists(f)
        ),
    )
except SceneError as exc:
    raise WorkflowError(str(exc)) from None


# Stages expected to run long (costly accuracy settings) are announced before any job,
# and so are Euler angles that all look like radians (they are taken as degrees).
for _line in expected_cost(SCENES, selected(config, SCENES)) + scene_notes(SCENES):
    print(_line, file=sys.stderr)

# A damaged cube (truncated, not netCDF) is set aside as <file>.damaged and rebuilt,
# instead of failing every figure and report job that reads it.
for _line in set_aside_damaged(Path("results").glob("*/*.nc")):
    print(_line, file=sys.stderr)


wildcard_constraints:
    scene="|".join(re.escape(name) for name in SCENES),


onstart:
    cache.start_run(cache.DEFAULT_ROOT)  # `surfwave cache info` counts hits from here


# Each job writes its progress and its summary line to its own log; the run ends with the
# summary lines of every cached stage ("bulk, scene x: 22 points, 14 from the cache, ...").
onsuccess:
    for _line in cache.run_summary(cache.DEFAULT_ROOT):
        print(_line, file=sys.stderr)
    exit_now()


onerror:
    for _line in cache.run_summary(cache.DEFAULT_ROOT):
        print(_line, file=sys.stderr)
    exit_now()


include: "workflow/rules/common.smk"
include: "workflow/rules/crystal.smk"
include: "workflow/rules/elastic.smk"
include: "workflow/rules/rayleigh.smk"
include: "workflow/rules/bulk.smk"
include: "workflow/rules/dispersion.smk"
include: "workflow/rules/entropy.smk"
include: "workflow/rules/surface_phonons.smk"
include: "workflow/rules/surface_wave.smk"
include: "workflow/rules/piezo.smk"
include: "workflow/rules/layered.smk"
# Figures, report, benchmarks: they define FIGURE_TARGETS and REPORT_TARGETS.
include: "workflow/rules/figures.smk"
include: "workflow/rules/report.smk"
include: "workflow/rules/benchmarks.smk"


rule all:
    default_target: True
    input:
        scene_targets(),
        globals().get("FIGURE_TARGETS", []),
        globals().get("REPORT_TARGETS", []),
