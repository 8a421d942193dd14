"""The ``surfwave layered`` command: every guided mode of films on a substrate, as a table.

Registered by :mod:`surfwave.cli` (``add_parser`` and ``run``); all checks of the stack happen in
:func:`surfwave.layered` (one error line, nothing computed).
"""
from __future__ import annotations

import argparse
import json
import re
import sys

import numpy as np

from surfwave.errors import InputError
from surfwave.layers.modes import label_family

EPILOG = """\
Films from the top down, each NAME:THICKNESS[:STRESS]: a material name (film database first:
SiO2 = fused silica, Si3N4, Pt-film, sapphire; the piezoelectric crystals ZnO, AlN, ...; the
elastic crystals Al, Au, Cu, diamond, ...; '<cubic metal>-poly' for an untextured polycrystal),
a thickness with a unit (nm, um, mm or m) and optionally an equibiaxial in-plane stress in GPa
(negative = compression). kh = wavenumber x total film thickness; --kh takes values or a sweep
START:STOP:STEP (stop included). Lab frame: x1 propagation, x3 outward normal (SAW frame).

examples:
  surfwave layered --substrate Si --film SiO2:1um --kh 0:5:0.05
  surfwave layered --substrate Si --film SiO2:1um:-0.3 --surface "(001)" --direction "[110]" --kh 0.5 1 2
  surfwave layered --substrate LiNbO3 --euler 0 38 0 --film SiO2:0.5um --kh 0:2:0.25
  surfwave layered --substrate Si --film diamond:1um --kh 0:1.5:0.1 --leaky
  surfwave layered --substrate Si --film Au-poly:100nm --frequency 1e8 5e8 1e9 --json
"""

_UNITS = {"nm": 1e-9, "um": 1e-6, "µm": 1e-6, "mm": 1e-3, "m": 1.0}
#: Most kh values of one sweep.
MAX_KH_POINTS = 100000


def add_parser(sub, parser_class) -> argparse.ArgumentParser:
    """Add the ``layered`` subcommand to the subparsers ``sub``."""
    lp = sub.add_parser(
        "layered", help="guided modes (Rayleigh, Sezawa, Love, leaky) of films on a crystal substrate",
        description="Every guided mode of a stack of films on a substrate against kh (or frequency): phase "
        "speed, labels, group velocity, K^2 of piezoelectric stacks, leaky modes on request.",
        epilog=EPILOG, formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    lp.add_argument("--substrate", required=True, help="substrate material name")
    lp.add_argument("--film", action="append", default=[], metavar="NAME:THICKNESS[:STRESS]",
                    help="a film (repeat from the top down), e.g. SiO2:1um or SiO2:500nm:-0.2")
    grid = lp.add_mutually_exclusive_group(required=True)
    grid.add_argument("--kh", nargs="+", help="kh values or START:STOP:STEP")
    grid.add_argument("--frequency", nargs="+", type=float, help="frequencies in Hz")
    lp.add_argument("--surface", default="(001)", help="substrate surface (hkl) (default (001))")
    lp.add_argument("--direction", default="[100]", help="propagation direction [uvw] or angle in degrees")
    lp.add_argument("--euler", nargs=3, type=float, metavar=("PHI", "THETA", "PSI"),
                    help="SAW Euler angles of the substrate, degrees (instead of --surface/--direction)")
    lp.add_argument("--stress", nargs="+", type=float, metavar="GPA",
                    help="substrate stress: one value (equibiaxial in the surface plane) or nine (3 x 3, SAW frame)")
    lp.add_argument("--electrical", default="free", choices=["free", "metallized"])
    lp.add_argument("--leaky", action="store_true", help="also continue modes above c_limit as leaky waves")
    lp.add_argument("--modes", type=int, default=None, metavar="N",
                    help="only the N slowest guided modes of each family (e.g. 2: R, S1, L0, L1)")
    lp.add_argument("--group", action="store_true", help="also print the group velocities")
    lp.add_argument("--json", action="store_true", help="print the result record as JSON")
    return lp


def parse_film(text: str) -> dict:
    """'NAME:THICKNESS[:STRESS]' -> a film mapping for :func:`surfwave.layered`."""
    parts = text.split(":")
    if len(parts) not in (2, 3) or not parts[0]:
        raise InputError(f"--film must be NAME:THICKNESS[:STRESS], e.g. SiO2:1um, got {text!r}")
    m = re.fullmatch(r"\s*([-+0-9.eE]+)\s*(nm|um|µm|mm|m)\s*", parts[1])
    if not m:
        raise InputError(f"--film {text!r}: the thickness needs a unit (nm, um, mm or m), e.g. 1um or 250nm")
    try:
        film: dict = {"name": parts[0], "thickness": float(m.group(1)) * _UNITS[m.group(2)]}
        if len(parts) == 3:
            film["stress"] = float(parts[2])
    except ValueError:
        raise InputError(f"--film {text!r}: thickness and stress must be numbers") from None
    return film


def parse_kh(values: list[str]) -> np.ndarray:
    """kh values, or one sweep START:STOP:STEP (stop included)."""
    if len(values) == 1 and ":" in values[0]:
        try:
            a, b, s = (float(v) for v in values[0].split(":"))
        except ValueError:
            raise InputError(f"--kh sweep must be START:STOP:STEP, got {values[0]!r}") from None
        if not (np.isfinite([a, b, s]).all() and s > 0 and b >= a):
            raise InputError(f"--kh sweep must have STEP > 0 and STOP >= START, got {values[0]!r}")
        n = int(np.floor((b - a) / s + 1e-9)) + 1
        if n > MAX_KH_POINTS:
            raise InputError(f"--kh sweep {values[0]!r} has {n} values, more than {MAX_KH_POINTS}")
        return a + s * np.arange(n)
    try:
        return np.array([float(v) for v in values])
    except ValueError:
        raise InputError(f"--kh must be numbers or START:STOP:STEP, got {values!r}") from None


def run(args) -> int:
    """Handler of ``surfwave layered``: compute and print the table (or JSON)."""
    import surfwave

    films = [parse_film(f) for f in args.film]
    stress = None
    if args.stress is not None:
        if len(args.stress) not in (1, 9):
            raise InputError(f"--stress takes one value or nine, got {len(args.stress)}")
        stress = args.stress[0] if len(args.stress) == 1 else np.reshape(args.stress, (3, 3))
    direction: str | float = args.direction
    try:
        direction = float(args.direction)
    except ValueError:
        pass
    kw: dict = {"surface": args.surface, "direction": direction, "euler": args.euler, "stress": stress,
                "electrical": args.electrical, "leaky": args.leaky, "modes": args.modes}
    if args.kh is not None:
        kw["kh"] = parse_kh(args.kh)
    else:
        kw["frequency"] = np.array(args.frequency)
    r = surfwave.layered(args.substrate, films, **kw)
    if args.json:
        out = {k: (v.tolist() if isinstance(v, np.ndarray) else v) for k, v in r.items()}
        json.dump(out, sys.stdout, default=lambda x: None if x != x else x)
        print()
        return 0
    print(format_table(r, group=args.group, by="kh" if args.kh is not None else "frequency"))
    return 0



def _limits_text(r) -> str:
    """``c_limit = ... m/s``, with each family's own limit where they differ (``mode_limit``)."""
    by_family: dict[str, float] = {}
    for lab, v in zip(np.ravel(r["mode"]), np.ravel(r["mode_limit"])):
        if lab and np.isfinite(v):
            by_family.setdefault({"R": "R, S"}.get(label_family(lab), label_family(lab) or "?"), float(v))
    if len({round(v, 6) for v in by_family.values()}) <= 1:
        return f"c_limit = {r['c_limit']:.3f} m/s"
    ordered = sorted(by_family.items(), key=lambda x: x[1])
    return "limits " + ", ".join(f"{v:.3f} m/s ({fam} modes)" for fam, v in ordered)


def format_table(r, *, group: bool = False, by: str = "kh") -> str:
    """The record as a text table: one row per kh (or frequency), one column per mode label."""
    labels: dict[str, list[float]] = {}
    for row_c, row_l in zip(r["c"], r["mode"]):
        for c, lab in zip(row_c, row_l):
            if lab:
                labels.setdefault(str(lab), []).append(float(c))
    cols = sorted(labels, key=lambda k: (np.mean(labels[k]), k))
    head = [by] + [f"c_{k}" for k in cols] + ([f"vg_{k}" for k in cols] if group else [])
    lines = [f"# {_limits_text(r)}; speeds in m/s" + ("; leaky attenuation in dB/wavelength"
                                                       if np.isfinite(r["attenuation"]).any() else ""),
             "  ".join(f"{h:>12}" for h in head)]
    first = r["kh"][:, 0] if by == "kh" else np.nanmax(r["frequency"], axis=1, initial=np.nan)
    for i in range(r["c"].shape[0]):
        val = {str(lab): j for j, lab in enumerate(r["mode"][i]) if lab}
        cells = [f"{first[i]:12.6g}"]
        for k in cols:
            j = val.get(k)
            cells.append(f"{r['c'][i, j]:12.3f}" if j is not None else f"{'':>12}")
        if group:
            for k in cols:
                j = val.get(k)
                g = r["group_velocity"][i, j] if j is not None else np.nan
                cells.append(f"{g:12.3f}" if np.isfinite(g) else f"{'':>12}")
        lines.append("  ".join(cells))
    leaky = [(i, j) for i in range(r["c"].shape[0]) for j in range(r["c"].shape[1])
             if np.isfinite(r["attenuation"][i, j])]
    if leaky:
        lines.append("# leaky modes (label~): " + ", ".join(
            f"{r['mode'][i, j]} at {first[i]:.4g}: {r['attenuation'][i, j]:.4g} dB/wl" for i, j in leaky[:20]))
    return "\n".join(lines)


def scene_row(name: str, sc: dict, built: bool, paper: bool, outputs: list[str]) -> dict:
    """JSON row of ``surfwave scenes`` for a layered scene (surfwave.pipeline.layered_scenes)."""
    def span(v):
        return [min(v), max(v), len(v)]

    films = [f"{f.get('material', f.get('name', 'film'))}:{f['thickness']:g}m" for f in sc["films"]]
    return {"scene": name, "kind": "layered", "built_by_all": built, "paper": paper,
            "substrate": sc["substrate"] if isinstance(sc["substrate"], str) else "mapping", "films": films,
            "orientations": [o["label"] for o in sc["orientations"]], "kh": span(sc["kh"]),
            "film_stress": span(sc["film_stress"]), "electrical": sc["electrical"], "leaky": sc["leaky"],
            "quantities": sc["quantities"], "accuracy": sc["accuracy"], "outputs": outputs}


def scene_text(r: dict) -> str:
    """Two lines of ``surfwave scenes`` for a layered scene row."""
    (klo, khi, nk), (slo, shi, ns) = r["kh"], r["film_stress"]
    return (f"{'*' if r['built_by_all'] else ' '}{'P' if r['paper'] else ' '} {r['scene']:<14} "
            f"{' / '.join(r['films'])} on {r['substrate']} {', '.join(r['orientations'])}, kh {klo:g}..{khi:g} "
            f"({nk}), film stress {slo:g}..{shi:g} GPa ({ns}), {'/'.join(r['electrical'])} -> "
            f"{', '.join(r['quantities'])}\n{'':18}figures and tables: {', '.join(r['outputs']) or 'none'}")
