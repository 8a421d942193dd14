"""Every crystal name the library knows, in one place: both databases, all aliases, did-you-mean.

Two databases hold crystals: the elastic one (``materials.yaml``,
:mod:`surfwave.real_crystals.materials`) and the piezoelectric one (``piezoelectric.yaml``,
:mod:`surfwave.real_crystals.piezo_materials`, which also holds the named cuts). A user who
types a name does not know which file it lives in; this module answers for both: the one list
(:func:`catalog`, printed by ``surfwave material --list``), the closest names to a mistyped
one (:func:`suggest`) and the message of an unknown name (:func:`unknown_name`), which every
lookup (``get_material``, ``get_piezo_material``, hence :func:`surfwave.material`, the CLI and
the scene checks) raises.

Names match case-, space-, hyphen-, underscore- and degree-sign-insensitively (``"linbo3"``,
``"Li Nb O3"``, ``"128° Y-X"``), as the piezoelectric lookup always did.

Examples
--------
>>> suggest("LiNbO")
['LiNbO3 (LiNbO3-Warner1967)']
>>> suggest("coper")
['copper (Cu)']
>>> suggest("LiTaO3-Kovac")[0]
'LiTaO3 Kovacs (LiTaO3-Kovacs1990)'
>>> [(e.name, e.database) for e in catalog() if e.name == "GaAs"]
[('GaAs', 'elastic'), ('GaAs', 'piezoelectric')]
"""
from __future__ import annotations

import difflib
import re
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Literal

from surfwave.errors import InputError

__all__ = ["CatalogEntry", "catalog", "name_key", "suggest", "unknown_name"]

Database = Literal["elastic", "piezoelectric", "film"]

#: Closeness (difflib ratio of the normalised names) a suggestion needs.
CUTOFF = 0.6


@dataclass(frozen=True)
class CatalogEntry:
    """One crystal of one database.

    Attributes
    ----------
    name : str
        Canonical name in its database (``"Cu"``, ``"LiNbO3-Warner1967"``).
    database : {"elastic", "piezoelectric", "film"}
        "film": the isotropic film database of the layered solver
        (:func:`surfwave.layers.films.film_catalog`), never in :func:`catalog`.
    aliases : tuple of str
        Other names that find it (as written in the database file).
    symmetry : str
        Crystal system (elastic: ``"cubic"``, ``"hexagonal"``) or point group (piezoelectric:
        ``"3m"``, ``"32"``, ``"6mm"``, ``"-43m"``).
    rho : float
        Density, kg/m^3.
    toec : bool
        Whether the database holds third-order constants for it.
    """

    name: str
    database: Database
    aliases: tuple[str, ...]
    symmetry: str
    rho: float
    toec: bool


def name_key(text: object) -> str:
    """Lookup key of a name: case-folded, without spaces, hyphens, underscores, degree signs or 'deg'."""
    t = str(text).casefold().replace("°", "").replace("deg", "")
    return re.sub(r"[\s\-_]+", "", t)


def catalog() -> list[CatalogEntry]:
    """Every crystal of both databases: the elastic ones, then the piezoelectric ones, each sorted.

    Returns
    -------
    list of CatalogEntry
        A crystal found in both (GaAs) appears once per database.
    """
    from surfwave.real_crystals.materials import available_materials, get_material
    from surfwave.real_crystals.piezo_materials import available_piezo_materials, get_piezo_material

    rows = []
    for n in available_materials():
        m = get_material(n)
        rows.append(CatalogEntry(m.name, "elastic", tuple(m.aliases), m.symmetry, float(m.rho), m.toec is not None))
    for n in available_piezo_materials():
        p = get_piezo_material(n)
        rows.append(CatalogEntry(p.name, "piezoelectric", tuple(p.aliases), p.crystal_class, float(p.rho),
                                 p.toec_voigt is not None))
    return rows


def _spellings(extra: Sequence[CatalogEntry] = ()) -> dict[str, tuple[str, str]]:
    """Normalised key -> (spelling as written, canonical name), over both databases (and ``extra``)."""
    table: dict[str, tuple[str, str]] = {}
    for e in (*catalog(), *extra):
        for spelling in (e.name, *e.aliases):
            table.setdefault(name_key(spelling), (spelling, e.name))
    return table


def suggest(name: object, n: int = 3, extra: Sequence[CatalogEntry] = ()) -> list[str]:
    """The known crystals closest to a mistyped name, over every name and alias of both databases.

    Parameters
    ----------
    name : str
        What the user typed.
    n : int
        At most this many suggestions (distinct crystals).
    extra : sequence of CatalogEntry
        More entries to search (a door that also knows the film database passes it).

    Returns
    -------
    list of str
        One per crystal, best first: its canonical name, or the close alias followed by the
        canonical name (``"copper (Cu)"``, ``"LiNbO3 (LiNbO3-Warner1967)"``).
        Empty when nothing is close (difflib ratio below :data:`CUTOFF`).
    """
    table = _spellings(extra)
    out: dict[str, str] = {}
    for key in difflib.get_close_matches(name_key(name), list(table), n=5 * n, cutoff=CUTOFF):
        spelling, canonical = table[key]
        if canonical not in out:
            out[canonical] = canonical if spelling == canonical else f"{spelling} ({canonical})"
    return list(out.values())[:n]


def _cut_of(name: object) -> str | None:
    from surfwave.real_crystals.piezo_materials import get_cut

    try:
        c = get_cut(str(name))
    except InputError:
        return None
    return f"{c.name} (Euler {c.euler}, constants {c.material})"


def unknown_name(name: object, database: Database, extra: Sequence[CatalogEntry] = ()) -> InputError:
    """The error for a crystal name that ``database`` does not hold: where it is, or what is close.

    Parameters
    ----------
    name : str
        The name looked up.
    database : {"elastic", "piezoelectric"}
        The database that was asked.
    extra : sequence of CatalogEntry
        More entries the asking door knows (the film database of the layered solver): searched
        for the did-you-mean and listed after the others; without them the message is the one
        every crystal lookup raises.

    Returns
    -------
    InputError
        Its message says, in this order of preference: that the name is a crystal of the other
        database, or a named cut; else the closest names of either database (did you mean) and
        every known name, by database. No argument syntax of one interface (Python or command
        line) is suggested: the caller adds it where it knows it.
    """
    kind = {"elastic": "material", "piezoelectric": "piezoelectric material", "film": "film material"}[database]
    key = name_key(name)
    other = [e for e in catalog() if e.database != database and key in {name_key(s) for s in (e.name, *e.aliases)}]
    if other:
        return InputError(f"{name!r} is not in the {database} database: it is {other[0].name} of the "
                          f"{other[0].database} database")
    cut = _cut_of(name)
    if cut is not None:
        return InputError(f"unknown {kind} {name!r}: it names a SAW cut, {cut}, not a crystal")
    close = suggest(name, extra=extra)
    hint = f" (did you mean {' or '.join(close)}?)" if close else ""
    by_db: dict[str, list[str]] = {}
    for e in (*catalog(), *extra):
        by_db.setdefault(e.database, []).append(e.name)
    known = "; ".join(f"{db}: {', '.join(names)}" for db, names in by_db.items())
    return InputError(f"unknown {kind} {name!r}{hint}; known materials: {known}")
