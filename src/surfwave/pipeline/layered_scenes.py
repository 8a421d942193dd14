"""Layered scenes (``substrate:`` with ``films:``): physics checks, job params and the scene's cube.

A layered scene is a stack (a substrate and films from the top down, each with its thickness and
optional Euler angles), one or more substrate orientations (a surface and direction, SAW Euler
angles, or a named cut), a kh grid, a grid of equibiaxial film stresses, electrical conditions of
the top surface and optionally the substrate's own prestress. Every point's inputs go through
:func:`surfwave.layers.stack.resolve_stack` (the resolver of :func:`surfwave.layered`) and the kh
check of :func:`surfwave.layered` here, before any job, so a bad thickness or an unknown film is
one line at ``snakemake -n``. Kept apart from :mod:`surfwave.pipeline.scenes` (which dispatches
here) and from the crystal and piezoelectric scene kinds.

Examples
--------
>>> scene, problems = check_layered_scene("s", {"substrate": "Si", "kh": [0.5, 1.0],
...     "films": [{"material": "fused-SiO2", "thickness": 1e-6}]})
>>> problems, scene["orientations"][0]["label"], scene["film_stress"]
([], '(001)[100]', [0.0])
"""
from __future__ import annotations

import copy
import warnings
from typing import Any

import numpy as np
import xarray as xr

from surfwave.errors import ConstantsNote, InputError
from surfwave.pipeline.grids import MAX_POINTS, SceneError, expand_grid
from surfwave.vocab import ELECTRICAL

#: Solver points (orientations x film stresses x electrical x kh) of one layered scene at most
#: (one point costs about 0.1-1 ms per mode on one core).
MAX_LAYERED_POINTS = 20_000
#: The ``method`` attribute of the cube.
METHOD = ("surfwave.layered: Stroh partial waves in every layer and the substrate, surface-impedance "
          "(Riccati) recursion through the films, every mode followed in kh (docs/physics/layered.md); "
          "surfwave.layers.cube.dispersion_cube per orientation")
#: The ``units_note`` attribute of the cube.
UNITS_NOTE = ("SI units: speeds m/s, frequency Hz, stresses GPa (film_stress equibiaxial in the surface "
              "plane; the substrate's stress in the scene attribute), kh = wavenumber x total film thickness")
#: Long name of the cube's orientation coordinate (added by :func:`scene_cube`).
ORIENTATION_ATTRS = {"long_name": "substrate orientation: (surface)[direction], SAW Euler angles "
                                  "(phi, theta, psi) in degrees, or a named cut"}


def is_layered_scene(raw: Any) -> bool:
    """A scene that names a ``substrate`` (films on a crystal substrate)."""
    return isinstance(raw, dict) and "substrate" in raw


def check_layered_scene(name: str, raw: dict) -> tuple[dict | None, list[str]]:
    """The expanded layered scene, or None and its problems (one line each).

    Parameters
    ----------
    name : str
        Scene name (every message names it).
    raw : dict
        The scene as the config gives it (schema-valid, defaults filled in).

    Returns
    -------
    (dict or None, list of str)
        The expanded scene (JSON-able: orientations resolved to keyword sets of
        :func:`surfwave.layered`, kh and film_stress as lists of floats) and no problems; or
        None and the problems.
    """
    try:
        return _expand(name, raw), []
    except SceneError as exc:
        return None, [str(exc)]


def _orientation(where: str, spec: Any, substrate: Any) -> dict:
    """``{"label", "euler"}`` or ``{"label", "surface", "direction"}`` of one orientation entry."""
    if not isinstance(spec, dict):
        raise SceneError(f"{where}: give {{surface, direction}}, {{euler: [phi, theta, psi]}} or {{cut}}, "
                         f"got {spec!r}")
    if "cut" in spec:
        from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material

        try:
            cut = get_cut(str(spec["cut"]))
        except InputError as exc:
            raise SceneError(f"{where}, key 'cut': {exc}") from None
        try:  # a cut belongs to one crystal: the substrate must be that crystal
            same = isinstance(substrate, str) and (
                get_piezo_material(substrate).formula == get_piezo_material(cut.material).formula)
        except InputError:
            same = False
        if not same:
            raise SceneError(f"{where}, key 'cut': value {spec['cut']!r} is a cut of "
                             f"{get_piezo_material(cut.material).formula}, not of the substrate {substrate!r}")
        return {"label": cut.name, "euler": [float(a) for a in cut.euler]}
    if "euler" in spec:
        e = [float(a) for a in spec["euler"]]
        return {"label": "Euler ({})".format(", ".join(f"{a:g}" for a in e)), "euler": e}
    surface, direction = str(spec.get("surface", "(001)")), spec.get("direction", "[100]")
    label = f"{surface}[{direction.strip('[]')}]" if isinstance(direction, str) else f"{surface} {direction:g} deg"
    return {"label": label, "surface": surface, "direction": direction}


def stack_kwargs(orientation: dict) -> dict:
    """Keywords of :func:`surfwave.layered` for one resolved orientation (``euler`` or ``surface``/``direction``)."""
    if "euler" in orientation:
        return {"euler": list(orientation["euler"])}
    return {"surface": orientation["surface"], "direction": orientation["direction"]}


def _expand(name: str, raw: dict) -> dict:
    from surfwave.layers.solve import checked_kh
    from surfwave.layers.stack import resolve_stack

    where = f"scene {name!r}"
    substrate, films = copy.deepcopy(raw["substrate"]), copy.deepcopy(list(raw["films"]))
    orients = [_orientation(f"{where}, key 'orientations[{i}]'", o, substrate)
               for i, o in enumerate(raw.get("orientations") or [{}])]
    labels = [o["label"] for o in orients]
    if len(set(labels)) != len(labels):
        raise SceneError(f"{where}, key 'orientations': the same orientation twice ({labels})")
    try:
        kh = checked_kh(expand_grid(raw["kh"], f"{where}, key 'kh'"))
    except InputError as exc:
        raise SceneError(f"{where}, key 'kh': {exc}") from None
    stresses = [float(s) for s in expand_grid(raw.get("film_stress", [0.0]), f"{where}, key 'film_stress'")]
    if len(set(stresses)) != len(stresses):
        raise SceneError(f"{where}, key 'film_stress': a stress is listed twice ({stresses})")
    swept = [i for i, f in enumerate(films) if not isinstance(f, dict) or f.get("stress") is None]
    if "film_stress" in raw and not swept:
        raise SceneError(f"{where}, key 'film_stress': every film gives its own 'stress', so the sweep would "
                         "stress none; remove 'film_stress' or a film's 'stress'")
    electrical = list(raw.get("electrical", ELECTRICAL))
    n = len(orients) * len(stresses) * len(electrical) * kh.size
    if n > min(MAX_LAYERED_POINTS, MAX_POINTS):
        raise SceneError(f"{where}: {n} points (orientations x film_stress x electrical x kh) exceed the limit "
                         f"of {min(MAX_LAYERED_POINTS, MAX_POINTS)}")
    piezo = False
    for o in orients:  # every point through the resolver of surfwave.layered, before any job
        for s in stresses:
            try:
                with warnings.catch_warnings():   # a constant set's note belongs to the job's log, not the check
                    warnings.simplefilter("ignore", ConstantsNote)
                    stack = resolve_stack(substrate, [f if i not in swept else {**f, "stress": s}
                                                      for i, f in enumerate(films)],
                                          stress=raw.get("stress"), **stack_kwargs(o))
            except InputError as exc:
                at = [f"orientation {o['label']!r}"] * (len(orients) > 1) + [f"film_stress {s:g} GPa"] * bool(s)
                raise SceneError(f"{where}{' (' + ', '.join(at) + ')' if at else ''}: {exc}") from None
            piezo = piezo or stack.piezo
    if not piezo and electrical == list(ELECTRICAL):  # the default: an elastic stack has one surface condition
        electrical = ["free"]
    if "metallized" in electrical and not piezo:
        raise SceneError(f"{where}, key 'electrical': value 'metallized' needs a piezoelectric layer or substrate "
                         "(an elastic stack takes free only)")
    return {
        "name": name,
        "kind": "layered",
        "substrate": substrate,
        "films": films,
        "orientations": orients,
        "kh": [float(x) for x in kh],
        "film_stress": stresses,
        "stress": copy.deepcopy(raw.get("stress")),
        "electrical": electrical,
        "leaky": bool(raw.get("leaky", False)),
        "piezo": bool(piezo),
        "quantities": list(raw.get("quantities", ["dispersion_layered"])),
        "accuracy": copy.deepcopy(raw.get("accuracy", {})),
    }


def layered_job_params(scene: dict) -> dict:
    """Everything the ``layered`` job reads from the config (JSON-able)."""
    params = {"scene": scene["name"], "stage": "layered"}
    keys = ("substrate", "films", "orientations", "kh", "film_stress", "stress", "electrical", "leaky")
    params.update({k: copy.deepcopy(scene.get(k)) for k in keys})
    return params


def scene_cube(job: dict) -> xr.Dataset:
    """The ``dispersion_layered`` cube of a layered scene: :func:`surfwave.layers.cube.dispersion_cube`
    per orientation, joined along a leading ``orientation`` dimension.

    Parameters
    ----------
    job : dict
        :func:`layered_job_params` of the scene.

    Returns
    -------
    xarray.Dataset
        Dimensions (orientation, film_stress, electrical, kh, mode) plus (film, sheet) for
        ``film_bulk_speed``; a mode label missing at one orientation is NaN there.
    """
    from surfwave.layers.cube import dispersion_cube

    parts = [dispersion_cube(job["substrate"], job["films"], np.asarray(job["kh"], dtype=float),
                             film_stress=job["film_stress"], electrical=job["electrical"], leaky=job["leaky"],
                             stress=job["stress"], keep_film_stress=True, **stack_kwargs(o))
             for o in job["orientations"]]
    labels = [o["label"] for o in job["orientations"]]
    if len(parts) == 1:
        ds = parts[0].expand_dims(orientation=labels)
        ds["film_bulk_speed"] = parts[0]["film_bulk_speed"]
    else:
        ds = xr.concat(parts, dim=xr.DataArray(labels, dims="orientation"), data_vars="all", coords="minimal",
                       compat="equals", join="outer", combine_attrs="override")
        ds["film_bulk_speed"] = parts[0]["film_bulk_speed"]  # a film's axes do not depend on the substrate's
        mean = ds["c"].mean(dim=[d for d in ds["c"].dims if d != "mode"]).values
        ds = ds.isel(mode=np.lexsort((ds["mode"].values, np.nan_to_num(mean, nan=np.inf))))
    ds["orientation"] = ("orientation", np.array(labels, dtype=str), dict(ORIENTATION_ATTRS))
    own = [i for i, f in enumerate(job["films"]) if isinstance(f, dict) and f.get("stress") is not None]
    if own:  # those films keep the stress the scene gives them (the scene attribute)
        ds["film_stress"].attrs["long_name"] = ("equibiaxial in-plane residual stress of every film without its "
                                                f"own stress (films {own} keep theirs)")
    return ds
