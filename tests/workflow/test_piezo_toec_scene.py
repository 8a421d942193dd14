"""A tiny GaAs piezoelectric scene with toec [false, true], end to end with real Snakemake runs.

References: the library's front door surfwave.material("GaAs", euler=..., stress=..., toec=...)
at the same points (itself checked against the sweep in
tests/real_crystals/test_piezo_sweep_toec.py); the interface checker
(../shared/tools/check_cubes.py); Snakemake's params rule (a changed toec_file changes the
job's params, so the job is scheduled again; an unchanged one is not).
"""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from test_workflow import CHECKER, make_workdir, smk

import surfwave
from surfwave.data.cube import open_cube
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.piezo_wave import MODEL, MODEL_TOEC

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]

CONFIG = """
run: []
scenes:
  gaas_toec:
    materials: [GaAs]
    euler: {phi: 0, theta: 0, psi: 45}
    stress: [-0.5, 0.0, 0.5]
    toec: [false, true]
  gaas_file:
    materials: [GaAs]
    euler: {phi: 0, theta: 0, psi: 45}
    electrical: [free]
    stress: [-0.5, 0.5]
    toec: [true]
    toec_file: sets/gaas_scaled.yaml
"""
EULER = np.array([[0.0, 0.0, 45.0]])


def _scaled(scale: float) -> dict:
    return {k: scale * v for k, v in get_material("GaAs").toec.items()}


def _write_set(wd, scale: float) -> None:
    text = "source: GaAs database set scaled for a test\n" + "".join(f"{k}: {v!r}\n"
                                                                      for k, v in _scaled(scale).items())
    (wd / "config" / "sets").mkdir(exist_ok=True)
    (wd / "config" / "sets" / "gaas_scaled.yaml").write_text(text)


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    wd = make_workdir(tmp_path_factory.mktemp("wf_piezo_toec"), CONFIG)
    _write_set(wd, 0.8)
    smk(wd, "-j2")
    return wd


def test_toec_cube_values_and_attributes(built):
    """The cube has a toec dim [false, true] before stress; stress_model names both models; the
    values equal surfwave.material at the same points; the file's scene records its set."""
    res = built / "results"
    ds = open_cube(res / "gaas_toec" / "surface_wave.nc")
    assert ds.c_R.dims == ("material", "surface", "angle", "electrical", "toec", "stress")
    assert ds.toec.values.tolist() == [False, True]
    assert ds.attrs["stress_model"] == f"toec=false: {MODEL}; toec=true: {MODEL_TOEC}"
    s = np.array([-0.5, 0.0, 0.5])
    for toec in (False, True):
        for el in ("free", "metallized"):
            ref = surfwave.material("GaAs", euler=np.repeat(EULER, 3, 0), stress=s, toec=toec, electrical=el)
            got = ds.isel(material=0, surface=0, angle=0).sel(electrical=el, toec=toec)
            np.testing.assert_allclose(got.c_R.values, ref["c_R"], rtol=1e-12, err_msg=f"{toec} {el}")
    f = open_cube(res / "gaas_file" / "surface_wave.nc")
    assert f.attrs["stress_model"] == MODEL_TOEC and f.attrs["toec_source"].startswith("GaAs database set")
    assert f.attrs["toec_file"].endswith("config/sets/gaas_scaled.yaml") and len(f.attrs["toec_file_sha256"]) == 64
    ref = surfwave.material("GaAs", euler=np.repeat(EULER, 2, 0), stress=np.array([-0.5, 0.5]), toec=_scaled(0.8))
    np.testing.assert_allclose(f.c_R.squeeze().values, ref["c_R"], rtol=1e-12)
    assert (res / "gaas_toec" / "piezo_vs_stress.png").stat().st_size > 0
    if CHECKER is not None:
        proc = subprocess.run([sys.executable, str(CHECKER), str(res)], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout + proc.stderr


def test_a_changed_file_reruns_only_its_scene(built):
    """Nothing to do after the build; after the file changes, the dry run schedules piezo_wave
    for the scene that reads it and not for the other."""
    dry = smk(built, "-n")
    assert "Nothing to be done" in dry.stdout + dry.stderr
    _write_set(built, 0.9)
    text = (lambda p: p.stdout + p.stderr)(smk(built, "-n"))
    assert "Nothing to be done" not in text and "scene=gaas_file" in text, text[-3000:]
    assert "scene=gaas_toec" not in text, text[-3000:]
