"""Real crystals by name: elastic constants, third-order constants and densities with sources.

The numbers live in one file, ``materials.yaml`` next to this module (room temperature;
C in GPa, rho in kg/m^3; each block names its published source). This module reads it once,
checks it, and hands out :class:`Material` records.

Examples
--------
>>> from surfwave.real_crystals.materials import get_material
>>> cu = get_material("copper")
>>> cu.name, cu.symmetry, cu.rho
('Cu', 'cubic', 8960.0)
>>> float(cu.voigt[0, 0]), float(cu.voigt[3, 3])
(168.4, 75.4)
>>> cu.toec["C111"]
-1271.0
"""
from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property, lru_cache
from importlib import resources
from typing import Callable, Literal

import numpy as np
import yaml

from surfwave.data.paper import SAFE_LOADER
from surfwave.errors import InputError
from surfwave.solvers.tensors import cubic_voigt, hexagonal_voigt

#: Independent second-order constants of each crystal class, in the order the constructors take.
SECOND_ORDER = {"cubic": ("C11", "C12", "C44"), "hexagonal": ("C11", "C12", "C13", "C33", "C44")}
#: The six independent third-order (Brugger) constants of a cubic crystal of the highest classes.
CUBIC_TOEC = ("C111", "C112", "C123", "C144", "C155", "C456")
_BUILDERS: dict[str, Callable[..., np.ndarray]] = {"cubic": cubic_voigt, "hexagonal": hexagonal_voigt}


@dataclass(frozen=True, eq=False)
class Material:
    """One crystal of the database.

    Attributes
    ----------
    name : str
        Canonical name (chemical symbol, ``"C-diamond"`` for diamond).
    symmetry : {"cubic", "hexagonal"}
    rho : float
        Density, kg/m^3, at the natural (unstressed) state.
    voigt : ndarray, shape (6, 6)
        Second-order stiffness in Voigt form, GPa, crystal axes (hexagonal: c axis along x3).
    constants : dict of str to float
        The independent second-order constants as printed (``C11``, ``C12``, ``C44`` or
        ``C11``, ``C12``, ``C13``, ``C33``, ``C44``), GPa.
    toec : dict of str to float or None
        Third-order constants ``C111``, ``C112``, ``C123``, ``C144``, ``C155``, ``C456``,
        GPa, Brugger convention (Lagrangian strain, energy per natural volume); None when the
        database has none for this crystal.
    sources : dict of str to str
        Quantity (``"rho"``, ``"C11"``, ..., ``"C456"``) -> full citation.
    temperature : float
        Temperature of the measurements, K.
    aliases : tuple of str
        Other accepted names (case-insensitive).
    """

    name: str
    symmetry: Literal["cubic", "hexagonal"]
    rho: float
    voigt: np.ndarray
    constants: dict
    toec: dict | None
    sources: dict
    temperature: float = 300.0
    aliases: tuple = field(default_factory=tuple)

    @cached_property
    def toec_voigt(self) -> np.ndarray | None:
        """Third-order constants as a Voigt array, shape (6, 6, 6), GPa (None if unknown); built
        once per record, read-only (like ``voigt``)."""
        if self.toec is None:
            return None
        from surfwave.real_crystals.toec import cubic_toec

        C3 = cubic_toec(**self.toec)
        C3.setflags(write=False)
        return C3


def _read() -> dict:
    text = resources.files("surfwave.real_crystals").joinpath("materials.yaml").read_text(encoding="utf-8")
    return yaml.load(text, Loader=SAFE_LOADER)


def read_constants(block: object, names: tuple, where: str, refs: dict) -> tuple[dict, str]:
    """The constants ``names`` of one YAML block as floats, and the citation of its source.

    Shared by the elastic and the piezoelectric databases (``materials.yaml``,
    ``piezoelectric.yaml``); ``where`` names the entry in every error.
    """
    if not isinstance(block, dict):
        raise InputError(f"{where}: expected a mapping of constants with a source, got {block!r}")
    src = block.get("source")
    if src not in refs:
        raise InputError(f"{where}: source {src!r} is not a key of the references")
    missing = [n for n in names if n not in block]
    extra = sorted(set(block) - set(names) - {"source"})
    if missing or extra:
        raise InputError(f"{where}: missing constants {missing}, unexpected keys {extra}")
    values = {n: float(block[n]) for n in names}
    bad = [n for n, v in values.items() if not np.isfinite(v)]
    if bad:
        raise InputError(f"{where}: non-finite constants {bad}")
    return values, refs[src]


def _build(name: str, entry: dict, refs: dict) -> Material:
    symmetry = entry.get("symmetry")
    if symmetry not in SECOND_ORDER:
        raise InputError(f"material {name}: symmetry {symmetry!r} not one of {sorted(SECOND_ORDER)}")
    constants, c_src = read_constants(entry.get("C"), SECOND_ORDER[symmetry], f"material {name} C", refs)
    rho_block = entry.get("rho") or {}
    rho, rho_src = read_constants({k: v for k, v in rho_block.items()}, ("value",), f"material {name} rho", refs)
    sources = {"rho": rho_src, **{k: c_src for k in constants}}
    toec = None
    if entry.get("toec") is not None:
        if symmetry != "cubic":
            raise InputError(f"material {name}: third-order constants are supported for cubic crystals only")
        toec, t_src = read_constants(entry["toec"], CUBIC_TOEC, f"material {name} toec", refs)
        sources.update({k: t_src for k in toec})
    voigt = _BUILDERS[symmetry](*(constants[k] for k in SECOND_ORDER[symmetry]))
    voigt.setflags(write=False)
    return Material(
        name=name, symmetry=symmetry, rho=rho["value"], voigt=voigt, constants=constants,
        toec=toec, sources=sources, temperature=float(entry.get("temperature_K", 300.0)),
        aliases=tuple(str(a) for a in entry.get("aliases", ())),
    )


@lru_cache(maxsize=1)
def _database() -> tuple[dict, dict]:
    raw = _read()
    refs = {str(k): " ".join(str(v).split()) for k, v in raw["references"].items()}
    materials = {str(n): _build(str(n), e, refs) for n, e in raw["materials"].items()}
    lookup: dict[str, str] = {}
    for n, m in materials.items():
        for key in (n, *m.aliases):
            k = key.casefold()
            if k in lookup and lookup[k] != n:
                raise InputError(f"materials.yaml: name {key!r} used by both {lookup[k]} and {n}")
            lookup[k] = n
    return materials, lookup


def available_materials() -> list[str]:
    """Canonical names of every material in the database, sorted."""
    return sorted(_database()[0])


def get_material(name: str | Material) -> Material:
    """The database record of a crystal (a :class:`Material` passes through).

    Parameters
    ----------
    name : str
        Chemical symbol or common name, case-insensitive (``"Cu"``, ``"copper"``,
        ``"GaAs"``, ``"diamond"``).

    Returns
    -------
    Material

    Raises
    ------
    InputError
        For an unknown name: :func:`surfwave.real_crystals.catalog.unknown_name` (the database
        that holds it, or the closest names and every known one, over both databases).
    """
    if isinstance(name, Material):
        return name
    materials, lookup = _database()
    key = str(name).strip().casefold()
    if key in lookup:
        return materials[lookup[key]]
    from surfwave.real_crystals.catalog import unknown_name

    raise unknown_name(name, "elastic")
