"""Every way of asking :func:`surfwave.material` a question, turned into one checked :class:`~surfwave.case.Case`.

The crystal: a name of the elastic database (``"Cu"``), of the piezoelectric database
(``"LiNbO3"``), a record, cubic C11, C12, C44 or a Voigt matrix (with ``piezo=`` and
``permittivity=`` for a piezoelectric crystal); the orientation: a surface and a direction or
angles, SAW Euler angles, or a named cut; the stress: a scalar (uniaxial along each propagation
direction), a 3 x 3 tensor in crystal axes, or one of them per point; the third-order constants:
off, the database's (True), or the caller's (six cubic values, a mapping of the class's names, a
(6, 6, 6) array); the electrical condition. The piezoelectric part is switched on by the
constants: a crystal with e and eps (a piezoelectric name, ``piezo=``), or any crystal asked
with Euler angles, a cut or an electrical condition (then e = 0, eps = 1: the potential
decouples and the answer is the elastic one). Each check runs once, in
:func:`surfwave.case.make_case`.

Examples
--------
>>> case = resolve_material("LiNbO3", cut="128Y-X")
>>> case.piezo, case.boundary.name, case.euler.tolist(), case.scalar
(True, 'free', [[0.0, 38.0, 0.0]], True)
>>> resolve_material("Cu", euler=(0, 0, 0), surface="(110)")
Traceback (most recent call last):
...
surfwave.errors.InputError: euler= sets the surface and the propagation direction: do not also give surface=, direction= or angle= (got surface='(110)')
"""  # noqa: E501 (a doctest's expected message)
from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace
from functools import lru_cache
from typing import Any

import numpy as np

from surfwave import validate
from surfwave.case import Case, check_constants, make_case
from surfwave.errors import InputError
from surfwave.real_crystals.loads import stress_tensor
from surfwave.real_crystals.materials import CUBIC_TOEC, Material, get_material
from surfwave.real_crystals.piezo_materials import (
    PiezoMaterial,
    get_cut,
    get_piezo_material,
    note_status,
    with_toec,
)
from surfwave.real_crystals.stressed_wave import Constants
from surfwave.real_crystals.toec import cubic_toec
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.orientation import lab_axes, reference_direction, surface_frame, surface_normal
from surfwave.solvers.tensors import cubic_voigt

__all__ = ["CONSTANT_KEYS", "DEFAULT_DIRECTION", "DEFAULT_SURFACE", "find_crystal", "piezo_wanted", "prestress",
           "resolve_constants", "resolve_material"]

#: Orientation of :func:`surfwave.material` when none is given: (001) surface, [100] direction.
DEFAULT_SURFACE, DEFAULT_DIRECTION = "(001)", "[100]"


def find_crystal(name) -> tuple[Material | None, PiezoMaterial | None]:
    """The records of a name in the elastic and the piezoelectric database (None where absent).

    A :class:`Material` or :class:`PiezoMaterial` passes through into its slot; anything that is
    not a string gives (None, None).
    """
    if isinstance(name, Material):
        return name, None
    if isinstance(name, PiezoMaterial):
        return None, name
    if not isinstance(name, str):
        return None, None
    return _find_by_name(name)


@lru_cache(maxsize=256)
def _find_by_name(name: str) -> tuple[Material | None, PiezoMaterial | None]:
    """:func:`find_crystal` of a string, once per name (a miss in a database costs a
    close-match search for its message; the records are immutable)."""
    found: list[Any] = []
    for lookup in (get_material, get_piezo_material):
        try:
            found.append(lookup(name))
        except InputError:
            found.append(None)
    return found[0], found[1]


def _cubic_six(toec) -> tuple:
    """The cubic six (C111, ..., C456) of a mapping by name, GPa (a ``source`` key ignored)."""
    names = dict(toec)
    names.pop("source", None)
    if set(names) != set(CUBIC_TOEC):
        raise InputError(f"third-order constants by name: here the cubic six {list(CUBIC_TOEC)} (GPa), got "
                         f"{sorted(names)}; a crystal of the piezoelectric database takes its class's names "
                         "(surfwave.real_crystals.toec_classes.TOEC_NAMES); else give a (6, 6, 6) Voigt array")
    return tuple(names[k] for k in CUBIC_TOEC)


def _caller_toec(toec) -> np.ndarray:
    """A caller's cubic third-order set: six values, a mapping of the six names, or (6, 6, 6); GPa."""
    if isinstance(toec, Mapping):
        toec = _cubic_six(toec)
    validate.toec_array(toec)                                       # numbers in a regular array
    t = validate.gpa_constants(toec, "third-order constants")
    if t.shape == (6,):
        return cubic_toec(*t)
    if t.shape == (6, 6, 6):
        return t
    raise InputError("toec must be True, (C111, C112, C123, C144, C155, C456) in GPa (a sequence or a "
                     f"mapping of these names) or a (6, 6, 6) Voigt array; got shape {t.shape}")


def _elastic_constants(C11, C12, C44, rho, voigt, toec) -> tuple[np.ndarray, Any, np.ndarray | None]:
    """(Voigt C (6, 6) GPa, rho, C3 (6, 6, 6) or None) of a crystal of the elastic database or
    given by its constants."""
    C3 = None
    elastic, _ = find_crystal(C11)
    if isinstance(C11, (str, Material)):
        m = elastic if elastic is not None else get_material(C11)   # unknown: the database's message
        if any(v is not None for v in (C12, C44, voigt)):
            raise InputError(f"material {m.name!r} given by name: do not also give C12, C44 or voigt=")
        C6 = np.array(m.voigt)
        rho = m.rho if rho is None else rho
        if toec is True:
            if m.toec is None:
                raise InputError(f"no third-order elastic constants for {m.name} in the materials database "
                                 f"(missing: {', '.join(CUBIC_TOEC)}); give toec=(C111, C112, C123, C144, "
                                 "C155, C456) in GPa")
            C3 = m.toec_voigt
    elif voigt is not None:
        if any(v is not None for v in (C11, C12, C44)):
            raise InputError("give either voigt= or C11, C12, C44, not both")
        C6 = validate.stiffness(voigt)
    else:
        for key, value in (("C11", C11), ("C12", C12), ("C44", C44)):
            if value is None:
                raise InputError(f"{key} is missing: give C11, C12, C44 (GPa), voigt= or a material name")
            if isinstance(value, bool) or not isinstance(value, (int, float, np.integer, np.floating)):
                raise InputError(f"{key} must be one number (GPa), got {value!r}")
        C6 = cubic_voigt(C11, C12, C44)
        if toec is True:
            raise InputError("toec=True takes the third-order constants from the materials database: "
                             "give the material by name (e.g. material('Cu', ...)) or pass toec=(C111, ...)")
    if toec is not None and toec is not True and toec is not False:
        C3 = _caller_toec(toec)
    if rho is None:
        raise InputError("the density rho (kg/m^3) is missing")
    return validate.gpa_constants(C6), validate.density(rho), C3


def piezo_wanted(C11, piezo=None, permittivity=None, euler=None, cut=None, electrical=None) -> bool:
    """Whether the piezoelectric part is switched on: any piezoelectric argument, or a name
    found only in the piezoelectric database (or a PiezoMaterial).

    Examples
    --------
    >>> piezo_wanted("LiNbO3"), piezo_wanted("GaAs"), piezo_wanted("GaAs", euler=(45, 0, 0)), piezo_wanted("Cu")
    (True, False, True, False)
    """
    if any(v is not None for v in (piezo, permittivity, euler, cut, electrical)):
        return True
    elastic, piezo_rec = find_crystal(C11)
    return piezo_rec is not None and elastic is None


def _constants(C11, C12, C44, rho, voigt, toec, piezo, permittivity, cut, cut_material) -> tuple[Constants, bool]:
    """The constants of a piezoelectric-route question, and whether toec is used."""
    explicit_toec = toec is not None and toec is not False and toec is not True
    if C11 is None and voigt is None and cut_material is not None:
        C11 = cut_material                                          # cut="128Y-X LiNbO3" alone
    elastic, piezo_rec = find_crystal(C11)
    by_name = piezo_rec is not None and (elastic is None or piezo is None)
    if by_name:
        assert piezo_rec is not None
        if any(v is not None for v in (C12, C44, voigt, piezo, permittivity)):
            raise InputError(f"material {C11!r} given by name: do not also give C12, C44, voigt=, piezo= or "
                             "permittivity=")
        mat = piezo_rec
        note_status(mat)                                            # one line for an unverified set
        if explicit_toec:                                           # the caller's set, checked for the class
            mat = with_toec(mat, toec)
        if cut_material is not None:
            want = get_piezo_material(cut_material).formula
            if mat.formula != want:
                raise InputError(f"cut {cut!r} is a cut of {want}, not of {C11!r} ({mat.formula})")
        constants = Constants.from_piezo_material(mat)
        if rho is not None:
            constants = replace(constants, rho=validate.density(rho))
        return constants, explicit_toec or toec is True
    C6, rho, C3 = _elastic_constants(C11, C12, C44, rho, voigt, toec)
    if piezo is None and permittivity is None:                      # non-piezoelectric crystal, e = 0
        piezo, permittivity = np.zeros((3, 6)), np.eye(3)
    elif piezo is None or permittivity is None:
        raise InputError("a piezoelectric crystal needs both piezo= (e, 3 x 6, C/m^2) and permittivity= "
                         "(eps_r, 3 x 3, relative)")
    e6, er = validate.piezo_constants(piezo, permittivity)
    return Constants(C6, rho, C3, e6, er), explicit_toec or toec is True


#: The keys of a mapping of constants (:func:`resolve_constants`): :func:`surfwave.material`'s names.
CONSTANT_KEYS = ("C11", "C12", "C44", "rho", "voigt", "toec", "piezo", "permittivity")


def resolve_constants(crystal=None, C12=None, C44=None, rho=None, *, voigt=None, toec=None, piezo=None,
                      permittivity=None, piezoelectric: bool | None = None) -> Constants:
    """The checked natural-state constants of a crystal, asked as :func:`surfwave.material` asks them.

    The constants step of :func:`resolve_material` on its own, for a door that has its own
    orientation and stress (the layered solver's substrate and films): the same names and
    aliases of both databases, the same refusals in the same words, and the checks of
    :func:`surfwave.case.check_constants` (units and the Pa guard, density bounds, piezoelectric
    magnitudes, eps_r >= 1, the third-order set).

    Parameters
    ----------
    crystal : str, Material, PiezoMaterial, float, mapping or None
        A name of either database, a record, C11 (GPa), or a mapping of :data:`CONSTANT_KEYS`
        (``{"voigt": ..., "rho": ...}``; the other arguments must then be left out).
    C12, C44, rho, voigt, toec, piezo, permittivity
        As in :func:`surfwave.material` (GPa, kg/m^3, C/m^2, relative).
    piezoelectric : bool or None
        None decides by :func:`piezo_wanted` (a name found only in the piezoelectric database,
        or ``piezo=``/``permittivity=`` given); True takes the piezoelectric record of a name
        found in both databases (and e = 0, eps_r = 1 for an elastic crystal); False the
        elastic record.

    Returns
    -------
    Constants
        ``voigt`` (6, 6) GPa, ``rho`` kg/m^3, ``toec`` (6, 6, 6) GPa or None, ``piezo`` (3, 6)
        C/m^2 and ``permittivity`` (3, 3) or None.

    Raises
    ------
    InputError
        The refusal of :func:`surfwave.material` for the same constants, word for word.

    Examples
    --------
    >>> c = resolve_constants({"voigt": np.diag([3.0, 3, 3, 1, 1, 1]) * 100, "rho": 3000})
    >>> c.rho, c.piezo is None, resolve_constants("LiNbO3").piezo.shape
    (3000.0, True, (3, 6))
    >>> resolve_constants(168.4e9, 121.4, 75.4, 8960)
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: elastic constants must be in GPa; the largest is 1.684e+11, which looks like Pa (divide by 1e9)
    """  # noqa: E501 (a doctest's expected message)
    if isinstance(crystal, Mapping):
        if any(v is not None for v in (C12, C44, rho, voigt, toec, piezo, permittivity)):
            raise InputError("constants given as a mapping: give every constant in it")
        extra = sorted(set(crystal) - set(CONSTANT_KEYS))
        if extra:
            raise InputError(f"unknown keys {extra} in the constants; accepted: {list(CONSTANT_KEYS)}")
        kw = dict(crystal)
        crystal, C12, C44, rho = (kw.get(k) for k in ("C11", "C12", "C44", "rho"))
        voigt, toec, piezo, permittivity = (kw.get(k) for k in ("voigt", "toec", "piezo", "permittivity"))
    constants, use_toec = _route_constants(crystal, C12, C44, rho, voigt, toec, piezo, permittivity, piezoelectric)
    check_constants(constants, use_toec)
    return constants


def _route_constants(C11, C12, C44, rho, voigt, toec, piezo, permittivity, piezoelectric: bool | None,
                     cut=None, cut_material=None) -> tuple[Constants, bool]:
    """(unchecked constants, whether toec is used) of the elastic or the piezoelectric route."""
    if piezoelectric or (piezoelectric is None and piezo_wanted(C11, piezo, permittivity)):
        return _constants(C11, C12, C44, rho, voigt, toec, piezo, permittivity, cut, cut_material)
    C6, rho, C3 = _elastic_constants(C11, C12, C44, rho, voigt, toec)
    return Constants(C6, rho, C3), C3 is not None


def _euler_values(euler) -> np.ndarray:
    """Euler angles (phi, theta, psi) in degrees as a float array (3,) or (m, 3), checked
    (:func:`surfwave.validate.euler_angles`, the guard of every door)."""
    return validate.euler_angles(euler)


def _orientation(surface, direction, angle, euler, cut) -> dict:
    """Lab axes (m, 3, 3), scalar flag, Euler angles (m, 3) or None, angle (m,), cut material, words."""
    if cut is not None and euler is not None:
        raise InputError(f"give either cut= or euler=, not both (got cut={cut!r}, euler={euler!r})")
    cut_material = None
    if cut is not None or euler is not None:
        given = {k: v for k, v in (("surface", surface), ("direction", direction), ("angle", angle)) if v is not None}
        if given:
            what = "cut=" if cut is not None else "euler="
            raise InputError(f"{what} sets the surface and the propagation direction: do not also give surface=, "
                             f"direction= or angle= (got {', '.join(f'{k}={v!r}' for k, v in given.items())})")
    if cut is not None:
        c = get_cut(cut)
        euler, cut_material = c.euler, c.material
    if euler is not None:
        e = _euler_values(euler)
        R = euler_lab_axes(e)
        e = e.reshape(-1, 3)
        return {"axes": R.reshape(-1, 3, 3), "scalar": R.ndim == 2, "euler": e, "angle": e[:, 2].copy(),
                "cut_material": cut_material, "where": "of the Euler angles"}
    surface = DEFAULT_SURFACE if surface is None else surface
    which = angle if angle is not None else DEFAULT_DIRECTION if direction is None else direction
    if not isinstance(which, str):
        which = validate.angle_values(which, "direction" if angle is None else "angle")
    R = lab_axes(surface, which)
    scalar = R.ndim == 2
    R = R.reshape(-1, 3, 3)
    if isinstance(surface, str):      # the surface's frame, computed once per surface
        _, ref, nr = surface_frame(surface)
    else:
        ref = reference_direction(surface)
        nr = np.cross(surface_normal(surface), ref)
    ang = np.degrees(np.arctan2(R[:, 0] @ nr, R[:, 0] @ ref))
    return {"axes": R, "scalar": scalar, "euler": None, "angle": ang, "cut_material": None, "where": surface}


def prestress(stress, axes: np.ndarray) -> np.ndarray:
    """Cauchy prestress in crystal axes (m, 3, 3), GPa, from each accepted form.

    A scalar (uniaxial along each x1), an (m,) array (one value per point), a 3 x 3 tensor
    (crystal axes, the same at every point) or an (m, 3, 3) array. Units, finiteness,
    symmetry and sigma . n = 0 are checked by :func:`surfwave.case.make_case`.
    """
    m = axes.shape[0]
    s = validate.gpa_stress(stress)
    if s.shape == ():
        return stress_tensor("along", s, axes)
    if s.shape == (m,):                                             # uniaxial along each x1, one per point
        return stress_tensor("along", 1.0, axes) * s[..., None, None]
    if s.shape in ((3, 3), (m, 3, 3)):
        return np.broadcast_to(s, (m, 3, 3))
    raise InputError(f"stress must be a scalar (uniaxial along the propagation) or a 3 x 3 tensor in crystal axes "
                     f"(GPa), or one of them per orientation ((m,) or (m, 3, 3), m = {m}); got shape {s.shape}")


def resolve_material(C11=None, C12=None, C44=None, rho=None, direction=None, stress=0.0, surface=None, *,
                     voigt=None, angle=None, toec=None, piezo=None, permittivity=None, euler=None, cut=None,
                     electrical=None, leaky=None, piezoelectric: bool | None = None) -> Case:
    """The checked :class:`~surfwave.case.Case` of a :func:`surfwave.material` question (same arguments).

    ``surface`` and ``direction`` default to (001) and [100]; given together with ``euler=`` or
    ``cut=`` they are refused (the Euler angles set both). ``piezoelectric``: None decides by
    :func:`piezo_wanted`; True switches the piezoelectric part on for any crystal (e = 0 for a
    non-piezoelectric one).

    Raises
    ------
    InputError
        Every refusal of :func:`surfwave.material`, one line each, before any solve.
    """
    if leaky is not None and not isinstance(leaky, (bool, np.bool_)):
        raise InputError(f"leaky must be None, True or False, got {leaky!r}")
    orient = _orientation(surface, direction, angle, euler, cut)
    if piezoelectric is None:
        piezoelectric = piezo_wanted(C11, piezo, permittivity, euler, cut, electrical)
    constants, use_toec = _route_constants(C11, C12, C44, rho, voigt, toec, piezo, permittivity, piezoelectric,
                                           cut, orient["cut_material"])
    sigma = prestress(stress, orient["axes"])
    return make_case(constants, orient["axes"], sigma, electrical=electrical, toec=use_toec, leaky=leaky,
                     where=orient["where"], angle=orient["angle"], euler=orient["euler"], scalar=orient["scalar"])
