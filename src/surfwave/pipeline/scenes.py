"""Scenes: the workflow's configuration, validated and expanded before any job runs.

A scene names a lattice, a loading, potentials, directions, a strain grid (d/d0), a theta
grid, the quantities wanted and per-method accuracy knobs (``config/config.yaml``,
``workflow/schemas/config.schema.yaml``). :func:`validate_config` fills the schema's
defaults into the config in place, checks it against the schema and against what the
lattices can physically take, and returns the expanded scenes. Every error names the
scene, the key and the offending value.

:func:`job_params` gives the exact parameters a workflow job uses (and nothing else), so
that Snakemake reruns a job when, and only when, something it depends on changes.

Examples
--------
>>> cfg = {"scenes": {"s": {"lattice": "fcc", "loading": "in_plane_hydrostatic",
...        "potentials": ["lj"], "d_over_d0": {"start": 0.98, "stop": 1.0, "step": 0.01},
...        "quantities": ["elastic"]}}}
>>> scenes = validate_config(cfg)
>>> scenes["s"]["d_over_d0"], scenes["s"]["directions"]
([0.98, 0.99, 1.0], ['[100]', '[110]'])
"""
from __future__ import annotations

import copy
import re
from functools import partial
from pathlib import Path
from typing import Any

from surfwave.errors import InputError, SurfwaveError
from surfwave.model_crystals.lattices import LATTICES, build, check_combination, check_d_over_d0
from surfwave.model_crystals.potentials import get_potential
from surfwave.pipeline.config_messages import join as _join
from surfwave.pipeline.config_messages import name_problems, rest_problems, schema_message
from surfwave.pipeline.crystal_scenes import check_crystal_scene, fcc_angles
from surfwave.pipeline.grids import DECIMALS, MAX_POINTS, SceneError, check_points, expand_grid, theta_grid  # noqa: F401 (public)
from surfwave.pipeline.layered_scenes import check_layered_scene, is_layered_scene
from surfwave.pipeline.piezo_scenes import check_piezo_scene, is_piezo_scene
from surfwave.pipeline.surface_phonons_scenes import DEFAULT_SURFACES, check_surfaces

#: The schema shipped with the workflow (repository layout; pass a path to override).
SCHEMA_PATH = Path(__file__).resolve().parents[3] / "workflow" / "schemas" / "config.schema.yaml"

#: Result cube written for each quantity, under results/<scene>/.
CUBES = {
    "elastic": "elastic.nc",
    "bulk": "bulk.nc",
    "rayleigh": "rayleigh.nc",
    "dispersion": "dispersion.nc",
    "displacements": "displacements.nc",
    "entropy": "entropy.nc",
    "surface_wave": "surface_wave.nc",
    "surface_phonons": "surface_phonons.nc",
    "dispersion_layered": "dispersion_layered.nc",
}
#: Quantities that exist only for the triangular lattice (row-by-row lattice dynamics).
TRIANGULAR_ONLY = ("dispersion", "displacements", "entropy")
#: Quantities that exist only for the FCC lattice (surfwave.dynamics.fcc_surface_phonons).
FCC_ONLY = ("surface_phonons",)
#: A number with an exponent that PyYAML (YAML 1.1) reads as text: "1.0e8", "1e8", "1e-3"
#: without a dot or a sign after e. YAML 1.2 (and every user) reads them as floats.
_YAML12_FLOAT = re.compile(r"^[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)[eE][-+]?[0-9]+$")


def _strict_loader():
    """A SafeLoader that reads YAML 1.2 floats ("1.0e8") as floats and refuses duplicate keys."""
    import yaml

    base: type = getattr(yaml, "CSafeLoader", yaml.SafeLoader)  # libyaml parser where built

    class StrictLoader(base):  # a base chosen at run time
        """SafeLoader + YAML 1.2 floats + :class:`DuplicateKeyError` on a repeated mapping key."""

        def construct_mapping(self, node, deep=False):
            seen: dict = {}
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge" or not isinstance(key_node, yaml.ScalarNode):
                    continue
                key = (key_node.tag, key_node.value)
                line = key_node.start_mark.line + 1
                if key in seen:
                    raise DuplicateKeyError(key_node.value, line, seen[key])
                seen[key] = line
            return super().construct_mapping(node, deep)

    StrictLoader.add_implicit_resolver("tag:yaml.org,2002:float", _YAML12_FLOAT, list("-+0123456789."))
    return StrictLoader


class DuplicateKeyError(ValueError):
    """A key repeated in one YAML mapping (YAML itself would silently keep the last one)."""

    def __init__(self, key: str, line: int, first: int):
        super().__init__(f"duplicate key {key!r} at line {line} (first defined at line {first}): YAML "
                         "keeps only the last definition; rename or remove one")
        self.key, self.line, self.first = key, line, first


def load_yaml(path: str | Path):
    """A config file read with YAML 1.2 floats ("1.0e8" is the float 1e8), duplicate keys refused.

    Raises
    ------
    SceneError
        Naming the file, the duplicated key and both lines; or the file's YAML syntax error.
    """
    import yaml

    try:
        with open(path, encoding="utf-8") as fh:
            data = yaml.load(fh, Loader=_strict_loader())
    except DuplicateKeyError as exc:
        raise SceneError(f"config file {str(path)!r}: {exc}") from None
    except yaml.YAMLError as exc:
        raise SceneError(f"config file {str(path)!r} is not valid YAML: {' '.join(str(exc).split())}") from None
    except UnicodeDecodeError as exc:
        raise SceneError(f"config file {str(path)!r} is not a text file (byte {exc.object[exc.start]:#04x} at "
                         f"offset {exc.start} is not UTF-8): give a YAML file") from None
    except OSError as exc:
        raise SceneError(f"config file {str(path)!r} cannot be read: {exc.strerror or exc}") from None
    if data is not None and not isinstance(data, dict):
        what = "a list" if isinstance(data, list) else f"the single value {data!r}"[:80]
        raise SceneError(f"config file {str(path)!r} holds {what}, not a mapping: a config is a mapping with "
                         "the key 'scenes' (and optionally 'run')")
    return data


def config_sources(paths) -> dict[str, list[str]]:
    """Scene name -> the config files (each once, in the given order) that define it.

    Reads every file with :func:`load_yaml`, so a duplicate key in any of them is refused
    here (SceneError naming file, key and lines). Snakemake merges a scene defined in two
    files key by key (later files win); :func:`validate_config` uses this map to say so
    when such a merged scene has problems.
    """
    sources: dict[str, list[str]] = {}
    seen = set()
    for path in paths:
        real = Path(path).resolve()
        if real in seen:
            continue
        seen.add(real)
        data = load_yaml(path) or {}
        scenes = data.get("scenes") if isinstance(data, dict) else None
        for name in scenes if isinstance(scenes, dict) else ():
            sources.setdefault(str(name), []).append(str(path))
    return sources


def _resolve_floats(node):
    """Strings that are YAML 1.2 floats ("1.0e8") as floats, in place, in dicts and lists.

    Snakemake reads config files with PyYAML (YAML 1.1), which leaves 1.0e8 as text; the
    schema would then refuse it with a message about types. No key of the config takes text
    that looks like a number (scene names start with a letter), so this is safe.
    """
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for key, value in list(items):
        if isinstance(value, str) and _YAML12_FLOAT.match(value.strip()):
            node[key] = float(value)
        elif isinstance(value, (dict, list)):
            _resolve_floats(value)


def load_schema(path: str | Path | None = None) -> dict:
    """Read the JSON schema (YAML file) of the config, with the accuracy knobs' defaults and
    bounds filled in from the library (:func:`surfwave.pipeline.knobs.inject`)."""
    import yaml

    from surfwave.data.paper import SAFE_LOADER
    from surfwave.pipeline.knobs import inject

    with open(path or SCHEMA_PATH) as fh:
        return inject(yaml.load(fh, Loader=SAFE_LOADER))


def _validator_with_defaults(schema: dict):
    import jsonschema

    base = jsonschema.Draft202012Validator

    def set_defaults(validator, properties, instance, schema):
        if isinstance(instance, dict):
            for name, sub in properties.items():
                if isinstance(sub, dict) and "default" in sub:
                    instance.setdefault(name, copy.deepcopy(sub["default"]))
        yield from base.VALIDATORS["properties"](validator, properties, instance, schema)

    cls = jsonschema.validators.extend(base, {"properties": set_defaults})
    return cls(schema)


def schema_problems(config: dict, schema: dict | str | Path | None = None) -> list[str]:
    """Fill defaults into ``config`` (in place); one message per schema violation, in key order."""
    if not isinstance(schema, dict):
        schema = load_schema(schema)
    return list(dict.fromkeys(schema_message(e, schema) for e in _schema_errors(config, schema)))


def _schema_errors(config: dict, schema: dict) -> list:
    validator = _validator_with_defaults(schema)
    return sorted(validator.iter_errors(config), key=lambda e: list(map(str, e.absolute_path)))


def _check_scene(name: str, raw: dict) -> tuple[dict | None, list[str]]:
    """The expanded scene (None if it has problems) and every problem found."""
    where = f"scene {name!r}"
    problems: list[str] = []
    lattice, loading = raw["lattice"], raw["loading"]
    pots = []
    for pot in raw["potentials"]:
        try:
            get_potential(pot)
            pots.append(pot)
        except InputError as exc:
            problems.append(f"{where}, key 'potentials': value {pot!r}: {exc}")
    angles = None
    if isinstance(raw.get("directions"), dict) or (
            isinstance(raw.get("directions"), list)
            and all(isinstance(x, (int, float)) for x in raw["directions"])):
        angles, found = fcc_angles(where, raw)  # propagation angles in the (001) surface
        problems += found
        raw = {**raw, "directions": ["[100]"]}   # the base frame the angles turn from
    directions = list(raw.get("directions") or LATTICES[lattice]["directions"])
    good_dirs = []
    for direction in directions:
        try:
            check_combination(lattice, loading, direction)
            good_dirs.append(direction)
        except InputError as exc:
            key = "loading" if "loading" in str(exc) else "directions"
            problems.append(f"{where}, key {key!r}: {exc}")
    for q in raw["quantities"]:
        if q in TRIANGULAR_ONLY and lattice != "triangular":
            problems.append(
                f"{where}, key 'quantities': value {q!r} needs lattice 'triangular', not {lattice!r}"
            )
        if q in FCC_ONLY and lattice != "fcc":
            problems.append(f"{where}, key 'quantities': value {q!r} needs lattice 'fcc', not {lattice!r}")
    if "surface_phonons" in raw["quantities"]:
        problems += check_surfaces(where, raw, good_dirs)
    d = None
    try:
        d = expand_grid(raw["d_over_d0"], f"{where}, key 'd_over_d0'")
        check_d_over_d0(lattice, loading, d)
        if lattice == "fcc" and loading == "uniaxial":
            for pot in pots:  # the lateral solve must succeed for every point
                for direction in good_dirs:
                    build(lattice, loading, pot, direction, d)
    except SceneError as exc:
        problems.append(str(exc))
    except SurfwaveError as exc:
        problems.append(f"{where}, key 'd_over_d0': {exc}")
    try:
        theta = theta_grid(raw["theta"], f"{where}, key 'theta'")
    except SceneError as exc:
        problems.append(str(exc))
    if angles is not None and d is not None and not problems:
        try:  # every (potential, angle, d/d0) is a point of the elastic and rayleigh cubes
            check_points(where, {"potentials": len(pots), "angles": len(angles), "d/d0": len(d)})
        except SceneError as exc:
            problems.append(str(exc))
    if problems or d is None:
        return None, problems
    return {
        "name": name,
        "lattice": lattice,
        "loading": loading,
        "potentials": list(raw["potentials"]),
        "directions": directions,
        "d_over_d0": [float(x) for x in d],
        "theta": [float(x) for x in theta],
        "quantities": list(raw["quantities"]),
        "accuracy": copy.deepcopy(raw["accuracy"]),
        **({"angles": angles} if angles is not None else {}),
        **({"surfaces": list(raw.get("surfaces", DEFAULT_SURFACES))}
           if "surfaces" in raw or "surface_phonons" in raw["quantities"] else {}),
    }, []


def _scene_check(name: str, raw: dict, sources: dict[str, list[str]] | None) -> tuple[dict | None, list[str]]:
    """The physical checks and expansion of one schema-valid scene, by its kind."""
    check = check_crystal_scene if "materials" in raw else _check_scene  # real crystals name materials
    if is_piezo_scene(raw):  # cuts or Euler angles (surfwave.pipeline.piezo_scenes)
        where = _key_dir(name, "toec_file", sources) if "toec_file" in raw else None
        check = partial(check_piezo_scene, base_dir=where)
    if is_layered_scene(raw):  # films on a substrate (surfwave.pipeline.layered_scenes)
        check = check_layered_scene
    return check(name, raw)


def _key_dir(name: str, key: str, sources: dict[str, list[str]] | None) -> str | None:
    """Directory of the last config file whose scene ``name`` gives ``key`` (the one Snakemake's
    merge keeps), where a relative path in that key is read from; None if no file gives it."""
    for path in reversed((sources or {}).get(name, [])):
        data = load_yaml(path) or {}
        scene = (data.get("scenes") or {}).get(name) if isinstance(data, dict) else None
        if isinstance(scene, dict) and key in scene:
            return str(Path(path).resolve().parent)
    return None


def _redefined(name: str, files: list[str]) -> str:
    return (f"scene {name!r} is defined in {files[0]} and again in {', '.join(files[1:])}: scene {name!r} "
            f"redefines the scene of {files[0]} and Snakemake merges the two key by key (the later file "
            "wins), so the problems above may name keys you never wrote; to define a new scene, give it "
            "a name of its own")


def validate_config(config: dict, schema: dict | str | Path | None = None,
                    sources: dict[str, list[str]] | None = None) -> dict[str, dict]:
    """Validate the whole config (defaults filled in place) and expand every scene.

    Strings that are YAML 1.2 floats ("1.0e8", which PyYAML and so Snakemake read as text)
    are turned into floats first, in place. A scene defined in several config files
    (``sources``, from :func:`config_sources`) is the key-by-key merge Snakemake makes of
    them: redefining a default scene's name extends that scene; if the merge has problems,
    one more line says where they may come from.

    Returns
    -------
    dict
        Scene name -> expanded scene (JSON-able dict: d_over_d0 and theta as lists of
        floats, directions filled in).

    Raises
    ------
    SceneError
        Schema violations, unknown potentials, unsupported lattice/loading/direction
        combinations, impossible d/d0, malformed grids, unknown scene names in ``run``:
        every problem of the config at once, one line each.
    """
    if not isinstance(config, dict):
        raise SceneError(f"the config must be a mapping with the key 'scenes', got {type(config).__name__}")
    _resolve_floats(config)
    if not isinstance(schema, dict):
        schema = load_schema(schema)
    errors = _schema_errors(config, schema)
    problems = list(dict.fromkeys(schema_message(e, schema) for e in errors))
    raw_scenes: dict = config["scenes"] if isinstance(config.get("scenes"), dict) else {}
    sources = sources or {}
    broken = {str(e.absolute_path[1]) for e in errors
              if len(e.absolute_path) >= 2 and e.absolute_path[0] == "scenes"}
    for name in sorted(broken):
        if len(sources.get(name, [])) > 1:
            problems.append(_redefined(name, sources[name]))
    scenes: dict[str, dict] = {}
    for name, raw in raw_scenes.items():
        if not isinstance(raw, dict):
            continue
        named, unknown = name_problems(name, raw)  # unknown names, reported along with any schema problem
        if name in broken or named:
            # every problem at once: the physical checks of the rest of the scene (the keys and names
            # that passed), best effort, their problems added to those already found
            problems += named + rest_problems(name, raw, errors, unknown, partial(_scene_check, sources=sources))
            continue
        scene, found = _scene_check(name, raw, sources)
        problems += found
        if found and len(sources.get(name, [])) > 1:
            problems.append(_redefined(name, sources[name]))
        if scene is not None:
            scenes[name] = scene
    problems = list(dict.fromkeys(problems))
    run = config.get("run", [])
    for name in run if isinstance(run, list) else []:
        if name not in raw_scenes:
            problems.append(
                f"key 'run': value {name!r} is not a scene; known scenes: {sorted(raw_scenes)}"
            )
    if problems:
        raise SceneError(_join(problems))
    return scenes


def scene_notes(scenes: dict[str, dict]) -> list[str]:
    """Notes (not errors) on validated scenes, one line each: Euler angles that all look like radians.

    Examples
    --------
    >>> scene_notes({"s": {"kind": "piezo", "euler": {"phi": [0.0], "theta": [0.663], "psi": [0.0]}}})[0][:60]
    "note: all Euler angles of scene 's' lie within 2 pi and 0.66"
    """
    from surfwave.validate import radians_note

    notes = []
    for name, scene in scenes.items():
        euler = scene.get("euler") if scene.get("kind") == "piezo" else None
        if isinstance(euler, dict):
            note = radians_note([a for k in ("phi", "theta", "psi") for a in euler.get(k, [])],
                                f"Euler angles of scene {name!r}")
            if note:
                notes.append(note)
    return notes


def selected(config: dict, scenes: dict[str, dict]) -> list[str]:
    """Names of the scenes rule ``all`` builds: ``config['run']``, or every scene if empty."""
    return list(config.get("run") or scenes)


def targets(scenes: dict[str, dict], names, results: str = "results") -> list[str]:
    """The cube paths the named scenes ask for (crystal.nc always; one cube per quantity)."""
    out = []
    for name in names:
        if scenes[name].get("kind") not in ("crystal", "piezo", "layered"):  # real crystals: no model-lattice cell
            out.append(f"{results}/{name}/crystal.nc")
        out += [f"{results}/{name}/{CUBES[q]}" for q in scenes[name]["quantities"]]
    return out


_STAGE_KEYS = {
    "crystal": ("lattice", "loading", "potentials", "directions", "d_over_d0"),
    "elastic": ("lattice", "loading", "potentials", "directions", "d_over_d0"),
    "rayleigh": ("lattice", "loading", "potentials", "directions", "d_over_d0"),
    "bulk": ("lattice", "loading", "potentials", "directions", "d_over_d0"),
    "dispersion": ("lattice", "loading", "potentials", "directions", "d_over_d0", "theta"),
    "displacements": ("lattice", "loading", "potentials", "directions", "d_over_d0", "theta"),
    "entropy": ("lattice", "loading", "potentials", "directions", "d_over_d0"),
    "surface_wave": ("materials", "surfaces", "angles", "directions", "stress", "loading", "toec"),
    "surface_phonons": ("lattice", "loading", "potentials", "directions", "d_over_d0", "surfaces"),
}
_STAGE_ACCURACY = {"crystal": "symmetry", "bulk": "bulk", "dispersion": "dispersion",
                   "displacements": "displacements", "entropy": "entropy",
                   "surface_wave": "surface_wave", "surface_phonons": "surface_phonons"}


def job_params(scene: dict, stage: str) -> dict[str, Any]:
    """Everything a stage's job reads from the config, and nothing more (JSON-able).

    Passing exactly this through Snakemake ``params:`` makes a job rerun when, and only
    when, a value it uses changes.
    """
    if stage not in _STAGE_KEYS:
        raise InputError(f"unknown stage {stage!r}; known stages: {sorted(_STAGE_KEYS)}")
    params = {"scene": scene["name"], "stage": stage}
    params.update({k: copy.deepcopy(scene[k]) for k in _STAGE_KEYS[stage]})
    acc = _STAGE_ACCURACY.get(stage)
    params["accuracy"] = copy.deepcopy(scene["accuracy"].get(acc, {})) if acc else {}
    if scene.get("angles") is not None and stage in ("elastic", "rayleigh"):
        params["angles"] = list(scene["angles"])  # FCC propagation angles (degrees)
    return params


def load_config(paths=("config/config.yaml",)) -> dict:
    """Read and merge YAML config files the way Snakemake does (later files win, dicts merge).

    Each file is read by :func:`load_yaml` (YAML 1.2 floats, duplicate keys refused).
    """
    def merge(a, b):
        for k, v in b.items():
            if isinstance(v, dict) and isinstance(a.get(k), dict):
                merge(a[k], v)
            else:
                a[k] = v
        return a

    config: dict = {}
    for p in paths:
        merge(config, load_yaml(p) or {})
    return config
