"""The one path from "crystal, cut, stress, model" to the surface wave of a real crystal.

:func:`surface_wave` is called by :func:`surfwave.api.material`, by
:func:`surfwave.real_crystals.acoustoelastic.surface_wave_speed` (and so the acoustoelastic
coefficients) and by :func:`surfwave.real_crystals.sweep.surface_wave_sweep` (the solver that
fills a real-crystal cube), so the API, the CLI and the cubes give the same numbers and the
same reasons. Per point it does, in this order:

1. GPa -> Pa, once (:data:`GPA`), where the wave-propagation tensor is built;
2. the stressed state: fixed-C (C* = C, rho = rho0, no deformation) or from the third-order
   constants (:func:`surfwave.real_crystals.toec.stressed_state`: deformation F, C*, rho0/J,
   Born stability of the stressed crystal), and the lab axes carried by F
   (:func:`surfwave.real_crystals.toec.deformed_axes`);
3. one traction check on the (deformed) surface, tolerance :data:`TRACTION_TOL`;
4. the surface wave where a state exists: :func:`surfwave.solvers.stroh.surface_wave`, or for
   a crystal with piezoelectric constants :func:`surfwave.solvers.piezo_saw.piezo_saw` (e and
   the clamped eps at their natural values rotated into the lab frame of the (deformed)
   crystal; free and metallized SAW, K^2, leaky wave, power flow; e = 0: the elastic solver);
5. the bulk waves along x1 and x2 (speeds and polarisations: eigenvalues of the Christoffel
   tensor of A, piezoelectrically stiffened for a piezoelectric crystal,
   :func:`surfwave.solvers.bulk_waves.axis_waves`) and optionally the stability flag.

A point without a state (deformation solve failed, Born-unstable, loaded surface) is NaN
(``wave_type`` "none") with its reason; outputs are allocated NaN and filled only where the
solver ran, so no point can carry another point's value. Nothing raises mid-batch.

:func:`stress_tensor` is the one load-to-stress function (loading kind + magnitude + axes ->
Cauchy stress in crystal axes).

Examples
--------
>>> from surfwave.real_crystals.materials import get_material
>>> from surfwave.solvers.orientation import lab_axes
>>> cu = Constants.from_material(get_material("Cu"))
>>> R = lab_axes("(001)", "[100]")
>>> r = surface_wave(cu, R, stress_tensor("along", 0.1, R), toec=True)
>>> round(float(r["c_R"]), 2)   # material("Cu", stress=0.1, toec=True)
2019.06
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING, Any, Sequence

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.real_crystals import toec as toec_model
from surfwave.real_crystals.loads import LOADINGS, TRACTION_TOL, check_stress, stress_tensor
from surfwave.solvers import stroh
from surfwave.solvers.boundary import Boundary, as_boundary
from surfwave.solvers.bulk_waves import BULK_POLARISATIONS, BULK_SPEEDS, axis_waves
from surfwave.solvers.leaky import leaky_wave
from surfwave.solvers.long_wave import long_wave_stable
from surfwave.solvers.piezo_saw import ELECTRICAL, PIEZO_KEYS, piezo_saw_conditions
from surfwave.solvers.piezo_tensors import EPS0, piezo_voigt_to_tensor, rotate3
from surfwave.solvers.tensors import rotate2, rotate4, tensor_to_voigt

if TYPE_CHECKING:
    from surfwave.real_crystals.piezo_materials import PiezoMaterial

__all__ = ["BULK_KEYS", "Constants", "ELECTRICAL", "GPA", "GRAZING_DEPTH", "LEAKY_KEYS", "LOADINGS", "PIEZO_KEYS",
           "REASON_LEAKY_OFF", "REASON_LEAKY_SUBSONIC", "REASON_NO_STATE", "REASON_TRACTION", "TRACTION_TOL",
           "check_stress", "electrical_error", "require_toec", "stress_tensor", "surface_wave",
           "surface_wave_conditions"]

#: Elastic constants and stresses are given in GPa; the solver gets Pa (speeds in m/s).
GPA = 1.0e9
#: Bulk-wave outputs of every point (speeds, m/s, then polarisations), :mod:`surfwave.solvers.bulk_waves`.
BULK_KEYS = BULK_SPEEDS + BULK_POLARISATIONS
#: Leaky-wave outputs of every crystal (elastic ones too): m/s, dB per wavelength, and ``leaky_reason``.
LEAKY_KEYS = ("c_leaky", "leaky_attenuation")
#: ``leaky_reason`` of an elastic point with a subsonic surface wave (the leaky wave is solved
#: only where none exists: "model only what a scene requires").
REASON_LEAKY_SUBSONIC = ("no leaky wave computed: a subsonic surface wave exists (c_R); the leaky wave is "
                         "solved only where it does not (wave_type pseudo)")
#: ``leaky_reason`` with ``leaky=False``.
REASON_LEAKY_OFF = "not computed (leaky=False)"
#: Reason of a point whose deformed surface carries a traction.
REASON_TRACTION = ("the deformed surface is loaded: sigma . n != 0 on the normal F^-T n0 (the stress "
                   "turns the surface plane), so the free surface is not in equilibrium")
#: Prefix of the reason of a point without a stressed state (the reason of
#: :func:`surfwave.real_crystals.toec.stressed_state` follows, e.g. the Born wording
#: :func:`surfwave.real_crystals.toec.born_reason`).
REASON_NO_STATE = "no stressed state: "
#: Penetration depth (1/e, in wavelengths) above which a surface wave is flagged ``grazing``: a
#: bulk-like wave grazing the limiting speed (e.g. rotated Y LiTaO3 near theta = 38 deg: 1e-4 m/s
#: below v_L, ~680 wavelengths deep, K^2 ~ 0). 50 wavelengths is the order of a substrate's
#: thickness at SAW wavelengths (0.35-0.5 mm at 4-10 um): such a wave reaches the back face and
#: is not a surface wave a device can use.
GRAZING_DEPTH = 50.0
#: Relative accuracy of rho c^2 of the piezoelectric SAW search (its solver's default).
PIEZO_TOL = 1e-12


@dataclass(frozen=True, eq=False)
class Constants:
    """The natural-state material constants of a real crystal, crystal axes.

    Attributes
    ----------
    voigt : ndarray, shape (6, 6)
        Second-order stiffness C, GPa.
    rho : float
        Density, kg/m^3.
    toec : ndarray, shape (6, 6, 6), or None
        Brugger third-order constants C3 (Voigt), GPa; None where unknown.
    piezo : ndarray, shape (3, 6), or None
        Piezoelectric stress constants e_kI, C/m^2 (crystal axes). With it, :func:`surface_wave`
        solves the coupled (u, phi) problem (all zeros: the elastic solver, the potential
        decoupled, and the piezoelectric keys filled: K2 = 0).
    permittivity : ndarray, shape (3, 3), or None
        Relative clamped permittivity eps_r (eps / EPS0), crystal axes; given with ``piezo``.
    """

    voigt: np.ndarray
    rho: float
    toec: np.ndarray | None = None
    piezo: np.ndarray | None = None
    permittivity: np.ndarray | None = None

    def __post_init__(self) -> None:
        """Normalise the constants: Voigt (6, 6) GPa (a (3, 3, 3, 3) tensor is converted), rho float."""
        C = np.asarray(self.voigt, dtype=float)
        if C.shape == (3, 3, 3, 3):
            C = tensor_to_voigt(C)
        if C.shape != (6, 6):
            raise InputError(f"the stiffness must be a 6 x 6 Voigt matrix (GPa), got shape {C.shape}")
        object.__setattr__(self, "voigt", C)
        object.__setattr__(self, "rho", float(self.rho))
        if self.toec is not None:
            object.__setattr__(self, "toec", np.asarray(self.toec, dtype=float))
        if (self.piezo is None) != (self.permittivity is None):
            raise InputError("a piezoelectric crystal needs both piezo (e, 3 x 6, C/m^2) and permittivity "
                             "(eps_r, 3 x 3, relative)")
        if self.piezo is not None:
            e6, er = np.asarray(self.piezo, dtype=float), np.asarray(self.permittivity, dtype=float)
            if e6.shape != (3, 6) or er.shape != (3, 3):
                raise InputError(f"piezo must be 3 x 6 (C/m^2) and permittivity 3 x 3, got shapes {e6.shape} "
                                 f"and {er.shape}")
            object.__setattr__(self, "piezo", e6)
            object.__setattr__(self, "permittivity", er)

    @classmethod
    def from_material(cls, material: Any) -> Constants:
        """The record of a :class:`surfwave.real_crystals.materials.Material` (or any object
        with ``voigt``, ``rho`` and ``toec``: None or the six cubic constants)."""
        return cls(np.asarray(material.voigt, dtype=float), material.rho,
                   None if material.toec is None else material.toec_voigt)

    @classmethod
    def from_piezo_material(cls, material: PiezoMaterial) -> Constants:
        """The record of a :class:`surfwave.real_crystals.piezo_materials.PiezoMaterial` (C, rho,
        e, eps_r; ``toec_voigt`` when the record carries third-order constants)."""
        C3 = getattr(material, "toec_voigt", None)
        return cls(np.asarray(material.voigt, dtype=float), material.rho, C3, material.e, material.eps_r)

    @property
    def is_piezo(self) -> bool:
        """True when piezoelectric constants (possibly all zero) are given."""
        return self.piezo is not None


def electrical_error(value) -> str:
    """The one refusal of an ``electrical`` value: one condition, and both come from every call."""
    both = ("; both conditions come from every call: c_free, c_metallized, K2 for the SAW and c_leaky_free, "
            "c_leaky_metallized, K2_leaky for the leaky SAW" if not isinstance(value, str) else "")
    return (f"electrical must be 'free' or 'metallized' (the condition of c_R, the polarisation, the power "
            f"flow and c_leaky), got {value!r}{both}")


# --------------------------------------------------------------------------- the surface wave


def surface_wave(constants: Constants, axes: ArrayLike, stress: ArrayLike, *, toec: bool = False,
                 tol: float | None = None, state_tol: float = toec_model.DEFAULT_TOL, bulk: bool = True,
                 electrical: str | Boundary | None = None, leaky: bool | None = None) -> dict:
    """Surface wave of a stressed real crystal at each point (the one path).

    Parameters
    ----------
    constants : Constants
        Natural-state constants (GPa, kg/m^3).
    axes : array_like, shape (..., 3, 3)
        Lab axes of the unstressed crystal, rows (x1 propagation, x2 inward normal, x3),
        crystal axes (:func:`surfwave.solvers.orientation.lab_axes`).
    stress : array_like, shape (..., 3, 3)
        Cauchy prestress in crystal axes, GPa (broadcast against ``axes``).
    toec : bool
        False: fixed-C model (C* = C, rho = rho0, the stress enters only through A = C +
        sigma delta). True: the stressed state of the third-order constants (the wave then
        runs along F m0 on the surface of normal F^-T n0; true phase speeds).
    tol : float, optional
        Relative accuracy of rho c^2 in the solver's root search (its default when None).
    state_tol : float
        Tolerance of the deformation solve, GPa.
    bulk : bool
        Also return ``stable`` (costs a stability test). The bulk speeds along x1 and x2 come
        either way (they are cheap).
    electrical : {"free", "metallized"} or Boundary, optional
        Piezoelectric crystals only (default "free"; :mod:`surfwave.solvers.boundary`): the
        surface condition of ``c_R``, the polarisation, the power flow and ``c_leaky``;
        ``c_free``, ``c_metallized`` and ``K2`` come either way.
    leaky : bool or None
        The leaky wave (``c_leaky``, ``leaky_attenuation``, ``leaky_reason``) radiating into
        the slowest bulk sheet (:func:`surfwave.solvers.leaky.leaky_wave`). True: solved at
        every point; False: nowhere (NaN, :data:`REASON_LEAKY_OFF`); None (default): only where
        needed, i.e. every point of a piezoelectric crystal (as True) and, for an elastic
        crystal, the points without a subsonic wave (``wave_type`` "pseudo"), while a
        ``surface`` point keeps NaN with :data:`REASON_LEAKY_SUBSONIC` (a leaky wave may coexist
        there, e.g. Cu (001) between ~26 and 45 deg: ask ``leaky=True``; it costs ~8x the
        subsonic solve per point). Elastic ``supersonic_decoupled`` points (with True or None):
        the exact mirror wave is the leaky branch's limit, c_leaky = c_R, attenuation 0.

    Returns
    -------
    dict
        Shapes ``(...)`` = the broadcast leading shape: ``c_R`` (m/s, NaN where none; real part
        for a pseudo wave), ``c_R_imag`` (m/s), ``c_limit`` (m/s), ``wave_type`` (object str),
        ``reason`` (object str, "" where a surface wave exists), ``polarisation`` (..., 3) and
        ``decay`` (..., 3) complex, ``penetration_depth`` (wavelengths), ``method`` (object
        str, "" where not solved), ``rho`` (kg/m^3, stressed state), ``ok`` (bool: a stressed,
        Born-stable state with a traction-free surface exists), ``F`` (..., 3, 3) (NaN where
        no state), ``axes`` (..., 3, 3) the lab axes of the stressed crystal; the bulk waves
        along x1 (``c_L_par``, ``c_T_par``, ``c_SH``) and along x2 (``c_T_perp``, ``c_L_perp``,
        ``c_SH_perp``) in m/s, the eigen-speeds of the Christoffel tensor of A (stiffened by e
        and eps for a piezoelectric crystal) named by polarisation (mostly u1, u2, u3 in that
        order of names per axis; :mod:`surfwave.solvers.bulk_waves`), NaN where imaginary or no
        state, each with ``polarisation_<name>`` (..., 3), the unit displacement in the lab
        frame; ``grazing`` (bool: a surface wave, ``c_R`` finite, deeper than
        :data:`GRAZING_DEPTH` wavelengths, i.e. a bulk-like wave grazing the limiting speed); with
        ``bulk`` also ``stable`` (bool: ``ok`` and the acoustic tensor positive
        definite in every direction). Everything that depends on a
        state is NaN where ``ok`` is False. Every crystal: ``c_leaky`` (m/s, omega / Re k of
        the leaky wave radiating into the slowest bulk sheet, NaN where none),
        ``leaky_attenuation`` (dB per wavelength, NaN where none) and ``leaky_reason`` (object
        str, "" where a leaky wave is reported). With piezoelectric constants (:data:`PIEZO_KEYS`):
        ``polarisation`` and ``decay`` have 4 components (u1, u2, u3, phi; phi in V per m of
        displacement), ``c_limit`` is the stiffened limiting speed, plus ``c_free``,
        ``c_metallized`` (m/s), ``K2`` (2 (c_free - c_metallized) / c_free), ``c_leaky`` (m/s),
        ``leaky_attenuation`` (dB per wavelength), ``leaky_reason``, ``power_flow_angle``
        (degrees, from x1 toward our +x3 = +x2 of the SAW frame), ``potential_share`` and
        ``electrical``.

    Notes
    -----
    Piezoelectric crystals: e and the clamped eps are held at their natural values (no stress
    derivatives in the database), rotated into the lab frame of the (deformed, with ``toec``)
    crystal; C* and rho are those of the stressed state as for any crystal. e = 0 is solved
    by the elastic Stroh solver, exactly as without piezoelectric constants.

    Raises
    ------
    InputError
        ``toec=True`` without third-order constants, bad shapes, an unknown ``electrical``,
        ``electrical`` without piezoelectric constants. Never for a point: those get NaN and a
        reason.
    """
    condition: Boundary | None = None
    if constants.is_piezo:
        if electrical is not None and not isinstance(electrical, Boundary) and electrical not in ELECTRICAL:
            raise InputError(electrical_error(electrical))
        condition = as_boundary("free" if electrical is None else electrical)
    elif electrical is not None:
        raise InputError(f"electrical={electrical!r} needs piezoelectric constants (piezo=, permittivity=)")
    return surface_wave_conditions(constants, axes, stress, conditions=(condition,), toec=toec, tol=tol,
                                   state_tol=state_tol, bulk=bulk, leaky=leaky)[None if condition is None
                                                                                else condition.name]


def require_toec(constants: Constants, toec: bool) -> None:
    """Refuse ``toec=True`` for constants without a third-order set (one wording for every door).

    Raises
    ------
    InputError
        ``toec`` is true and ``constants.toec`` is None; the message names the constants a set needs.
    """
    if toec and constants.toec is None:
        what = ("of the piezoelectric database only GaAs carries them; give a set as toec= (a (6, 6, 6) Voigt "
                "array in GPa, or the class's named constants, e.g. the 14 of quartz (class 32): C111, C112, "
                "C113, C114, C123, C124, C133, C134, C144, C155, C222, C333, C344, C444)"
                if constants.is_piezo else "C111, C112, C123, C144, C155, C456")
        raise InputError(f"toec=True needs third-order constants ({what}), and this crystal has none")


def surface_wave_conditions(constants: Constants, axes: ArrayLike, stress: ArrayLike, *,
                            conditions: Sequence[str | Boundary | None] = ELECTRICAL, toec: bool = False,
                            tol: float | None = None,
                            state_tol: float = toec_model.DEFAULT_TOL, bulk: bool = True,
                            leaky: bool | None = None) -> dict:
    """:func:`surface_wave` for several electrical conditions from one stressed state and one solve.

    The stressed state, the bulk speeds and the piezoelectric solves are shared: the subsonic
    search and (piezoelectric crystals) the leaky search always solve both conditions, so both
    cost what one costs (:func:`surfwave.solvers.piezo_saw.piezo_saw_conditions`).

    Parameters
    ----------
    constants, axes, stress, toec, tol, state_tol, bulk, leaky
        As :func:`surface_wave`.
    conditions : sequence of {"free", "metallized"} or of Boundary objects, or (None,)
        Distinct electrical conditions (piezoelectric crystals; results keyed by their names,
        :mod:`surfwave.solvers.boundary`); ``(None,)`` for a crystal
        without piezoelectric constants.

    Returns
    -------
    dict
        Condition -> the dict :func:`surface_wave` returns for it.

    Raises
    ------
    InputError
        As :func:`surface_wave`; also repeated or unknown conditions.
    """
    conditions = tuple(conditions)
    allowed = ELECTRICAL if constants.is_piezo else (None,)
    known = all(isinstance(c, Boundary) or c in allowed for c in conditions) and (
        constants.is_piezo or conditions == (None,))
    names = tuple(c.name if isinstance(c, Boundary) else c for c in conditions)
    if not conditions or len(set(names)) != len(names) or not known:
        raise InputError(f"conditions must be distinct values of {allowed} (or Boundary objects), got {conditions!r}")
    axes = np.asarray(axes, dtype=float)
    sigma = np.asarray(stress, dtype=float)
    if axes.shape[-2:] != (3, 3) or sigma.shape[-2:] != (3, 3):
        raise InputError(f"axes and stress must have shape (..., 3, 3), got {axes.shape} and {sigma.shape}")
    shape = np.broadcast_shapes(axes.shape[:-2], sigma.shape[:-2])
    axes = np.broadcast_to(axes, shape + (3, 3)).reshape(-1, 3, 3)
    sigma = np.broadcast_to(sigma, shape + (3, 3)).reshape(-1, 3, 3)
    require_toec(constants, toec)
    outs = _surface_wave(constants, axes, sigma, bool(toec), tol, state_tol, bulk, conditions, leaky)
    if shape == (sigma.shape[0],):       # already (n, ...): no reshaped views
        return outs
    return {c: {k: v.reshape(shape + v.shape[1:]) for k, v in out.items()} for c, out in outs.items()}


def _surface_wave(constants: Constants, axes, sigma, toec: bool, tol, state_tol, bulk: bool, conditions,
                  leaky: bool | None) -> dict:
    n = sigma.shape[0]
    # the stressed state (Born stability included) and the axes it carries
    st = toec_model.stressed_state(constants.voigt, constants.toec if toec else None, sigma, constants.rho,
                                   tol=state_tol)
    ok = np.asarray(st["ok"], dtype=bool).copy()
    reason = np.full(n, "", dtype=object)
    reason[~ok] = [REASON_NO_STATE + r for r in np.asarray(st["reason"])[~ok]]
    F = np.where(ok[:, None, None], st["F"], np.eye(3))
    lab = toec_model.deformed_axes(F, axes)
    s_lab = rotate2(sigma, lab)
    # the one traction check: sigma . n on the (deformed) surface
    scale = np.maximum(np.abs(sigma).max(axis=(-2, -1)), 1e-300)
    loaded = ok & (np.abs(s_lab[:, 1, :]).max(-1) > TRACTION_TOL * scale)
    reason[loaded] = REASON_TRACTION
    ok &= ~loaded
    s_lab[:, 1, :] = 0.0   # zero to TRACTION_TOL already; exactly zero for the solver
    s_lab[:, :, 1] = 0.0
    # the surface wave where a state exists; everything else stays NaN
    idx = np.flatnonzero(ok)
    if constants.is_piezo:   # rotated in Pa, as the piezoelectric front always did (same bits as before)
        C_lab = rotate4(st["C_star"][idx] * GPA, lab[idx])
    else:
        C_lab = rotate4(st["C_star"][idx], lab[idx]) * GPA
    A = stroh.wave_propagation_tensor(C_lab, s_lab[idx] * GPA)
    rho = st["rho"][idx]
    sws = _solve(A, rho, constants, lab[idx], tol, conditions, leaky)
    shared: dict = {}
    shared["rho"] = np.full(n, np.nan)
    shared["rho"][idx] = rho
    shared.update(ok=ok, F=st["F"], axes=lab)
    shared.update(_bulk(A, rho, n, idx, constants, lab[idx]))
    if bulk:
        shared["stable"] = np.zeros(n, dtype=bool)
        shared["stable"][idx] = _long_wave_stable(st["C_star"][idx], sigma[idx])
    names = [c.name if isinstance(c, Boundary) else c for c in conditions]
    # the shared arrays go to the last condition as they are, to the others as copies
    return {c: _assemble(constants, sws[c], c, idx, reason, shared, copy=i < len(names) - 1)
            for i, c in enumerate(names)}


def _assemble(constants: Constants, sw: dict, electrical, idx, reason, shared: dict, copy: bool = True) -> dict:
    """One condition's output arrays (n points) from the solver dict ``sw`` of the points ``idx``
    with a state; points without one keep NaN and their ``reason``; ``shared`` (state, bulk
    speeds) is copied in (``copy``) or put in as it is (the last condition's)."""
    n = reason.shape[0]
    out: dict = {}
    floats = PIEZO_KEYS if constants.is_piezo else LEAKY_KEYS
    for key, name in (("c_R", "c"), ("c_R_imag", "c_imag"), ("c_limit", "c_limit"),
                      ("penetration_depth", "penetration_depth")) + tuple((k, k) for k in floats):
        out[key] = np.full(n, np.nan)
        out[key][idx] = sw[name]
    width = 4 if constants.is_piezo else 3
    for key in ("polarisation", "decay"):
        out[key] = np.full((n, width), np.nan + 0j)
        out[key][idx] = sw[key]
    out["leaky_reason"] = reason.copy()
    out["leaky_reason"][idx] = sw["leaky_reason"]
    if constants.is_piezo:
        out["electrical"] = np.full(n, electrical, dtype=object)
    out["wave_type"] = np.full(n, "none", dtype=object)
    out["wave_type"][idx] = sw["wave_type"]
    out["reason"] = reason.copy()
    out["reason"][idx] = sw["reason"]
    out["method"] = np.full(n, "", dtype=object)
    out["method"][idx] = sw["method"]
    with np.errstate(invalid="ignore"):
        out["grazing"] = np.isfinite(out["c_R"]) & (out["penetration_depth"] > GRAZING_DEPTH)
    out.update({k: v.copy() for k, v in shared.items()} if copy else shared)
    return out


def _solve(A: np.ndarray, rho: np.ndarray, constants: Constants, lab: np.ndarray, tol, conditions=(None,),
           leaky: bool | None = None) -> dict:
    """The bare solver on the points with a state (A in Pa, lab frame; rho kg/m^3), per condition.

    Without piezoelectric constants: :func:`surfwave.solvers.stroh.surface_wave` (condition
    None). With them: e and eps_r rotated into ``lab`` (natural values),
    :func:`surfwave.solvers.piezo_saw.piezo_saw_conditions`.
    """
    if not constants.is_piezo:
        sw = stroh.surface_wave(A, rho, **({} if tol is None else {"tol": tol}))
        return {None: {**sw, **_elastic_leaky(A, rho, sw, leaky)}}
    leaky = True if leaky is None else leaky
    e, eps = _lab_piezo(constants, lab)
    return piezo_saw_conditions(A, rho, e, eps, conditions=conditions, tol=PIEZO_TOL if tol is None else tol,
                                leaky=leaky)


def _elastic_leaky(A: np.ndarray, rho: np.ndarray, sw: dict, leaky: bool | None) -> dict:
    """The leaky wave of elastic points (:func:`surfwave.solvers.leaky.leaky_wave`).

    Parameters
    ----------
    A : ndarray, shape (m, 3, 3, 3, 3)
        Wave-propagation tensor, Pa, lab frame.
    rho : ndarray, shape (m,)
        Density, kg/m^3.
    sw : dict
        :func:`surfwave.solvers.stroh.surface_wave` of the same points (``c``, ``wave_type``,
        ``reason``).
    leaky : bool or None
        True: solved at every point; None: only where ``wave_type`` is "pseudo" (``surface``
        points: NaN, :data:`REASON_LEAKY_SUBSONIC`); False: nowhere (NaN,
        :data:`REASON_LEAKY_OFF`).

    Returns
    -------
    dict of ndarray, shape (m,)
        ``c_leaky`` (m/s), ``leaky_attenuation`` (dB per wavelength), ``leaky_reason`` (object,
        "" where a leaky wave is reported): the solver's values and reasons where it is asked;
        at ``supersonic_decoupled`` points (True or None) the exact mirror wave, c_leaky = c_R
        and attenuation 0 (the limit of the leaky branch: delta is even in the angle from the
        mirror); ``none`` points keep the subsonic solver's reason where not solved.
    """
    m = len(rho)
    c_leaky, att = np.full(m, np.nan), np.full(m, np.nan)
    if leaky is False:
        return {"c_leaky": c_leaky, "leaky_attenuation": att,
                "leaky_reason": np.full(m, REASON_LEAKY_OFF, dtype=object)}
    wt = np.asarray(sw["wave_type"])
    reason = np.asarray(sw["reason"], dtype=object).copy()
    reason[wt == "surface"] = REASON_LEAKY_SUBSONIC
    ask = np.flatnonzero((wt == "pseudo") if leaky is None else np.ones(m, dtype=bool))
    if ask.size:
        with np.errstate(invalid="ignore"):
            lw = leaky_wave(A[ask], np.broadcast_to(rho, (m,))[ask])
        c_leaky[ask], att[ask], reason[ask] = lw["c_leaky"], lw["leaky_attenuation"], lw["reason"]
    exact = wt == "supersonic_decoupled"
    c_leaky[exact] = sw["c"][exact]
    att[exact] = 0.0
    reason[exact] = ""
    return {"c_leaky": c_leaky, "leaky_attenuation": att, "leaky_reason": reason}


def _bulk(A: np.ndarray, rho: np.ndarray, n: int, idx: np.ndarray, constants: Constants, lab: np.ndarray) -> dict:
    """Bulk speeds and polarisations along x1 and x2 (:func:`surfwave.solvers.bulk_waves.axis_waves`:
    eigenvalues of the Christoffel tensor of A, stiffened by e and eps for a piezoelectric
    crystal), n points, NaN where no state."""
    e, eps = _lab_piezo(constants, lab) if constants.is_piezo else (None, None)
    waves = axis_waves(A, rho, e, eps)
    if idx.size == n:                    # every point has a state: the waves as they are (fresh arrays)
        return waves
    out = {}
    for key, v in waves.items():
        out[key] = np.full((n,) + v.shape[1:], np.nan)
        out[key][idx] = v
    return out


def _lab_piezo(constants: Constants, lab: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """e (m, 3, 3, 3), C/m^2, and the clamped eps (m, 3, 3), F/m, at natural values rotated into ``lab``."""
    e6, eps_r = constants.piezo, constants.permittivity
    assert e6 is not None and eps_r is not None, "called for piezoelectric constants only"
    return rotate3(piezo_voigt_to_tensor(e6), lab), rotate2(eps_r * EPS0, lab)


def _long_wave_stable(C: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """:func:`surfwave.solvers.long_wave.long_wave_stable` in crystal axes, once where every
    point has the same C and sigma (a fixed-C crystal under one stress tensor)."""
    if len(C) > 1 and np.array_equal(C, np.broadcast_to(C[:1], C.shape)) \
            and np.array_equal(sigma, np.broadcast_to(sigma[:1], sigma.shape)):
        return np.broadcast_to(long_wave_stable(C[:1], sigma[:1]), (len(C),)).copy()
    return long_wave_stable(np.ascontiguousarray(C), np.ascontiguousarray(sigma))
