"""Run a workflow script by hand, without Snakemake running it (for debugging, e.g. with pdb).

``python workflow/scripts/<rule>.py [SCENE] [CONFIGFILE ...] [WILDCARD=VALUE ...]`` (from the
repository root) parses the workflow with Snakemake's API, takes the rule of the same name
and fills its wildcards, so the script sees exactly the ``input``, ``output``, ``params``
and ``log`` the rule would give it, nothing retyped. Inputs are not built: run the
upstream stages first (or ``snakemake <input file>``).
"""
from __future__ import annotations

import sys
from functools import lru_cache
from pathlib import Path
from types import SimpleNamespace
from typing import Sequence

DEFAULT_CONFIG = "config/config.yaml"


def _parse(argv: list[str]) -> tuple[str | None, list[str], dict[str, str]]:
    """(scene, config files, wildcard values) from ``SCENE [CONFIGFILE ...] [NAME=VALUE ...]``."""
    scene, configs, wildcards = None, [], {}
    for arg in argv:
        if "=" in arg:
            key, value = arg.split("=", 1)
            wildcards[key] = value
        elif arg.endswith((".yaml", ".yml", ".json")):
            configs.append(arg)
        elif scene is None:
            scene = arg
        else:
            raise SystemExit(f"unexpected argument {arg!r} (a second scene?)")
    return scene, configs, ({"scene": scene} if scene else {}) | wildcards


@lru_cache(maxsize=4)
def _workflow(snakefile: Path, configfiles: tuple[Path, ...]):
    """The parsed workflow (Snakemake's API, as ``snakemake --configfile ...`` would load it)."""
    from snakemake.api import ConfigSettings, OutputSettings, ResourceSettings, SnakemakeApi, StorageSettings

    with SnakemakeApi(OutputSettings()) as api:
        return api.workflow(resource_settings=ResourceSettings(), storage_settings=StorageSettings(),
                            config_settings=ConfigSettings(configfiles=list(configfiles)),
                            snakefile=snakefile)._workflow


def standalone(rule: str, argv: Sequence[str] | None = None, snakefile: str | Path = "Snakefile") -> SimpleNamespace:
    """A stand-in for Snakemake's ``snakemake`` object, built from the rule itself.

    Parameters
    ----------
    rule : str
        Name of the rule (the script's file name without ``.py``); ``{scene}`` in it is
        replaced by the scene (rules made per scene, such as ``figures_{scene}``).
    argv : list of str, optional
        ``[SCENE] [CONFIGFILE ...] [WILDCARD=VALUE ...]``; default ``sys.argv[1:]``
        (SCENE where the rule has a ``scene`` wildcard). The
        config files extend ``config/config.yaml`` as ``--configfile`` does; the other
        wildcards of the rule (e.g. ``potential=lj``) are given as ``name=value``.
    snakefile : path
        The workflow's Snakefile (run from the repository root).

    Returns
    -------
    types.SimpleNamespace
        ``input``, ``output``, ``params``, ``log``, ``wildcards`` (Snakemake's own
        containers, filled by the rule), ``rule``, ``threads`` (1) and ``config``.
    """
    argv = list(sys.argv[1:] if argv is None else argv)
    scene, configs, values = _parse(argv)
    script = Path(sys.argv[0]).name if sys.argv[0].endswith(".py") else f"{rule}.py"
    usage = f"usage: python workflow/scripts/{script} [SCENE] [CONFIGFILE ...] [WILDCARD=VALUE ...]"
    if "{scene}" in rule:
        if scene is None:
            raise SystemExit(f"which scene? {usage}")
        rule = rule.replace("{scene}", scene)
    from snakemake.iocontainers import Wildcards

    files = tuple(Path(f).resolve() for f in (DEFAULT_CONFIG, *configs))
    workflow = _workflow(Path(snakefile).resolve(), files)
    try:
        r = workflow.get_rule(rule)
    except Exception as exc:  # snakemake's UnknownRuleException
        raise SystemExit(f"no rule {rule!r} in {snakefile}: {exc}") from None
    scenes = workflow.config.get("scenes", {})
    if "scene" in r.wildcard_names and scene not in scenes:
        raise SystemExit(f"unknown scene {scene!r}; known scenes: {sorted(scenes)}; {usage}")
    missing = sorted(set(r.wildcard_names) - set(values))
    if missing:
        raise SystemExit(f"rule {rule!r} needs the wildcards {missing} (as name=value); {usage}")
    wildcards = Wildcards(fromdict={k: values[k] for k in r.wildcard_names})
    inputs = r.expand_input(wildcards)[0]
    output = r.expand_output(wildcards)[0]
    params = r.expand_params(wildcards, inputs, output, None)[0]
    log = r.expand_log(wildcards)
    config = workflow.config
    for path in (*output, *log):
        Path(path).parent.mkdir(parents=True, exist_ok=True)
    print(f"{rule} (by hand): writes {list(output)}, log {list(log)}", file=sys.stderr)
    return SimpleNamespace(input=inputs, output=output, params=params, log=log, wildcards=wildcards,
                           rule=rule, threads=1, config=config)
