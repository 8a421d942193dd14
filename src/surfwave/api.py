"""The library's front door: one call per question.

:func:`point` answers "what are the bulk speeds and the Rayleigh speed of this prestressed
model crystal at these strains?"; :func:`material` answers the same for a real crystal from
measured elastic constants (or a material name), optionally with third-order constants.
"""
from __future__ import annotations

from typing import cast

import numpy as np

from surfwave import validate
from surfwave.case import material_result
from surfwave.errors import InputError
from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.records import MaterialResult, PointResult
from surfwave.resolve import resolve_material
from surfwave.solvers import long_wave, rayleigh, stroh
from surfwave.solvers.orientation import direction_angle, lab_axes
from surfwave.solvers.tensors import rotate2, rotate4
from surfwave.vocab import Direction

__all__ = ["MaterialResult", "PointResult", "material", "point"]


def _extras(C: np.ndarray, sigma: np.ndarray) -> dict:
    """The general solver's outputs for lab-frame V C and V sigma (rho = m = 1)."""
    sw = stroh.surface_wave(stroh.wave_propagation_tensor(C, sigma), 1.0)
    return {"c2_limit": sw["c_limit"] ** 2, "polarisation": sw["polarisation"], "decay": sw["decay"],
            "penetration_depth": sw["penetration_depth"], "_sw": sw}


def point(lattice: str, loading: str, potential: str, direction, d_over_d0, *, load_direction=None,
          min_eig: bool = False, details: bool = False) -> PointResult:
    """Stress, bulk sound speeds, stability and Rayleigh speed of a prestressed crystal.

    Parameters
    ----------
    lattice : {"fcc", "triangular"}
    loading : {"uniaxial", "in_plane_hydrostatic"}
    potential : str
        A registered potential (``"harmonic"``, ``"lj"``, ...).
    direction : str or float or array_like of float
        ``"[100]"``, ``"[110]"`` (FCC, mirror directions of the (001) surface) or ``"[10]"``
        (triangular rows), as in the paper; or (FCC) any Miller direction in the (001)
        surface (``"[210]"``) or an angle in degrees from [100] toward [010] (float or 1-D
        array of m angles). Non-mirror directions use the general (Stroh) solver.
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the load direction (1 = unstressed).
    load_direction : {None, "[100]", "[110]"}
        FCC: the direction of the uniaxial load (the stretch d/d0 is along it); None = the
        propagation direction, which must then be "[100]" or "[110]" for uniaxial loading.
        In-plane hydrostatic loading has no direction (any value is accepted and ignored).
    min_eig : bool
        Also return ``min_acoustic_eig``, the lowest eigenvalue of V Q(n) over all
        directions (K d0^2), which needs the direction scan at every strain. Without it
        ``stable`` comes from :func:`surfwave.solvers.long_wave.long_wave_stable` (a
        sufficient test of stability, a certificate of instability, the scan only where
        neither decides): the same flags, several times faster.
    details : bool
        Mirror directions only: also return the general solver's ``c2_limit``,
        ``polarisation``, ``decay`` and ``penetration_depth``. Off by default: the Stroh solve
        would cost most of the call (FCC in-plane hydrostatic: 1.9e5 strain points/s
        without, 3.5e4 with, one core), and Eq. (17) alone gives ``c2_R``. Off the mirrors the
        general solver is the route to ``c2_R`` itself, so they are always returned there.

    Returns
    -------
    PointResult (a dict; keys in :class:`surfwave.records.PointResult`)
        Shapes: (n,) per strain, or (n, m) for an array of m angles (scalar angle or string:
        (n,)). ``stress`` (sigma_xx V / K d0^2, x = propagation), ``c2_L_par``, ``c2_T_par``,
        ``c2_L_perp``, ``c2_T_perp``, ``c2_SH`` (NaN in 2D), ``c2_R`` (K d0^2 / m; the real
        part for a pseudo wave), ``c2_limit`` (v_L^2), ``wave_type``, ``reason``,
        ``polarisation`` (..., d) and ``decay`` (..., d) complex, ``penetration_depth``
        (wavelengths) (at mirror directions only with ``details``), ``stable`` (n,) (long-wave
        stability in every direction), ``min_acoustic_eig`` (n,) (only with ``min_eig``), ``C``
        and ``S`` (..., d, d, d, d; times V, lab frame of the propagation),
        ``volume``, ``d_over_d0`` (n,), and ``angle`` (degrees from [100], FCC only).

    Raises
    ------
    InputError, GeometryError
        Unknown names, a direction outside the (001) surface, a uniaxial load without
        direction, an impossible geometry (the message names the value).

    Examples
    --------
    >>> import surfwave
    >>> r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.0)
    >>> round(float(r["c2_R"][0]), 4)   # Table I: 0.3596
    0.3596
    >>> surfwave.point("fcc", "in_plane_hydrostatic", "lj", [0.0, 20.0, 45.0], [0.98, 1.0])["c2_R"].shape
    (2, 3)
    """
    classic = isinstance(direction, str) and direction in ("[100]", "[110]", "[10]") \
        and load_direction in (None, direction)
    if classic:
        out, sigma = elastic.properties_and_stress(lattice, loading, potential, direction, d_over_d0, min_eig)
        ray = rayleigh.solve(out["S"], 1.0, out["c2_SH"])
        out.update(c2_R=ray["c2_R"], wave_type=ray["wave_type"], reason=ray["reason"])
        if details:
            extra = _extras(out["C"], sigma)
            extra.pop("_sw")
            out.update(extra)
        if lattice == "fcc":
            out["angle"] = np.full(out["c2_R"].shape, direction_angle("(001)", direction))
        return cast(PointResult, out)
    return _point_general(lattice, loading, potential, direction, d_over_d0, load_direction, min_eig)


def _point_general(lattice, loading, potential, direction, d_over_d0, load_direction, min_eig) -> PointResult:
    """:func:`point` at any direction of the FCC (001) surface (the general solver)."""
    if lattice != "fcc":
        raise InputError(f"directions other than the mirror ones need lattice 'fcc', got {lattice!r} "
                         f"with direction {direction!r}")
    angle = direction_angle("(001)", direction) if isinstance(direction, str) else direction
    angle = np.asarray(validate.angle_values(angle, "direction"), dtype=float)
    if angle.ndim > 1:
        raise InputError(f"angles must be a scalar or a 1-D array, got shape {angle.shape}")
    if loading == "in_plane_hydrostatic":
        load: Direction = "[100]"  # tetragonal: the loading has no in-plane direction
    elif load_direction in ("[100]", "[110]"):
        load = load_direction
    else:
        raise InputError(f"uniaxial loading along {direction!r} needs load_direction '[100]' or '[110]' "
                         f"(got {load_direction!r}): the lateral relaxation is solved for loads along "
                         "the mirror directions")
    crystal = build(lattice, loading, potential, load, d_over_d0)
    sigma_l = elastic.stress(crystal.bonds, potential)                     # (n, 3, 3), load frame
    C_l = elastic.elastic_constants(crystal.bonds, potential)
    # load lab frame -> crystal axes -> propagation lab frame, composed into one rotation
    rot = np.atleast_3d(lab_axes("(001)", angle)).reshape(-1, 3, 3) @ lab_axes("(001)", load).T   # (m, 3, 3)
    C = rotate4(C_l[:, None], rot[None])                                    # (n, m, 3, 3, 3, 3)
    sigma = rotate2(sigma_l[:, None], rot[None])
    S = elastic.stress_derivatives(sigma, C)
    out: dict = {"d_over_d0": crystal.d_over_d0, "volume": crystal.volume, "stress": sigma[..., 0, 0]}
    out.update(elastic.sound_speeds(S))
    if min_eig:
        out["stable"], out["min_acoustic_eig"], _ = long_wave.long_wave_stability(C_l, sigma_l,
                                                                               long_wave.STABILITY_DIRECTIONS)
    else:
        out["stable"] = long_wave.long_wave_stable(C_l, sigma_l, long_wave.STABILITY_DIRECTIONS)
    extra = _extras(C, sigma)
    sw = extra.pop("_sw")
    out.update(extra)
    out.update(c2_R=sw["c"] ** 2, wave_type=sw["wave_type"], reason=sw["reason"], C=C, S=S)
    out["angle"] = np.broadcast_to(angle.reshape(-1), out["c2_R"].shape).copy()
    if angle.ndim == 0:  # a scalar angle: no angle axis
        for key in _ANGLE_KEYS:
            out[key] = out[key][:, 0]
    return cast(PointResult, out)


#: Outputs of :func:`point` that carry the angle axis (the rest depend on the strain only).
_ANGLE_KEYS = ("stress", "c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH", "c2_R", "c2_limit",
               "wave_type", "reason", "polarisation", "decay", "penetration_depth", "C", "S", "angle")


#: Largest |elastic constant| (GPa) accepted (:data:`surfwave.validate.MAX_CONSTANT_GPA`, the one bound):
#: diamond's C11 is about 1080 GPa; larger values are almost surely given in Pa.
MAX_GPA = validate.MAX_CONSTANT_GPA


def material(C11=None, C12=None, C44=None, rho=None, direction=None, stress=0.0, surface=None, *,
             voigt=None, angle=None, toec=None, piezo=None, permittivity=None, euler=None, cut=None,
             electrical=None, leaky=None) -> MaterialResult:
    """Surface-wave and bulk speeds of a real crystal on any surface, in any direction, under stress.

    Parameters
    ----------
    C11, C12, C44 : float
        Cubic elastic constants, GPa. Without ``toec`` they are taken as the stressed crystal's
        constants (fixed-C model); with ``toec`` they are the unstressed (natural-state) ones.
        Or C11 is a material name from the database (``"Cu"``, ``"copper"``, ``"GaAs"``, ...,
        :func:`surfwave.real_crystals.materials.available_materials`), which supplies the constants and
        the density (an explicit ``rho`` wins). Or:
    voigt : array_like, shape (6, 6), keyword only
        A full Voigt stiffness of any symmetry, crystal axes, GPa (instead of C11, C12, C44).
    rho : float
        Density, kg/m^3 (natural state with ``toec``).
    direction : str or float or array_like of float
        A Miller direction "[uvw]" lying in the surface, or an angle in degrees from the
        surface's reference direction ((001): [100]; (110): [001]; (111): [1-10]) toward
        n x reference (:mod:`surfwave.solvers.orientation`). Default (None): "[100]".
    stress : float or array_like, shape (3, 3), (m,) or (m, 3, 3)
        A scalar: uniaxial stress along the propagation direction; a 3 x 3 Cauchy stress in
        crystal axes; or one of them per direction. GPa (at most 1e3 GPa: larger values are
        taken for Pa and refused), negative = compression. It must lie in the surface plane.
    surface : str
        "(hkl)". Default (None): "(001)".
    angle : float or array_like, optional, keyword only
        Same as an angle ``direction`` (wins over it).
    toec : None, True or sequence of 6 floats or array_like (6, 6, 6), keyword only
        Third-order elastic constants (C111, C112, C123, C144, C155, C456) in GPa, Brugger
        convention (Lagrangian strain, energy per unit natural volume, as tabulated), or a
        Voigt (6, 6, 6) array; True takes them from the database (the material must be given
        by name). The crystal then deforms under the stress
        (:func:`surfwave.real_crystals.toec.stressed_state`): the constants C* and density rho0/J of
        the stressed state are used, the wave propagates along F m0 (m0 the given direction of
        the unstressed crystal) on the surface of normal F^-T n0, and speeds are true phase
        speeds in the stressed state (docs/physics/third-order-constants.md). A stress beyond the
        model's range gives NaN with the reason. Piezoelectric crystals: True (GaAs only in the
        database), or the caller's set as a mapping of the class's named constants (e.g. the 14 of
        quartz, ``{"C111": ..., ..., "C444": ...}``,
        :data:`surfwave.real_crystals.toec_classes.TOEC_NAMES`) or a (6, 6, 6) Voigt array, in
        the database's axis setting (checked: invariant under the crystal's class).
    piezo : array_like, shape (3, 6), keyword only
        Piezoelectric stress constants e_kI, C/m^2, crystal axes (with ``voigt`` and ``permittivity``).
    permittivity : array_like, shape (3, 3), keyword only
        Clamped relative permittivity eps_r (eps / EPS0), crystal axes, symmetric positive definite.
    euler : array_like, shape (3,) or (m, 3), keyword only
        SAW Euler angles (phi, theta, psi) in degrees, ZXZ, lab x1 = propagation, x3 = outward
        normal (:mod:`surfwave.solvers.euler`); replaces ``surface``/``direction`` (giving them
        too is refused). Works for any crystal (a non-piezoelectric one is solved with e = 0).
    cut : str, keyword only
        A named cut (``"128Y-X LiNbO3"``, ``"ST-X quartz"``, ``"128Y-X"`` with the material given;
        :func:`surfwave.real_crystals.piezo_materials.available_cuts`).
    electrical : {"free", "metallized"}, keyword only
        Electrical condition of ``c_R`` (default "free"); ``c_free``, ``c_metallized`` and ``K2``
        are returned either way.
    leaky : None, True or False, keyword only
        The leaky wave radiating into the slowest bulk sheet (``c_leaky``, ``leaky_attenuation``,
        ``leaky_reason``; :func:`surfwave.real_crystals.stressed_wave.surface_wave`). None
        (default): where needed, i.e. every point of a piezoelectric crystal and, for an elastic
        one, where no subsonic wave exists (``pseudo``; an exact ``supersonic_decoupled`` wave
        is the branch's limit, attenuation 0); True: at every point (the leaky wave can coexist
        with the subsonic one, e.g. Cu (001) from ~26 to 45 deg; ~8x the cost of the subsonic
        solve); False: not solved.

    With any of ``piezo``, ``permittivity``, ``euler``, ``cut``, ``electrical``, or a name found
    only in the piezoelectric database (``"LiNbO3"``, ``"quartz"``, ``"LiTaO3"``, ...), the call is
    answered by :func:`surfwave.real_crystals.piezo_route.material_piezo` (fixed-constants model;
    extra outputs ``c_free``, ``c_metallized``, ``K2``, ``c_leaky``, ``leaky_attenuation`` (dB per
    wavelength), ``power_flow_angle`` (degrees), ``potential_share``, ``euler``; ``polarisation``
    (..., 4) with the potential). Crystals of the elastic database ("Cu", "GaAs") keep the elastic
    route unless a piezoelectric argument is given.

    Returns
    -------
    MaterialResult (a dict; keys in :class:`surfwave.records.MaterialResult`)
        Floats for one direction, arrays of shape (m,) for m angles: ``c_R`` (m/s, NaN where
        none; real part for a pseudo wave), ``c_R_imag``, ``c_limit`` (v_L), ``c_L_par``,
        ``c_T_par``, ``c_L_perp``, ``c_T_perp``, ``c_SH`` (bulk speeds along x1 and x2, m/s,
        NaN where imaginary), ``wave_type``, ``reason``, ``stable`` (Born stability and
        positive acoustic tensor in every direction), ``polarisation`` (..., 3) and ``decay``
        (..., 3) complex (see :func:`surfwave.solvers.stroh.surface_wave`),
        ``penetration_depth`` (wavelengths), ``angle`` (degrees from the reference), ``method``,
        ``rho`` (density of the stressed state, kg/m^3), ``toec`` (bool, third-order model used),
        ``c_leaky`` (m/s, NaN where no leaky wave), ``leaky_attenuation`` (dB per wavelength,
        NaN where no leaky wave) and ``leaky_reason`` ("" where one is reported, else why not).
        Every number is NaN (``wave_type`` "none", ``stable`` False, ``method`` "") where the
        crystal has no stressed state: the deformation solve fails, the stressed crystal is
        not Born-stable, or the stress loads the deformed surface; ``reason`` says which, in
        the words the cube uses (the computation is
        :func:`surfwave.real_crystals.stressed_wave.surface_wave`, shared with the cube).

    Raises
    ------
    InputError
        One line, before any solve, the same by every door (:func:`surfwave.resolve.resolve_material`,
        checks in :func:`surfwave.case.make_case`): missing or non-finite constants, constants
        in Pa (hint given), rho outside [1, 1e12] kg/m^3, piezoelectric constants above
        100 C/m^2 or eps_r below 1, complex or boolean numbers, a direction not in the surface,
        ``euler=``/``cut=`` with ``surface=``/``direction=``/``angle=``, a stress with
        sigma . n != 0 (component named) or beyond 1e3 GPa, an unknown material name (known
        ones listed), toec=True for a material without third-order constants (the material
        and the missing constants named), third-order constants in Pa or given as True.

    Examples
    --------
    >>> r = material(2.0, 1.0, 1.0, 1e9, "[100]")   # nearest-neighbour FCC ratios
    >>> round(r["c_R"] ** 2 / 1.0, 6)               # (3 - sqrt 3)/2 C44/rho, m^2/s^2
    0.633975
    >>> round(material(168.4, 121.4, 75.4, 8960, "[1-10]", surface="(111)")["c_R"], 1)
    1613.5
    >>> round(material("Cu", direction="[100]", stress=0.1, toec=True)["c_R"], 2)  # 2012.12 unstressed
    2019.06
    >>> r = material("LiNbO3", cut="128Y-X")      # Warner 1967 set; published 3979 m/s, K^2 5.3 %
    >>> round(r["c_free"], 1), round(r["c_metallized"], 1), round(100 * r["K2"], 2)
    (3994.2, 3887.6, 5.34)
    """
    case = resolve_material(C11, C12, C44, rho, direction, stress, surface, voigt=voigt, angle=angle, toec=toec,
                            piezo=piezo, permittivity=permittivity, euler=euler, cut=cut, electrical=electrical,
                            leaky=leaky)
    return cast(MaterialResult, material_result(case))
