"""Real-crystal scenes: the cube builder (surfwave.real_crystals.sweep) and the config checks.

References, each independent of the general (Stroh) solver the cube uses:
- Cu (001)[100] unstressed, 2012.12 m/s (docs/physics/paper.md, C11, C12, C44 = 168.4, 121.4, 75.4 GPa,
  rho 8960 kg/m^3);
- at mirror directions under stress along the propagation, the sagittal secular equation
  Eq. (17) of the seed paper (surfwave.solvers.rayleigh.solve) on S of Eq. (A11);
- an isotropic solid with Poisson ratio 1/4 (C11 = 3 C44, C12 = C44): c_R / c_T =
  sqrt(2 - 2/sqrt 3) = 0.919402 on every surface and in every direction (docs/physics/paper.md);
- the crystal's mirror symmetry: c_R(angle) = c_R(2 w - angle) about each mirror line w;
- A = C + sigma: a stress sigma_33 across a wave travelling in the x1-x2 plane enters only
  terms with d/dx3, so with fixed constants it leaves c_R exactly unchanged.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.model_crystals import elastic
from surfwave.pipeline.scenes import SceneError, validate_config
from surfwave.real_crystals.materials import Material, get_material
from surfwave.real_crystals.sweep import applied_stress, surface_wave_sweep, symmetry_reduced_range
from surfwave.solvers import rayleigh
from surfwave.solvers.tensors import cubic_voigt, rotate4, voigt_to_tensor

ISOTROPIC = Material(name="iso", symmetry="cubic", rho=5000.0, voigt=cubic_voigt(150.0, 50.0, 50.0),
                     constants={"C11": 150.0, "C12": 50.0, "C44": 50.0}, toec=None, sources={})


def test_copper_001_100_unstressed():
    """2012.12 m/s (docs/physics/paper.md); along [110] copper's sagittal wave is faster than the slow
    shear bulk wave polarised along [1-10] (sqrt((C11 - C12)/2 rho) = 1620 m/s), so it is the
    mirror-protected supersonic_decoupled kind (docs/physics/paper.md: a mirror-protected wave is labelled, not dropped)."""
    ds = surface_wave_sweep([get_material("Cu")], ["(001)"], [0.0, 45.0])
    c = ds.c_R.sel(material="Cu", surface="(001)")
    assert round(float(c.sel(angle=0.0)), 2) == 2012.12
    assert ds.wave_type.sel(material="Cu", surface="(001)").values.tolist() == ["surface",
                                                                               "supersonic_decoupled"]
    assert float(c.sel(angle=45.0)) > np.sqrt((168.4 - 121.4) / 2 * 1e9 / 8960) == pytest.approx(1619.5, abs=0.5)
    assert ds.c_R.dims == ("material", "surface", "angle")
    assert ds.polarisation.dims == ("material", "surface", "angle", "component")


@pytest.mark.parametrize("name", ["Cu", "Si"])
def test_mirror_directions_under_stress_match_eq17(name):
    """(001) [100] and [110] under uniaxial stress along x1 (fixed constants) against Eq. (17)
    on S = A (Eq. A11) in the lab frame: two independent routes to the same c_R."""
    mat = get_material(name)
    stress = np.array([-0.4, 0.0, 0.3])
    ds = surface_wave_sweep([mat], ["(001)"], [0.0, 45.0], stress=stress, loadings=["along"])
    C = voigt_to_tensor(mat.voigt)
    for angle, axes in ((0.0, np.eye(3)[[0, 2, 1]] * [[1], [-1], [1]]),
                        (45.0, np.array([[1, 1, 0], [0, 0, 1], [1, -1, 0]]) / np.array([[2 ** .5], [1], [2 ** .5]]))):
        C_lab = rotate4(C, axes)
        sigma = np.zeros((stress.size, 3, 3))
        sigma[:, 0, 0] = stress
        S = elastic.stress_derivatives(sigma, np.broadcast_to(C_lab, (stress.size,) + C_lab.shape)) * 1e9
        ref = np.sqrt(rayleigh.solve(S, mat.rho)["c2_R"])
        got = ds.c_R.sel(material=name, surface="(001)", angle=angle, loading="along", toec=False).values
        np.testing.assert_allclose(got, ref, rtol=1e-8)


def test_isotropic_closed_form_every_surface_and_angle():
    """Poisson ratio 1/4: c_R = 0.919402 c_T whatever the surface and direction."""
    ds = surface_wave_sweep([get_material(ISOTROPIC)], ["(001)", "(110)", "(111)"], [0.0, 17.0, 45.0, 80.0])
    c_T = np.sqrt(50e9 / 5000.0)
    np.testing.assert_allclose(ds.c_R.values / c_T, np.sqrt(2 - 2 / np.sqrt(3)), rtol=1e-7)
    assert set(ds.wave_type.values.ravel()) == {"surface"}


def test_mirror_symmetry_in_the_cube_and_reduced_ranges():
    """c_R and v_L are mirror-symmetric about w = 45 (001), 90 (110), 30 (111) degrees."""
    widths = {sf: symmetry_reduced_range(sf, [get_material("Cu").voigt]) for sf in ("(001)", "(110)", "(111)")}
    assert widths == {"(001)": 45.0, "(110)": 90.0, "(111)": 30.0}
    offsets = np.array([3.0, 11.0, 22.0])
    for sf, w in widths.items():
        angles = np.concatenate([w - offsets, w + offsets])
        ds = surface_wave_sweep([get_material("Cu")], [sf], angles).sel(material="Cu", surface=sf)
        for var in ("c_R", "c_limit"):
            v = ds[var].values
            np.testing.assert_allclose(v[:3], v[3:], rtol=1e-7, err_msg=f"{sf} {var}")


def test_loadings_fixed_constants():
    """Fixed constants: 'across' leaves c_R unchanged (sigma_33 meets only d/dx3 terms),
    'biaxial' equals 'along', and axis_100 equals 'along' at angle 0 on (001)."""
    ds = surface_wave_sweep([get_material("Cu")], ["(001)"], [0.0, 30.0], stress=[-0.5, 0.0, 0.5],
                            loadings=["along", "across", "biaxial", "axis_100"], toec=[False])
    c = ds.c_R.sel(material="Cu", surface="(001)", toec=False)
    np.testing.assert_allclose(c.sel(loading="across").values,
                               np.broadcast_to(c.sel(loading="along", stress=0.0).values[:, None], (2, 3)),
                               rtol=1e-9)
    np.testing.assert_allclose(c.sel(loading="biaxial"), c.sel(loading="along"), rtol=1e-9)
    np.testing.assert_allclose(c.sel(loading="axis_100", angle=0.0), c.sel(loading="along", angle=0.0),
                               rtol=1e-9)
    assert c.sel(loading="along", angle=0.0, stress=0.5) > c.sel(loading="along", angle=0.0, stress=-0.5)


def test_stress_lies_in_the_surface():
    """sigma . n = 0 for every loading; an axis normal to the surface is refused by name."""
    from surfwave.solvers import orientation

    axes = np.asarray(orientation.lab_axes("(111)", np.array([0.0, 20.0])), dtype=float)
    for loading in ("along", "across", "biaxial", "axis_1-10"):
        sig = applied_stress(loading, axes, [1.0])
        assert np.abs(np.einsum("asij,aj->asi", sig, axes[:, 1])).max() < 1e-12, loading
    with pytest.raises(InputError, match="axis_100"):
        applied_stress("axis_100", axes, [1.0])


def test_toec_needs_third_order_constants():
    with pytest.raises(InputError, match="'W'.*C111"):
        surface_wave_sweep([get_material("W")], ["(001)"], [0.0], stress=[0.0, 0.1], toec=[True])


def _cfg(**over):
    scene = {"materials": ["Cu"], "surfaces": ["(001)"]}
    scene.update(over)
    return {"scenes": {"rc": scene}}


def test_config_defaults_and_expansion():
    """Default angles: the symmetry-reduced range (union over surfaces); directions -> angles."""
    out = validate_config(_cfg(surfaces=["(001)", "(111)"], angles={"symmetric": True, "step": 5}))["rc"]
    assert out["angles"] == [float(a) for a in range(0, 50, 5)] and out["stress"] is None
    # step 7 divides neither range: each surface's mirror angle (30, 45) is still on the grid
    out = validate_config(_cfg(surfaces=["(001)", "(111)"], angles={"symmetric": True, "step": 7}))["rc"]
    assert out["angles"] == [0.0, 7.0, 14.0, 21.0, 28.0, 30.0, 35.0, 42.0, 45.0]
    out = validate_config(_cfg(directions=["[110]", "[100]"], stress=[-0.1, 0.0, 0.1]))["rc"]
    assert out["angles"] == [0.0, 45.0] and out["directions"] == ["[100]", "[110]"]
    assert out["loading"] == ["along"] and out["toec"] == [False]


@pytest.mark.parametrize("over, words", [
    ({"materials": ["Cuu"]}, ["'rc'", "materials", "'Cuu'", "did you mean Cu"]),
    ({"surfaces": ["(00x)"]}, ["'rc'", "surfaces", "(00x)"]),
    ({"directions": ["[111]"]}, ["'rc'", "directions", "[111]", "(001)"]),
    ({"stress": [0.0, 0.1], "loading": ["axis_001"]}, ["'rc'", "loading", "axis_001", "surface"]),
    ({"materials": ["Cu", "W"], "stress": [0.0, 0.1], "toec": [True]}, ["'rc'", "toec", "W", "C111"]),
    ({"loading": ["across"]}, ["'rc'", "stress"]),
    ({"angles": {"start": 0, "stop": 45, "step": 7}}, ["'rc'", "angles", "7"]),
    ({"stress": {"start": 0.5, "stop": -0.5, "step": 0.1}}, ["'rc'", "stress", "before start"]),
    ({"lattice": "fcc"}, ["'rc'", "lattice"]),
])
def test_bad_crystal_scene_names_scene_key_value(over, words):
    with pytest.raises(SceneError) as err:
        validate_config(_cfg(**over))
    for w in words:
        assert w in str(err.value), (w, str(err.value))


@pytest.mark.parametrize("direction, angle", [("[100]", 0.0), ("[110]", 45.0)])
def test_acoustoelastic_coefficients_match_the_mirror_route(direction, angle):
    """K = (1/c) dc/dsigma from the cube (general solver, stressed lab frame F x1, F^-T x2)
    against surfwave.real_crystals.acoustoelastic (Eq. 17 on the deformed mirror frame, its own
    stress construction and central difference), with and without third-order constants."""
    from surfwave.real_crystals.acoustoelastic import acoustoelastic_coefficients
    from surfwave.report.acoustoelastic import PER_TPA, coefficients

    cu = get_material("Cu")
    h = 1e-3
    ds = surface_wave_sweep([get_material("Cu")], ["(001)"], [angle], stress=[-h, 0.0, h],
                            loadings=["along", "across", "biaxial"], toec=[False, True])
    K = coefficients(ds).K.sel(material="Cu", surface="(001)", angle=angle)
    ref = acoustoelastic_coefficients(cu.voigt, cu.toec_voigt, cu.rho, "(001)", direction)
    for model, tv in (("fixed_C", False), ("toec", True)):
        for loading, value in ref[model].items():
            assert float(K.sel(loading=loading, toec=tv)) == pytest.approx(value * PER_TPA, rel=1e-5, abs=1e-6), \
                (model, loading)
