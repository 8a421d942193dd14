"""Messages of the config checks: one line per problem, naming the scene, the key and the value.

:func:`schema_message` turns one ``jsonschema`` error into that line: for a key that takes
several shapes (``oneOf``: a list, a grid, a number) it reports the branch the value was meant
for, or, when the value has none of the shapes (``stress: "0.1"``, ``theta: null``), the shapes
it may take. A scene-level unknown or missing key also says which kind of scene the keys make
(model lattice, elastic real crystal, piezoelectric) and what that kind needs, with a
did-you-mean for a mistyped key. :func:`name_problems` checks a scene's names (materials, cuts,
potentials) and :func:`rest_problems` runs the physical checks on what is left of a scene that
already has problems, so one run reports every problem of a config.

Examples
--------
>>> suggest("electrcal", ["electrical", "stress", "materials"])
" (did you mean 'electrical'?)"
>>> scene_kind({"materials": ["LiNbO3"], "euler": {"theta": -52}})
'piezo_scene'
"""
from __future__ import annotations

import difflib
from collections.abc import Callable
from typing import Any

from surfwave.errors import InputError

#: Scene kinds: the schema's definition name -> (what it is called, how the config selects it,
#: what it needs). The selection mirrors the ``if``/``then`` of the schema's ``scenes`` key.
KINDS: dict[str, tuple[str, str, str]] = {
    "scene": ("model-lattice scene", "no 'materials' key",
              "lattice, loading, potentials, d_over_d0 and quantities"),
    "crystal_scene": ("elastic real-crystal scene", "'materials' without 'cuts' or 'euler'",
                      "materials and surfaces (and angles or directions)"),
    "piezo_scene": ("piezoelectric scene", "'materials' with 'cuts' or 'euler'",
                    "materials and either cuts or euler"),
    "layered_scene": ("layered scene", "'substrate'", "substrate, films and kh"),
}
#: JSON types as a user reads them.
_TYPE_WORDS = {"array": "a list", "object": "a mapping", "number": "a number", "integer": "an integer",
               "string": "text", "boolean": "true or false", "null": "null (empty)"}


def where(path) -> str:
    """"scene 'name', key 'a/b'" for a path into the config (or "key 'run'")."""
    parts = list(path)
    if len(parts) >= 2 and parts[0] == "scenes":
        key = "/".join(str(p) for p in parts[2:]) or "(scene)"
        return f"scene {parts[1]!r}, key {key!r}"
    return f"key {'/'.join(str(p) for p in parts) or '(top level)'!r}"


def brief(value: Any, limit: int = 60) -> str:
    """``repr(value)`` on one line, cut to ``limit`` characters."""
    text = " ".join(repr(value).split())
    return text if len(text) <= limit else text[:limit - 5] + " ...]"


def suggest(word: str, choices) -> str:
    """" (did you mean 'x'?)" for the closest of ``choices``, or ""."""
    close = difflib.get_close_matches(str(word), [str(c) for c in choices], n=1, cutoff=0.6)
    return f" (did you mean {close[0]!r}?)" if close else ""


def join(messages: list[str]) -> str:
    """One message, or "N problems in the config:" and one indented line per problem."""
    if len(messages) == 1:
        return messages[0]
    return f"{len(messages)} problems in the config:\n" + "\n".join(f"  - {m}" for m in messages)


def scene_kind(raw: Any) -> str:
    """The schema definition a scene is checked against (a key of :data:`KINDS`)."""
    if isinstance(raw, dict) and "substrate" in raw:
        return "layered_scene"
    if isinstance(raw, dict) and "materials" in raw:
        return "piezo_scene" if ("cuts" in raw or "euler" in raw) else "crystal_scene"
    return "scene"


def kind_keys(schema: dict | None) -> dict[str, list[str]]:
    """Kind -> the keys its schema definition allows (empty lists without a schema)."""
    defs = (schema or {}).get("$defs", {})
    return {k: sorted(defs.get(k, {}).get("properties", {})) for k in KINDS}


def _what_it_needs(kind: str) -> str:
    name, selected_by, needs = KINDS[kind]
    others = "; ".join(f"{_a(n)} ({s}) needs {w}" for k, (n, s, w) in KINDS.items() if k != kind)
    return f"read as {_a(name)} ({selected_by}), which needs {needs}; {others}"


def _a(noun: str) -> str:
    return ("an " if noun[0] in "aeiou" else "a ") + noun


def _unknown_keys(err, path: list, schema: dict | None) -> str:
    props = err.schema.get("properties", {}) if isinstance(err.schema, dict) else {}
    extra = sorted(str(k) for k in err.instance if k not in props)
    scene_level = len(path) == 2 and path[0] == "scenes"
    kind = scene_kind(err.instance) if scene_level else ""
    others = {k: keys for k, keys in kind_keys(schema).items() if k != kind} if scene_level else {}
    notes = []
    for key in extra:
        note = suggest(key, props)
        owners = [k for k, keys in others.items() if key in keys]
        owners = [k for k in owners if k != "layered_scene"] if len(owners) > 1 else owners  # shared keys
        if owners:
            note = " (a key of " + " and ".join(f"{KINDS[k][0]}s, which have {KINDS[k][1]}" for k in owners) + ")"
        elif not note:
            for k, keys in others.items():
                close = difflib.get_close_matches(key, keys, n=1, cutoff=0.6)
                if close:
                    note = f" (did you mean {close[0]!r}, a key of {KINDS[k][0]}s?)"
                    break
        notes.append(f"{key!r}{note}")
    msg = (f"config error in {where(path + extra[:1])}: unknown key{'s' if len(extra) > 1 else ''} "
           f"{', '.join(notes)}")
    if scene_level:
        return msg + f"; the scene is read as {_a(KINDS[kind][0])} ({KINDS[kind][1]}), keys: {', '.join(props)}"
    return msg + f" (allowed keys: {sorted(props)})"


def _missing_keys(err, path: list) -> str:
    props = err.schema.get("properties", {}) if isinstance(err.schema, dict) else {}
    missing = [k for k in err.validator_value if k not in err.instance] or ["?"]
    msg = (f"config error in {where(path + missing[:1])}: required key{'s' if len(missing) > 1 else ''} "
           f"{', '.join(repr(k) for k in missing)} {'are' if len(missing) > 1 else 'is'} missing")
    if len(path) == 2 and path[0] == "scenes":
        return msg + f": the scene is {_what_it_needs(scene_kind(err.instance))}"
    what = props.get(missing[0], {}).get("description", "") if isinstance(props.get(missing[0]), dict) else ""
    return msg + (f"; expected: {what}" if what else "")


def _shapes(err) -> list[str]:
    """What each branch of a failed ``oneOf`` accepts, in words ("a list", "'symmetric'")."""
    shapes: list[str] = []
    for branch in err.validator_value:
        if not isinstance(branch, dict):
            continue
        if "const" in branch:
            shapes.append(repr(branch["const"]))
        elif "$ref" in branch:
            shapes.append("a grid {start, stop, step}" if branch["$ref"].endswith("/grid") else "a mapping")
        else:
            kinds = branch.get("type", "value")
            for t in kinds if isinstance(kinds, list) else [kinds]:
                word = _TYPE_WORDS.get(t, str(t))
                if t == "array" and isinstance(branch.get("items"), dict):
                    item = branch["items"]
                    inner = (" of " + " or ".join(repr(v) for v in item["enum"]) if "enum" in item else
                             f" of {_TYPE_WORDS.get(item.get('type'), 'values')}s" if "type" in item else "")
                    word += inner.replace("a numbers", "numbers").replace("an integers", "integers")
                if t == "object" and branch.get("required"):
                    word += " {" + ", ".join(branch["required"]) + ", ...}"
                shapes.append(word)
    return list(dict.fromkeys(shapes))


def _type_word(value: Any) -> str:
    if value is None:
        return "null (an empty value)"
    if isinstance(value, bool):
        return "true/false"
    if isinstance(value, str):
        return "text"
    if isinstance(value, (int, float)):
        return "a number"
    return "a list" if isinstance(value, list) else "a mapping" if isinstance(value, dict) else type(value).__name__


def _text_hint(value: Any) -> str:
    """A hint for a number written as text ("0.1" in quotes, or 1.0e8 read by YAML 1.1)."""
    if not isinstance(value, str):
        return ""
    try:
        number = float(value)
    except ValueError:
        return ""
    if "e" in value.lower() and "." not in value:
        return f"; YAML reads {value} as text: write it with a decimal point, e.g. {number:.1e}"
    return f"; {value!r} is text: write the number without quotes"


def branch_error(err):
    """The error to report for a failed ``oneOf``, or None if the value fits none of its shapes.

    A branch whose errors all lie inside the value (a key of the right kind of object, an
    item of a list) matched the value's shape: its deepest error (``{symmetric: true,
    step: 0}`` -> the step, not "'symmetric' was expected"). None when every branch refuses
    the value itself by its type or its constant (then no branch's error is the user's
    problem: the shape is). Else the shallowest error that is not a type mismatch.
    """
    depth = len(err.absolute_path)
    branches: dict = {}
    for e in err.context:
        branches.setdefault(e.relative_schema_path[0] if e.relative_schema_path else 0, []).append(e)
    inside = [errs for errs in branches.values() if all(len(e.absolute_path) > depth for e in errs)]
    if inside:
        errs = min(inside, key=len)
        return max(errs, key=lambda e: len(e.absolute_path))
    if all(len(e.absolute_path) == depth and e.validator in ("type", "const", "enum") for e in err.context):
        return None  # the value itself has none of the shapes ('sym', null): say which shapes there are
    for skip in (("type", "const", "enum"), ("type",)):
        deeper = [e for e in err.context if e.validator not in skip]
        if deeper:
            return min(deeper, key=lambda e: len(e.absolute_path))
    return None


def schema_message(err, schema: dict | None = None) -> str:
    """One line naming the scene, the key and the offending value of a schema error.

    Parameters
    ----------
    err : jsonschema.ValidationError
    schema : dict, optional
        The whole config schema: scene-level messages then name the kinds of scene whose keys
        a mistyped or misplaced key belongs to.
    """
    for _ in range(32):  # descend through nested oneOf; each step goes strictly deeper
        if err.validator != "oneOf" or not err.context:
            break
        inner = branch_error(err)
        if inner is None or inner is err:
            path = list(err.absolute_path)
            hint = err.schema.get("description", "") if isinstance(err.schema, dict) else ""
            return (f"config error in {where(path)}: value {brief(err.instance)} is {_type_word(err.instance)}, "
                    f"which is none of the accepted forms ({', '.join(_shapes(err))})"
                    + _text_hint(err.instance) + (f"; expected: {hint}" if hint else ""))
        err = inner
    path = list(err.absolute_path)
    if err.validator == "additionalProperties" and isinstance(err.instance, dict):
        return _unknown_keys(err, path, schema)
    if err.validator == "required" and isinstance(err.instance, dict):
        return _missing_keys(err, path)
    hint = err.schema.get("description", "") if isinstance(err.schema, dict) else ""
    said = " ".join(err.message.split())[:200]
    msg = f"config error in {where(path)}: value {brief(err.instance)} is invalid ({said})"
    if err.validator == "type":
        msg += _text_hint(err.instance)
    return msg + (f"; expected: {hint}" if hint else "")


def rest_problems(name: str, raw: dict, errors: list, unknown: dict[str, set],
                  check: Callable[[str, dict], tuple[Any, list[str]]]) -> list[str]:
    """Problems of the physical checks of a scene that already has problems, on what is left of it.

    The keys with schema errors (and unknown keys) are dropped, the unknown names removed from
    their lists; if the scene keeps its kind and every key that kind requires, the checks run on
    the rest and their problems are returned (so a mistyped key and a stress in Pa come in one
    run). Best effort: a check that fails otherwise on a scene already known to be broken adds
    nothing. ``check(name, scene)`` returns (expanded scene or None, problems).
    """
    drop: set = set()
    for e in errors:
        path = list(e.absolute_path)
        if len(path) < 2 or path[0] != "scenes" or str(path[1]) != name:
            continue
        if len(path) == 2:
            if e.validator != "additionalProperties" or not isinstance(e.instance, dict):
                return []  # a missing required key, or the scene is not a mapping: nothing to check
            props = e.schema.get("properties", {}) if isinstance(e.schema, dict) else {}
            drop.update(k for k in e.instance if k not in props)
        else:
            drop.add(path[2])
    rest = {k: v for k, v in raw.items() if k not in drop}
    for key, names in unknown.items():
        if isinstance(rest.get(key), list):
            rest[key] = [v for v in rest[key] if v not in names]
            if not rest[key]:
                return []
    required = {"scene": ("lattice", "loading", "potentials", "d_over_d0", "quantities", "theta", "accuracy"),
                "crystal_scene": ("materials", "surfaces", "loading", "toec", "quantities", "accuracy"),
                "piezo_scene": ("materials",), "layered_scene": ("substrate", "films", "kh")}
    kind = scene_kind(rest)
    if kind != scene_kind(raw) or any(k not in rest for k in required[kind]):
        return []
    try:
        return check(name, rest)[1]
    except Exception:  # noqa: BLE001 (best effort on a scene whose problems are already reported)
        return []


def name_problems(name: str, raw: dict) -> tuple[list[str], dict[str, set]]:
    """Unknown names in a scene's lists of materials, cuts or potentials (did-you-mean included).

    Checked even when the scene has schema problems, so that one run reports every problem
    (a mistyped key no longer hides a mistyped material). A material of the piezoelectric
    database in an elastic real-crystal scene is told what makes a scene piezoelectric.
    """
    from surfwave.model_crystals.potentials import get_potential
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.piezo_materials import get_cut, get_piezo_material

    kind = scene_kind(raw)
    unknown: dict[str, set] = {}
    lookups: dict[str, dict[str, Callable[[str], object]]] = {
        "scene": {"potentials": get_potential}, "crystal_scene": {"materials": get_material},
        "piezo_scene": {"materials": get_piezo_material, "cuts": get_cut}, "layered_scene": {}}
    keys = lookups[kind]
    problems = []
    for key, lookup in keys.items():
        values = raw.get(key)
        for value in values if isinstance(values, list) else ():
            if not isinstance(value, str):
                continue  # the schema reports it
            try:
                lookup(value)
            except InputError as exc:
                note = str(exc)
                if kind == "crystal_scene":
                    try:
                        get_piezo_material(value)
                        note = ("it is a crystal of the piezoelectric database: a piezoelectric scene gives "
                                "'cuts' or 'euler' (Euler angles) with its materials")
                    except InputError:
                        pass
                problems.append(f"scene {name!r}, key {key!r}: value {value!r}: {note}")
                unknown.setdefault(key, set()).add(value)
    return problems, unknown
