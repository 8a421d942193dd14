"""Piezoelectric scenes (``materials:`` with ``cuts:`` or ``euler:``): physics checks and job params.

Kept apart from :mod:`surfwave.pipeline.crystal_scenes` (elastic real crystals) and
:mod:`surfwave.pipeline.scenes` (which dispatches here). Every problem names the scene, the key
and the value; grid caps are checked before any job.

Examples
--------
>>> scene, problems = check_piezo_scene("s", {"materials": ["quartz"], "cuts": ["ST-X"],
...     "electrical": ["free", "metallized"], "quantities": ["surface_wave"], "accuracy": {}})
>>> scene["cuts"], scene["materials"], problems
(['ST-X quartz'], ['quartz-Bechmann1958'], [])
"""
from __future__ import annotations

import copy

from surfwave.pipeline.crystal_scenes import check_angle_range, stress_grid, unique_records
from surfwave.pipeline.grids import MAX_POINTS, SceneError, expand_grid
from surfwave.vocab import ELECTRICAL

#: Solver points of one piezoelectric scene at most (each costs ~2 ms free + metallized + leaky).
MAX_PIEZO_POINTS = 20_000


def is_piezo_scene(raw) -> bool:
    """A real-crystal scene with named cuts or Euler angles."""
    return isinstance(raw, dict) and "materials" in raw and ("cuts" in raw or "euler" in raw)


def _angle(spec, where: str) -> list[float]:
    if isinstance(spec, (int, float)) and not isinstance(spec, bool):
        angles = [float(spec)]
    else:
        angles = [float(v) for v in expand_grid(spec, where)]
    check_angle_range(angles, where)
    return angles


def check_piezo_scene(name: str, raw: dict) -> tuple[dict | None, list[str]]:
    """The expanded piezoelectric scene, or None and its problems."""
    try:
        return _expand(name, raw), []
    except SceneError as exc:
        return None, [str(exc)]


def _expand(name: str, raw: dict) -> dict:
    from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material
    from surfwave.real_crystals.piezo_sweep import scene_points

    where = f"scene {name!r}"
    for key in ("surfaces", "angles", "directions", "loading", "toec"):
        if key in raw:
            raise SceneError(f"{where}, key {key!r}: not used by a piezoelectric scene (cuts/euler set the "
                             "orientation; stress is uniaxial along the propagation, fixed constants)")
    if "cuts" in raw and "euler" in raw:
        raise SceneError(f"{where}, key 'euler': give either 'cuts' or 'euler', not both")
    mats = unique_records(where, "materials", raw["materials"], get_piezo_material)
    cuts = euler = None
    if "cuts" in raw:
        cuts = []
        for c, cut in zip(raw["cuts"], unique_records(where, "cuts", raw["cuts"], get_cut)):
            want = get_piezo_material(cut.material).formula
            wrong = [m.name for m in mats if m.formula != want]
            if wrong:
                raise SceneError(f"{where}, key 'cuts': value {c!r} is a cut of {want}, not of {wrong}")
            cuts.append(cut.name)
    else:
        spec = raw["euler"]
        euler = {k: _angle(spec.get(k, 0.0), f"{where}, key 'euler.{k}'") for k in ("phi", "theta", "psi")}
    stress = None
    if "stress" in raw:
        stress = stress_grid(where, raw["stress"])
    electrical = list(raw.get("electrical", ELECTRICAL))
    n = scene_points(len(mats), cuts, euler, electrical, stress)
    if n > min(MAX_PIEZO_POINTS, MAX_POINTS):
        raise SceneError(f"{where}: {n} points (materials x orientations x electrical x stress) exceed the limit "
                         f"of {min(MAX_PIEZO_POINTS, MAX_POINTS)}")
    return {
        "name": name,
        "kind": "piezo",
        "materials": [m.name for m in mats],
        "cuts": cuts,
        "euler": euler,
        "electrical": electrical,
        "stress": stress,
        "quantities": list(raw.get("quantities", ["surface_wave"])),
        "accuracy": copy.deepcopy(raw.get("accuracy", {})),
    }


def piezo_job_params(scene: dict) -> dict:
    """Everything the ``piezo_wave`` job reads from the config (JSON-able)."""
    params = {"scene": scene["name"], "stage": "piezo_wave"}
    params.update({k: copy.deepcopy(scene[k]) for k in ("materials", "cuts", "euler", "electrical", "stress")})
    params["accuracy"] = copy.deepcopy(scene["accuracy"].get("piezo_wave", {}))
    return params
