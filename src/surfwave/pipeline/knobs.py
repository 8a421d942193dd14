"""Accuracy knobs of the workflow: one place for each default and each limit.

The config schema (``workflow/schemas/config.schema.yaml``) lists the knobs with their
types and meaning only; :func:`inject` writes the defaults and bounds below into it when
it is loaded (:func:`surfwave.pipeline.scenes.load_schema`). The defaults are the library
functions' own defaults (``surfwave.model_crystals.phonons.DEFAULT_*``, the ``tol`` keyword
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
from typing import Iterable, cast

from surfwave.model_crystals import phonons


def _keyword_default(func, name):
    return inspect.signature(func).parameters[name].default


@dataclass(frozen=True)
class Knob:
    """One accuracy setting: default, inclusive bounds (None = unbounded), and why."""

    default: object
    minimum: float | None = None
    maximum: float | None = None
    why: str = ""
    #: this knob's share of the seconds per point at the default (2-core machine) ...
    cost_seconds: float = 0.0
    #: ... scaled by (value / default) ** cost_power
    cost_power: float = 0.0


def _table() -> dict[str, dict[str, Knob]]:
    from surfwave.dynamics import entropy, fcc_surface_entropy, fcc_surface_phonons, triangular_surface

    return {
        "symmetry": {
            "symprec": Knob(1.0e-5, 1.0e-10, 1.0e-1,
                            "spglib tolerance in d0: below 1e-10 rounding of the positions "
                            "breaks symmetries, above 0.1 distinct structures merge"),
        },
        "bulk": {
            "supercell": Knob(phonons.DEFAULT_SUPERCELL, 2, 8,
                              "N of the N x N x N supercell: 2 is the smallest in which "
                              "nearest-neighbour images are unambiguous; cost grows as N^4",
                              cost_seconds=0.015, cost_power=4.0),
            "displacement": Knob(phonons.DEFAULT_DISPLACEMENT, 1.0e-6, 1.0e-2,
                                 "finite-displacement amplitude in d0: the error grows as "
                                 "amplitude^2 (1e-4 relative at 1e-2) and roundoff as "
                                 "1e-16/amplitude (1e-10 at 1e-6)"),
            "zone_mesh": Knob(phonons.DEFAULT_ZONE_MESH, 2, 200,
                              "q points per axis of the full-zone stability scan; cost "
                              "grows as mesh^3", cost_seconds=0.0022, cost_power=3.0),
            "long_wave": Knob(phonons.DEFAULT_LONG_WAVE),
        },
        "dispersion": {
            "tol": Knob(_keyword_default(triangular_surface.surface_mode, "tol"), 1.0e-14, 1.0e-2,
                        "coupling left to the rows beyond the decimation depth, relative to the "
                        "row coupling: the error of omega_lattice against Eq. (15) stops "
                        "improving (about 5e-9) below tol = 1e-8 (benchmarks/bench_dispersion.py); "
                        "below 1e-14 only the time grows"),
            "check_points": Knob(triangular_surface.DEFAULT_CHECK_POINTS, 1, None,
                                 "strains per 0.2 of d/d0 checked by the numerical lattice-dynamics "
                                 "solve (those nearest to the lattice d/d0 = 1 + j 0.2/check_points, "
                                 "so extending a grid keeps its checks), about 1 s each at "
                                 "512 theta; the others are NaN in omega_lattice ('not checked "
                                 "(sample)'); the analytic omega is computed at every strain"),
        },
        "displacements": {
            "n_rows": Knob(None, 1, 10_000, "rows below the surface"),
        },
        "entropy": {
            "tol": Knob(_keyword_default(entropy.surface_entropy, "tol"), 1.0e-10, 1.0e-2,
                        "absolute quadrature error in k_B: rounding limits the error "
                        "estimate to a few 1e-12, so a tolerance below 1e-10 cannot be met"),
        },
        "surface_phonons": {
            "path_density": Knob(fcc_surface_phonons.DEFAULT_PATH_DENSITY, 0.5, 200.0,
                                 "q points per rad/d0 along the path of high-symmetry points: each "
                                 "point costs ~3 ms per strain (benchmarks/bench_surface_phonons.py)"),
            "n_omega": Knob(200, 10, 4000, "frequencies of the spectral density; cost and cube size "
                                           "grow linearly"),
            "omega_max": Knob(3.5, 0.1, 100.0, "top of the spectral-density grid, sqrt(K/m) (the bulk "
                                               "band ends at 2 sqrt 2 = 2.83 at zero stress)"),
            "eta": Knob(1.0e-2, 1.0e-8, 1.0, "broadening of the spectral density in omega^2 (K/m): below "
                                              "the grid spacing squared the peaks are missed between points"),
            "entropy_grid": Knob(fcc_surface_entropy.N_GRID, 8, 512,
                                 "reduced-q grid (n x n, with n/2 and n/4 for Richardson) of the exact "
                                 "surface entropy: error ~1e-5 k_B at 64, cost ~ n^2"),
        },
        # real-crystal scenes ($defs/crystal_scene)
        "surface_wave": {
            "tol": Knob(None, 1.0e-14, 1.0e-6,
                        "relative accuracy of rho c^2 asked of the Stroh root search "
                        "(surfwave.solvers.stroh.surface_wave, default 1e-12): the range "
                        "benchmarks/bench_stroh.py measures; below 1e-14 rounding stops the "
                        "search (genuine surface waves come out as 'pseudo' NaN at 1e-30), "
                        "above 1e-6 c_R moves by more than the figures show (1 % at 0.5)"),
        },
    }


#: Accuracy blocks of real-crystal scenes ($defs/crystal_scene); the others are model scenes'.
CRYSTAL_BLOCKS = ("surface_wave",)


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
    blocks = dict(out["$defs"]["scene"]["properties"]["accuracy"]["properties"])
    crystal = out["$defs"].get("crystal_scene", {}).get("properties", {}).get("accuracy", {})
    blocks.update(crystal.get("properties", {}))
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
    """Rough seconds per point for ``settings``.

    Knobs with a cost model (:attr:`Knob.cost_seconds`, :attr:`Knob.cost_power`) add their
    own terms, cost_seconds * (value / default) ** cost_power (phonopy: force constants
    ~ N^4 in the supercell size, zone scan ~ mesh^3; measured on the 2-core machine,
    supercell 2..4 and zone_mesh 8..64); a method without such knobs costs
    ``seconds_at_default``.
    """
    terms = []
    for name, knob in knobs().get(block, {}).items():
        if knob.cost_power:
            value = settings.get(name, knob.default)
            terms.append(knob.cost_seconds * (float(value) / float(cast(float, knob.default))) ** knob.cost_power)
    return sum(terms) if terms else seconds_at_default


#: Seconds per point at the default accuracy, measured on the 2-core development machine
#: (README, "Speed and accuracy"; upper ends of the measured ranges): phonopy bulk speeds
#: and zone scan per strain point; the surface-mode solve per strain and theta; the
#: entropy quadratures per strain.
SECONDS_PER_POINT = {"bulk": 0.017, "dispersion": 0.7 / (8 * 40), "entropy": 0.008}
#: Jobs expected to run longer than this get a line before the run starts.
ANNOUNCE_SECONDS = 10.0


def expected_cost(scenes: dict, names: Iterable[str], announce: float = ANNOUNCE_SECONDS) -> list[str]:
    """Lines stating the expected time of each costly stage of the named scenes (before any job).

    Parameters
    ----------
    scenes : dict
        Expanded scenes (:func:`surfwave.pipeline.scenes.validate_config`).
    names : iterable of str
        Scenes the run builds.
    announce : float
        Only stages expected to take longer than this many seconds are listed.
    """
    lines = []
    for name in names:
        sc = scenes[name]
        if sc.get("kind") in ("crystal", "piezo", "layered"):  # real crystals, stacks: ~1 s per thousand points
            continue
        n_pot, n_d = len(sc["potentials"]), len(sc["d_over_d0"])
        for stage in ("bulk", "dispersion", "entropy"):
            if stage not in sc["quantities"]:
                continue
            if stage == "dispersion":  # the lattice-dynamics check runs on a sample of the strains
                from surfwave.dynamics.triangular_surface import check_sample

                checks = sc["accuracy"].get(stage, {}).get("check_points", _table()[stage]["check_points"].default)
                points = n_pot * check_sample(sc["d_over_d0"], checks).size
            else:
                points = n_pot * n_d * (len(sc["directions"]) if stage == "bulk" else 1)
            per = SECONDS_PER_POINT[stage] * (len(sc["theta"]) if stage == "dispersion" else 1)
            seconds = points * estimated_cost(stage, sc["accuracy"].get(stage, {}), per)
            if seconds > announce:
                settings = ", ".join(f"{k} {v}" for k, v in sc["accuracy"].get(stage, {}).items())
                lines.append(f"surfwave: {stage}, scene {name}: {points} points at {settings or 'defaults'}, "
                             f"expected about {seconds:.0f} s ({seconds / 60:.1f} min) before the "
                             "cache; progress in results/" + f"{name}/logs/")
    return lines
