"""A user's own scene never rewrites the paper's report (real Snakemake runs, marker `workflow`).

Reference: Snakemake's own up-to-date check (`-n` prints "Nothing to be done") and the
report's input list (surfwave.pipeline.targets.report_inputs), which must name the paper's
scenes of paper_values.yaml only.
"""
from __future__ import annotations

import pytest
from test_workflow import built, own_copy, scheduled, smk  # noqa: F401 (fixture reused)

from surfwave.pipeline.targets import paper_scenes, report_inputs, scene_outputs

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]

MINE = """
run: [mine]
scenes:
  mine:
    lattice: fcc
    loading: uniaxial
    potentials: [lj]
    directions: ["[100]"]
    d_over_d0: [1.0]
    quantities: [elastic, rayleigh, bulk]
    accuracy: {bulk: {zone_mesh: 2}}
"""


def test_report_inputs_ignore_user_scenes():
    """A user scene asking for bulk used to feed report.md (its bulk section)."""
    mine = {"quantities": ["elastic", "rayleigh", "bulk"]}
    assert report_inputs({"mine": mine}) == []
    assert "results/table1/bulk.nc" in report_inputs({"table1": mine, "mine": mine})
    both = {"mine": mine, "table1": mine}
    assert "summary" in scene_outputs(both, "mine") and "summary" not in scene_outputs(both, "table1")
    assert {"table1", "fig2", "triangular", "entropy"} <= set(paper_scenes())


def test_user_scene_does_not_schedule_the_paper_report(built, tmp_path):  # noqa: F811 (fixture)
    """A user scene with bulk used to rewrite report.md ("0 PASS ... 18 not computed") and
    leave the default config out of date; now the run schedules its summary, never the report.
    (A dry run: the real run was checked by hand, see the report of issue 12.)"""
    wd = own_copy(built, tmp_path / "wf")
    (wd / "my.yaml").write_text(MINE)
    # In the same run: a truncated cube (which made every figure and report job fail with
    # an h5py traceback) is named in one line and set aside, so Snakemake rebuilds it.
    damaged = wd / "results" / "tiny_fcc" / "rayleigh.nc"
    damaged.write_bytes(damaged.read_bytes()[:4000])
    dry = smk(wd, "-n", "--configfile", "config/config.yaml", "my.yaml")
    text = dry.stdout + dry.stderr
    assert "rule report_md:" not in text
    assert ("figures_mine", "mine") in scheduled(dry)
    line = next(ln for ln in text.splitlines() if "is damaged" in ln)
    assert "results/tiny_fcc/rayleigh.nc" in line and "truncated" in line and "rebuilds it" in line
    assert not damaged.exists() and damaged.with_name("rayleigh.nc.damaged").exists()


def test_scene_summary_counts(tmp_path):
    """summary.md of a synthetic scene: ranges, NaN counts and unstable counts as built."""
    import numpy as np
    import xarray as xr

    from surfwave.data import cube
    from surfwave.report.summary import scene_summary

    d = [0.9, 1.0, 1.1]
    ds = xr.Dataset({"c2_R": (("strain",), np.array([np.nan, 0.3, 0.31]), {"long_name": "c_R^2", "units": "1"}),
                     "stable": (("strain",), np.array([False, True, True]), {"long_name": "stable"}),
                     "reason": (("strain",), np.array(["unstable", "", ""]), {"long_name": "why"})},
                    coords=cube.strain_coords(d))
    path = cube.write(ds, tmp_path / "mine" / "rayleigh.nc")
    text = scene_summary([path, tmp_path / "mine" / "bulk.nc"], "mine")
    assert "| `c2_R` | c_R^2 | 3 | 1 |" in text
    assert "`stable` False (unstable) at 1 of 3 points" in text and "1 points: unstable" in text
    assert "d/d0: 0.9 .. 1.1 (3 values)" in text and "### `bulk.nc`\n\nnot computed" in text
