"""A tiny FCC surface-phonons scene end to end with a real Snakemake run (marker `workflow`).

References: the library call with the same arguments (surfwave.surface_phonons, itself checked
against Eq. 17, thick slabs and phonopy in tests/dynamics/test_fcc_surface_phonons.py); the
interface checker (CF attributes); Snakemake's up-to-date check; the scene checks (a surface the
loading cannot take fails before any job).
"""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest
from test_workflow import CHECKER, make_workdir, smk

import surfwave
from surfwave.data.cube import open_cube

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]

SCENE = """
run: [tiny_phonons]
scenes:
  tiny_phonons:
    lattice: fcc
    loading: uniaxial
    potentials: [lj]
    directions: ["[110]"]
    d_over_d0: [0.98, 1.02]
    quantities: [elastic, surface_phonons]   # elastic.nc: a cube the interface checker knows
    surfaces: ["(001)", "(111)"]
    accuracy:
      surface_phonons: {path_density: 2.0, n_omega: 20, entropy_grid: 8}
"""


@pytest.fixture(scope="module")
def built(tmp_path_factory):
    wd = make_workdir(tmp_path_factory.mktemp("wf_phonons"), SCENE)
    smk(wd, "-j1")
    return wd


def test_cube_and_figures(built):
    """Cube with dims (potential, cut, strain, q, mode, ...), CF attributes, the three figures
    and the summary; the surface modes equal the library's at the same path to 1e-12."""
    res = built / "results" / "tiny_phonons"
    for f in ("surface_phonons_dispersion_lj.png", "surface_phonons_soft_modes_lj.png",
              "surface_phonons_entropy_lj.png", "summary.md"):
        assert (res / f).stat().st_size > 0, f
    ds = open_cube(res / "surface_phonons.nc")
    assert {"potential", "cut", "strain", "q", "mode", "frequency"} <= set(ds.dims)
    assert list(ds.cut.values) == ["(001) load [110]", "(111) load [110]"]
    for var in ("omega", "band_edges", "spectral_density", "S_surface_exact", "softest_omega2"):
        assert "long_name" in ds[var].attrs and "units" in ds[var].attrs, var
    ref = surfwave.surface_phonons("lj", "uniaxial", [0.98, 1.02], surface="(111)", q="GMKG", path_density=2.0,
                                   load_direction="[110]")
    got = ds.sel(potential="lj", cut="(111) load [110]")
    n_q, n_m = ref["omega"].shape[1:]
    np.testing.assert_allclose(got.omega.values[:, :n_q, :n_m], ref["omega"], rtol=1e-12, equal_nan=True)
    assert json.loads(ds.attrs["path_labels"])["(111) load [110]"]["labels"] == list("GMKG")
    if CHECKER is not None:
        proc = subprocess.run([sys.executable, str(CHECKER), str(built / "results")], capture_output=True, text=True)
        assert proc.returncode == 0, proc.stdout + proc.stderr


def test_rerun_is_a_no_op_and_bad_surface_fails_first(built, tmp_path):
    """A second run has nothing to do; a uniaxial scene whose load direction does not lie in a
    surface ((111) with [100]) fails the scene check before any job."""
    out = smk(built, "-n", check=False)
    assert "Nothing to be done" in out.stdout + out.stderr
    bad = make_workdir(tmp_path, SCENE.replace('directions: ["[110]"]', 'directions: ["[100]"]'))
    out = smk(bad, "-n", check=False)
    assert out.returncode != 0 and "'(111)' contains none of the load directions" in out.stdout + out.stderr
