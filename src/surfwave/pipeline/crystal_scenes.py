"""Real-crystal scenes (a ``materials:`` key) and FCC model scenes with propagation angles:
the physics checks and expansion that follow the schema (``$defs/crystal_scene``).

Kept apart from :mod:`surfwave.pipeline.scenes` (which dispatches here) so that each scene
kind's checks live in one place. Every problem names the scene, the key and the value.

Examples
--------
>>> scene, problems = check_crystal_scene("s", {"materials": ["Cu"], "surfaces": ["(001)"],
...     "directions": ["[110]", "[100]"], "loading": ["along"], "toec": [False],
...     "quantities": ["surface_wave"], "accuracy": {}})
>>> scene["angles"], scene["directions"], problems
([0.0, 45.0], ['[100]', '[110]'], [])
"""
from __future__ import annotations

import copy

import numpy as np

from surfwave.errors import InputError
from surfwave.pipeline.grids import DECIMALS, MAX_POINTS, SceneError, check_points, expand_grid

#: Quantities an FCC scene with propagation angles can compute.
ANGLE_QUANTITIES = ("elastic", "rayleigh")


def fcc_angles(where: str, raw: dict) -> tuple[list[float] | None, list[str]]:
    """Angles (degrees from [100] in the (001) surface) of an FCC scene's ``directions`` grid."""
    from surfwave.model_crystals.fcc_angles import LOADING

    problems = []
    if raw["lattice"] != "fcc":
        problems.append(f"{where}, key 'directions': angles need lattice 'fcc', not {raw['lattice']!r}")
    if raw["loading"] != LOADING:
        problems.append(f"{where}, key 'loading': value {raw['loading']!r} with angles as directions: "
                        f"only {LOADING!r} keeps the stressed crystal the same in every direction")
    for q in raw["quantities"]:
        if q not in ANGLE_QUANTITIES:
            problems.append(f"{where}, key 'quantities': value {q!r} is not available with angles "
                            f"as directions (choose from {list(ANGLE_QUANTITIES)})")
    try:
        angles = [float(a) for a in expand_grid(raw["directions"], f"{where}, key 'directions'")]
        check_angle_range(angles, f"{where}, key 'directions'")
    except SceneError as exc:
        return None, problems + [str(exc)]
    return (None if problems else angles), problems


def unique_records(where: str, key: str, names, lookup) -> list:
    """Database records of ``names`` (``lookup(name)``), refusing unknown names and two spellings
    of one record ("Cu" and "copper" would give two labels Cu in one cube)."""
    records: list = []
    given: dict[str, str] = {}
    for n in names:
        try:
            rec = lookup(n)
        except InputError as exc:
            raise SceneError(f"{where}, key {key!r}: value {n!r}: {exc}") from None
        if rec.name in given:
            raise SceneError(f"{where}, key {key!r}: values {given[rec.name]!r} and {n!r} name the same "
                             f"{key[:-1]} {rec.name!r}; give it once")
        given[rec.name] = n
        records.append(rec)
    return records


def stress_grid(where: str, spec) -> list[float]:
    """The stress values of a scene, GPa; values beyond :data:`MAX_STRESS_GPA` look like Pa."""
    from surfwave.validate import gpa_stress

    stress = [float(x) for x in expand_grid(spec, f"{where}, key 'stress'")]
    for x in stress:   # the one Pa guard (MAX_STRESS_GPA) and its wording, as surfwave.material
        try:
            gpa_stress(x)
        except InputError as exc:
            raise SceneError(f"{where}, key 'stress': value {x!r}: {exc}") from None
    return stress


def check_angle_range(angles, where: str) -> None:
    """SceneError if an angle exceeds :data:`surfwave.validate.MAX_ANGLE` in magnitude."""
    from surfwave.validate import MAX_ANGLE

    big = [a for a in angles if abs(a) > MAX_ANGLE]
    if big:
        raise SceneError(f"{where}: value {big[0]!r} degrees: angles beyond {MAX_ANGLE:g} degrees lose "
                         "precision in float64 (the angle computed would not be the angle labelled); "
                         "reduce it modulo 360")


def crystal_angles(where: str, raw: dict, surfaces: list[str], voigts: list) -> tuple[list, list | None]:
    """Angles (degrees) of a real-crystal scene and their Miller labels (or None)."""
    from surfwave.real_crystals.sweep import symmetry_reduced_range
    from surfwave.solvers import orientation

    if "directions" in raw:
        if "angles" in raw:
            raise SceneError(f"{where}, key 'directions': give either 'angles' or 'directions', not both")
        angles = []
        for direction in raw["directions"]:
            found = []
            for sf in surfaces:
                try:
                    found.append(round(orientation.direction_angle(sf, direction), DECIMALS))
                except InputError as exc:
                    raise SceneError(f"{where}, key 'directions': value {direction!r}: {exc}") from None
            if len(set(found)) > 1:
                raise SceneError(f"{where}, key 'directions': value {direction!r} lies at different "
                                 f"angles in the surfaces {surfaces} ({found} degrees); give "
                                 "'angles' instead, or one surface per scene")
            angles.append(found[0])
        if len(set(angles)) < len(angles):
            raise SceneError(f"{where}, key 'directions': two directions give the same angle {angles}")
        order = np.argsort(angles)
        return [float(angles[i]) for i in order], [raw["directions"][i] for i in order]
    spec = raw.get("angles", "symmetric")
    if spec == "symmetric" or (isinstance(spec, dict) and "symmetric" in spec):
        # Each surface's range [0, w] by the step, w itself included (a mirror line), merged.
        step = float(spec.get("step", 1.0)) if isinstance(spec, dict) else 1.0
        if not (np.isfinite(step) and step > 0):
            raise SceneError(f"{where}, key 'angles': step {step!r} must be a positive number of degrees")
        grid = set()
        for sf in surfaces:
            w = symmetry_reduced_range(sf, voigts)
            if w / step + 1 > MAX_POINTS:
                raise SceneError(f"{where}, key 'angles': step {step!r} gives {w / step + 1:.4g} angles over "
                                 f"the {w:g} degrees of surface {sf}, more than the limit of {MAX_POINTS}")
            grid.update(np.round(np.arange(0.0, w - 1e-9, step), DECIMALS).tolist() + [w])
        return sorted(float(a) for a in grid), None
    angles = [float(a) for a in expand_grid(spec, f"{where}, key 'angles'")]
    check_angle_range(angles, f"{where}, key 'angles'")
    return angles, None


def check_crystal_scene(name: str, raw: dict) -> tuple[dict | None, list[str]]:
    """The expanded real-crystal scene (``materials:`` key), or None and its problem."""
    try:
        return _expand_crystal_scene(name, raw), []
    except SceneError as exc:
        return None, [str(exc)]


def _expand_crystal_scene(name: str, raw: dict) -> dict:
    """Physical checks and expansion of a real-crystal scene; the first problem raises."""
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.sweep import applied_stress
    from surfwave.solvers import orientation

    where = f"scene {name!r}"
    mats = unique_records(where, "materials", raw["materials"], get_material)
    surfaces = []
    for sf in raw["surfaces"]:
        try:
            orientation.lab_axes(sf, 0.0)
        except (InputError, ValueError) as exc:
            raise SceneError(f"{where}, key 'surfaces': value {sf!r}: {exc}") from None
        surfaces.append(sf)
    angles, directions = crystal_angles(where, raw, surfaces, [m.voigt for m in mats])
    stress = None
    if "stress" in raw:
        stress = stress_grid(where, raw["stress"])
        for loading in raw["loading"]:
            for sf in surfaces:
                try:  # an axis_<hkl> must lie in every surface: no stress on the free face
                    axes = np.asarray(orientation.lab_axes(sf, 0.0), dtype=float).reshape(1, 3, 3)
                    applied_stress(loading, axes, [1.0])
                except InputError as exc:
                    raise SceneError(f"{where}, key 'loading': value {loading!r}, surface {sf!r}: "
                                     f"{exc}") from None
        if True in raw["toec"]:
            lacking = [m.name for m in mats if m.toec is None]
            if lacking:
                raise SceneError(
                    f"{where}, key 'toec': value true needs third-order elastic constants "
                    f"(C111, C112, C123, C144, C155, C456), which the database lacks for "
                    f"material(s) {lacking}; remove them or use toec: [false]")
    elif raw.get("toec", [False]) != [False] or raw.get("loading", ["along"]) != ["along"]:
        raise SceneError(f"{where}, key 'stress': 'loading' and 'toec' need a stress grid")
    sizes = {"materials": len(mats), "surfaces": len(surfaces), "angles": len(angles)}
    if stress:
        sizes.update({"stresses": len(stress), "loadings": len(raw["loading"]), "toec": len(raw["toec"])})
    check_points(where, sizes)
    from surfwave.real_crystals.sweep import scene_cases

    try:  # every point through the one resolver: the refusals of surfwave.material, before any job
        scene_cases(mats, surfaces, angles, stress, raw["loading"] if stress else ("along",),
                    raw["toec"] if stress else (False,))
    except InputError as exc:
        raise SceneError(f"{where}: {exc}") from None
    return {
        "name": name,
        "kind": "crystal",
        "materials": [m.name for m in mats],
        "surfaces": surfaces,
        "angles": angles,
        "directions": directions,
        "stress": stress,
        "loading": list(raw["loading"]) if stress else ["along"],
        "toec": [bool(t) for t in raw["toec"]] if stress else [False],
        "quantities": list(raw["quantities"]),
        "accuracy": copy.deepcopy(raw["accuracy"]),
    }
