"""A tiny piezoelectric scene end to end with real Snakemake runs (marker `workflow`).

References: the library call with the same arguments (surfwave.real_crystals.piezo_wave.piezo_wave,
itself checked against published cut values in tests/real_crystals/test_piezo_wave.py); the
interface checker (../shared/tools/check_cubes.py: names, dims, attributes); Snakemake's own
up-to-date check (a rerun has nothing to do); the scene checks (a bad cut fails before any job).
"""
from __future__ import annotations

import subprocess
import sys

import numpy as np
import pytest
from test_workflow import CHECKER, make_workdir, smk

from surfwave.data.cube import open_cube
from surfwave.real_crystals.piezo_materials import get_cut
from surfwave.real_crystals.piezo_wave import piezo_wave
from surfwave.solvers.euler import euler_lab_axes

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]

PIEZO = """
run: []
scenes:
  tiny_cuts:
    materials: [LiNbO3]
    euler: {phi: 0, theta: [-26, 0, 38], psi: 0}
  tiny_stress:
    materials: [quartz]
    cuts: ["ST-X quartz"]
    electrical: [metallized]
    stress: [-0.1, 0.0, 0.1]
"""


@pytest.fixture(scope="module")
def piezo_built(tmp_path_factory):
    wd = make_workdir(tmp_path_factory.mktemp("wf_piezo"), PIEZO)
    smk(wd, "-j2")
    return wd


def test_cubes_figures_and_values(piezo_built):
    """Both scenes build their cube, figure and summary; the cube has the public dims (material,
    surface, angle) plus electrical [and stress], CF attributes and provenance, and its values
    equal the library's piezo_wave at the same points to 1e-12."""
    res = piezo_built / "results"
    for f in ("tiny_cuts/piezo_vs_angle.png", "tiny_cuts/summary.md", "tiny_stress/piezo_vs_stress.png",
              "tiny_stress/summary.md"):
        assert (res / f).stat().st_size > 0, f
    ds = open_cube(res / "tiny_cuts" / "surface_wave.nc")
    assert {"material", "surface", "angle", "electrical"} <= set(ds.dims) and "stress" not in ds.dims
    assert ds.euler_theta.values.tolist() == [-26.0, 0.0, 38.0]
    assert list(ds.component.values) == ["u1", "u2", "u3", "phi"] and ds.polarisation.dtype.kind == "c"
    for var in ("K2", "c_leaky", "leaky_attenuation", "power_flow_angle", "potential_share", "c_R"):
        assert "long_name" in ds[var].attrs and "units" in ds[var].attrs, var
    assert ds.attrs["scene_name"] == "tiny_cuts" and "fixed constants" in ds.attrs["stress_model"]
    R = euler_lab_axes([[0, -26, 0], [0, 0, 0], [0, 38, 0]])
    for el in ("free", "metallized"):
        ref = piezo_wave("LiNbO3", R, electrical=el)
        got = ds.sel(electrical=el).isel(material=0, angle=0)
        for key in ("c_R", "c_leaky", "leaky_attenuation", "power_flow_angle"):
            np.testing.assert_allclose(got[key].values, ref[key], rtol=1e-12, atol=1e-12, err_msg=key)
        np.testing.assert_allclose(got.K2.values, ref["K2"], rtol=1e-12)
    st = open_cube(res / "tiny_stress" / "surface_wave.nc")
    assert st.stress.values.tolist() == [-0.1, 0.0, 0.1] and list(st.electrical.values) == ["metallized"]
    c = get_cut("ST-X quartz")
    ref = piezo_wave(c.material, np.repeat(c.lab_axes[None], 3, 0), np.array([-0.1, 0.0, 0.1]),
                     electrical="metallized")
    np.testing.assert_allclose(st.c_R.isel(material=0, surface=0, angle=0, electrical=0, toec=0).values, ref["c_R"],
                               rtol=1e-12)
    if CHECKER is not None:
        proc = subprocess.run([sys.executable, str(CHECKER), str(res)], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout + proc.stderr


def test_rerun_is_a_no_op_and_a_bad_cut_fails_first(piezo_built, tmp_path):
    """A second run has nothing to do; a scene with an unknown cut or a cut of another crystal fails
    before any job with a message naming scene, key and value."""
    dry = smk(piezo_built, "-n")
    assert "Nothing to be done" in dry.stdout + dry.stderr
    for scene, word in (('materials: [quartz]\n    cuts: ["17Y-X"]', "'17Y-X'"),
                        ('materials: [LiNbO3]\n    cuts: ["ST-X quartz"]', "is a cut of SiO2")):
        (piezo_built / "bad.yaml").write_text(f"scenes:\n  bad:\n    {scene}\n")
        proc = smk(piezo_built, "-n", "--configfile", "config/config.yaml", "bad.yaml", check=False)
        text = proc.stdout + proc.stderr
        assert proc.returncode != 0 and "scene 'bad', key 'cuts'" in text and word in text, text[-2000:]
