"""FCC model scenes with propagation angles (surfwave.model_crystals.fcc_angles).

References:
- on the mirror directions (0 and 45 degrees) the paper's own route, surfwave.point with
  directions "[100]" and "[110]" (lattice built in that frame, Eq. 17);
- the tetragonal mirror at 45 degrees: c_R(45 + x) = c_R(45 - x) under in-plane hydrostatic
  stress (the crystal and the stress are symmetric about the (1-10) plane);
- at zero stress the nearest-neighbour FCC crystal is cubic with C11:C12:C44 = 2:1:1 (docs/physics/paper.md),
  so its speed at any angle equals the real-crystal cube's for those constants (a different
  frame, unit system and code path through the same solver).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.model_crystals import fcc_angles
from surfwave.pipeline.scenes import SceneError, validate_config
from surfwave.real_crystals.materials import Material

D = np.array([0.97, 1.0, 1.03])


@pytest.mark.parametrize("potential", ["lj", "harmonic"])
def test_mirror_angles_equal_the_paper_route(potential):
    out = fcc_angles.properties_at_angles(potential, [0.0, 45.0], D)
    ray = fcc_angles.rayleigh_at_angles(out["C"], out["stress"], out["S"], [0.0, 45.0])
    for i, direction in enumerate(("[100]", "[110]")):
        ref = surfwave.point("fcc", "in_plane_hydrostatic", potential, direction, D)
        np.testing.assert_allclose(out["c2_T_par"][i], ref["c2_T_par"], rtol=1e-12)
        np.testing.assert_allclose(out["c2_SH"][i], ref["c2_SH"], rtol=1e-12)
        np.testing.assert_allclose(ray["c2_R"][i], ref["c2_R"], rtol=1e-12)


def test_off_mirror_symmetric_about_45_and_matches_cubic_material():
    angles = np.array([20.0, 70.0])
    out = fcc_angles.properties_at_angles("lj", angles, D)
    ray = fcc_angles.rayleigh_at_angles(out["C"], out["stress"], out["S"], angles)
    np.testing.assert_allclose(ray["c2_R"][0], ray["c2_R"][1], rtol=1e-7)
    assert np.all(np.isin(ray["wave_type"], ["surface", "pseudo", "supersonic_decoupled"]))
    # zero stress: cubic 2:1:1, the real-crystal route (SI units, crystal frame) gives the same
    from surfwave.real_crystals.sweep import surface_wave_sweep
    from surfwave.solvers.tensors import cubic_voigt

    mat = Material(name="nn", symmetry="cubic", rho=1000.0, voigt=cubic_voigt(2.0, 1.0, 1.0),
                   constants={}, toec=None, sources={})
    c = surface_wave_sweep([mat], ["(001)"], [20.0]).c_R.values.ravel()[0]
    # rho c^2 / C44 in both: reduced c2_R = V rho c^2 (m = 1) and V C44 = V C_yzyz (lab frame)
    np.testing.assert_allclose(ray["c2_R"][0, 1] / out["C"][0, 1, 1, 2, 1, 2], c ** 2 / (1e9 / 1000.0),
                               rtol=1e-7)


def test_uniaxial_angles_refused():
    with pytest.raises(InputError, match="uniaxial"):
        fcc_angles.properties_at_angles("lj", [10.0], D, loading="uniaxial")
    cfg = {"scenes": {"a": {"lattice": "fcc", "loading": "uniaxial", "potentials": ["lj"],
                            "directions": {"start": 0, "stop": 45, "step": 15},
                            "d_over_d0": [1.0], "quantities": ["elastic", "bulk"]}}}
    with pytest.raises(SceneError) as err:
        validate_config(cfg)
    for w in ("scene 'a'", "loading", "'uniaxial'", "quantities", "'bulk'"):
        assert w in str(err.value), (w, str(err.value))
    cfg["scenes"]["a"].update(loading="in_plane_hydrostatic", quantities=["elastic", "rayleigh"])
    scene = validate_config(cfg)["a"]
    assert scene["angles"] == [0.0, 15.0, 30.0, 45.0] and scene["directions"] == ["[100]"]
