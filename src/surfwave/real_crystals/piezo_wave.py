"""Surface waves of (prestressed) piezoelectric crystals: free, metallized, K^2, leaky, power flow.

One call per question "what does a SAW do on this cut of this crystal?", vectorised over m
orientations (lab axes from Euler angles, a named cut, or a Miller surface and direction).

Model (say it whenever a prestress is given): fixed constants, A_ijkl = C_ijkl + sigma0_jl
delta_ik with C the stiffness at constant field of the data set (the stressed crystal's
constants are taken equal to the natural ones); the piezoelectric constants e and the clamped
permittivity eps are held at their natural values (their stress derivatives are not in the
database). The prestress must lie in the surface plane (sigma0 . n = 0): a stress that loads
the surface is refused with the words of :func:`surfwave.material` (the one check,
:func:`surfwave.real_crystals.loads.check_stress`); with the third-order model, a point
whose *deformed* surface the stress loads is NaN with a reason.

This module only resolves arguments (a material name or explicit constants, lab axes, a
stress given as a scalar or a tensor); the physics is the one real-crystal path,
:func:`surfwave.real_crystals.stressed_wave.surface_wave` (stressed state, traction check,
Born stability, then :func:`surfwave.solvers.piezo.piezo_surface_wave` for both electrical
conditions and :func:`surfwave.solvers.leaky.leaky_wave`), shared with the elastic crystals,
:func:`surfwave.material` and the cubes.
"""
from __future__ import annotations

from typing import Iterable, Sequence

import numpy as np
from numpy.typing import ArrayLike

from surfwave import validate
from surfwave.errors import InputError
from surfwave.real_crystals import stressed_wave as sw_path
from surfwave.real_crystals.loads import TRACTION_TOL, check_stress, stress_tensor
from surfwave.real_crystals.piezo_materials import (
    EPS0,
    PiezoMaterial,
    check_piezo_record,
    get_piezo_material,
    note_status,
)
from surfwave.solvers.boundary import Boundary, as_boundary
from surfwave.solvers.piezo_tensors import piezo_voigt_to_tensor, rotate3
from surfwave.solvers.tensors import rotate2, rotate4, voigt_to_tensor

__all__ = ["MODEL", "MODEL_TOEC", "piezo_wave", "piezo_wave_conditions", "resolve_piezo_material", "stress_model"]

#: The prestress model, recorded in every result and cube.
MODEL = ("fixed constants: A = C + sigma0 delta (C^E of the data set); e and clamped eps at their natural "
         "values (no stress derivatives)")
#: The prestress model with third-order constants (``toec=True``), recorded likewise.
MODEL_TOEC = ("third-order constants: the stressed state (deformation F, C*, rho0/J) of the Brugger constants; "
              "e and clamped eps at their natural values, rotated with the crystal (no stress derivatives)")


def stress_model(toec: Iterable[bool]) -> str:
    """The prestress model text of a result or cube: :data:`MODEL` or :data:`MODEL_TOEC` for one
    model, ``"toec=false: ...; toec=true: ..."`` for both (``toec``: the models, a sequence of bool)."""
    models = [bool(t) for t in toec]
    if len(models) == 1:
        return MODEL_TOEC if models[0] else MODEL
    return "; ".join(f"toec={str(t).lower()}: {MODEL_TOEC if t else MODEL}" for t in models)


#: Largest |stress| (GPa) accepted; larger values are almost surely in Pa (the one bound,
#: :data:`surfwave.validate.MAX_STRESS_GPA`).
MAX_STRESS_GPA = validate.MAX_STRESS_GPA
#: The one traction tolerance and wording (:mod:`surfwave.real_crystals.stressed_wave`).
TRACTION_RTOL = TRACTION_TOL
REASON_TRACTION = sw_path.REASON_TRACTION
ELECTRICAL = sw_path.ELECTRICAL


def resolve_piezo_material(material: str | PiezoMaterial | None = None, *, voigt: ArrayLike | None = None,
                           e: ArrayLike | None = None, eps_r: ArrayLike | None = None,
                           rho: float | None = None) -> PiezoMaterial:
    """A :class:`PiezoMaterial` from a database name, a record, or explicit constants.

    Parameters
    ----------
    material : str or PiezoMaterial or None
        Name or alias in the piezoelectric database (``"LiNbO3"``, ``"quartz"``, ...); None: the
        explicit constants below. An explicit ``rho`` overrides the record's density.
    voigt : array_like, shape (6, 6), GPa
    e : array_like, shape (3, 6), C/m^2
    eps_r : array_like, shape (3, 3), relative (clamped) permittivity
    rho : float, kg/m^3

    Raises
    ------
    InputError
        Unknown name; explicit constants missing, of the wrong shape, non-finite, in Pa, not
        positive definite (stiffness, eps_r) (:func:`check_piezo_record`); e beyond 100 C/m^2,
        eps_r below 1, rho outside [1, 1e12] kg/m^3 (:mod:`surfwave.validate`).
    """
    if material is not None:
        if any(v is not None for v in (voigt, e, eps_r)):
            raise InputError(f"material {material!r} given by name: do not also give voigt=, piezo= or "
                             "permittivity=")
        m = get_piezo_material(material)
        if rho is None:
            return m
        return PiezoMaterial(**{**m.__dict__, "rho": validate.density(rho)})
    for key, value in (("voigt", voigt), ("piezo (e)", e), ("permittivity (eps_r)", eps_r), ("rho", rho)):
        if value is None:
            raise InputError(f"{key} is missing: a piezoelectric crystal needs voigt (6 x 6, GPa), piezo "
                             "(3 x 6, C/m^2), permittivity (3 x 3, relative) and rho (kg/m^3), or a name")
    try:
        C6, e6, er = (np.asarray(x, dtype=float) for x in (voigt, e, eps_r))
    except (TypeError, ValueError) as exc:
        raise InputError(f"piezoelectric constants must be numeric arrays: {exc}") from None
    assert rho is not None  # refused above when missing
    check_piezo_record(C6, e6, er, rho, name="constants")
    validate.piezo_constants(e, eps_r)                 # the bounds of every door: C/m^2, eps_r >= 1
    rho = validate.density(rho)
    return PiezoMaterial(name="user", formula="", crystal_class="", rho=float(rho), voigt=C6, e=e6, eps_r=er,
                         constants={}, setting="user-supplied, crystal axes", sources={})


def _prestress(stress, axes: np.ndarray) -> np.ndarray:
    """Cauchy prestress in crystal axes (m, 3, 3), GPa.

    From a scalar (uniaxial along each x1), a 3 x 3 tensor (crystal axes, the same at every
    point), an (m,) array (uniaxial along x1, one value per point) or an (m, 3, 3) array.
    """
    m = axes.shape[0]
    s = validate.gpa_stress(stress)                              # numbers, finite, the one Pa guard
    if s.shape == () or s.shape == (m,):                         # uniaxial along each x1: the one loading
        return stress_tensor("along", 1.0, axes) * s[..., None, None]
    if s.shape in ((3, 3), (m, 3, 3)):
        if not np.allclose(s, np.swapaxes(s, -1, -2), rtol=0, atol=1e-12 * max(np.abs(s).max(), 1e-300)):
            raise InputError(f"the stress tensor must be symmetric, got {s.tolist()}")
        return np.broadcast_to(s, (m, 3, 3)).copy()
    raise InputError(f"stress must be a scalar (uniaxial along the propagation), a 3 x 3 tensor in crystal "
                     f"axes (GPa), or one of them per orientation ((m,) or (m, 3, 3), m = {m}); got shape {s.shape}")


def _axes(axes) -> np.ndarray:
    R = np.asarray(axes, dtype=float)
    if R.shape[-2:] != (3, 3) or R.ndim not in (2, 3):
        raise InputError(f"lab axes must have shape (3, 3) or (m, 3, 3), got {R.shape}")
    R = R.reshape(-1, 3, 3)
    if not np.all(np.isfinite(R)) or np.abs(R @ np.swapaxes(R, -1, -2) - np.eye(3)).max() > 1e-9:
        raise InputError("lab axes must be finite rotation matrices (rows x1, x2, x3 in crystal axes)")
    return R


def piezo_wave(material: str | PiezoMaterial | None = None, axes: ArrayLike | None = None, stress: ArrayLike = 0.0, *,
               electrical: str = "free", leaky: bool = True, tol: float = 1e-12, voigt: ArrayLike | None = None,
               e: ArrayLike | None = None, eps_r: ArrayLike | None = None, rho: float | None = None, toec: bool = False,
               bulk: bool = False) -> dict:
    """SAW of a piezoelectric crystal on m cuts: free and metallized speeds, K^2, leaky wave, power flow.

    Parameters
    ----------
    material : str or PiezoMaterial or None
        Piezoelectric database name or record; None: give ``voigt``, ``e``, ``eps_r``, ``rho``.
    axes : array_like, shape (m, 3, 3) or (3, 3)
        Lab axes (rows x1 = propagation, x2 = INWARD normal, x3 = x1 x x2) in crystal
        coordinates: :func:`surfwave.solvers.euler.euler_lab_axes`, a named cut's
        ``lab_axes``, or :func:`surfwave.solvers.orientation.lab_axes`.
    stress : float or array_like, shape (3, 3), (m,) or (m, 3, 3)
        Prestress, GPa (negative = compression): a scalar is uniaxial along each propagation
        direction x1; a 3 x 3 Cauchy tensor is in crystal axes; (m,) and (m, 3, 3): one per
        orientation. Fixed-constants model (:data:`MODEL`) unless ``toec``.
    electrical : {"free", "metallized"}
        Condition of ``c_R``, the power flow, the polarisation and the leaky wave.
    leaky : bool
        Also solve for the leaky wave (``c_leaky``, ``leaky_attenuation``; NaN otherwise). Where
        no subsonic SAW exists and the leaky root does not attenuate (a mirror direction), that
        root is reported as the SAW (``wave_type`` "supersonic_decoupled", as the elastic solver).
    tol : float
        Relative accuracy of rho c^2 of the subsonic wave.
    voigt, e, eps_r, rho
        Explicit constants (GPa; C/m^2, 3 x 6; relative, 3 x 3; kg/m^3); see
        :func:`resolve_piezo_material`.
    toec : bool
        Third-order model of the stressed state (:data:`MODEL_TOEC`): needs ``toec_voigt`` in
        the record (the database: GaAs only; else InputError naming what is missing; the API
        takes a caller's set, :func:`surfwave.material`).
    bulk : bool
        Also ``stable`` (:func:`stressed_wave.surface_wave`); the stiffened bulk waves along x1
        and x2 (``c_L_par``, ..., ``polarisation_SH_perp``) come either way.

    Returns
    -------
    dict of ndarray, leading shape (m,)
        ``c_R`` m/s (the subsonic SAW of the requested condition, NaN if none), ``c_free``,
        ``c_metallized`` m/s, ``K2`` (fraction, 2 (c_free - c_metallized) / c_free), ``c_limit``
        m/s (stiffened limiting speed), ``c_leaky`` m/s and ``leaky_attenuation`` dB per
        wavelength (leaky wave radiating into the slowest bulk sheet; NaN where none),
        ``leaky_reason``, ``power_flow_angle`` degrees (from x1 toward our +x3 = +x2 of the
        SAW convention), ``polarisation`` (m, 4) complex (u1, u2, u3 unit mechanical norm; phi
        in V per m of displacement), ``potential_share``, ``decay`` (m, 4) complex,
        ``penetration_depth`` wavelengths, ``wave_type``, ``reason``, ``method``, ``electrical``,
        ``C`` (m, 3, 3, 3, 3) Pa (the natural C^E in the lab frame; with ``toec`` the solver used
        the stressed state's C*), ``e`` (m, 3, 3, 3) C/m^2, ``eps`` (m, 3, 3) F/m, ``sigma`` (m, 3, 3)
        GPa (lab frame), ``rho`` (m,) kg/m^3, ``model`` (str); and every key of
        :func:`surfwave.real_crystals.stressed_wave.surface_wave` (``ok``, ``F``, ``axes``, ...).
        A point without a (Born-stable) stressed state, or (``toec``) whose deformed surface the
        stress loads, is NaN with the reason of that function.

    Raises
    ------
    InputError
        Bad constants (see :func:`resolve_piezo_material`), axes that are not rotations, stress
        not scalar or 3 x 3, non-finite or in Pa, a stress that loads a surface (sigma . n != 0,
        as :func:`surfwave.material` words it), unknown ``electrical``; all before any solve.

    Examples
    --------
    >>> from surfwave.real_crystals.piezo_materials import get_cut
    >>> cut = get_cut("Y-Z LiNbO3")
    >>> r = piezo_wave(cut.material, cut.lab_axes)
    >>> round(float(r["c_free"][0])), round(float(r["c_metallized"][0]))   # Slobodnik 1973: 3488 / 3404
    (3488, 3404)
    """
    if not isinstance(electrical, Boundary) and electrical not in ELECTRICAL:
        raise InputError(sw_path.electrical_error(electrical))
    electrical = as_boundary(electrical).name
    return piezo_wave_conditions(material, axes, stress, conditions=(electrical,), leaky=leaky, tol=tol,
                                 voigt=voigt, e=e, eps_r=eps_r, rho=rho, toec=toec, bulk=bulk)[electrical]


def piezo_wave_conditions(material: str | PiezoMaterial | None = None, axes: ArrayLike | None = None,
                          stress: ArrayLike = 0.0, *, conditions: Sequence[str] = ELECTRICAL, leaky: bool = True,
                          tol: float = 1e-12, voigt: ArrayLike | None = None, e: ArrayLike | None = None,
                          eps_r: ArrayLike | None = None, rho: float | None = None, toec: bool = False,
                          bulk: bool = False) -> dict:
    """:func:`piezo_wave` for several electrical conditions from one solve (both cost what one costs).

    Parameters
    ----------
    material, axes, stress, leaky, tol, voigt, e, eps_r, rho, toec, bulk
        As :func:`piezo_wave`.
    conditions : sequence of {"free", "metallized"}
        Distinct conditions.

    Returns
    -------
    dict
        Condition -> the dict :func:`piezo_wave` returns for it.

    Raises
    ------
    InputError
        As :func:`piezo_wave`; also repeated or unknown conditions.
    """
    conditions = tuple(conditions)                                  # checked by surface_wave_conditions
    mat = resolve_piezo_material(material, voigt=voigt, e=e, eps_r=eps_r, rho=rho)
    note_status(mat)                                                # one line for an unverified set
    if axes is None:
        raise InputError("lab axes are missing: give Euler angles, a named cut or a surface and direction")
    R = _axes(axes)
    sigma_c = check_stress(_prestress(stress, R), R, "of the lab axes")   # the one check, its words
    rs = sw_path.surface_wave_conditions(sw_path.Constants.from_piezo_material(mat), R, sigma_c,
                                         conditions=conditions, toec=toec, tol=tol, bulk=bulk, leaky=leaky)
    lab = rs[conditions[0]]["axes"]
    extra = dict(C=rotate4(voigt_to_tensor(mat.voigt) * 1e9, lab), e=rotate3(piezo_voigt_to_tensor(mat.e), lab),
                 eps=rotate2(mat.eps_r * EPS0, lab), sigma=rotate2(sigma_c, lab),
                 model=stress_model([toec]))
    for r in rs.values():
        r["c_imag"] = r["c_R_imag"]
        r.update(extra)
    return rs
