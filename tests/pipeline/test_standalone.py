"""Stage scripts run by hand take input, output, params and log from their rule.

Reference: the rules themselves (workflow/rules/*.smk), parsed by Snakemake's API, and the
job parameters of surfwave.pipeline.scenes.job_params for the same scene: nothing is
retyped in the scripts, so a path or parameter changed in a rule reaches the hand run too.
"""
from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest

from surfwave.pipeline.scenes import job_params, load_config, validate_config
from surfwave.pipeline.standalone import standalone

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = sorted(p.stem for p in (ROOT / "workflow" / "scripts").glob("*.py"))


@pytest.fixture
def workflow_copy(tmp_path, monkeypatch):
    """The workflow definition in a temporary directory (hand runs create results/ dirs)."""
    for name in ("workflow", "config"):
        shutil.copytree(ROOT / name, tmp_path / name)
    shutil.copy(ROOT / "Snakefile", tmp_path / "Snakefile")
    monkeypatch.chdir(tmp_path)
    return tmp_path


def test_stage_and_figure_rules_fill_the_stand_in(workflow_copy):
    """elastic (scene wildcard, params from job_params) and the per-scene figures rule
    (`figures_triangular`, named after the scene): paths and params are the rule's."""
    job = standalone("elastic", ["table1"])
    assert job.input.crystal == "results/table1/crystal.nc"
    assert list(job.output) == ["results/table1/elastic.nc"]
    assert job.log[0].startswith("results/table1/logs/")
    scenes = validate_config(load_config(["config/config.yaml"]))
    assert job.params.job == job_params(scenes["table1"], "elastic")
    assert any(f.endswith("surfwave/model_crystals/elastic.py") for f in job.input.code)

    fig = standalone("figures_{scene}", ["triangular"])
    assert fig.output.dispersion_lj == "results/triangular/dispersion_lj.png"
    assert fig.output.theta_c == "results/triangular/theta_c.png"
    assert fig.input.dispersion == "results/triangular/dispersion.nc"
    assert fig.params.cubes == ["dispersion", "displacements"]
    assert os.path.isdir("results/triangular/logs")
    with pytest.raises(SystemExit, match="which scene"):
        standalone("figures_{scene}", [])
    with pytest.raises(SystemExit, match="unknown scene 'nope'"):
        standalone("elastic", ["nope"])


def test_every_rule_script_has_a_hand_run():
    """Every script a rule runs (benchmark runners aside, whose rule wildcard is the script
    name itself) builds its stand-in through surfwave.pipeline.standalone."""
    for name in SCRIPTS:
        if name.startswith("benchmark_"):
            continue
        text = (ROOT / "workflow" / "scripts" / f"{name}.py").read_text()
        assert "standalone(" in text and "SimpleNamespace" not in text, name
