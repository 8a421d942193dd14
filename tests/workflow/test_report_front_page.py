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


def _readme_outputs() -> list[str]:
    """Regexes of the result files the README's "After `make reproduce`" table names: each row's
    first cell is a path, then file names of the same directory or extensions of the file before."""
    import re

    text = (REPO / "README.md").read_text()
    table = text.split("After `make reproduce`, `results/` holds:")[1].split("\n\n")[1]
    out = []
    for row in table.splitlines()[2:]:
        items = re.findall(r"`([^`]+)`", row.split("|")[1])
        folder, path = items[0].rsplit("/", 1)[0], items[0]
        for item in items:
            path = (item if item.startswith("results/") else f"{path.rsplit('.', 1)[0]}{item}"
                    if item.startswith(".") else f"{folder}/{item}")
            out.append(re.escape(path).replace(re.escape("<potential>"), r"\w+")
                       .replace(re.escape("<scene>"), r"\w+").replace(re.escape("<cube>"), r"\w+"))
    return out


def test_readme_lists_every_figure_and_table_of_the_default_scenes():
    """Issue 27: table1/speeds_vs_stress.png was drawn but not listed in the README."""
    import re

    from surfwave.pipeline.scenes import validate_config
    from surfwave.pipeline.targets import scene_outputs

    scenes = validate_config(load_config([REPO / "config" / "config.yaml"]))
    listed = _readme_outputs()
    missing = [f"results/{name}/{f}" for name in scenes for f in scene_outputs(scenes, name).values()
               if not any(re.fullmatch(p, f"results/{name}/{f}") for p in listed)]
    assert not missing, f"README.md does not list {missing}"
