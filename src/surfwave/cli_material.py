"""The crystal listing and the third-order options of ``surfwave material`` (--list, --toec, --toec-file).

:mod:`surfwave.cli` calls :func:`list_materials` for ``--list`` (every crystal of both databases,
:mod:`surfwave.real_crystals.catalog`), :func:`toec_arg` to turn --toec / --toec-file into the
``toec`` argument of :func:`surfwave.material` (refusing, in the command line's words, what
cannot work), and :func:`toec_words` to put a library message about third-order constants into
those words (--toec-file, not ``toec=``).
"""
from __future__ import annotations

import argparse
import json
import re

from surfwave.errors import InputError
from surfwave.real_crystals.catalog import CatalogEntry

__all__ = ["list_materials", "toec_arg", "toec_words"]


def _toec_file(path: str) -> dict:
    """Named third-order constants (GPa) from a YAML mapping, for ``--toec-file``."""
    from surfwave.real_crystals.piezo_materials import read_toec_file

    try:
        return read_toec_file(path)[0]
    except InputError as err:
        raise InputError(f"--toec-file: {err}") from None


def list_materials(as_json: bool) -> int:
    """Print every crystal of both databases (``material --list``), with its aliases."""
    from surfwave.real_crystals.catalog import catalog

    rows = catalog()
    if as_json:
        print(json.dumps([{"name": e.name, "database": e.database, "symmetry": e.symmetry, "rho": e.rho,
                           "toec": e.toec, "aliases": list(e.aliases)} for e in rows], indent=2))
        return 0
    heads = {"elastic": "elastic database (materials.yaml): --surface with --direction or --angle, or --euler",
             "piezoelectric": "piezoelectric database (piezoelectric.yaml): --cut ('--list-cuts'), --euler, "
                              "or --surface/--direction"}
    print("# every crystal --material accepts (any name or alias, case-insensitive); class, density, "
          "third-order constants (TOEC), other names")
    width = max(len(e.name) for e in rows)
    for db, head in heads.items():
        print(head)
        for e in (r for r in rows if r.database == db):
            toec = "yes" if e.toec else "no "
            print(f"  {e.name:<{width}}  {e.symmetry:<9} rho {e.rho:6.0f} kg/m^3  TOEC {toec}  "
                  f"{', '.join(e.aliases)}".rstrip())
    both = sorted({e.name for e in rows if e.database == "elastic"} & {e.name for e in rows if e.database != "elastic"})
    if both:
        print(f"{', '.join(both)}: in both; by name alone the elastic solver, with --cut, --euler or --electrical "
              "the piezoelectric one")
    return 0


def toec_arg(args: argparse.Namespace) -> object:
    """The ``toec`` argument of :func:`surfwave.material` from --toec / --toec-file, with the
    command line's own words for what is missing (--toec-file, not a Python argument)."""
    from surfwave.real_crystals.materials import CUBIC_TOEC

    if args.toec_file is not None:
        if args.toec is not None:
            raise InputError("give --toec or --toec-file, not both")
        return _toec_file(args.toec_file)
    if args.toec is None:
        return None
    crystal = _named_crystal(args)
    if crystal is not None and crystal.database == "elastic" and crystal.symmetry != "cubic":
        raise InputError(f"{crystal.name} ({crystal.symmetry}) has no third-order constants in the database, and "
                         "the command line takes them only for cubic crystals (--toec with six values) and the "
                         "piezoelectric database's (--toec-file FILE); the Python call takes a (6, 6, 6) Voigt "
                         "array, surfwave.material(..., toec=C3)")
    if crystal is not None and crystal.symmetry not in ("cubic", "-43m") and len(args.toec) in (0, 6):
        what = ("has no third-order constants in the database" if len(args.toec) == 0 else
                f"is of class {crystal.symmetry}: the six values of --toec are the cubic set")
        raise InputError(f"{crystal.name} {what}; give its set with --toec-file FILE (a YAML mapping "
                         f"name: GPa of the class's constants: {_class_names(crystal.symmetry)})")
    if len(args.toec) == 0:
        if crystal is None:
            raise InputError("--toec without values takes the database's third-order constants of --material; "
                             f"with constants given, give six values ({' '.join(CUBIC_TOEC)}, GPa) or --toec-file FILE")
        if not crystal.toec:
            raise InputError(f"no third-order constants for {crystal.name} in the database; give six values "
                             f"--toec {' '.join(CUBIC_TOEC)} (GPa) or --toec-file FILE")
        return True
    if len(args.toec) == 6:
        return tuple(args.toec)
    raise InputError(f"--toec takes no value (the database's) or six ({' '.join(CUBIC_TOEC)}, GPa), got "
                     f"{len(args.toec)}; any crystal class: --toec-file FILE")


def toec_words(message: str, args: argparse.Namespace) -> str:
    """A library message about third-order constants in the command line's words (--toec,
    --toec-file) instead of the Python arguments (``toec=``); other messages pass unchanged."""
    if args.toec is None and args.toec_file is None:
        return message
    if args.toec_file is not None and "third-order" in message:
        message = f"--toec-file {args.toec_file}: {message}"
    message = re.sub(r"give toec=\(C111, C112, C123, C144, C155, C456\) in GPa",
                     "give six values --toec C111 C112 C123 C144 C155 C456 (GPa) or --toec-file FILE", message)
    message = message.replace("toec=True", "--toec")
    message = re.sub(r"; else give a \(6, 6, 6\) Voigt array$", "", message)
    if "toec=" in message:
        message += " (command line: --toec with six cubic values, or --toec-file FILE for any class)"
    return message


def _named_crystal(args: argparse.Namespace) -> CatalogEntry | None:
    """The catalog entry of the crystal the command names (--material or the cut's), or None."""
    from surfwave.real_crystals.catalog import catalog, name_key
    from surfwave.real_crystals.piezo_materials import get_cut

    name = args.material
    piezo = args.cut is not None or args.euler is not None or args.electrical is not None
    if name is None and args.cut is not None:
        try:
            name = get_cut(args.cut).material
        except InputError:
            return None
    if name is None:
        return None
    hits = [e for e in catalog() if name_key(name) in {name_key(s) for s in (e.name, *e.aliases)}]
    hits.sort(key=lambda e: (e.database == "piezoelectric") != piezo)
    return hits[0] if hits else None


def _class_names(symmetry: str) -> str:
    from surfwave.real_crystals.toec_classes import TOEC_NAMES

    names = TOEC_NAMES.get("6mm" if symmetry == "hexagonal" else symmetry)
    return " ".join(names) if names else "see 'surfwave material --help'"
