"""The piezoelectric options of ``surfwave material``: --cut, --euler, --electrical, --list-cuts.

:mod:`surfwave.cli` adds these options (:func:`add_options`), turns them into keyword arguments
of :func:`surfwave.material` (:func:`material_kwargs`) and prints a piezoelectric result with
:func:`print_result`.
"""
from __future__ import annotations

import re
import sys
from collections.abc import Mapping
from typing import Any

import numpy as np

from surfwave.errors import InputError
from surfwave.validate import radians_note

__all__ = ["EPILOG", "add_options", "angle_text", "cell", "list_cuts", "material_kwargs", "print_result"]

EPILOG = """\
Piezoelectric crystals (quartz, LiNbO3, LiTaO3, AlN, ZnO, GaN, langasite, GaAs): a name of the
piezoelectric database (--material LiNbO3), a named cut (--cut 128Y-X; 'surfwave material
--list-cuts') or SAW Euler angles --euler PHI THETA PSI in degrees (ZXZ; x1 = propagation,
x3 = outward normal); any one of the three may be a sweep START:STOP:STEP (STOP included),
printed as a table (one sweep at a time: --stress, too, takes a list of values or a sweep).
Angles are degrees; when all look like radians (within 2 pi, one not a whole number) a note says
so. Output: free and metallized SAW speeds, K2 = 2 (v_free - v_met) / v_free,
the leaky SAW (radiating into the slowest bulk sheet) with its attenuation in dB per
wavelength for --electrical (default free), and the power-flow angle (degrees, from x1
toward +x2 of the SAW frame). --euler works for any crystal (Cu: e = 0). Prestress: fixed
constants (A = C + sigma delta); e and eps at their natural values.

piezoelectric examples:
  surfwave material --list-cuts
  surfwave material --material LiNbO3 --cut 128Y-X                  # 3994.2 / 3887.6 m/s, K2 5.34 %
  surfwave material --cut "ST-X quartz" --stress -0.1
  surfwave material --cut "ST-X quartz" --stress -0.2:0.2:0.05           # a stress sweep, as a table
  surfwave material --material LiNbO3 --euler 0 -90:90:10 0              # rotated Y cuts, X propagation
  surfwave material --material LiTaO3 --euler 0 -54 0 --electrical metallized --json
"""


#: Printed where a SAW is a bulk-like grazing wave (``grazing``).
GRAZING_NOTE = ("grazing: the SAW is a bulk-like wave at the limiting speed, deeper than 50 wavelengths "
                "(penetration_depth): not a surface wave to design on")


def add_options(mt) -> None:
    """Add the piezoelectric options to the ``material`` sub-parser."""
    # let a sweep that starts negative ("-90:90:2") be a value, as argparse already does for "-54"
    # (also with an exponent, "-1e-3", and a sweep's "-inf"/"-nan", which the range parser refuses in one line)
    mt._negative_number_matcher = re.compile(r"^-(\d+\.?\d*|\.\d+|inf|nan)([eE][-+]?\d+)?(:[-+\w.:]*)?$")
    g = mt.add_argument_group("piezoelectric crystals and Euler-angle cuts")
    g.add_argument("--cut", help='a named SAW cut: "128Y-X", "ST-X quartz", "Y-Z LiNbO3", ... (see --list-cuts)')
    g.add_argument("--euler", nargs=3, metavar=("PHI", "THETA", "PSI"),
                   help="SAW Euler angles in degrees (ZXZ); one of them may be a sweep START:STOP:STEP")
    g.add_argument("--electrical", choices=["free", "metallized"],
                   help="surface condition of c_R, the leaky wave and the power flow (default free)")
    g.add_argument("--list-cuts", action="store_true", help="list the named cuts and exit")


def list_cuts() -> int:
    """Print the named cuts: name, Euler angles, constant set, published values."""
    from surfwave.real_crystals.piezo_materials import available_cuts, get_cut

    print(f"{'cut':<16} {'Euler (deg)':<22} {'constants':<22} {'wave':<9} published")
    for name in available_cuts():
        c = get_cut(name)
        pub = ", ".join(f"{k} {v}" for k, v in c.published.items() if k != "source")
        eul = "(" + ", ".join(f"{a:g}" for a in c.euler) + ")"
        print(f"{c.name:<16} {eul:<22} {c.material:<22} {c.wave:<9} {pub}")
    return 0


def _sweep(text: str) -> np.ndarray:
    from surfwave.cli_sweeps import sweep

    return sweep(text, "--euler")


def material_kwargs(args) -> tuple[dict, int | None]:
    """Keyword arguments of :func:`surfwave.material` from --cut/--euler/--electrical.

    Returns the dict (empty when none is given) and the index of the swept Euler angle (None).
    """
    kw: dict = {}
    swept = None
    if args.cut is not None and args.euler is not None:
        raise InputError(f"give either --cut or --euler, not both (got --cut {args.cut!r})")
    if args.cut is not None:
        kw["cut"] = args.cut
    if args.euler is not None:
        if args.direction is not None or args.angle is not None:
            raise InputError("--euler sets the surface and the propagation: do not also give --direction or --angle")
        parts = [_sweep(t) for t in args.euler]
        sweeps = [i for i, p in enumerate(parts) if p.size > 1]
        if len(sweeps) > 1:
            raise InputError(f"only one Euler angle may be a sweep, got sweeps for {len(sweeps)}: {args.euler}")
        if sweeps:
            swept = sweeps[0]
            n = parts[swept].size
            kw["euler"] = np.column_stack([np.broadcast_to(p, (n,)) for p in parts])
        else:
            kw["euler"] = np.array([p[0] for p in parts])
        note = radians_note(kw["euler"], "--euler angles")
        if note:
            print(note, file=sys.stderr)
    if args.electrical is not None:
        kw["electrical"] = args.electrical
    return kw, swept


def cell(v, fmt: str, width: int = 10) -> str:
    """``v`` in ``fmt``; ``nan`` for None/NaN; never a negative zero ("-0.0000" -> " 0.0000")."""
    if v is None or (isinstance(v, float) and np.isnan(v)):
        return f"{'nan':>{width}}"
    text = format(v, fmt)
    return re.sub(r"-(?=0*\.?0*$)", " ", text) if re.fullmatch(r"\s*-[0.]+", text) else text


_f = cell


def angle_text(a: float | None) -> str:
    """An angle in degrees with every digit it has, up to 1e-6 (132.75 -> "132.75", -54 -> "-54", -0 -> "0").

    >>> [angle_text(a) for a in (0.0, -0.0, 132.75, -54.0, 1e-05, 38.123456789)]
    ['0', '0', '132.75', '-54', '0.00001', '38.123457']
    """
    if a is None or np.isnan(a):
        return "nan"
    text = f"{a:.6f}".rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def _leaky_expected(args, row: dict) -> bool:
    """Whether a missing leaky wave is news: a named leaky cut, or no subsonic SAW to report."""
    from surfwave.real_crystals.piezo_materials import get_cut

    if args.cut is not None and get_cut(args.cut).wave == "leaky":
        return True
    return row["c_R"] is None


def print_result(args, r: Mapping[str, Any], rows: list[dict], swept: int | None) -> int:
    """Print a piezoelectric :func:`surfwave.material` result as a table (sweep) or a list."""
    electrical = rows[0]["electrical"]
    where = (f"cut {args.cut}" if args.cut else
             f"Euler {' '.join(args.euler)}" if args.euler else f"surface {args.surface}")
    print(f"# {args.material + ', ' if args.material else ''}{where}, stress "
          f"{' '.join(args.stress)} GPa, "
          f"{'third-order constants' if np.any(r['toec']) else 'fixed constants'}; "
          f"leaky wave and PFA for a {electrical} surface")
    if np.ndim(r["c_R"]) == 0:
        row = rows[0]
        if row["euler"] is not None:
            items = [("euler", " ".join(angle_text(a) for a in row["euler"]) + " deg (phi theta psi)")]
        else:
            toward = (f"direction {args.direction}" if args.direction else
                      f"{angle_text(row['angle'])} deg from the reference direction")
            items = [("surface", f"{args.surface}, {toward}")]
        for key, unit, fmt in (("c_free", "m/s", "10.2f"), ("c_metallized", "m/s", "10.2f"),
                               ("c_limit", "m/s", "10.2f"), ("c_leaky", "m/s", "10.2f"),
                               ("leaky_attenuation", "dB/wavelength", "10.5f"), ("power_flow_angle", "deg", "10.4f"),
                               ("potential_share", "", "10.3g")):
            items.append((key, f"{_f(row[key], fmt)} {unit}"))
        items.append(("K2", f"{_f(None if row['K2'] is None else 100 * row['K2'], '10.4f')} %"))
        for key in ("c_leaky_free", "c_leaky_metallized"):
            items.append((key, f"{_f(row.get(key), '10.2f')} m/s"))
        k2l = row.get("K2_leaky")
        items.append(("K2_leaky", f"{_f(None if k2l is None else 100 * k2l, '10.4f')} %"))
        items.append(("wave_type", f"{row['wave_type']}   stable = {row['stable']}"))
        for key, text in items:
            print(f"{key:>17} = {text}")
        if row["reason"]:
            print(f"{'note':>17}: {row['reason']}")
        if row["leaky_reason"] and (row["c_leaky"] is not None or _leaky_expected(args, row)):
            print(f"{'note':>17}: {row['leaky_reason']}")
        if row.get("grazing"):
            print(f"{'note':>17}: {GRAZING_NOTE}")
        return 0
    label = ("phi", "theta", "psi")[swept] if swept is not None else "angle"
    print_table(rows, label, [angle_text(row["euler"][swept] if swept is not None else row["angle"]) for row in rows])
    return 0


def print_table(rows: list[dict], label: str, first: list[str]) -> None:
    """The piezoelectric sweep table: one line per row, ``first`` (texts) in the column ``label``
    (the swept Euler angle or angle, or the stress of a stress sweep)."""
    header = [label, "v_free", "v_met", "K2 (%)", "c_leaky", "dB/lambda", "K2_leaky(%)", "PFA (deg)", "wave_type"]
    print("  ".join(f"{h:>10}" for h in header))
    for row, a in zip(rows, first):
        k2 = None if row["K2"] is None else 100 * row["K2"]
        k2l = None if row.get("K2_leaky") is None else 100 * row["K2_leaky"]
        wave = row["wave_type"] + ("*" if row.get("grazing") else "")
        cells = [f"{a:>10}", _f(row["c_free"], "10.2f"), _f(row["c_metallized"], "10.2f"), _f(k2, "10.4f"),
                 _f(row["c_leaky"], "10.2f"), _f(row["leaky_attenuation"], "10.5f"), _f(k2l, "11.4f", 11),
                 _f(row["power_flow_angle"], "10.4f"), f"{wave:>10}"]
        print("  ".join(cells))
    if any(row.get("grazing") for row in rows):
        print(f"* {GRAZING_NOTE}")


def scene_row(name: str, sc: dict, built: bool, paper: bool, outputs: list[str]) -> dict:
    """JSON row of ``surfwave scenes`` for a piezoelectric scene."""
    def span(v):
        return [min(v), max(v), len(v)]

    st = sc["stress"] or [0.0]
    where = ({"cuts": sc["cuts"]} if sc["cuts"] is not None
             else {"euler": {k: span(v) for k, v in sc["euler"].items()}})
    return {"scene": name, "kind": "piezo", "built_by_all": built, "paper": paper, "materials": sc["materials"],
            **where, "electrical": sc["electrical"], "stress": span(st), "quantities": sc["quantities"],
            "accuracy": sc["accuracy"], "outputs": outputs}


def scene_text(r: dict) -> str:
    """Two lines of ``surfwave scenes`` for a piezoelectric scene row."""
    if "cuts" in r:
        where = "cuts " + ", ".join(r["cuts"])
    else:
        where = "Euler " + " ".join(f"{k} {lo:g}..{hi:g} ({n})" for k, (lo, hi, n) in r["euler"].items())
    slo, shi, ns = r["stress"]
    return (f"{'*' if r['built_by_all'] else ' '}{'P' if r['paper'] else ' '} {r['scene']:<14} "
            f"{'/'.join(r['materials'])}, {where}, {'/'.join(r['electrical'])}, stress {slo:g}..{shi:g} GPa "
            f"({ns}) -> {', '.join(r['quantities'])}\n{'':18}figures and tables: {', '.join(r['outputs']) or 'none'}")
