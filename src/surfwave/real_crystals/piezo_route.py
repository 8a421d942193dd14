"""The piezoelectric / Euler-angle branch of :func:`surfwave.material` (the front door delegates here).

:func:`surfwave.material` sends a call here when it carries ``piezo=``, ``permittivity=``,
``euler=``, ``cut=`` or ``electrical=``, or names a crystal found only in the piezoelectric
database (``"LiNbO3"``, ``"quartz"``, ...). A crystal of the elastic database (``"Cu"``, and
``"GaAs"`` unless a piezoelectric argument is given) keeps the elastic route. A
non-piezoelectric crystal given with ``euler=`` is solved here with e = 0 (the potential
decouples; the result equals the elastic solver's).
"""
from __future__ import annotations

from dataclasses import replace

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.real_crystals.piezo_wave import piezo_wave, resolve_piezo_material
from surfwave.real_crystals.stressed_wave import BULK_KEYS

__all__ = ["is_piezo_call", "material_piezo"]


def _piezo_only_name(name) -> bool:
    """True for a name found in the piezoelectric database but not in the elastic one."""
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.piezo_materials import get_piezo_material

    if not isinstance(name, str):
        from surfwave.real_crystals.piezo_materials import PiezoMaterial

        return isinstance(name, PiezoMaterial)
    try:
        get_material(name)
        return False
    except InputError:
        pass
    try:
        get_piezo_material(name)
        return True
    except InputError:
        return False


def is_piezo_call(C11, *, piezo=None, permittivity=None, euler=None, cut=None, electrical=None) -> bool:
    """Whether :func:`surfwave.material` must take the piezoelectric / Euler route."""
    return any(v is not None for v in (piezo, permittivity, euler, cut, electrical)) or _piezo_only_name(C11)


def _orientation(cut, euler, surface, direction, angle, material):
    """Lab axes (m, 3, 3), scalar flag, Euler angles (m, 3) or None, angle (m,), cut material name."""
    from surfwave.real_crystals.piezo_materials import get_cut
    from surfwave.solvers.euler import euler_lab_axes
    from surfwave.solvers.orientation import lab_axes, reference_direction, surface_normal

    if cut is not None and euler is not None:
        raise InputError(f"give either cut= or euler=, not both (got cut={cut!r}, euler={euler!r})")
    cut_material = None
    if cut is not None:
        c = get_cut(cut)
        euler, cut_material = c.euler, c.material
    if euler is not None:
        e = validate.euler_angles(euler)                            # numbers, (3,) or (m >= 1, 3), finite
        R = euler_lab_axes(e)
        scalar = e.ndim == 1
        e = e.reshape(-1, 3)
        return R.reshape(-1, 3, 3), scalar, e, e[:, 2].copy(), cut_material
    which = direction if angle is None else angle
    R = lab_axes(surface, which)
    scalar = R.ndim == 2
    R = R.reshape(-1, 3, 3)
    ref = reference_direction(surface)
    ang = np.degrees(np.arctan2(R[:, 0] @ np.cross(surface_normal(surface), ref), R[:, 0] @ ref))
    return R, scalar, None, ang, cut_material


def material_piezo(C11=None, C12=None, C44=None, rho=None, direction="[100]", stress=0.0, surface="(001)", *,
                   voigt=None, angle=None, toec=None, piezo=None, permittivity=None, euler=None, cut=None,
                   electrical=None, leaky=None) -> dict:
    """:func:`surfwave.material` for piezoelectric crystals and Euler-angle cuts (same arguments).

    Returns the keys of :func:`surfwave.material` (``polarisation`` and ``decay`` with a fourth
    component, the potential; bulk speeds are piezoelectrically stiffened eigen-speeds; ``c_limit`` is
    the piezoelectrically stiffened limiting speed) plus those of
    :func:`surfwave.real_crystals.piezo_wave.piezo_wave`: ``c_free``, ``c_metallized``, ``K2``,
    ``c_leaky``, ``leaky_attenuation``, ``leaky_reason``, ``power_flow_angle``,
    ``potential_share``, ``electrical``, ``model``, and ``euler`` ((m, 3) degrees, or NaN for a
    surface/direction orientation). Everything is computed by
    :func:`surfwave.real_crystals.stressed_wave.surface_wave` (through
    :func:`surfwave.real_crystals.piezo_wave.piezo_wave`): bulk speeds, ``stable`` and the
    reasons are those of the one path. ``toec=True`` needs third-order constants in the record
    (of the piezoelectric database only GaAs has them: InputError naming them otherwise);
    ``toec`` may also be the caller's set: a mapping of the class's named constants (a crystal
    given by name; :data:`surfwave.real_crystals.toec_classes.TOEC_NAMES`) or a (6, 6, 6) Voigt
    array in GPa, checked for invariance under the crystal's class
    (:func:`surfwave.real_crystals.toec_classes.checked_toec`).
    """
    from surfwave.real_crystals.piezo_materials import get_piezo_material, with_toec

    explicit_toec = toec is not None and toec is not False and toec is not True
    electrical = "free" if electrical is None else electrical
    piezo_name = _piezo_only_name(C11) or (isinstance(C11, str) and piezo is None and _in_piezo_db(C11))
    R, scalar, eul, ang, cut_material = _orientation(cut, euler, surface, direction, angle, C11)
    if C11 is None and voigt is None and cut_material is not None:
        C11, piezo_name = cut_material, True                        # cut="128Y-X LiNbO3" alone
    if piezo_name:
        if any(v is not None for v in (C12, C44, voigt, piezo, permittivity)):
            raise InputError(f"material {C11!r} given by name: do not also give C12, C44, voigt=, piezo= or "
                             "permittivity=")
        mat = resolve_piezo_material(C11, rho=rho)
        if explicit_toec:                                           # the caller's set, checked for the class
            mat = with_toec(mat, toec)
        C3 = None
        if cut_material is not None:
            want = get_piezo_material(cut_material).formula
            if mat.formula != want:
                raise InputError(f"cut {cut!r} is a cut of {want}, not of {C11!r} ({mat.formula})")
    else:
        from surfwave.api import _resolve_material

        C6, rho, C3 = _resolve_material(C11, C12, C44, rho, voigt, toec)     # cubic six (named or not) or an array
        if rho is None:
            raise InputError("the density rho (kg/m^3) is missing")
        if piezo is None and permittivity is None:                  # non-piezoelectric crystal, e = 0
            piezo, permittivity = np.zeros((3, 6)), np.eye(3)
        elif piezo is None or permittivity is None:
            raise InputError("a piezoelectric crystal needs both piezo= (e, 3 x 6, C/m^2) and permittivity= "
                             "(eps_r, 3 x 3, relative)")
        mat = resolve_piezo_material(None, voigt=C6, e=piezo, eps_r=permittivity, rho=rho)
    if C3 is not None:                          # a crystal given by constants: a checked set, or the elastic database's
        mat = replace(mat, toec_voigt=C3, sources={**mat.sources, "toec": "given by the caller" if explicit_toec
                                                   else "the elastic database"})
    use_toec = explicit_toec or toec is True
    r = piezo_wave(mat, R, stress, electrical=electrical, toec=use_toec, bulk=True,
                   leaky=True if leaky is None else bool(leaky))
    out = {key: r[key] for key in ("c_L_par", "c_T_par", "c_L_perp", "c_T_perp", "c_SH", "c_R", "c_R_imag",
                                   "c_limit", "wave_type", "reason", "stable", "polarisation", "decay",
                                   "penetration_depth", "method", "rho")}
    out.update(angle=ang, toec=np.full(R.shape[0], use_toec))
    for key in ("c_free", "c_metallized", "K2", "c_leaky", "leaky_attenuation", "leaky_reason",
                "power_flow_angle", "potential_share", "electrical", "c_leaky_free", "c_leaky_metallized",
                "K2_leaky", "grazing") + BULK_KEYS:
        out[key] = r[key]
    out["euler"] = eul if eul is not None else np.full((R.shape[0], 3), np.nan)
    if scalar:
        out = {k: (v[0] if np.ndim(v[0]) else np.asarray(v[0]).item()) for k, v in out.items()}
        for key in ("wave_type", "reason", "method", "leaky_reason", "electrical"):
            out[key] = str(out[key])
        out["stable"] = bool(out["stable"])
        out["toec"] = bool(out["toec"])
    out["model"] = r["model"]
    return out


def _in_piezo_db(name) -> bool:
    from surfwave.real_crystals.piezo_materials import get_piezo_material

    try:
        get_piezo_material(name)
        return True
    except InputError:
        return False
