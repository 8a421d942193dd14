"""Film materials by name: the crystal databases plus isotropic film materials with sources.

:func:`lookup` turns a name into the material record the stack resolver needs. It searches, in
this order, the film database ``films.yaml`` next to this module (isotropic films: fused silica,
polycrystalline metals, ..., every number with its source), the piezoelectric database
(:mod:`surfwave.real_crystals.piezo_materials`) and the elastic crystal database
(:mod:`surfwave.real_crystals.materials`). A name with the suffix ``-poly`` (``"Au-poly"``)
gives the Voigt-Reuss-Hill isotropic average of a cubic crystal of the elastic database: the
untextured polycrystal (sputtered metal films).
"""
from __future__ import annotations

from functools import lru_cache
from importlib import resources

import numpy as np
import yaml

from surfwave.data.paper import SAFE_LOADER
from surfwave.errors import InputError
from surfwave.real_crystals.catalog import CatalogEntry, name_key, unknown_name
from surfwave.solvers.tensors import cubic_voigt

__all__ = ["available_films", "film_catalog", "hill_average", "lookup"]


@lru_cache(maxsize=1)
def _film_db() -> dict:
    """The records of ``films.yaml``: name -> {voigt (6, 6) GPa, rho, eps_r (3, 3) or None, aliases, sources}."""
    from surfwave.layers.stack import isotropic_voigt
    from surfwave.solvers.piezo_tensors import trigonal_3m_voigt

    text = resources.files("surfwave.layers").joinpath("films.yaml").read_text(encoding="utf-8")
    raw = yaml.load(text, Loader=SAFE_LOADER) or {}
    refs = {str(k): " ".join(str(v).split()) for k, v in (raw.get("references") or {}).items()}
    out = {}

    def val(entry, key, name):
        block = entry.get(key)
        if not isinstance(block, dict) or block.get("source") not in refs or "value" not in block:
            raise InputError(f"films.yaml: {name} {key} needs a value and a known source")
        return float(block["value"]), refs[block["source"]]

    for name, entry in (raw.get("materials") or {}).items():
        sources: dict[str, str] = {}
        rho, sources["rho"] = val(entry, "rho", name)
        if "trigonal" in entry:
            blk = dict(entry["trigonal"])
            if blk.pop("source", None) not in refs:
                raise InputError(f"films.yaml: {name} trigonal constants need a known source")
            keys = ("C11", "C12", "C13", "C14", "C33", "C44")
            voigt = trigonal_3m_voigt(*(float(blk[k]) for k in keys))
            sources["C"] = refs[entry["trigonal"]["source"]]
        else:
            E, sources["E"] = val(entry, "E", name)
            nu, sources["nu"] = val(entry, "nu", name)
            voigt = isotropic_voigt(E, nu)
        eps = None
        if "permittivity" in entry:
            e, sources["permittivity"] = val(entry, "permittivity", name)
            eps = e * np.eye(3)
        elif "permittivity_11" in entry:
            e11, sources["permittivity"] = val(entry, "permittivity_11", name)
            e33, _ = val(entry, "permittivity_33", name)
            eps = np.diag([e11, e11, e33])
        out[str(name)] = {"voigt": np.asarray(voigt, dtype=float), "rho": rho, "eps_r": eps,
                          "aliases": tuple(str(a) for a in entry.get("aliases", ())), "sources": sources}
    return out


def available_films() -> list[str]:
    """Names of the isotropic film materials of ``films.yaml``."""
    return sorted(_film_db())


def hill_average(C6) -> tuple[float, float]:
    """Voigt-Reuss-Hill bulk and shear moduli (GPa) of an untextured polycrystal of Voigt stiffness C6 (GPa).

    Parameters
    ----------
    C6 : array_like, shape (6, 6)

    Returns
    -------
    K, G : float
        Hill averages (mean of the Voigt and Reuss bounds), GPa.
    """
    C = np.asarray(C6, dtype=float)
    S = np.linalg.inv(C)
    Kv = (C[0, 0] + C[1, 1] + C[2, 2] + 2 * (C[0, 1] + C[1, 2] + C[0, 2])) / 9
    Gv = (C[0, 0] + C[1, 1] + C[2, 2] - C[0, 1] - C[1, 2] - C[0, 2] + 3 * (C[3, 3] + C[4, 4] + C[5, 5])) / 15
    Kr = 1 / (S[0, 0] + S[1, 1] + S[2, 2] + 2 * (S[0, 1] + S[1, 2] + S[0, 2]))
    Gr = 15 / (4 * (S[0, 0] + S[1, 1] + S[2, 2]) - 4 * (S[0, 1] + S[1, 2] + S[0, 2])
               + 3 * (S[3, 3] + S[4, 4] + S[5, 5]))
    return 0.5 * (Kv + Kr), 0.5 * (Gv + Gr)


def film_catalog() -> list[CatalogEntry]:
    """The film database as catalog entries (database ``"film"``), for the one did-you-mean
    (:func:`surfwave.real_crystals.catalog.unknown_name`)."""
    rows = []
    for n, rec in _film_db().items():
        iso = rec["voigt"][0, 3] == 0 and np.isclose(rec["voigt"][0, 0], rec["voigt"][2, 2])
        rows.append(CatalogEntry(n, "film", rec["aliases"], "isotropic" if iso else "anisotropic", rec["rho"], False))
    return rows


def lookup(name: str, where: str = "material", *, film: bool = True) -> dict:
    """The record of a named material: ``name``, ``voigt`` (6, 6) GPa, ``rho``, ``e`` (3, 6) or None, ``eps_r``.

    A film name is looked up in ``films.yaml`` first (so "SiO2" is fused silica for a film), a
    substrate name in the crystal databases first (so "SiO2" is alpha-quartz for a substrate).
    A crystal is resolved by :func:`surfwave.resolve.resolve_constants` (the names, aliases and
    checks of :func:`surfwave.material`), its piezoelectric record where it has one (GaAs).

    Raises
    ------
    InputError
        An unknown name: the message of :func:`surfwave.material` (did you mean, the known
        crystals), the film database added to both, after ``where``.
    """
    from surfwave.real_crystals.materials import get_material
    from surfwave.resolve import find_crystal, resolve_constants

    key = str(name).strip()
    if film:
        hit = _from_film_db(key)
        if hit is not None:
            return hit
    if key.casefold().endswith("-poly"):
        try:
            m = get_material(key[:-5])
        except InputError as exc:
            raise InputError(f"{where}: {exc}") from None
        K, G = hill_average(m.voigt)
        lam = K - 2 * G / 3
        C = cubic_voigt(lam + 2 * G, lam, G)   # isotropic: a cubic stiffness with C11 - C12 = 2 C44
        return {"name": f"{m.name}-poly", "voigt": C, "rho": m.rho, "e": None, "eps_r": None, "conductor": False}
    elastic, piezo = find_crystal(key)
    if elastic is None and piezo is None:
        hit = _from_film_db(key)
        if hit is not None:
            return hit
        unknown = unknown_name(key, "elastic", extra=film_catalog())
        raise InputError(f"{where}: {unknown} (or '<cubic>-poly', the isotropic average of a cubic crystal)")
    try:
        c = resolve_constants(key, piezoelectric=piezo is not None)
    except InputError as exc:
        raise InputError(f"{where}: {exc}") from None
    rec = piezo if piezo is not None else elastic
    assert rec is not None
    return {"name": rec.name, "voigt": c.voigt, "rho": c.rho, "e": c.piezo, "eps_r": c.permittivity,
            "conductor": False}


def _from_film_db(key: str) -> dict | None:
    """The record of a film-database name or alias (matched as every crystal name is: :func:`name_key`)."""
    want = name_key(key)
    for n, rec in _film_db().items():
        if want in (name_key(n), *(name_key(a) for a in rec["aliases"])):
            return {"name": n, "voigt": rec["voigt"].copy(), "rho": rec["rho"], "e": None,
                    "eps_r": None if rec["eps_r"] is None else rec["eps_r"].copy(), "conductor": False}
    return None
