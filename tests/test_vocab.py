"""The vocabularies, result records and cube metadata are defined once (issue 21, item 3).

References: the values are the module's own (surfwave.vocab, surfwave.records,
surfwave.data.variables); everything else (config schema, command line, solvers, cubes of a
default run) must agree with them. The list of variables a default run writes was read off a
finished default run (``make reproduce`` of commit 9667c5c, the code before the package
re-layout: its results/*/*.nc).
"""
from __future__ import annotations

import importlib
import pkgutil
import re
from pathlib import Path
from typing import get_args

import numpy as np
import pytest

import surfwave
from surfwave import vocab
from surfwave.data.variables import CUBES, MODEL_COORDS, PIEZO_WAVE_COORDS, SURFACE_WAVE_COORDS
from surfwave.pipeline.scenes import load_schema
from surfwave.records import MaterialResult, PointResult

#: Data variables of every cube of the default run (results/<scene>/<cube>.nc, all scenes).
DEFAULT_RUN = {
    "crystal": ["cell", "mirror_x", "mirror_z", "space_group", "space_group_number", "volume"],
    "elastic": ["C", "S", "c2_L_par", "c2_L_perp", "c2_SH", "c2_T_par", "c2_T_perp", "min_acoustic_eig",
                "stable", "stress", "volume"],
    "bulk": ["c2_L_par_deviation", "c2_L_par_phonopy", "c2_L_perp_deviation", "c2_L_perp_phonopy",
             "c2_SH_deviation", "c2_SH_phonopy", "c2_T_par_deviation", "c2_T_par_phonopy", "c2_T_perp_deviation",
             "c2_T_perp_phonopy", "min_c2_direction", "min_c2_phonopy", "min_omega2", "min_omega2_q", "reason",
             "stable_phonon", "supercell_used"],
    "rayleigh": ["c2_R", "kappa1", "kappa2", "reason", "wave_type"],
    "dispersion": ["R1", "R2", "amplitude_ratio", "boundary_residual", "c2_R", "c2_R_long_wave", "depth",
                   "n_surface_modes", "omega", "omega_L", "omega_T", "omega_bulk_min", "omega_lattice",
                   "omega_lattice_deviation", "omega_lattice_error", "omega_sine_law", "polarisation", "q1", "q2",
                   "reason", "reason_lattice", "sine_law_deviation", "theta_c"],
    "displacements": ["reason", "u", "v"],
    "entropy": ["S_surface_estimate", "S_surface_estimate_error", "S_surface_exact", "S_surface_exact_error",
                "bulk_mean_log_omega", "bulk_mean_log_omega_error", "n_theta", "reason"],
    "surface_wave": ["c_R", "c_R_imag", "c_limit", "decay", "penetration_depth", "polarisation", "reason", "rho",
                     "symmetric_range", "wave_type"],
}
#: String and boolean variables: the cube builders drop their units.
UNITLESS = {"reason", "reason_lattice", "wave_type", "space_group", "mirror_x", "mirror_z", "stable",
            "stable_phonon"}


def _schema_defs() -> dict:
    return load_schema()["$defs"]


# --- vocabularies -------------------------------------------------------------------------

@pytest.mark.parametrize("literal, values", [
    (vocab.WaveType, vocab.WAVE_TYPES), (vocab.Lattice, vocab.LATTICES), (vocab.Loading, vocab.LOADINGS),
    (vocab.Direction, vocab.DIRECTIONS), (vocab.StressLoading, vocab.STRESS_LOADINGS),
    (vocab.Electrical, vocab.ELECTRICAL),
])
def test_tuples_are_the_literals_values(literal, values):
    assert tuple(get_args(literal)) == values and len(set(values)) == len(values)


def test_schema_enums_are_the_vocabularies():
    """The JSON schema's enums of model-lattice scenes == the Literals' values (order included)."""
    scene = _schema_defs()["scene"]["properties"]
    assert tuple(scene["lattice"]["enum"]) == vocab.LATTICES
    assert tuple(scene["loading"]["enum"]) == vocab.LOADINGS
    assert tuple(scene["directions"]["oneOf"][0]["items"]["enum"]) == vocab.DIRECTIONS


def test_schema_electrical_is_the_vocabulary():
    """Piezoelectric scenes: the electrical enum and its default are the vocabulary's."""
    found = [v["properties"]["electrical"] for v in _schema_defs().values()
             if isinstance(v, dict) and "electrical" in v.get("properties", {})]
    assert found
    for prop in found:
        assert tuple(prop["items"]["enum"]) == vocab.ELECTRICAL and tuple(prop["default"]) == vocab.ELECTRICAL


def test_schema_stress_loadings_are_the_vocabulary():
    """Real-crystal scenes: the loading pattern's alternatives are the stress loadings (axis as axis_<hkl>)."""
    pattern = _schema_defs()["crystal_scene"]["properties"]["loading"]["items"]["pattern"]
    alternatives = re.fullmatch(r"\^\((.*)\)\$", pattern).group(1).split("|")
    assert tuple(a.split("_")[0] for a in alternatives) == vocab.STRESS_LOADINGS
    for kind in vocab.STRESS_LOADINGS:
        assert re.match(pattern, kind if kind != "axis" else "axis_1-10")


def test_modules_use_the_vocabularies():
    """The solvers, lattices, loadings and figures take their values from surfwave.vocab."""
    from surfwave.model_crystals import fcc_angles, lattices
    from surfwave.plots.surface_wave import TYPE_STYLES
    from surfwave.real_crystals import acoustoelastic, sweep
    from surfwave.solvers import rayleigh, stroh

    assert stroh.WAVE_TYPES is vocab.WAVE_TYPES and fcc_angles.WAVE_TYPES is vocab.WAVE_TYPES
    assert rayleigh.WAVE_TYPES is vocab.SAGITTAL_WAVE_TYPES
    assert set(vocab.SAGITTAL_WAVE_TYPES) | {"pseudo"} == set(vocab.WAVE_TYPES)
    assert set(TYPE_STYLES) <= set(vocab.WAVE_TYPES)
    assert tuple(lattices.LATTICES) == vocab.LATTICES
    for spec in lattices.LATTICES.values():
        assert set(spec["loadings"]) <= set(vocab.LOADINGS) and set(spec["directions"]) <= set(vocab.DIRECTIONS)
    assert acoustoelastic.LOADINGS == vocab.STRESS_LOADINGS
    assert set(sweep.LOADINGS) | {"axis"} == set(vocab.STRESS_LOADINGS)
    from surfwave.solvers import leaky, piezo

    assert leaky.ELECTRICAL is vocab.ELECTRICAL and piezo.ELECTRICAL is vocab.ELECTRICAL
    from surfwave.real_crystals import piezo_sweep, piezo_wave

    assert piezo_wave.ELECTRICAL is vocab.ELECTRICAL and piezo_sweep.ELECTRICAL is vocab.ELECTRICAL


def test_cli_choices_are_the_vocabularies():
    from surfwave.cli import _parser

    sub = next(a for a in _parser()._actions if a.dest == "command")
    point = {a.dest: a.choices for a in sub.choices["point"]._actions}
    assert tuple(point["lattice"]) == vocab.LATTICES
    assert tuple(point["loading"]) == vocab.LOADINGS
    assert tuple(point["direction"]) == vocab.DIRECTIONS


def test_solver_wave_types_stay_in_the_vocabulary():
    """Wave types the solvers actually return (FCC LJ [100]/[110] and off-mirror angles)."""
    seen = set()
    for direction in ("[100]", "[110]", [10.0, 30.0]):
        seen |= set(np.ravel(surfwave.point("fcc", "in_plane_hydrostatic", "lj", direction, [0.97, 1.0])["wave_type"]))
    seen.add(surfwave.material("Cu", direction="[110]")["wave_type"])
    assert seen <= set(vocab.WAVE_TYPES) and "surface" in seen


# --- records ------------------------------------------------------------------------------

@pytest.mark.parametrize("args, kwargs", [
    (("fcc", "in_plane_hydrostatic", "lj", "[110]", [0.98, 1.0]), {}),
    (("fcc", "in_plane_hydrostatic", "lj", "[100]", [1.0]), {"details": True, "min_eig": True}),
    (("fcc", "in_plane_hydrostatic", "lj", [0.0, 20.0], [1.0]), {}),
    (("triangular", "uniaxial", "harmonic", "[10]", [0.9, 1.0]), {}),
])
def test_point_keys_are_the_record(args, kwargs):
    """point() returns every required key of PointResult and no key the record does not know."""
    keys = set(surfwave.point(*args, **kwargs))
    assert PointResult.__required_keys__ <= keys <= PointResult.__required_keys__ | PointResult.__optional_keys__


@pytest.mark.parametrize("kwargs", [{"direction": "[110]"}, {"angle": [0.0, 15.0]}])
def test_material_keys_are_the_record(kwargs):
    assert set(surfwave.material("Cu", **kwargs)) == MaterialResult.__required_keys__


def test_records_exported_by_the_api():
    assert surfwave.api.PointResult is PointResult and surfwave.api.MaterialResult is MaterialResult


# --- cube metadata ------------------------------------------------------------------------

@pytest.mark.parametrize("cube", sorted(DEFAULT_RUN))
def test_table_covers_the_default_run(cube):
    """Every data variable of the default run has a long_name in the table (units where numeric)."""
    table = CUBES[cube]
    for name in DEFAULT_RUN[cube]:
        assert table[name]["long_name"], (cube, name)
        assert (name in UNITLESS) or "units" in table[name], (cube, name)


def test_units_agree_across_cubes():
    """A variable name carries one unit in every cube (penetration_depth was "wavelength" in the
    solver's table and "1" in the surface_wave cube; it is "1": a depth in wavelengths)."""
    units: dict[str, set] = {}
    for table in CUBES.values():
        for name, meta in table.items():
            units.setdefault(name, set()).add(meta.get("units"))
    assert {n: u for n, u in units.items() if len(u) > 1} == {}
    assert CUBES["surface_wave"]["penetration_depth"]["units"] == "1"
    assert all(u == {None} for n, u in units.items() if n in UNITLESS - {"stable", "stable_phonon"})


def test_no_second_metadata_table():
    """No module of the package keeps its own variable table (the one table is surfwave.data.variables)."""
    found = []
    for info in pkgutil.walk_packages(surfwave.__path__, "surfwave."):
        if info.name.endswith("__main__"):
            continue
        module = importlib.import_module(info.name)
        for attr, value in vars(module).items():
            if (attr.endswith("VARIABLES") and isinstance(value, dict) and value
                    and not any(value is table for table in CUBES.values())):
                found.append(f"{info.name}.{attr}")
    assert found == []


def test_piezo_cube_carries_the_table():
    """A piezoelectric cube (128Y-X LiNbO3, free and metallized) writes only variables and
    coordinates of the table, with the table's attributes."""
    from surfwave.real_crystals.piezo_sweep import piezo_wave_sweep

    ds = piezo_wave_sweep(["LiNbO3"], cuts=["128Y-X"])
    for name, var in ds.data_vars.items():
        assert var.attrs.get("long_name") == CUBES["piezo_wave"][name]["long_name"], name
        assert var.attrs.get("units") == CUBES["piezo_wave"][name].get("units"), name
    for name in ("material", "surface", "angle", "electrical", "euler_phi", "euler_psi", "cut"):
        assert ds[name].attrs == PIEZO_WAVE_COORDS[name], name


def test_coordinate_tables():
    assert MODEL_COORDS["angle"]["units"] == "degree" and SURFACE_WAVE_COORDS["angle"]["units"] == "degree"
    assert SURFACE_WAVE_COORDS["stress"]["units"] == "GPa"


@pytest.mark.skipif(not (Path(__file__).resolve().parents[1] / "results" / "table1" / "rayleigh.nc").is_file(),
                    reason="no default run in results/ (make reproduce)")
def test_written_cubes_carry_the_table():
    """If a default run exists in results/, its cubes' attributes are the table's."""
    from surfwave.data.cube import open_cube

    root = Path(__file__).resolve().parents[1] / "results"
    for path in sorted(root.glob("*/*.nc")):
        if path.stem not in DEFAULT_RUN:
            continue
        ds = open_cube(path)
        if path.stem == "rayleigh" and "angle" in ds.dims:
            table = CUBES["rayleigh_angles"]
        elif path.stem == "surface_wave" and "electrical" in ds.dims:
            table = CUBES["piezo_wave"]
        else:
            table = CUBES[path.stem]
        for name, var in ds.data_vars.items():
            assert var.attrs.get("long_name") == table[name]["long_name"], (path, name)
            if name not in UNITLESS:
                assert var.attrs.get("units") == table[name].get("units"), (path, name)
