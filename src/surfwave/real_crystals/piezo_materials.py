"""Piezoelectric crystals by name, and named SAW cuts (Euler angles + published values).

The numbers live in ``piezoelectric.yaml`` next to this module (C in GPa at constant field,
e in C/m^2, clamped relative permittivity, rho in kg/m^3; every block names its source and
each entry says how its numbers were checked). This module reads the file once, builds the
full tensors from the independent constants by the class's symmetry rules
(:mod:`surfwave.solvers.piezo_tensors`), validates them (:func:`check_piezo_record`) and hands
out :class:`PiezoMaterial` records and :class:`Cut` records.

Examples
--------
>>> ln = get_piezo_material("LiNbO3-Warner1967")
>>> ln.crystal_class, ln.rho, float(ln.voigt[0, 3]), float(ln.e[1, 1])
('3m', 4700.0, 9.0, 2.5)
>>> cut = get_cut("128° Y-X")
>>> cut.name, cut.material, cut.euler
('128Y-X LiNbO3', 'LiNbO3-Warner1967', (0.0, 38.0, 0.0))
>>> lab_tensors(ln, cut.lab_axes)["C"].shape
(3, 3, 3, 3)
"""
from __future__ import annotations

import difflib
from dataclasses import dataclass, field, replace
from functools import lru_cache
from importlib import resources
from pathlib import Path
from typing import Any, Callable, Mapping

import numpy as np
import yaml
from numpy.typing import ArrayLike

from surfwave.data.paper import SAFE_LOADER
from surfwave.errors import InputError
from surfwave.real_crystals.catalog import name_key
from surfwave.real_crystals.materials import read_constants
from surfwave.real_crystals.toec_classes import TOEC_NAMES, toec_from_named, toec_from_user
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.piezo_tensors import (
    EPS0,
    cubic_43m_piezo,
    hexagonal_6mm_piezo,
    hexagonal_6mm_voigt,
    piezo_voigt_to_tensor,
    rotate3,
    trigonal_3m_piezo,
    trigonal_3m_voigt,
    trigonal_32_piezo,
    uniaxial_eps,
)
from surfwave.solvers.tensors import rotate2, rotate4, voigt_to_tensor
from surfwave.validate import MAX_CONSTANT_GPA

#: Per crystal class: (independent C names or None for "from materials.yaml", e names, eps names,
#: C builder, e builder).
CLASSES: dict[str, tuple[tuple[str, ...] | None, tuple[str, ...], tuple[str, ...],
                        Callable[..., np.ndarray] | None, Callable[..., np.ndarray]]] = {
    "3m": (("C11", "C12", "C13", "C14", "C33", "C44"), ("e15", "e22", "e31", "e33"), ("eps11", "eps33"),
           trigonal_3m_voigt, trigonal_3m_piezo),
    "32": (("C11", "C12", "C13", "C14", "C33", "C44"), ("e11", "e14"), ("eps11", "eps33"),
           trigonal_3m_voigt, trigonal_32_piezo),
    "6mm": (("C11", "C12", "C13", "C33", "C44"), ("e15", "e31", "e33"), ("eps11", "eps33"),
            hexagonal_6mm_voigt, hexagonal_6mm_piezo),
    "-43m": (None, ("e14",), ("eps11",), None, cubic_43m_piezo),
}
#: Largest stiffness accepted, GPa (a value above this was almost surely written in Pa).
C_MAX_GPA = MAX_CONSTANT_GPA


@dataclass(frozen=True, eq=False)
class PiezoMaterial:
    """One piezoelectric crystal (one published constant set).

    Attributes
    ----------
    name : str
        Canonical name, e.g. ``"LiNbO3-Kovacs1990"``, ``"quartz-Bechmann1958"``, ``"AlN"``.
    formula : str
    crystal_class : {"3m", "32", "6mm", "-43m"}
    rho : float
        Density, kg/m^3.
    voigt : ndarray, shape (6, 6), float64
        Stiffness at constant electric field, GPa, crystal axes (standard setting).
    e : ndarray, shape (3, 6), float64
        Piezoelectric stress constants e_kI, C/m^2.
    eps_r : ndarray, shape (3, 3), float64
        Clamped relative permittivity (eps^S / EPS0) unless ``note`` says otherwise.
    constants : dict of str to float
        The independent constants as printed (GPa, C/m^2, relative).
    setting : str
        Axis convention of the set (IEEE 1949 / 1978 / 1987, signs).
    sources : dict of str to str
        ``"rho"``, ``"C"``, ``"e"``, ``"eps_r"`` -> full citation.
    note : str
        How the numbers were checked, and doubts.
    aliases : tuple of str
    status : str
        "" for a checked set; "unverified: ..." or "provisional: ..." (piezoelectric.yaml
        ``status``) for one whose numbers were not checked against a second copy:
        :func:`note_status` says so at run time.
    toec_voigt : ndarray, shape (6, 6, 6), or None
        Brugger third-order constants, GPa, crystal axes (``sources["toec"]`` names them); None
        where the database has none (every non-cubic crystal so far). GaAs takes the set of
        the elastic database's GaAs entry.
    """

    name: str
    formula: str
    crystal_class: str
    rho: float
    voigt: np.ndarray
    e: np.ndarray
    eps_r: np.ndarray
    constants: dict
    setting: str
    sources: dict
    note: str = ""
    aliases: tuple = field(default_factory=tuple)
    toec_voigt: np.ndarray | None = None
    status: str = ""

    @property
    def C_tensor(self) -> np.ndarray:
        """Stiffness C_ijkl in Pa, shape (3, 3, 3, 3)."""
        return voigt_to_tensor(self.voigt) * 1e9

    @property
    def e_tensor(self) -> np.ndarray:
        """Piezoelectric stress constants e_kij in C/m^2, shape (3, 3, 3)."""
        return piezo_voigt_to_tensor(self.e)

    @property
    def eps(self) -> np.ndarray:
        """Absolute clamped permittivity eps_kl in F/m, shape (3, 3)."""
        return self.eps_r * EPS0


@dataclass(frozen=True)
class Cut:
    """A named SAW cut: crystal set, Euler angles and the published values.

    Attributes
    ----------
    name : str
    material : str
        Canonical name of the :class:`PiezoMaterial` whose constants the published values use.
    euler : tuple of float
        (phi, theta, psi), degrees, SAW ZXZ convention (:mod:`surfwave.solvers.euler`).
    description : str
    wave : {"rayleigh", "leaky"}
    published : dict
        ``v_free``, ``v_metallized``, ``v`` (m/s), ``K2_percent``; ``source`` (citation).
    note : str
    aliases : tuple of str
    """

    name: str
    material: str
    euler: tuple
    description: str
    wave: str
    published: dict
    note: str = ""
    aliases: tuple = ()

    @property
    def lab_axes(self) -> np.ndarray:
        """Our lab axes (rows x1 propagation, x2 inward normal, x3) in crystal axes, (3, 3)."""
        return euler_lab_axes(*self.euler)


def check_piezo_record(voigt: ArrayLike, e: ArrayLike, eps_r: ArrayLike, rho: float, name: str = "record") -> None:
    """Refuse a constant set that cannot be right.

    Parameters
    ----------
    voigt : array_like, shape (6, 6)
        Stiffness, GPa. Must be finite, symmetric, |C| <= 1e5 GPa (larger means Pa) and
        positive definite.
    e : array_like, shape (3, 6)
        Piezoelectric stress constants, C/m^2, finite.
    eps_r : array_like, shape (3, 3)
        Relative permittivity, finite, symmetric, positive definite.
    rho : float
        Density, kg/m^3, finite and > 0.
    name : str
        Used in the messages.

    Raises
    ------
    InputError
        With the offending value in the message.
    """
    C = np.asarray(voigt, dtype=float)
    e = np.asarray(e, dtype=float)
    eps = np.asarray(eps_r, dtype=float)
    if C.shape != (6, 6):
        raise InputError(f"{name}: stiffness must be 6 x 6 (Voigt, GPa), got shape {C.shape}")
    if e.shape != (3, 6):
        raise InputError(f"{name}: piezoelectric matrix e must be 3 x 6 (C/m^2), got shape {e.shape}")
    if eps.shape != (3, 3):
        raise InputError(f"{name}: eps_r must be 3 x 3, got shape {eps.shape}")
    for label, arr in (("stiffness", C), ("e", e), ("eps_r", eps)):
        if not np.all(np.isfinite(arr)):
            bad = arr[~np.isfinite(arr)][0]
            raise InputError(f"{name}: non-finite {label} entry {bad}")
    rho = float(rho)
    if not np.isfinite(rho) or rho <= 0:
        raise InputError(f"{name}: density must be finite and > 0 kg/m^3, got {rho}")
    big = np.max(np.abs(C))
    if big > C_MAX_GPA:
        raise InputError(f"{name}: stiffness entry {big:g} exceeds {C_MAX_GPA:g} GPa; constants must be "
                         "in GPa, not Pa")
    if not np.allclose(C, C.T, rtol=0, atol=1e-12 * max(big, 1.0)):
        raise InputError(f"{name}: stiffness is not symmetric (max |C - C^T| = {np.max(np.abs(C - C.T)):g} GPa)")
    wc = np.linalg.eigvalsh(C)
    if wc[0] <= 0:
        raise InputError(f"{name}: stiffness is not positive definite (smallest eigenvalue {wc[0]:g} GPa)")
    if not np.allclose(eps, eps.T, rtol=0, atol=1e-12 * max(np.max(np.abs(eps)), 1.0)):
        raise InputError(f"{name}: eps_r is not symmetric: {eps.tolist()}")
    we = np.linalg.eigvalsh(eps)
    if we[0] <= 0:
        raise InputError(f"{name}: eps_r is not positive definite (smallest eigenvalue {we[0]:g}), "
                         f"eps_r = {eps.tolist()}")


def read_database() -> dict:
    """The piezoelectric database as stored (piezoelectric.yaml: ``materials``, ``cuts``,
    ``references``), read afresh; :func:`get_piezo_material` and :func:`get_cut` give checked records."""
    text = resources.files("surfwave.real_crystals").joinpath("piezoelectric.yaml").read_text(encoding="utf-8")
    return yaml.load(text, Loader=SAFE_LOADER)


def _block(entry: dict, key: str, names: tuple, where: str, refs: dict) -> tuple[dict, str]:
    """Constants ``names`` of the block ``key`` of one entry (:func:`materials.read_constants`)."""
    return read_constants(entry.get(key), names, f"{where}: {key}", refs)


def _build(name: str, entry: dict, refs: dict) -> PiezoMaterial:
    cls = str(entry.get("crystal_class"))
    if cls not in CLASSES:
        raise InputError(f"piezo material {name}: crystal_class {cls!r} not one of {sorted(CLASSES)}")
    c_names, e_names, eps_names, c_builder, e_builder = CLASSES[cls]
    where = f"piezo material {name}"
    e_vals, e_src = _block(entry, "e", e_names, where, refs)
    eps_vals, eps_src = _block(entry, "eps_r", eps_names, where, refs)
    if c_names is None:  # cubic: the elastic set of materials.yaml
        from surfwave.real_crystals.materials import get_material

        base = get_material(entry["elastic_from"])
        voigt = np.array(base.voigt, dtype=float)
        rho = float(base.rho)
        c_vals = dict(base.constants)
        src = entry.get("C_source")
        if src not in refs:
            raise InputError(f"{where}: C_source {src!r} is not a key of the references")
        c_src = rho_src = refs[src]
        eps = np.eye(3) * eps_vals["eps11"]
        C3 = base.toec_voigt                                    # the elastic entry's set, one place
        toec_src = (f"the elastic database's {base.name} entry: {base.sources.get('C111', '')}"
                    if C3 is not None else "")
    else:
        c_vals, c_src = _block(entry, "C", c_names, where, refs)
        (rho_vals, rho_src) = _block(entry, "rho", ("value",), where, refs)
        rho = rho_vals["value"]
        assert c_builder is not None  # every class with its own C names has a builder
        voigt = c_builder(*(c_vals[k] for k in c_names))
        eps = uniaxial_eps(eps_vals["eps11"], eps_vals["eps33"])
        C3, toec_src = None, ""
        if "toec" in entry:                                     # Brugger constants by name, GPa
            t_vals, toec_src = _block(entry, "toec", TOEC_NAMES[cls], where, refs)
            C3 = toec_from_named(cls, t_vals)
    e = e_builder(*(e_vals[k] for k in e_names))
    check_piezo_record(voigt, e, eps, rho, name=where)
    for arr in (voigt, e, eps):
        arr.setflags(write=False)
    return PiezoMaterial(
        name=name, formula=str(entry.get("formula", name)), crystal_class=cls, rho=float(rho), voigt=voigt,
        e=e, eps_r=eps, constants={**c_vals, **e_vals, **eps_vals},
        setting=" ".join(str(entry.get("setting", "")).split()),
        sources={"rho": rho_src, "C": c_src, "e": e_src, "eps_r": eps_src, **({"toec": toec_src} if toec_src else {})},
        note=" ".join(str(entry.get("note", "")).split()),
        aliases=tuple(str(a) for a in entry.get("aliases", ())),
        toec_voigt=C3,
        status=" ".join(str(entry.get("status", "")).split()),
    )


def _key(text: str) -> str:
    """Lookup key: case-folded, without spaces, hyphens, underscores, degree signs or 'deg'."""
    return name_key(text)


def _lookup(items: dict, kind: str) -> dict[str, str]:
    table: dict[str, str] = {}
    for n, rec in items.items():
        for alias in (n, *rec.aliases):
            k = _key(alias)
            if k in table and table[k] != n:
                raise InputError(f"piezoelectric.yaml: {kind} name {alias!r} used by both {table[k]} and {n}")
            table[k] = n
    return table


@lru_cache(maxsize=1)
def _database() -> tuple[dict, dict, dict, dict]:
    raw = read_database()
    refs = {str(k): " ".join(str(v).split()) for k, v in raw["references"].items()}
    mats = {str(n): _build(str(n), e, refs) for n, e in raw["materials"].items()}
    cut_refs = {str(k): " ".join(str(v).split()) for k, v in raw["cut_references"].items()}
    cuts = {}
    for n, c in raw["cuts"].items():
        if c["material"] not in mats:
            raise InputError(f"cut {n}: material {c['material']!r} is not in piezoelectric.yaml")
        pub = dict(c["published"])
        if pub.get("source") not in cut_refs:
            raise InputError(f"cut {n}: source {pub.get('source')!r} is not a key of cut_references")
        pub["source"] = cut_refs[pub["source"]]
        euler = tuple(float(a) for a in c["euler"])
        euler_lab_axes(*euler)  # validates
        cuts[str(n)] = Cut(name=str(n), material=str(c["material"]), euler=euler,
                           description=str(c.get("description", "")), wave=str(c.get("wave", "rayleigh")),
                           published=pub, note=" ".join(str(c.get("note", "")).split()),
                           aliases=tuple(str(a) for a in c.get("aliases", ())))
    return mats, _lookup(mats, "material"), cuts, _lookup(cuts, "cut")


def available_piezo_materials() -> list[str]:
    """Canonical names of every piezoelectric constant set, sorted."""
    return sorted(_database()[0])


def _unknown(name, lookup: dict, names: list, kind: str) -> InputError:
    close = difflib.get_close_matches(_key(name), list(lookup), n=5, cutoff=0.6)
    hint = list(dict.fromkeys(lookup[c] for c in close))
    extra = f" (did you mean {' or '.join(hint)}?)" if hint else ""
    return InputError(f"unknown {kind} {name!r}{extra}; known {kind}s: {', '.join(names)}")


def get_piezo_material(name: str | PiezoMaterial) -> PiezoMaterial:
    """The record of a piezoelectric crystal (a :class:`PiezoMaterial` passes through).

    Parameters
    ----------
    name : str
        Canonical name or alias, case-, space- and hyphen-insensitive: ``"LiNbO3"`` (the
        Kovacs 1990 set), ``"LiNbO3-Warner1967"``, ``"quartz"``, ``"LGS"``, ``"AlN"``, ...

    Raises
    ------
    InputError
        Unknown name: :func:`surfwave.real_crystals.catalog.unknown_name` (the database that
        holds it, or the closest names and every known one, over both databases).
    """
    if isinstance(name, PiezoMaterial):
        return name
    mats, lookup, _, _ = _database()
    k = _key(name)
    if k in lookup:
        return mats[lookup[k]]
    from surfwave.real_crystals.catalog import unknown_name

    raise unknown_name(name, "piezoelectric")


def note_status(material: PiezoMaterial) -> str:
    """Say once (a :class:`surfwave.errors.ConstantsNote` warning, one line) that ``material`` is an
    unverified or provisional constant set; returns the note ("" for a checked set).

    Python shows a warning once per distinct text and place, so a sweep over many points of
    one set notes it once. ``python -W "ignore:constant set"`` (or
    ``warnings.filterwarnings("ignore", category=ConstantsNote)``) silences it.

    Examples
    --------
    >>> import warnings
    >>> with warnings.catch_warnings(record=True) as seen:
    ...     warnings.simplefilter("always")
    ...     text = note_status(get_piezo_material("LiTaO3"))
    >>> text.startswith("constant set LiTaO3-Kovacs1990 is unverified")
    True
    """
    import warnings

    from surfwave.errors import ConstantsNote

    if not material.status:
        return ""
    kind, _, why = material.status.partition(":")
    text = (f"constant set {material.name} is {kind.strip()} ({why.strip()}); see "
            "docs/piezoelectric-materials.md before relying on the last digits")
    warnings.warn(text, ConstantsNote, stacklevel=_caller_level())
    return text


def _caller_level() -> int:
    """``stacklevel`` of the first frame outside the surfwave package (the caller's own line)."""
    import sys
    from types import FrameType

    package = str(Path(__file__).resolve().parents[1])
    frame: FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and str(Path(frame.f_code.co_filename).resolve()).startswith(package):
        frame, level = frame.f_back, level + 1
    return level


def available_cuts() -> list[str]:
    """Canonical names of the named cuts, sorted."""
    return sorted(_database()[2])


def get_cut(name: str) -> Cut:
    """A named cut by name or alias (``"128Y-X"``, ``"128YX"``, ``"128° Y-X"``, ``"ST-X quartz"``).

    Raises
    ------
    InputError
        Unknown name; the message lists the known cuts.
    """
    _, _, cuts, lookup = _database()
    k = _key(name)
    if k in lookup:
        return cuts[lookup[k]]
    raise _unknown(name, lookup, available_cuts(), "cut")


def with_toec(material: PiezoMaterial, toec: Mapping[str, float] | ArrayLike,
              source: str = "given by the caller") -> PiezoMaterial:
    """``material`` carrying a caller's third-order constants, checked for its class.

    Parameters
    ----------
    material : PiezoMaterial
    toec : mapping or array_like
        Named constants of the class or a (6, 6, 6) Voigt array, GPa
        (:func:`surfwave.real_crystals.toec_classes.toec_from_user`).
    source : str
        What ``sources["toec"]`` says.

    Returns
    -------
    PiezoMaterial
        A copy with ``toec_voigt`` set.
    """
    cls = material.crystal_class if material.crystal_class in TOEC_NAMES else None
    return replace(material, toec_voigt=toec_from_user(toec, cls), sources={**material.sources, "toec": source})


class _UniqueKeyLoader(yaml.SafeLoader):
    """A safe YAML loader that refuses a key given twice in one mapping (YAML keeps the last
    silently: a second ``C111`` would replace the first)."""

    def construct_mapping(self, node, deep=False):  # noqa: D102 (yaml API)
        seen: dict = {}
        for key_node, _ in node.value:
            key = self.construct_object(key_node, deep=deep)
            if key in seen:
                raise yaml.constructor.ConstructorError(
                    None, None, f"key {key!r} is given twice (lines {seen[key] + 1} and "
                    f"{key_node.start_mark.line + 1}); give each constant once", key_node.start_mark)
            seen[key] = key_node.start_mark.line
        return super().construct_mapping(node, deep=deep)


def read_toec_file(path: str | Path) -> tuple[dict, bytes]:
    """Named third-order constants (GPa) from a YAML mapping ``name: value`` (``source:`` allowed).

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    (dict, bytes)
        The mapping as read, and the file's bytes (for a content hash).

    Raises
    ------
    InputError
        Unreadable file, invalid YAML, a key given twice, not a mapping, or a value that is not
        a number.
    """
    try:
        text = Path(path).read_bytes()
    except OSError as err:
        raise InputError(f"cannot read {str(path)!r} ({err.strerror or err})") from None
    try:
        data = yaml.load(text, Loader=_UniqueKeyLoader)
    except yaml.YAMLError as err:
        raise InputError(f"{str(path)!r} is not valid YAML: {' '.join(str(err).split())}") from None
    if not isinstance(data, dict) or not data:
        raise InputError(f"{str(path)!r} must be a mapping of named third-order constants in GPa (and an "
                         f"optional 'source'), got {type(data).__name__}")
    data = {str(k): v for k, v in data.items()}
    bad = [k for k, v in data.items() if k != "source" and (isinstance(v, bool) or not isinstance(v, (int, float)))]
    if bad:
        raise InputError(f"{str(path)!r}: these values are not numbers (GPa): {bad}")
    return data, text


def lab_tensors(material: str | PiezoMaterial, R: ArrayLike) -> dict[str, Any]:
    """A crystal's tensors in lab axes, SI units, ready for the piezoelectric Stroh solver.

    Parameters
    ----------
    material : str or PiezoMaterial
    R : array_like, shape (..., 3, 3)
        Rows = lab axes in crystal coordinates (:func:`surfwave.solvers.euler.euler_lab_axes`,
        :func:`surfwave.solvers.orientation.lab_axes`).

    Returns
    -------
    dict
        ``C`` (..., 3, 3, 3, 3) Pa; ``e`` (..., 3, 3, 3) C/m^2 (e_kij); ``eps`` (..., 3, 3) F/m;
        ``rho`` float kg/m^3.
    """
    m = get_piezo_material(material)
    R = np.asarray(R, dtype=float)
    return {"C": rotate4(m.C_tensor, R), "e": rotate3(m.e_tensor, R), "eps": rotate2(m.eps, R), "rho": m.rho}
