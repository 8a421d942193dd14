"""Tiny layered scenes end to end with real Snakemake runs (marker `workflow`).

References: :func:`surfwave.layered` called directly with the same arguments (itself checked
against closed forms and a second solver in tests/layers/); the interface checker
(../shared/tools/check_cubes.py: its per-file check of dimensions, CF attributes and global
attributes, applied to dispersion_layered.nc); Snakemake's own up-to-date check (a rerun has
nothing to do); the scene checks (a bad thickness fails before any job, in one line).
"""
from __future__ import annotations

import importlib.util

import numpy as np
import pytest
from test_workflow import CHECKER, make_workdir, smk

import surfwave
from surfwave.data.cube import open_cube

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]

LAYERED = """
run: []
scenes:
  tiny_stack:
    substrate: Si
    films: [{material: fused-SiO2, thickness: 1.0e-6}]
    orientations: [{surface: "(001)", direction: "[100]"}, {euler: [0, 0, 30]}]
    kh: [0.5, 1.5, 3.0]
    film_stress: [-0.5, 0.0, 0.5]
  tiny_piezo:
    substrate: sapphire
    films: [{material: ZnO, thickness: 0.5e-6}]
    orientations: [{euler: [0, 0, 90]}]
    kh: [0.5, 1.5]
    electrical: [free, metallized]
  tiny_two:
    substrate: Si
    films: [{material: Si3N4, thickness: 0.2e-6, stress: 0.8}, {material: fused-SiO2, thickness: 0.5e-6}]
    kh: [1.0, 2.0]
    film_stress: [-0.5, 0.0]
"""
DIMS = ("orientation", "film_stress", "electrical", "kh", "mode")


@pytest.fixture(scope="module")
def layered_built(tmp_path_factory):
    wd = make_workdir(tmp_path_factory.mktemp("wf_layered"), LAYERED)
    smk(wd, "-j2")
    return wd


def _same_as_library(got, ref, keys=("c", "group_velocity", "K2", "power_flow_angle", "frequency")):
    """Each mode of the library's rows (label -> column) equals the cube's entry of that label."""
    for row, labels in enumerate(ref["mode"]):
        for col, lab in enumerate(labels):
            if not lab:
                continue
            for key in keys:
                np.testing.assert_allclose(got[key].isel(kh=row).sel(mode=str(lab)).values, ref[key][row, col],
                                           rtol=1e-12, atol=1e-12, err_msg=f"{key} {lab} kh[{row}]")
        found = got["c"].isel(kh=row).values
        assert np.isfinite(found).sum() == sum(bool(lab) for lab in labels)  # no mode more, none less


def test_cube_equals_the_library_and_passes_the_checker(layered_built):
    """dispersion_layered.nc holds, at every orientation x film stress x electrical, what
    surfwave.layered returns for the same stack; it has CF attributes and provenance; every
    figure and the summary are written."""
    res = layered_built / "results"
    for f in ("tiny_stack/dispersion_layered.png", "tiny_stack/dispersion_layered_vs_stress.png",
              "tiny_stack/summary.md", "tiny_piezo/dispersion_layered.png", "tiny_piezo/k2_layered.png"):
        assert (res / f).stat().st_size > 0, f
    ds = open_cube(res / "tiny_stack" / "dispersion_layered.nc")
    assert set(DIMS) <= set(ds.dims) and ds.film_stress.values.tolist() == [-0.5, 0.0, 0.5]
    assert ds.orientation.values.tolist() == ["(001)[100]", "Euler (0, 0, 30)"]
    assert ds.attrs["scene_name"] == "tiny_stack" and "surfwave.layered" in ds.attrs["method"]
    films = [{"name": "fused-SiO2", "thickness": 1.0e-6}]
    for orient, kw in (("(001)[100]", {"surface": "(001)", "direction": "[100]"}), ("Euler (0, 0, 30)",
                                                                                   {"euler": [0, 0, 30]})):
        for sig in (-0.5, 0.0, 0.5):
            ref = surfwave.layered("Si", [{**films[0], "stress": sig}], kh=[0.5, 1.5, 3.0], **kw)
            got = ds.sel(orientation=orient, film_stress=sig, electrical="free")
            _same_as_library(got, ref)
            assert float(got.c_limit) == pytest.approx(ref["c_limit"], rel=1e-12)
    pz = open_cube(res / "tiny_piezo" / "dispersion_layered.nc")
    for el in ("free", "metallized"):
        ref = surfwave.layered("sapphire", [{"name": "ZnO", "thickness": 0.5e-6}], euler=[0, 0, 90],
                               kh=[0.5, 1.5], electrical=el)
        _same_as_library(pz.sel(orientation="Euler (0, 0, 90)", film_stress=0.0, electrical=el), ref)
    assert np.nanmax(pz.K2.values) > 0
    two = open_cube(res / "tiny_two" / "dispersion_layered.nc")  # the top film keeps its own 0.8 GPa
    for sig in (-0.5, 0.0):
        ref = surfwave.layered("Si", [{"name": "Si3N4", "thickness": 0.2e-6, "stress": 0.8},
                                      {"name": "fused-SiO2", "thickness": 0.5e-6, "stress": sig}], kh=[1.0, 2.0])
        _same_as_library(two.sel(orientation="(001)[100]", film_stress=sig, electrical="free"), ref)
    assert "films [0] keep theirs" in two.film_stress.attrs["long_name"]
    if CHECKER is not None:  # the checker's own rules for a cube file (it has no entry for this name yet)
        spec = importlib.util.spec_from_file_location("check_cubes", CHECKER)
        checker = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(checker)
        for scene in ("tiny_stack", "tiny_piezo", "tiny_two"):
            assert checker.check_file(res / scene / "dispersion_layered.nc", DIMS, ["c", "c_limit", "K2"]) == []


def test_rerun_is_a_no_op_and_a_bad_stack_fails_first(layered_built):
    """A second run has nothing to do; a film thickness given in micrometres fails before any job,
    in one line naming the scene."""
    dry = smk(layered_built, "-n")
    assert "Nothing to be done" in dry.stdout + dry.stderr
    (layered_built / "bad.yaml").write_text(
        "scenes:\n  bad:\n    substrate: Si\n    films: [{material: fused-SiO2, thickness: 1.0}]\n    kh: [1.0]\n")
    proc = smk(layered_built, "-n", "--configfile", "config/config.yaml", "bad.yaml", check=False)
    text = proc.stdout + proc.stderr
    lines = [ln for ln in text.splitlines() if "scene 'bad'" in ln]
    assert proc.returncode != 0 and len(lines) == 1 and "film thicknesses are in metres" in lines[0], text[-2000:]
    assert not (layered_built / "results" / "bad").exists()
