"""Accuracy knobs of the workflow: one place for each default and each limit.

The config schema (``workflow/schemas/config.schema.yaml``) lists the knobs with their
types and meaning only; :func:`inject` writes the defaults and bounds below into it when
it is loaded (:func:`surfwave.pipeline.scenes.load_schema`). The defaults are the library
functions' own defaults (``surfwave.continuum.phonons.DEFAULT_*``, the ``tol`` keyword
defaults of the surface-mode and entropy solvers), so the workflow, the schema and a
direct library call cannot disagree. The library is the source rather than the schema
because the library is used without the workflow (``surfwave.point``, the benchmarks),
and must stand on its own.

Each bound says why: what the method can do (an attainable error floor, a finite
difference that stays in the harmonic regime) or what it can afford.
"""
from __future__ import annotations

import copy
import inspect
from dataclasses import dataclass

from surfwave.continuum import phonons


def _keyword_default(func, name):
    return inspect.signature(func).parameters[name].default


@dataclass(frozen=True)
class Knob:
    """One accuracy setting: default, inclusive bounds (None = unbounded), and why."""

    default: object
    minimum: float | None = None
    maximum: float | None = None
    why: str = ""
    #: seconds per point at the default, times (value / default) ** cost_power
    cost_power: float = 0.0


def _table() -> dict[str, dict[str, Knob]]:
    from surfwave.dynamics import entropy, triangular_surface

    return {
        "symmetry": {
            "symprec": Knob(1.0e-5, 1.0e-10, 1.0e-1,
                            "spglib tolerance in d0: below 1e-10 rounding of the positions "
                            "breaks symmetries, above 0.1 distinct structures merge"),
        },
        "bulk": {
            "supercell": Knob(phonons.DEFAULT_SUPERCELL, 2, 8,
                              "N of the N x N x N supercell: 2 is the smallest in which "
                              "nearest-neighbour images are unambiguous; cost grows as N^6",
                              cost_power=6.0),
            "displacement": Knob(phonons.DEFAULT_DISPLACEMENT, 1.0e-6, 1.0e-2,
                                 "finite-displacement amplitude in d0: the error grows as "
                                 "amplitude^2 (1e-4 relative at 1e-2) and roundoff as "
                                 "1e-16/amplitude (1e-10 at 1e-6)"),
            "zone_mesh": Knob(phonons.DEFAULT_ZONE_MESH, 2, 200,
                              "q points per axis of the full-zone stability scan; cost "
                              "grows as mesh^3", cost_power=3.0),
            "long_wave": Knob(phonons.DEFAULT_LONG_WAVE),
        },
        "dispersion": {
            "tol": Knob(_keyword_default(triangular_surface.surface_mode, "tol"), 1.0e-13, 1.0e-2,
                        "relative decimation tolerance: rounding limits the surface-mode "
                        "error estimate to about 3e-14, so a tolerance below 1e-13 cannot be met"),
        },
        "displacements": {
            "n_rows": Knob(None, 1, 10_000, "rows below the surface"),
        },
        "entropy": {
            "tol": Knob(_keyword_default(entropy.surface_entropy, "tol"), 1.0e-10, 1.0e-2,
                        "absolute quadrature error in k_B: rounding limits the error "
                        "estimate to a few 1e-12, so a tolerance below 1e-10 cannot be met"),
        },
    }


_CACHE: dict = {}


def knobs() -> dict[str, dict[str, Knob]]:
    """Method block -> knob name -> :class:`Knob` (built once)."""
    if not _CACHE:
        _CACHE.update(_table())
    return _CACHE


def inject(schema: dict) -> dict:
    """A copy of the config schema with every knob's default, bounds and reason filled in.

    Raises
    ------
    KeyError
        A knob of :func:`knobs` missing from the schema, or a schema knob without an entry
        here (the two lists must match).
    """
    out = copy.deepcopy(schema)
    blocks = out["$defs"]["scene"]["properties"]["accuracy"]["properties"]
    table = knobs()
    if set(blocks) != set(table):
        raise KeyError(f"schema accuracy blocks {sorted(blocks)} differ from the library's {sorted(table)}")
    for block, entries in table.items():
        props = blocks[block]["properties"]
        if set(props) != set(entries):
            raise KeyError(f"schema knobs of {block!r} {sorted(props)} differ from the library's {sorted(entries)}")
        for name, knob in entries.items():
            spec = props[name]
            spec["default"] = knob.default
            if knob.minimum is not None:
                spec["minimum"] = knob.minimum
            if knob.maximum is not None:
                spec["maximum"] = knob.maximum
            if knob.why:
                spec["description"] = (spec.get("description", "") + " " + knob.why).strip()
    return out


def estimated_cost(block: str, settings: dict, seconds_at_default: float) -> float:
    """Rough seconds per point for ``settings``: the default's cost scaled by each knob's power law."""
    factor = 1.0
    for name, knob in knobs().get(block, {}).items():
        value = settings.get(name, knob.default)
        if knob.cost_power and isinstance(value, (int, float)) and knob.default:
            factor *= (float(value) / float(knob.default)) ** knob.cost_power
    return seconds_at_default * factor
