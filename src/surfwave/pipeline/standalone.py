"""Run a workflow stage script by hand, without Snakemake (for debugging, e.g. with pdb).

``python workflow/scripts/<stage>.py SCENE [CONFIGFILE ...]`` (from the repository root)
builds a stand-in for Snakemake's ``snakemake`` object from the config files, runs the stage
for one scene, writes ``results/<scene>/<stage>.nc`` and logs to the terminal.
"""
from __future__ import annotations

import sys
from types import SimpleNamespace

from surfwave.pipeline.scenes import job_params, load_config, validate_config


def standalone(stage: str, argv=None, inputs: dict | None = None) -> SimpleNamespace:
    """A stand-in for Snakemake's ``snakemake`` object, to run a stage script by hand.

    ``python workflow/scripts/<stage>.py SCENE [CONFIGFILE ...]`` (from the repository root)
    runs the stage for one scene of ``config/config.yaml`` (plus the given files), writes
    ``results/<scene>/<stage>.nc`` and logs to the terminal. Useful for debugging with pdb.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv:
        raise SystemExit(f"usage: python workflow/scripts/{stage}.py SCENE [CONFIGFILE ...]")
    name, files = argv[0], ["config/config.yaml", *argv[1:]]
    config = load_config(files)
    scenes = validate_config(config)
    if name not in scenes:
        raise SystemExit(f"unknown scene {name!r}; known scenes: {sorted(scenes)}")
    from surfwave.data.cache import DEFAULT_ROOT

    inputs = {k: v.format(scene=name) for k, v in (inputs or {}).items()}
    return SimpleNamespace(
        input=SimpleNamespace(**inputs),
        output=[f"results/{name}/{stage}.nc"],
        log=["/dev/stderr"],
        params=SimpleNamespace(job=job_params(scenes[name], stage), cache=str(DEFAULT_ROOT)),
        wildcards=SimpleNamespace(scene=name),
        rule=stage,
    )


