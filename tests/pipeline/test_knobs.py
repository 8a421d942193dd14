"""Config limits: one source for defaults and bounds, every bad knob refused, all at once.

References: the library's own defaults (``phonons.DEFAULT_*``, the ``tol`` keyword
defaults of ``surface_mode`` and ``surface_entropy``) and the attainable error floors
measured with those solvers (``test_tol_floor_is_attainable``).
"""
import copy

import numpy as np
import pytest
import yaml

from surfwave.dynamics import entropy
from surfwave.model_crystals import phonons
from surfwave.pipeline import knobs, scenes
from surfwave.pipeline.scenes import SceneError, load_config, validate_config


@pytest.fixture(scope="module")
def base():
    return load_config([scenes.SCHEMA_PATH.parents[2] / "config" / "config.yaml"])


def _refused(base, mutate):
    cfg = copy.deepcopy(base)
    mutate(cfg)
    with pytest.raises(SceneError) as exc:
        validate_config(cfg)
    return str(exc.value)


def test_schema_file_holds_no_knob_numbers():
    """The schema YAML names the knobs only; defaults and bounds come from the library."""
    raw = yaml.safe_load(open(scenes.SCHEMA_PATH))
    blocks = raw["$defs"]["scene"]["properties"]["accuracy"]["properties"]
    for block in blocks.values():
        for spec in block["properties"].values():
            assert not {"default", "minimum", "maximum"} & set(spec), spec


def test_defaults_equal_the_library_defaults(base):
    """Reference: the library functions' own defaults (a direct call and the workflow agree)."""
    cfg = copy.deepcopy(base)
    validate_config(cfg)
    bulk = cfg["scenes"]["table1"]["accuracy"]["bulk"]
    assert bulk == {"supercell": phonons.DEFAULT_SUPERCELL, "displacement": phonons.DEFAULT_DISPLACEMENT,
                    "zone_mesh": phonons.DEFAULT_ZONE_MESH, "long_wave": phonons.DEFAULT_LONG_WAVE}
    import inspect
    tol = inspect.signature(entropy.surface_entropy).parameters["tol"].default
    assert cfg["scenes"]["entropy"]["accuracy"]["entropy"]["tol"] == tol


@pytest.mark.parametrize("block,knob,value,word", [
    ("bulk", "supercell", 1, "minimum of 2"),            # passed the schema, then the job failed
    ("bulk", "displacement", 10.0, "maximum of 0.01"),   # ran and wrote c2 ~ 1e194
    ("bulk", "zone_mesh", 1, "minimum of 2"),
])
def test_bulk_knobs_bounded(base, block, knob, value, word):
    """A supercell below 2 is refused by phonons.bulk_speeds itself; a displacement of 10 d0 is
    not a small displacement (the force-constant error grows as amplitude^2)."""
    msg = _refused(base, lambda c: c["scenes"]["table1"].update(accuracy={block: {knob: value}}))
    assert "scene 'table1'" in msg and f"accuracy/{block}/{knob}" in msg and repr(value) in msg
    assert word in msg


def test_tol_below_floor_refused_naming_the_floor(base):
    """tol = 1e-30 was accepted and silently not met; the message states the floor."""
    msg = _refused(base, lambda c: c["scenes"]["entropy"].update(accuracy={"entropy": {"tol": 1e-30}}))
    assert "1e-30" in msg and "minimum of 1e-10" in msg and "cannot be met" in msg


def test_tol_floor_is_attainable():
    """At the floor the solver's own error estimate meets the tolerance (so the floor is not
    set too high-handedly), reference: surface_entropy's error estimates."""
    floor = knobs.knobs()["entropy"]["tol"].minimum
    r = entropy.surface_entropy("lj", [1.0], tol=floor)
    assert r["S_surface_exact_error"][0] <= floor
    assert r["bulk_mean_log_omega_error"][0] <= floor


def test_infinite_stop_refused_not_overflow(base):
    """d_over_d0 stop = .inf crashed with OverflowError."""
    msg = _refused(base, lambda c: c["scenes"]["table1"].update(
        d_over_d0={"start": 0.9, "stop": float("inf"), "step": 0.01}))
    assert "scene 'table1'" in msg and "d_over_d0" in msg and "inf" in msg


def test_all_problems_reported_at_once(base):
    """Two mistakes in two scenes, one schema and one physics: both named in one error."""
    def two(c):
        c["scenes"]["table1"]["potentials"] = ["nonesuch"]
        c["scenes"]["fig2"]["accuracy"] = {"bulk": {"supercell": 1}}
        c["scenes"]["entropy"]["d_over_d0"] = [2.5]
    msg = _refused(base, two)
    assert msg.startswith("3 problems")
    assert "'nonesuch'" in msg and "supercell" in msg and "scene 'entropy'" in msg


def test_inject_refuses_mismatched_knob_lists():
    """A knob added to the schema without a library entry is caught when the schema loads."""
    raw = yaml.safe_load(open(scenes.SCHEMA_PATH))
    raw["$defs"]["scene"]["properties"]["accuracy"]["properties"]["bulk"]["properties"]["extra"] = {}
    with pytest.raises(KeyError, match="extra"):
        knobs.inject(raw)


def test_costly_settings_announced_before_any_job():
    """supercell 8, zone_mesh 200 ran for minutes per point with no sign of life: the
    expected time is stated up front (cost model measured on supercell 2..4, mesh 8..64);
    the defaults stay silent."""
    cfg = {"scenes": {"big": {"lattice": "fcc", "loading": "in_plane_hydrostatic", "potentials": ["lj"],
                              "d_over_d0": [0.99, 1.0], "quantities": ["elastic", "bulk"],
                              "accuracy": {"bulk": {"supercell": 8, "zone_mesh": 200}}}}}
    sc = validate_config(cfg)
    (line,) = knobs.expected_cost(sc, ["big"])
    assert "bulk, scene big: 4 points" in line and "supercell 8" in line
    per_point = knobs.estimated_cost("bulk", {"supercell": 8, "zone_mesh": 200}, 0.0)
    assert 10 < per_point < 300  # minutes for the scene, not milliseconds and not days
    cfg["scenes"]["big"]["accuracy"] = {}
    assert knobs.expected_cost(validate_config(cfg), ["big"]) == []


def test_implausible_phonopy_speeds_become_nan_with_reason():
    """c2 ~ 1e194 (what displacement 10 d0 gave) against the analytic long-wave speed: NaN,
    stable_phonon False, a reason; a point within 1e-6 of the analytic value is kept.
    Reference: the analytic cube values themselves (Eq. A11 route)."""
    import xarray as xr

    from surfwave.model_crystals.sanity import check_bulk

    dims = ("potential", "direction", "strain")
    coords = {"potential": ["lj"], "direction": ["[100]"], "strain": [0.0, 0.01]}
    ana = xr.Dataset({n: (dims, np.full((1, 1, 2), v)) for n, v in
                      {"c2_L_par": 1.0, "c2_T_par": 0.5, "c2_L_perp": 1.0, "c2_T_perp": 0.5, "c2_SH": 0.5}.items()},
                     coords=coords)
    bulk = xr.Dataset({f"{n}_phonopy": ana[n] * (1 + 1e-6) for n in ana}, coords=coords)
    bulk["c2_L_par_phonopy"][0, 0, 1] = 1e194
    bulk["stable_phonon"] = (dims, np.ones((1, 1, 2), bool))
    bulk["reason"] = (dims, np.full((1, 1, 2), ""))
    out, n = check_bulk(bulk, ana)
    assert n == 1
    assert np.isnan(out["c2_T_par_phonopy"][0, 0, 1]) and not bool(out["stable_phonon"][0, 0, 1])
    assert "implausible" in str(out["reason"][0, 0, 1].values)
    assert bool(out["stable_phonon"][0, 0, 0]) and str(out["reason"][0, 0, 0].values) == ""
    assert float(out["c2_T_par_phonopy"][0, 0, 0]) == pytest.approx(0.5, rel=1e-5)
