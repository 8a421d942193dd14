"""Scenes: schema defaults, grid expansion without drift, errors that name scene/key/value."""
from __future__ import annotations

import copy

import numpy as np
import pytest

from surfwave.pipeline import scenes
from surfwave.pipeline.scenes import SceneError, expand_grid, job_params, validate_config


def base(**over):
    scene = {"lattice": "fcc", "loading": "in_plane_hydrostatic", "potentials": ["lj"],
             "d_over_d0": [0.98, 1.0], "quantities": ["elastic"]}
    scene.update(over)
    return {"scenes": {"s1": scene}}


def test_table1_grid_has_no_float_drift():
    """0.88 ... 1.10 by 0.01 (Table I) gives 23 points equal to the decimals one types."""
    g = expand_grid({"start": 0.88, "stop": 1.10, "step": 0.01})
    assert g.size == 23
    assert g[5] == 0.93 and g[-1] == 1.1 and g[12] == 1.0
    assert list(g) == [round(0.88 + 0.01 * i, 2) for i in range(23)]


def test_list_is_sorted_and_duplicates_rejected():
    assert list(expand_grid([1.0, 0.9])) == [0.9, 1.0]
    with pytest.raises(SceneError, match="appears twice"):
        expand_grid([1.0, 1.0])


def test_defaults_filled_and_directions_expanded():
    cfg = base()
    out = validate_config(cfg)
    s = cfg["scenes"]["s1"]
    assert s["accuracy"]["bulk"]["supercell"] == 2 and s["theta"] == {"n": 32}
    assert cfg["run"] == []
    assert out["s1"]["directions"] == ["[100]", "[110]"]
    assert len(out["s1"]["theta"]) == 32 and 0 < min(out["s1"]["theta"]) < max(out["s1"]["theta"]) < np.pi


def test_user_accuracy_keeps_other_defaults():
    cfg = base(accuracy={"bulk": {"supercell": 3}})
    validate_config(cfg)
    assert cfg["scenes"]["s1"]["accuracy"]["bulk"] == {
        "supercell": 3, "displacement": 3e-5, "zone_mesh": 8, "long_wave": "curvature"}


@pytest.mark.parametrize(
    "over, words",
    [
        ({"lattice": "bcc"}, ["'s1'", "lattice", "'bcc'"]),
        ({"potentials": ["morse", "buckingham"]}, ["'s1'", "potentials", "'buckingham'"]),
        ({"directions": ["[111]"]}, ["'s1'", "directions", "[111]"]),
        ({"directions": ["[10]"]}, ["'s1'", "directions", "'[10]'"]),
        ({"quantities": ["elastic", "phonons"]}, ["'s1'", "quantities", "'phonons'"]),
        ({"quantities": ["entropy"]}, ["'s1'", "quantities", "'entropy'", "triangular"]),
        ({"d_over_d0": [0.9, 1.5]}, ["'s1'", "d_over_d0", "1.5"]),
        ({"d_over_d0": {"start": 0.9, "stop": 1.0, "step": 0.03}}, ["'s1'", "d_over_d0", "0.03"]),
        ({"d_over_d0": {"start": 1.0, "stop": 0.9, "step": 0.01}}, ["'s1'", "d_over_d0", "before start"]),
        ({"d_over_d0": {"start": 0.9, "stop": 1.0}}, ["'s1'", "d_over_d0"]),
        ({"d_over_d0": {"start": 0.9, "stop": 1.0, "step": 0}}, ["'s1'", "d_over_d0"]),
        ({"theta": [0.5, 4.0]}, ["'s1'", "theta"]),
        ({"loading": "biaxial"}, ["'s1'", "loading", "'biaxial'"]),
        ({"accuracy": {"bulk": {"supercell": 0}}}, ["'s1'", "accuracy/bulk/supercell", "0"]),
        ({"colour": "red"}, ["'s1'", "colour"]),
    ],
)
def test_bad_scene_names_scene_key_value(over, words):
    with pytest.raises(SceneError) as err:
        validate_config(base(**over))
    for w in words:
        assert w in str(err.value), (w, str(err.value))


def test_triangular_loading_and_impossible_stretch():
    cfg = base(lattice="triangular", loading="in_plane_hydrostatic")
    with pytest.raises(SceneError, match="loading"):
        validate_config(cfg)
    cfg = base(lattice="triangular", loading="uniaxial", d_over_d0=[2.0])
    with pytest.raises(SceneError, match="d_over_d0.*2"):
        validate_config(cfg)


def test_run_must_name_scenes():
    cfg = base()
    cfg["run"] = ["s1", "nope"]
    with pytest.raises(SceneError, match="'run'.*'nope'"):
        validate_config(cfg)


def test_user_configfile_merges_with_defaults(tmp_path):
    default = tmp_path / "a.yaml"
    default.write_text("scenes:\n  s1: {lattice: fcc, loading: uniaxial, potentials: [lj],"
                       " d_over_d0: [1.0], quantities: [elastic]}\n")
    user = tmp_path / "b.yaml"
    user.write_text("run: [mine]\nscenes:\n  mine: {lattice: triangular, loading: uniaxial,"
                    " potentials: [harmonic], d_over_d0: [1.0], quantities: [entropy]}\n"
                    "  s1: {potentials: [harmonic]}\n")
    cfg = scenes.load_config([default, user])
    out = validate_config(cfg)
    assert set(out) == {"s1", "mine"} and out["s1"]["potentials"] == ["harmonic"]
    assert out["s1"]["lattice"] == "fcc"
    assert scenes.selected(cfg, out) == ["mine"]
    assert scenes.targets(out, ["mine"]) == ["results/mine/crystal.nc", "results/mine/entropy.nc"]


def test_job_params_hold_only_what_the_stage_uses():
    cfg = base(quantities=["elastic", "bulk"])
    s = validate_config(cfg)["s1"]
    el, bulk = job_params(s, "elastic"), job_params(s, "bulk")
    assert el["accuracy"] == {} and "quantities" not in el and "theta" not in el
    assert bulk["accuracy"]["supercell"] == 2
    # Changing a bulk knob or the quantities leaves the elastic job's params unchanged.
    cfg2 = copy.deepcopy(cfg)
    cfg2["scenes"]["s1"]["accuracy"]["bulk"]["supercell"] = 3
    cfg2["scenes"]["s1"]["quantities"] = ["elastic"]
    s2 = validate_config(cfg2)["s1"]
    assert job_params(s2, "elastic") == el and job_params(s2, "bulk") != bulk


@pytest.mark.parametrize(
    "over, words",
    [
        ({"potential": ["lj"]}, ["'s1'", "unknown key 'potential'", "potentials"]),
        ({"accuracy": {"bulk": {"displacment": 1e-3}}}, ["'s1'", "accuracy/bulk/displacment",
                                                          "unknown key", "displacement"]),
        ({"accuracy": {"bulk": {"displacement": "tiny"}}}, ["'s1'", "displacement", "'tiny'",
                                                             "not of type 'number'"]),
        ({"d_over_d0": {"start": 0.9, "stop": 1.0}}, ["'s1'", "d_over_d0/step", "missing"]),
        ({"theta": [0.0, 1.0]}, ["'s1'", "theta/0", "0.0"]),
    ],
)
def test_schema_messages_name_the_offending_key(over, words):
    cfg = base(**over)
    with pytest.raises(SceneError) as err:
        validate_config(cfg)
    for w in words:
        assert w in str(err.value), (w, str(err.value))
    assert "{'lattice'" not in str(err.value)  # never the whole scene dumped


def test_default_config_is_valid():
    cfg = scenes.load_config([scenes.SCHEMA_PATH.parents[2] / "config" / "config.yaml"])
    out = validate_config(cfg)
    assert {"table1", "fig2", "fig2_uniaxial", "triangular", "entropy"} <= set(out)
    assert len(out["table1"]["d_over_d0"]) == 23


def test_theta_grid_with_exact_pi_fractions():
    """{n, pi_fractions}: midpoints plus exact multiples of pi (the paper's Fig. 3 values);
    a coinciding midpoint is not duplicated; fractions outside (0, 1) are refused."""
    from surfwave.pipeline.scenes import SceneError, theta_grid

    th = theta_grid({"n": 30, "pi_fractions": [0.05, 0.125, 0.25, 0.5]})
    for f in (0.05, 0.125, 0.25, 0.5):
        assert np.any(th == f * np.pi)
    assert np.all(np.diff(th) > 1e-9)
    assert th.size == 30 + 4 - 2  # pi/20 and pi/4 are midpoints (2i+1) pi/60 already
    with pytest.raises(SceneError, match="pi_fractions"):
        theta_grid({"n": 4, "pi_fractions": [1.5]})
