"""Layered scenes: bad input is one line before any job, through the resolver of surfwave.layered.

References: the refusals of :func:`surfwave.layers.stack.resolve_stack` (the same message text
must come out of the scene check, prefixed by the scene), the schema's scene dispatch (a scene
with ``substrate`` is a layered scene), and the piezoelectric database's cuts (ST-X quartz is
Euler (0, 132.75, 0)).
"""
from __future__ import annotations

import pytest

from surfwave.errors import InputError
from surfwave.layers.stack import resolve_stack
from surfwave.pipeline.grids import SceneError
from surfwave.pipeline.layered_scenes import check_layered_scene, layered_job_params
from surfwave.pipeline.scenes import targets, validate_config
from surfwave.pipeline.targets import scene_outputs

SIO2 = {"material": "fused-SiO2", "thickness": 1.0e-6}
GOOD = {"substrate": "Si", "films": [SIO2], "kh": {"start": 0.5, "stop": 1.5, "step": 0.5}}
SURFACE_LOAD = [[0, 0, 0], [0, 0, 0], [0, 0, 1.0]]

BAD = [  # (changes to GOOD, the key the message names, a fragment of the resolver's message)
    ({"films": [{**SIO2, "thickness": -1.0e-6}]}, "film 0 (from the top)", "thickness must be >= 0 m"),
    ({"films": [{**SIO2, "thickness": 1.0}]}, "film 0 (from the top)", "in metres (1 um = 1e-6)"),
    ({"films": [{"material": "SiO3", "thickness": 1e-6}]}, "film 0 (from the top)", "unknown material 'SiO3'"),
    ({"stress": SURFACE_LOAD}, "substrate", "prestress must lie in the surface plane (001)"),
    ({"films": [{"E": 70.0, "nu": 0.5, "rho": 2200.0, "thickness": 1e-6}]}, "scene 's'",  # layer not named
     "Poisson's ratio nu must lie in (-1, 0.5)"),
    ({"kh": [0.5, -1.0]}, "key 'kh'", "kh must lie in [0, "),
    ({"electrical": ["metallized"]}, "key 'electrical'", "needs a piezoelectric layer"),
    ({"orientations": [{"cut": "ST-X quartz"}]}, "key 'cut'", "is a cut of SiO2, not of the substrate 'Si'"),
    ({"films": [SIO2, {**SIO2, "stress": SURFACE_LOAD}]}, "film 1 (from the top)",
     "prestress must lie in the surface plane of the film and its interfaces"),
    ({"films": [{**SIO2, "stress": 0.5}], "film_stress": [0, 1]}, "key 'film_stress'", "every film gives its own"),
]


@pytest.mark.parametrize("change, key, fragment", BAD)
def test_bad_layered_scene_is_one_line(change, key, fragment):
    """Each bad input is one problem, one line, naming the scene and what is wrong."""
    scene, problems = check_layered_scene("s", {**GOOD, **change})
    assert scene is None and len(problems) == 1, problems
    assert "\n" not in problems[0] and problems[0].startswith("scene 's'")
    assert key in problems[0] and fragment in problems[0], problems[0]


@pytest.mark.parametrize("films, stress", [([{**SIO2, "thickness": -1e-6}], None), ([SIO2], SURFACE_LOAD)])
def test_scene_message_is_the_resolvers(films, stress):
    """The scene check passes the resolver's own message through (one set of checks, not two)."""
    with pytest.raises(InputError) as exc:
        resolve_stack("Si", films, stress=stress)
    _, problems = check_layered_scene("s", {**GOOD, "films": films, "stress": stress})
    assert problems[0].endswith(str(exc.value))


def test_film_stress_outside_the_range_is_refused_at_that_stress():
    """A film stress in Pa (1e9) is refused by the resolver at that grid point, which the message names."""
    _, problems = check_layered_scene("s", {**GOOD, "film_stress": [0.0, 1.0e9]})
    assert len(problems) == 1 and "film_stress 1e+09 GPa" in problems[0] and "looks like Pa" in problems[0]


def test_validate_config_dispatches_and_expands():
    """Through validate_config: the schema fills the defaults, the scene expands, targets and outputs follow."""
    cfg = {"scenes": {"stack": {**GOOD, "orientations": [{"surface": "(001)", "direction": "[110]"},
                                                          {"euler": [0, 0, 30]}],
                                "film_stress": [-1, 0, 1]},
                      "love": {"substrate": "quartz", "films": [SIO2], "kh": [1.0],
                               "orientations": [{"cut": "ST-X quartz"}]}}}
    scenes = validate_config(cfg)
    s = scenes["stack"]
    assert s["kind"] == "layered" and s["kh"] == [0.5, 1.0, 1.5] and s["electrical"] == ["free"]
    assert [o["label"] for o in s["orientations"]] == ["(001)[110]", "Euler (0, 0, 30)"]
    assert targets(scenes, ["stack"]) == ["results/stack/dispersion_layered.nc"]
    assert set(scene_outputs(scenes, "stack")) == {"layered_dispersion", "layered_stress", "summary"}
    love = scenes["love"]
    assert love["piezo"] and love["orientations"][0]["euler"] == [0.0, 132.75, 0.0]
    assert love["electrical"] == ["free", "metallized"]  # the default; an elastic stack gets [free]
    assert "layered_k2" in scene_outputs(scenes, "love")
    job = layered_job_params(love)
    assert job["stage"] == "layered" and job["orientations"] == love["orientations"]


def test_validate_config_reports_schema_and_physics_in_one_run():
    """A mistyped key and a bad thickness in two scenes: both reported, one line each."""
    cfg = {"scenes": {"a": {**GOOD, "kh_grid": [1.0]},
                      "b": {**GOOD, "films": [{**SIO2, "thickness": -1.0}]}}}
    with pytest.raises(SceneError) as exc:
        validate_config(cfg)
    text = str(exc.value)
    assert "2 problems" in text and "unknown key 'kh_grid'" in text and "layered scene" in text
    assert "scene 'b': film 0 (from the top): the thickness must be >= 0 m" in text
