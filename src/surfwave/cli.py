"""Command-line interface: ``surfwave point|material|potentials|cache``.

Run ``surfwave --help`` or ``surfwave <command> --help``.
"""
from __future__ import annotations

import argparse
import json
import sys
from pathlib import Path

import numpy as np

from surfwave import __version__
from surfwave.errors import SurfwaveError

SPEED_KEYS = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH", "c2_R")

EPILOG_POINT = """\
Reduced units: nearest-neighbour distance d0 = 1, mass m = 1, spring constant K = phi''(d0) = 1.
Speeds squared are in K d0^2/m; stress is sigma0_xx V/(K d0^2). Lab frame: x = propagation,
y = surface normal (into the crystal), z = in-plane normal to x.

examples:
  surfwave point --lattice fcc --loading in_plane_hydrostatic --potential lj --direction "[110]" --d-over-d0 1.02
  surfwave point --lattice triangular --loading uniaxial --potential harmonic --direction "[10]" --d-over-d0 0.9 1.0 1.1 --json
"""

EPILOG_MATERIAL = """\
The (001) surface of a cubic crystal; the measured constants are taken as those of the
(stressed) crystal and the in-plane stress sigma_xx enters through Eq. (A11).

example (copper, room temperature):
  surfwave material --C11 168.4 --C12 121.4 --C44 75.4 --rho 8960 --direction "[100]"
"""


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
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
    pt.add_argument("--lattice", required=True, choices=["fcc", "triangular"])
    pt.add_argument("--loading", required=True, choices=["uniaxial", "in_plane_hydrostatic"],
                    help="uniaxial stress along the propagation direction, or in-plane hydrostatic (fcc)")
    pt.add_argument("--potential", required=True,
                    help="pair potential: harmonic, lj or any registered one (see 'surfwave potentials')")
    pt.add_argument("--direction", required=True, choices=["[100]", "[110]", "[10]"],
                    help="propagation direction; '[10]' = close-packed rows of the triangular lattice")
    pt.add_argument("--d-over-d0", required=True, type=float, nargs="+", metavar="D",
                    help="stretch along the propagation direction, 1 = unstressed (one or more values)")
    pt.add_argument("--json", action="store_true", help="print JSON instead of a table")

    mt = sub.add_parser(
        "material", help="Rayleigh and bulk speeds (m/s) of a real cubic crystal from C11, C12, C44",
        description="Rayleigh and bulk sound speeds on the (001) surface of a cubic crystal.",
        epilog=EPILOG_MATERIAL, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    mt.add_argument("--C11", required=True, type=float, help="elastic constant C11, GPa")
    mt.add_argument("--C12", required=True, type=float, help="elastic constant C12, GPa")
    mt.add_argument("--C44", required=True, type=float, help="elastic constant C44, GPa")
    mt.add_argument("--rho", required=True, type=float, help="density, kg/m^3")
    mt.add_argument("--direction", required=True, choices=["[100]", "[110]"],
                    help="propagation direction in the (001) surface")
    mt.add_argument("--stress", type=float, default=0.0,
                    help="in-plane stress sigma_xx along the propagation direction, GPa (negative = compression)")
    mt.add_argument("--json", action="store_true", help="print JSON instead of a table")

    sub.add_parser("potentials", help="list the registered pair potentials")

    cc = sub.add_parser("cache", help="inspect or empty the parameter cache (results/cache)")
    cc.add_argument("action", choices=["info", "clear"])
    cc.add_argument("--root", default="results/cache", type=Path,
                    help="cache directory (default: results/cache)")
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
        row = {"d_over_d0": float(d), "stress": float(r["stress"][i])}
        row.update({k: (None if np.isnan(r[k][i]) else float(r[k][i])) for k in SPEED_KEYS})
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


def _cmd_material(args) -> int:
    from surfwave.api import material

    r = material(args.C11, args.C12, args.C44, args.rho, args.direction, args.stress)
    if args.json:
        print(json.dumps(r, indent=2))
        return 0
    print(f"# cubic crystal, (001) surface, propagation {args.direction}, sigma_xx = {args.stress} GPa")
    for key in ("c_R", "c_T_par", "c_L_par", "c_T_perp", "c_L_perp", "c_SH"):
        print(f"{key:>10} = {r[key]:10.2f} m/s")
    print(f"{'wave_type':>10} = {r['wave_type']}   stable = {r['stable']}")
    if r["reason"]:
        print(f"      note: {r['reason']}")
    return 0


def _cmd_potentials(args) -> int:
    from surfwave.continuum.potentials import available_potentials, get_potential

    for name in available_potentials():
        print(f"{name:>10}  {get_potential(name).description}")
    return 0


def _cmd_cache(args) -> int:
    from surfwave.data import cache

    if args.action == "info":
        info = cache.info(args.root)
        for key, value in info.items():
            if key == "size":
                value = f"{value} bytes ({value / 1e6:.2f} MB)"
            print(f"{key}: {value}")
    else:
        n = cache.clear(args.root)
        print(f"removed {n} cache entries from {args.root}")
    return 0


def main(argv: list[str] | None = None) -> int:
    """Entry point of the ``surfwave`` command."""
    args = _parser().parse_args(argv)
    handler = {"point": _cmd_point, "material": _cmd_material,
               "potentials": _cmd_potentials, "cache": _cmd_cache}[args.command]
    try:
        return handler(args)
    except SurfwaveError as exc:
        print(f"surfwave {args.command}: error: {exc}", file=sys.stderr)
        return 2


if __name__ == "__main__":
    sys.exit(main())
