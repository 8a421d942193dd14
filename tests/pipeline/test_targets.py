"""What each scene's figures job writes, reads and where it runs (surfwave.pipeline.targets).

Reference: the list of outputs documented in the README ("After make reproduce, results/
holds") and docs/cluster.md (the SLURM groups), written out here by hand.
"""
from pathlib import Path

import pytest

from surfwave.pipeline.scenes import load_config, validate_config
from surfwave.pipeline.targets import figure_group, report_entry, scene_output_inputs, scene_outputs

SCENES = validate_config(load_config([Path(__file__).parents[2] / "config" / "config.yaml"]))


@pytest.mark.parametrize("scene, files, cubes, group", [
    ("table1", ["speeds_vs_stress.png", "table1.md", "table1.csv", "table1_diff.png"],
     ["elastic", "rayleigh"], "scene_light"),
    ("fig2", ["speeds_vs_stress.png"], ["elastic", "rayleigh"], "scene_light"),
    ("triangular", ["dispersion_harmonic.png", "dispersion_lj.png", "theta_c.png",
                    "fig3_displacements_harmonic.png", "fig3_displacements_lj.png"],
     ["dispersion", "displacements"], "scene_dispersion"),
    ("entropy", ["entropy_vs_strain.png"], ["entropy"], "scene_entropy"),
    ("crystals", ["surface_wave_angles.png", "summary.md"], ["surface_wave"], "scene_crystal"),
    ("acoustoelastic", ["surface_wave_vs_stress.png", "acoustoelastic.md", "acoustoelastic.csv",
                        "summary.md"], ["surface_wave"], "scene_crystal"),
])
def test_default_scenes(scene, files, cubes, group):
    out = scene_outputs(SCENES, scene)
    assert list(out.values()) == files and all(k.isidentifier() for k in out)
    got_cubes, modules = scene_output_inputs(SCENES, scene)
    assert list(got_cubes) == cubes
    assert modules[0] == "plots.figure_set"
    assert figure_group(got_cubes) == group


def test_user_fcc_scene_with_bulk_rides_with_bulk_and_reads_every_cube():
    """A user scene's summary reads bulk.nc, which itself follows crystal and elastic: its
    figures job must not join scene_light (Snakemake refuses a group with an outside job
    between two members)."""
    mine = {**SCENES["table1"]}
    scenes = {**SCENES, "mine": mine}
    cubes, _ = scene_output_inputs(scenes, "mine")
    assert list(cubes) == ["elastic", "rayleigh", "bulk"]
    assert scene_outputs(scenes, "mine") == {"speeds": "speeds_vs_stress.png", "summary": "summary.md"}
    assert figure_group(cubes) == "scene_bulk"


def test_report_entries():
    assert report_entry("dispersion_lj") == ("dispersion.rst", "Triangular lattice")
    assert report_entry("table1_png")[0] == "table1_diff.rst"
    assert report_entry("table1_md") is None and report_entry("summary") is None
