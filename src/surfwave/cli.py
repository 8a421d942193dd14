"""Command-line interface: ``surfwave point|material|potentials|scenes|cache info|cache clear|layered|fit-film``.

Run ``surfwave --help`` or ``surfwave <command> --help`` (also ``python -m surfwave``).
Mistyped commands, choices and options get a "did you mean" suggestion.
"""
from __future__ import annotations

import argparse
import difflib
import json
import os
import re
import sys
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np

from surfwave import __version__, cli_fit, cli_layered, cli_material, cli_piezo
from surfwave.errors import SurfwaveError
from surfwave.vocab import DIRECTIONS, LATTICES, LOADINGS

SPEED_KEYS = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH", "c2_R")

EPILOG_POINT = """\
Reduced units: nearest-neighbour distance d0 = 1, mass m = 1, spring constant K = phi''(d0) = 1.
Speeds squared are in K d0^2/m; stress is sigma0_xx V/(K d0^2). Lab frame: x = propagation,
y = surface normal (into the crystal), z = in-plane normal to x.

examples:
  surfwave point --lattice fcc --loading in_plane_hydrostatic --potential lj --direction "[110]" --d-over-d0 1.02
  surfwave point --lattice triangular --loading uniaxial --potential harmonic --direction "[10]" --d-over-d0 0.9 1.0 1.1 --json
"""  # noqa: E501 (commands to copy, printed by --help)

EPILOG_MATERIAL = """\
The crystal: a name from the materials database (--material Cu; 'surfwave material --list'),
cubic constants --C11 --C12 --C44, or a full 6x6 Voigt stiffness (GPa, crystal axes), with
--rho (kg/m^3; a named material brings its own). Propagation: a Miller direction in the
surface, or --angle in degrees from the surface's reference direction ((001): [100];
(110): [001]; (111): [1-10]) toward n x reference. Prestress: --stress S (uniaxial along
the propagation) or nine values (the Cauchy tensor in crystal axes, row by row; it must lie
in the surface plane); a list of other length (-0.1 0 0.1) or START:STOP:STEP is a sweep of
uniaxial stresses, printed as a table (one orientation). Below v_L (the lowest bulk trace
velocity) the surface wave is found by the Stroh/impedance solver, at mirror directions by
Eq. (17).

Two models of the stressed crystal:
  fixed constants (default): the given constants are those of the stressed crystal; the
    stress enters only through the wave-propagation tensor A = C + sigma delta.
  --toec (third-order constants; --toec alone takes them from the database, or give six
    values C111 C112 C123 C144 C155 C456 in GPa): Brugger constants (Lagrangian strain,
    energy per unit natural volume, the sign convention of the tables); the given second-
    and third-order constants are those of the UNSTRESSED crystal; the crystal deforms
    (F) under the stress, the wave travels along F m0 (m0 the given direction) on the
    surface of normal F^-T n0, and speeds are true phase speeds in the stressed state.
  --toec-file FILE: the same model with your constants from a YAML mapping (name: GPa), the
    crystal class's names (quartz or LiNbO3: the 14 from C111 to C444; cubic: the six); needed
    for piezoelectric crystals other than GaAs, whose measured sets the database lacks.

examples:
  surfwave material --material Cu --direction "[100]"                    # 2012.12 m/s
  surfwave material --material Cu --direction "[100]" --stress 0.1 --toec
  surfwave material --C11 168.4 --C12 121.4 --C44 75.4 --rho 8960 --surface "(111)" --direction "[1-10]"
  surfwave material --material Si --surface "(110)" --angle 0:90:15
  surfwave material --material Cu --direction "[100]" --stress -0.2:0.2:0.1 --toec
"""


class _Parser(argparse.ArgumentParser):
    """argparse with "did you mean" for mistyped commands, choices and options."""

    def error(self, message):  # noqa: D102 (argparse API)
        hint = _suggestion(self, message)
        super().error(message + (f"; did you mean {hint}?" if hint else ""))


def _suggestion(parser: argparse.ArgumentParser, message: str) -> str | None:
    m = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
    if m:
        choices = re.findall(r"'?([^',\s][^',]*)'?", m.group(2))
        close = difflib.get_close_matches(m.group(1), [c.strip() for c in choices], n=1, cutoff=0.5)
        return repr(close[0]) if close else None
    m = re.search(r"unrecognized arguments: (.*)", message)
    if m:
        options = _all_options(parser)
        for word in m.group(1).split():
            if word.startswith("-"):
                close = difflib.get_close_matches(word.split("=")[0], options, n=1, cutoff=0.6)
                if close:
                    return repr(close[0])
    return None


def _all_options(parser: argparse.ArgumentParser) -> list[str]:
    """Every option string of ``parser`` and of its subcommands (recursively)."""
    options = [o for a in parser._actions for o in a.option_strings]
    for sub in (a for a in parser._actions if isinstance(a, argparse._SubParsersAction)):
        for sp in sub.choices.values():
            options += _all_options(sp)
    return options


def _check_options(parser: argparse.ArgumentParser, argv: list[str]) -> None:
    """Refuse an unknown ``--option`` first (argparse would first complain about the
    required options it hides), so that the error can suggest the intended one."""
    known = set(_all_options(parser))
    for word in argv:
        if word.startswith("--") and word.split("=")[0] not in known:
            parser.error(f"unrecognized arguments: {word}")


def _parser() -> argparse.ArgumentParser:
    p = _Parser(
        prog="surfwave",
        description="Rayleigh (surface acoustic) waves in prestressed crystals.",
        epilog="Reproduce the paper: 'make reproduce' (snakemake -j2). Docs: README.md.",
    )
    p.add_argument("--version", action="version", version=f"surfwave {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND", required=True)

    pt = sub.add_parser(
        "point", help="bulk sound speeds, stability and Rayleigh speed of a prestressed model crystal",
        description="Bulk sound speeds, long-wave stability and the Rayleigh speed of a "
        "prestressed nearest-neighbour crystal at one or more strains.",
        epilog=EPILOG_POINT, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    pt.add_argument("--lattice", required=True, choices=list(LATTICES))
    pt.add_argument("--loading", required=True, choices=list(LOADINGS),
                    help="uniaxial stress along the propagation direction, or in-plane hydrostatic (fcc)")
    pt.add_argument("--potential", required=True,
                    help="pair potential: harmonic, lj or any registered one (see 'surfwave potentials')")
    pt.add_argument("--direction", required=True, choices=list(DIRECTIONS),
                    help="propagation direction; '[10]' = close-packed rows of the triangular lattice")
    pt.add_argument("--d-over-d0", required=True, type=float, nargs="+", metavar="D",
                    help="stretch along the propagation direction, 1 = unstressed (one or more values)")
    pt.add_argument("--json", action="store_true", help="print JSON instead of a table")

    mt = sub.add_parser(
        "material", help="surface-wave and bulk speeds (m/s) of a real crystal, any surface and direction",
        description="Surface (Rayleigh) wave, limiting speed and bulk sound speeds of a real crystal "
        "on any surface, in any direction, under prestress.",
        epilog=EPILOG_MATERIAL + "\n" + cli_piezo.EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    mt.add_argument("--material", help="a crystal of the materials database by name (Cu, Si, GaAs, ...)")
    mt.add_argument("--list", action="store_true",
                    help="list every crystal of the elastic and piezoelectric databases, with aliases, and exit")
    mt.add_argument("--C11", type=float, help="cubic elastic constant C11, GPa")
    mt.add_argument("--C12", type=float, help="cubic elastic constant C12, GPa")
    mt.add_argument("--C44", type=float, help="cubic elastic constant C44, GPa")
    mt.add_argument("--voigt", type=float, nargs=36, metavar="C",
                    help="full 6x6 Voigt stiffness (36 values, row by row), GPa, crystal axes (instead of C11 C12 C44)")
    mt.add_argument("--rho", type=float, help="density, kg/m^3 (a named material brings its own)")
    mt.add_argument("--surface", help='surface plane "(hkl)" (default "(001)"; not with --euler or --cut)')
    where = mt.add_mutually_exclusive_group()
    where.add_argument("--direction", help='propagation direction "[uvw]" in the surface (default: the reference)')
    where.add_argument("--angle", help="angle in degrees from the reference direction, or a sweep START:STOP:STEP "
                       "(STOP included) printed as a table")
    mt.add_argument("--stress", nargs="+", default=["0"], metavar="S",
                    help="prestress, GPa (negative = compression): one value (uniaxial along the propagation), "
                    "nine (Cauchy tensor in crystal axes, row by row), or a sweep of uniaxial stresses printed as "
                    "a table: a list of values (-0.1 0 0.1) or START:STOP:STEP (STOP included)")
    mt.add_argument("--toec", type=float, nargs="*", metavar="C",
                    help="third-order model: no value = the database's constants of --material; or "
                    "six values C111 C112 C123 C144 C155 C456, GPa (Brugger)")
    mt.add_argument("--toec-file", metavar="YAML",
                    help="third-order model with your constants: a YAML mapping name: value in GPa (Brugger), "
                    "the crystal class's names (quartz, LiNbO3: C111 C112 C113 C114 C123 C124 C133 C134 C144 "
                    "C155 C222 C333 C344 C444; cubic: C111 C112 C123 C144 C155 C456); a 'source' key is allowed")
    mt.add_argument("--json", action="store_true", help="print JSON instead of a table")
    cli_piezo.add_options(mt)

    sub.add_parser(
        "potentials", help="list the registered pair potentials (names usable in scenes and 'point')",
        description="List the registered pair potentials: the names accepted by 'surfwave point "
        "--potential' and by a scene's 'potentials' key, with their form and parameters. New "
        "potentials join surfwave.model_crystals.potentials.register(...).")

    sc = sub.add_parser(
        "scenes", help="list the configured scenes and what each computes",
        description="List the scenes of the workflow's config (config/config.yaml, plus any "
        "--configfile, merged as Snakemake does): lattice, loading, potentials, grid, quantities.")
    sc.add_argument("--configfile", nargs="+", type=Path, default=[],
                    help="extra config files merged over the default config, as for snakemake")
    sc.add_argument("--json", action="store_true", help="print JSON instead of a table")

    cc = sub.add_parser("cache", help="inspect ('cache info') or empty ('cache clear') the parameter cache",
                        description="The parameter cache of expensive points (RESULTS/cache).")
    csub = cc.add_subparsers(dest="action", metavar="ACTION", required=True, parser_class=_Parser)
    for name, text in (("info", "entries, size, hits and misses of the last run, and which cache was read"),
                       ("clear", "delete every cache entry (results are kept); refuses a directory that is not a "
                                 "surfwave cache (no SURFWAVE_CACHE marker, or files that are not cache entries)")):
        a = csub.add_parser(name, help=text, description=text[0].upper() + text[1:] + ".")
        where = a.add_mutually_exclusive_group()
        where.add_argument("--results", type=Path, default=Path("results"), metavar="DIR",
                           help="results directory of the workflow; the cache is DIR/cache (default: results)")
        where.add_argument("--root", type=Path, help="the cache directory itself")
        if name == "info":
            a.add_argument("--json", action="store_true", help="print JSON")
    cli_fit.add_parser(sub)
    cli_layered.add_parser(sub, _Parser)
    return p


def _json_default(value):
    if isinstance(value, np.generic):
        return value.item()
    raise TypeError(type(value))


def _cmd_point(args) -> int:
    from surfwave.api import point

    r = point(args.lattice, args.loading, args.potential, args.direction, args.d_over_d0)
    rows = []
    for i, d in enumerate(r["d_over_d0"]):
        row: dict[str, Any] = {"d_over_d0": float(d), "stress": float(r["stress"][i])}
        res: dict[str, Any] = dict(r)
        row.update({k: (None if np.isnan(res[k][i]) else float(res[k][i])) for k in SPEED_KEYS})
        row.update(wave_type=str(r["wave_type"][i]), stable=bool(r["stable"][i]), reason=str(r["reason"][i]))
        rows.append(row)
    if args.json:
        print(json.dumps(rows if len(rows) > 1 else rows[0], indent=2, default=_json_default))
        return 0
    print(f"# {args.lattice} {args.loading} {args.potential} {args.direction}; speeds^2 in K d0^2/m")
    header = ["d/d0", "stress"] + list(SPEED_KEYS) + ["stable", "wave_type"]
    print("  ".join(f"{h:>10}" for h in header))
    for row in rows:
        vals = [row["d_over_d0"], row["stress"]] + [row[k] for k in SPEED_KEYS]
        cells = [f"{v:10.4f}" if v is not None else f"{'nan':>10}" for v in vals]
        print("  ".join(cells + [f"{str(row['stable']):>10}", f"{row['wave_type']:>10}"]))
        if row["reason"]:
            print(f"    note: {row['reason']}")
    return 0


def _angles(text: str) -> np.ndarray | float:
    """One angle "15" or a sweep "0:90:5" (stop included) in degrees (:func:`surfwave.cli_sweeps.sweep`)."""
    from surfwave.cli_sweeps import sweep

    values = sweep(text, "--angle")
    return float(values[0]) if ":" not in text else values


def _material_rows(r: Mapping[str, Any]) -> list[dict]:
    """JSON-ready rows (one per direction) of a :func:`surfwave.material` result."""
    n = np.size(r["c_R"])
    rows = []
    for i in range(n):
        row: dict[str, Any] = {}
        for key, value in r.items():
            v = np.asarray(value)
            v = np.asarray(v[i]) if v.ndim and v.shape[0] == n and np.ndim(r["c_R"]) else v
            if key == "euler":
                row[key] = None if np.all(np.isnan(v)) else [float(x) for x in np.ravel(v)]
            elif key in ("polarisation", "decay"):
                row[key] = {"re": [None if np.isnan(x) else float(x) for x in v.real],
                            "im": [None if np.isnan(x) else float(x) for x in v.imag]}
            elif v.dtype.kind == "f" and v.ndim:        # a vector: the bulk waves' polarisations
                row[key] = [None if np.isnan(x) else float(x) for x in v]
            elif v.dtype.kind == "f":
                row[key] = None if np.isnan(v) else float(v)
            elif v.dtype.kind == "b":
                row[key] = bool(v)
            else:
                row[key] = str(v)
        rows.append(row)
    return rows


def _cmd_material(args) -> int:
    from surfwave.api import material
    from surfwave.cli_sweeps import run_stress_sweep, stress_values
    from surfwave.errors import InputError

    if args.list:
        return cli_material.list_materials(args.json)
    if args.list_cuts:
        return cli_piezo.list_cuts()
    piezo_kw, swept = cli_piezo.material_kwargs(args)
    given = [n for n in ("C11", "C12", "C44", "voigt") if getattr(args, n) is not None]
    if args.material is not None:
        if given:
            raise InputError(f"give either --material or constants, not both (got --material and --{given[0]})")
        constants = {"C11": args.material}
    elif args.voigt is not None:
        if any(v is not None for v in (args.C11, args.C12, args.C44)):
            raise InputError("give either --voigt or --C11 --C12 --C44, not both")
        constants = {"voigt": np.reshape(args.voigt, (6, 6))}
    elif args.cut is not None and not given:        # the cut names its crystal
        constants = {}
    else:
        missing = [n for n in ("C11", "C12", "C44") if getattr(args, n) is None]
        if missing:
            raise InputError(f"missing {', '.join('--' + m for m in missing)} (GPa), or give --voigt "
                             "or --material")
        constants = {"C11": args.C11, "C12": args.C12, "C44": args.C44}
    if args.rho is None and args.material is None and not (args.cut is not None and not given):
        raise InputError("missing --rho (kg/m^3); a named --material brings its own")
    toec = cli_material.toec_arg(args)
    stress, stress_sweep = stress_values(args.stress)
    oriented = args.euler is None and args.cut is None      # else the Euler angles set surface and direction
    direction: Any
    if args.angle is not None:
        direction = _angles(args.angle)
    elif args.direction is not None:
        direction = args.direction
    else:
        direction = 0.0 if oriented else None
    if oriented and args.surface is None:
        args.surface = "(001)"

    def call(stress):
        try:
            return material(rho=args.rho, direction=direction, stress=stress, surface=args.surface, toec=toec,
                            **constants, **piezo_kw)
        except InputError as err:
            raise InputError(cli_material.toec_words(str(err), args)) from None

    if stress_sweep is not None:
        if swept is not None or np.ndim(direction):
            raise InputError("one sweep at a time: a --stress sweep with one orientation (not with an --angle or "
                             "--euler sweep)")
        where = (f"cut {args.cut}" if args.cut else f"Euler {' '.join(args.euler)}" if args.euler else
                 f"surface {args.surface}, " + (f"direction {direction}" if isinstance(direction, str)
                                                   else f"angle {direction:g} deg"))
        name = f"{args.material}, " if args.material else ""
        model = "third-order constants (stressed state)" if toec is not None else "fixed constants"
        return run_stress_sweep(call, stress_sweep, args.json, f"{name}{where}, {model}", _material_rows,
                                {True: cli_piezo.print_table, False: _elastic_table})
    r = call(stress)
    rows = _material_rows(r)
    if args.json:
        print(json.dumps(rows if np.ndim(r["c_R"]) else rows[0], indent=2))
        return 0
    if "K2" in r:
        return cli_piezo.print_result(args, r, rows, swept)
    what = f"propagation {direction}" if isinstance(direction, str) else "angle from the reference"
    model = "third-order constants (stressed state)" if toec is not None else "fixed constants"
    name = f"{args.material}, " if args.material else ""
    print(f"# {name}surface {args.surface}, {what}, stress "
          f"{' '.join(args.stress)} GPa, {model}")
    if np.ndim(direction) == 0:
        row = rows[0]
        for key in ("angle", "c_R", "c_limit", "c_T_par", "c_L_par", "c_T_perp", "c_L_perp", "c_SH", "c_SH_perp"):
            val = row[key]
            unit = "deg" if key == "angle" else "m/s"
            print(f"{key:>17} = " + (f"{cli_piezo.cell(val, '10.2f')} {unit}" if val is not None else "       nan"))
        print(f"{'penetration_depth':>17} = " + (f"{cli_piezo.cell(row['penetration_depth'], '10.3f')} wavelengths"
                                                  if row["penetration_depth"] is not None else "       nan"))
        print(f"{'wave_type':>17} = {row['wave_type']}   stable = {row['stable']}")
        pol = np.array(row["polarisation"]["re"], dtype=float) + 1j * np.array(row["polarisation"]["im"], dtype=float)
        print(f"{'polarisation':>17} = " + "  ".join(
            f"{cli_piezo.cell(u.real, '+.4f').replace(' ', '+')}{cli_piezo.cell(u.imag, '+.4f').replace(' ', '+')}i"
            for u in pol))
        if row["reason"]:
            print(f"             note: {row['reason']}")
        if row.get("grazing"):
            print(f"             note: {cli_piezo.GRAZING_NOTE}")
        return 0
    _elastic_table(rows, "angle", [cli_piezo.cell(row["angle"], "10.2f") for row in rows])
    return 0


def _elastic_table(rows: list[dict], label: str, first: list[str]) -> None:
    """The elastic sweep table: one line per row, ``first`` (texts) in the column ``label``."""
    header = [label, "c_R", "c_limit", "c_T_par", "c_L_par", "depth", "wave_type"]
    print("  ".join(f"{h:>10}" for h in header))
    for row, a in zip(rows, first):
        vals = [row[k] for k in ("c_R", "c_limit", "c_T_par", "c_L_par", "penetration_depth")]
        cells = [f"{a:>10}"] + [cli_piezo.cell(v, "10.2f") for v in vals]
        print("  ".join(cells + [f"{row['wave_type']:>10}"]))


def _cmd_potentials(args) -> int:
    from surfwave.model_crystals.potentials import available_potentials, get_potential

    for name in available_potentials():
        print(f"{name:>10}  {get_potential(name).description}")
    return 0


def _default_configs() -> list[Path]:
    """config/config.yaml of the working directory, else the one shipped with this checkout."""
    from surfwave.pipeline.scenes import SCHEMA_PATH

    here = Path("config/config.yaml")
    return [here if here.is_file() else SCHEMA_PATH.parents[2] / "config" / "config.yaml"]


def _cmd_scenes(args) -> int:
    from surfwave.pipeline.scenes import config_sources, load_config, scene_notes, selected, validate_config
    from surfwave.pipeline.targets import paper_scenes, scene_outputs

    files = _default_configs() + list(args.configfile)
    missing = [str(f) for f in files if not Path(f).is_file()]
    if missing:
        raise SurfwaveError(f"config file(s) not found: {missing}")
    config = load_config(files)
    scenes = validate_config(config, sources=config_sources(files))
    for note in scene_notes(scenes):
        print(note, file=sys.stderr)
    run = set(selected(config, scenes))
    paper = set(paper_scenes())
    rows = []
    for name, sc in scenes.items():
        if sc.get("kind") == "piezo":  # piezoelectric: materials x cuts/Euler angles x electrical [x stress]
            rows.append(cli_piezo.scene_row(name, sc, name in run, name in paper,
                                            list(scene_outputs(scenes, name).values())))
            continue
        if sc.get("kind") == "layered":  # films on a substrate: orientations x film stress x electrical x kh
            rows.append(cli_layered.scene_row(name, sc, name in run, name in paper,
                                              list(scene_outputs(scenes, name).values())))
            continue
        if sc.get("kind") == "crystal":  # real crystals: materials x surfaces x angles [x stress]
            a, st = sc["angles"], sc["stress"] or [0.0]
            rows.append({"scene": name, "built_by_all": name in run, "paper": name in paper,
                         "materials": sc["materials"], "surfaces": sc["surfaces"],
                         "angles": [min(a), max(a), len(a)], "stress": [min(st), max(st), len(st)],
                         "loading": sc["loading"], "toec": sc["toec"], "quantities": sc["quantities"],
                         "accuracy": sc["accuracy"], "outputs": list(scene_outputs(scenes, name).values())})
            continue
        d = sc["d_over_d0"]
        rows.append({"scene": name, "built_by_all": name in run, "paper": name in paper,
                     "lattice": sc["lattice"], "loading": sc["loading"], "potentials": sc["potentials"],
                     "directions": sc["directions"], "d_over_d0": [min(d), max(d), len(d)],
                     "n_theta": len(sc["theta"]), "quantities": sc["quantities"],
                     # the knobs the scene's jobs use (crystal.nc, always built, uses symmetry)
                     "accuracy": {k: v for k, v in sc["accuracy"].items()
                                  if k == "symmetry" or k in sc["quantities"]},
                     "outputs": list(scene_outputs(scenes, name).values())})
    if args.json:
        print(json.dumps(rows, indent=2))
        return 0
    print(f"# scenes of {', '.join(str(f) for f in files)} ('*' = built by 'snakemake', "
          "P = read by the paper's report.md)")
    for r in rows:
        if r.get("kind") == "piezo":
            print(cli_piezo.scene_text(r))
            continue
        if r.get("kind") == "layered":
            print(cli_layered.scene_text(r))
            continue
        if "materials" in r:
            (alo, ahi, na), (slo, shi, ns) = r["angles"], r["stress"]
            print(f"{'*' if r['built_by_all'] else ' '}{'P' if r['paper'] else ' '} {r['scene']:<14} "
                  f"{'/'.join(r['materials'])} on {' '.join(r['surfaces'])}, angles {alo:g}..{ahi:g} "
                  f"({na}), stress {slo:g}..{shi:g} GPa ({ns}, {'/'.join(r['loading'])}, toec "
                  f"{'/'.join(str(t).lower() for t in r['toec'])}) -> {', '.join(r['quantities'])}")
            print(f"{'':18}figures and tables: {', '.join(r['outputs']) or 'none'}")
            continue
        lo, hi, n = r["d_over_d0"]
        theta = f", {r['n_theta']} theta" if {"dispersion", "displacements"} & set(r["quantities"]) else ""
        print(f"{'*' if r['built_by_all'] else ' '}{'P' if r['paper'] else ' '} {r['scene']:<14} "
              f"{r['lattice']}, {r['loading']}, {'/'.join(r['potentials'])}, {' '.join(r['directions'])}, "
              f"d/d0 {lo:g}..{hi:g} ({n} points{theta}) -> {', '.join(r['quantities'])}")
        print(f"{'':18}figures and tables: {', '.join(r['outputs']) or 'none'}")
    return 0


def _cmd_cache(args) -> int:
    from surfwave.data import cache

    root = (args.root if args.root is not None else args.results / "cache").resolve()
    ours, why = cache.check_store(root)
    if args.action == "info":
        if not ours:
            if args.json:
                print(json.dumps({"root": str(root), "surfwave_cache": False, "reason": why}, indent=2))
            else:
                print(f"surfwave cache info: {why}", file=sys.stderr)
            return 2
        info = cache.info(root)
        info["exists"] = root.is_dir()
        if args.json:
            print(json.dumps({**info, "surfwave_cache": True, "reason": why}, indent=2))
            return 0
        print(f"cache: {root}" + ("" if info["exists"] else
                                  "  (no such directory: run from the workflow's directory or pass --results DIR)"))
        if "older surfwave" in why:
            print(f"note: {why}")
        for key, value in info.items():
            if key in ("root", "exists"):
                continue
            if key == "size":
                value = f"{value} bytes ({value / 1e6:.2f} MB)"
            print(f"{key}: {value}")
    else:
        n = cache.clear(root)  # refuses (InputError -> exit 2) anything not provably ours
        if "older surfwave" in why:
            print(f"note: {why}")
        print(f"removed {n} cache entries from {root}")
    return 0


def _show_note(message, category, filename, lineno, file=None, line=None) -> None:
    """Warnings as the command shows them: a :class:`surfwave.errors.ConstantsNote` is its own one
    line on stderr; any other warning keeps Python's format."""
    from surfwave.errors import ConstantsNote

    if issubclass(category, ConstantsNote):
        print(f"note: {message}", file=sys.stderr)
    else:
        sys.stderr.write(warnings.formatwarning(message, category, filename, lineno, line))


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``surfwave`` command."""
    parser = _parser()
    argv = sys.argv[1:] if argv is None else list(argv)
    _check_options(parser, argv)
    args = parser.parse_args(argv)
    handler = {"point": _cmd_point, "material": _cmd_material, "potentials": _cmd_potentials,
               "scenes": _cmd_scenes, "cache": _cmd_cache, "fit-film": cli_fit.run,
               "layered": cli_layered.run}[args.command]
    try:
        with warnings.catch_warnings():
            warnings.showwarning = _show_note
            return handler(args)
    except SurfwaveError as exc:
        print(f"surfwave {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except BrokenPipeError:  # the reader stopped early (`surfwave ... | head`): not an error
        os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())
        return 0


if __name__ == "__main__":
    sys.exit(main())
