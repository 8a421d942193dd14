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
import hashlib
from pathlib import Path

import numpy as np

from surfwave.errors import InputError
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
    bad = [a for a in angles if not np.isfinite(a)]
    if bad:
        raise SceneError(f"{where}: value {bad[0]!r} degrees: Euler angles must be finite numbers")
    check_angle_range(angles, where)
    return angles


def check_piezo_scene(name: str, raw: dict, base_dir: str | Path | None = None) -> tuple[dict | None, list[str]]:
    """The expanded piezoelectric scene, or None and its problems.

    ``base_dir``: the directory of the config file that gave ``toec_file`` (a relative path is
    read from there; the working directory if None).
    """
    try:
        return _expand(name, raw, base_dir), []
    except SceneError as exc:
        return None, [str(exc)]


def _expand(name: str, raw: dict, base_dir=None) -> dict:
    from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material
    from surfwave.real_crystals.piezo_sweep import scene_points

    where = f"scene {name!r}"
    for key in ("surfaces", "angles", "directions", "loading"):
        if key in raw:
            raise SceneError(f"{where}, key {key!r}: not used by a piezoelectric scene (cuts/euler set the "
                             "orientation; stress is uniaxial along the propagation)")
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
    toec = [bool(t) for t in raw.get("toec", [False])]
    if "stress" in raw:
        stress = stress_grid(where, raw["stress"])
    elif toec != [False] or "toec_file" in raw:
        raise SceneError(f"{where}, key 'stress': 'toec' and 'toec_file' need a stress grid")
    toec_set = _toec_file(where, raw, mats, toec, base_dir) if stress else None
    electrical = list(raw.get("electrical", ELECTRICAL))
    n = scene_points(len(mats), cuts, euler, electrical, stress, toec)
    if n > min(MAX_PIEZO_POINTS, MAX_POINTS):
        raise SceneError(f"{where}: {n} points (materials x orientations x electrical x toec x stress) exceed "
                         f"the limit of {min(MAX_PIEZO_POINTS, MAX_POINTS)}")
    from surfwave.real_crystals.piezo_sweep import scene_cases

    try:  # every point through the one resolver: the refusals of surfwave.material, before any job
        scene_cases([m.name for m in mats], cuts=cuts, euler=euler, electrical=electrical, stress=stress,
                    toec=toec if stress else [False], toec_constants=toec_set["constants"] if toec_set else None)
    except InputError as exc:
        raise SceneError(f"{where}: {exc}") from None
    return {
        "name": name,
        "kind": "piezo",
        "materials": [m.name for m in mats],
        "cuts": cuts,
        "euler": euler,
        "electrical": electrical,
        "stress": stress,
        "toec": toec if stress else [False],
        "toec_file": toec_set,
        "quantities": list(raw.get("quantities", ["surface_wave"])),
        "accuracy": copy.deepcopy(raw.get("accuracy", {})),
    }


def piezo_job_params(scene: dict) -> dict:
    """Everything the ``piezo_wave`` job reads from the config (JSON-able)."""
    params = {"scene": scene["name"], "stage": "piezo_wave"}
    keys = ("materials", "cuts", "euler", "electrical", "stress", "toec", "toec_file")
    params.update({k: copy.deepcopy(scene.get(k)) for k in keys})  # toec_file: the file's content and hash
    params["accuracy"] = copy.deepcopy(scene["accuracy"].get("piezo_wave", {}))
    return params


def _toec_file(where: str, raw: dict, mats: list, toec: list[bool], base_dir) -> dict | None:
    """The scene's third-order set: None, or ``{"path", "sha256", "constants"}`` (the file's
    named constants, GPa, and its ``source``), checked for the materials' one crystal class.

    Without ``toec_file`` every material needs the database's own set where ``toec`` has true.
    """
    if "toec_file" not in raw:
        if True in toec:
            lacking = [m.name for m in mats if m.toec_voigt is None]
            if lacking:
                raise SceneError(f"{where}, key 'toec': value true needs third-order elastic constants, which the "
                                 f"database lacks for material(s) {lacking} (of the piezoelectric database only "
                                 "GaAs has them); give toec_file, remove them, or use toec: [false]")
        return None
    given = raw["toec_file"]
    if True not in toec:
        raise SceneError(f"{where}, key 'toec_file': value {given!r} is not used with toec: {toec}; "
                         "add true to 'toec'")
    classes = sorted({m.crystal_class for m in mats})
    if len(classes) > 1:
        raise SceneError(f"{where}, key 'toec_file': one set of third-order constants for materials of "
                         f"different crystal classes {classes} ({[m.name for m in mats]}); give one class "
                         "per scene")
    path = Path(str(given)).expanduser()
    if not path.is_absolute() and base_dir is not None:
        path = Path(base_dir) / path
    from surfwave.real_crystals.piezo_materials import read_toec_file
    from surfwave.real_crystals.toec_classes import toec_from_user

    try:
        constants, text = read_toec_file(path)
        toec_from_user(constants, classes[0])                       # the library's own check and message
    except InputError as exc:
        raise SceneError(f"{where}, key 'toec_file': value {given!r}: {exc}") from None
    return {"path": str(path.resolve()), "sha256": hashlib.sha256(text).hexdigest(),
            "constants": {k: (str(v) if k == "source" else float(v)) for k, v in constants.items()}}
