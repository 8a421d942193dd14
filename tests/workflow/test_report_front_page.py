"""The HTML report's front page (workflow/report/workflow.rst, `snakemake --report`) names
every default scene and every figure category, so a new scene or category cannot be left off.

Reference: the default config (config/config.yaml, as the workflow loads it) and the report
categories of surfwave.pipeline.targets.REPORT_ENTRIES.
"""
from __future__ import annotations

from pathlib import Path

from surfwave.pipeline.scenes import load_config
from surfwave.pipeline.targets import REPORT_ENTRIES

REPO = Path(__file__).resolve().parents[2]
FRONT = (REPO / "workflow" / "report" / "workflow.rst").read_text()


def test_front_page_lists_every_default_scene():
    scenes = load_config([REPO / "config" / "config.yaml"])["scenes"]
    missing = [name for name in scenes if f"``{name}``" not in FRONT]
    assert not missing, f"workflow/report/workflow.rst does not name the default scenes {missing}"
    assert "rotated_y_cuts" in scenes          # the piezoelectric scenes are among those checked


def test_front_page_points_to_every_figure_category():
    cats = {cat for _, cat in REPORT_ENTRIES.values()}
    short = {c.split(":")[0] for c in cats}      # "Fig. 2: sound speeds versus stress" -> "Fig. 2"
    missing = [c for c in short if f"**{c}" not in FRONT]
    assert not missing, f"workflow/report/workflow.rst does not point to the categories {missing}"
