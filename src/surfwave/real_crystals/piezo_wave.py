"""Surface waves of (prestressed) piezoelectric crystals: free, metallized, K^2, leaky, power flow.

One call per question "what does a SAW do on this cut of this crystal?", vectorised over m
orientations (lab axes from Euler angles, a named cut, or a Miller surface and direction).

Model (say it whenever a prestress is given): fixed constants, A_ijkl = C_ijkl + sigma0_jl
delta_ik with C the stiffness at constant field of the data set (the stressed crystal's
constants are taken equal to the natural ones); the piezoelectric constants e and the clamped
permittivity eps are held at their natural values (their stress derivatives are not in the
database). The prestress must lie in the surface plane (sigma0 . n = 0); a point where it does
not is NaN with a reason.

Solvers: :func:`surfwave.solvers.piezo.piezo_surface_wave` (subsonic SAW, both electrical
conditions) and :func:`surfwave.solvers.leaky.leaky_wave` (the leaky wave radiating into the
slowest bulk sheet, for the requested electrical condition).
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError
from surfwave.real_crystals.piezo_materials import EPS0, PiezoMaterial, check_piezo_record, get_piezo_material
from surfwave.solvers.piezo import piezo_surface_wave
from surfwave.solvers.piezo_tensors import piezo_voigt_to_tensor, rotate3
from surfwave.solvers.tensors import rotate2, rotate4, voigt_to_tensor

__all__ = ["MODEL", "piezo_wave", "resolve_piezo_material"]

#: The prestress model, recorded in every result and cube.
MODEL = ("fixed constants: A = C + sigma0 delta (C^E of the data set); e and clamped eps at their natural "
         "values (no stress derivatives)")
#: Largest |stress| (GPa) accepted; larger values are almost surely in Pa.
MAX_STRESS_GPA = 1e3
#: sigma0 . n above this fraction of max |sigma0|: the prestress loads the surface.
TRACTION_RTOL = 1e-9
REASON_TRACTION = "prestress loads the surface (sigma0 . n != 0): the fixed-C model needs an in-plane stress"
ELECTRICAL = ("free", "metallized")
#: |delta| (Im k / Re k) of a leaky root at or below which it is an exact (non-radiating) supersonic wave.
DELTA_EXACT = 1e-10


def resolve_piezo_material(material=None, *, voigt=None, e=None, eps_r=None, rho=None) -> PiezoMaterial:
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
        positive definite (stiffness, eps_r), rho <= 0 (:func:`check_piezo_record`).
    """
    if material is not None:
        if any(v is not None for v in (voigt, e, eps_r)):
            raise InputError(f"material {material!r} given by name: do not also give voigt=, piezo= or "
                             "permittivity=")
        m = get_piezo_material(material)
        if rho is None:
            return m
        check_piezo_record(m.voigt, m.e, m.eps_r, rho, name=m.name)
        return PiezoMaterial(**{**m.__dict__, "rho": float(rho)})
    for key, value in (("voigt", voigt), ("piezo (e)", e), ("permittivity (eps_r)", eps_r), ("rho", rho)):
        if value is None:
            raise InputError(f"{key} is missing: a piezoelectric crystal needs voigt (6 x 6, GPa), piezo "
                             "(3 x 6, C/m^2), permittivity (3 x 3, relative) and rho (kg/m^3), or a name")
    try:
        C6, e6, er = (np.asarray(x, dtype=float) for x in (voigt, e, eps_r))
    except (TypeError, ValueError) as exc:
        raise InputError(f"piezoelectric constants must be numeric arrays: {exc}") from None
    check_piezo_record(C6, e6, er, rho, name="constants")
    return PiezoMaterial(name="user", formula="", crystal_class="", rho=float(rho), voigt=C6, e=e6, eps_r=er,
                         constants={}, setting="user-supplied, crystal axes", sources={})


def _prestress(stress, x1: np.ndarray) -> np.ndarray:
    """Cauchy prestress in crystal axes (m, 3, 3), GPa.

    From a scalar (uniaxial along each x1), a 3 x 3 tensor (crystal axes, the same at every
    point), an (m,) array (uniaxial along x1, one value per point) or an (m, 3, 3) array.
    """
    m = x1.shape[0]
    try:
        s = np.asarray(stress, dtype=float)
    except (TypeError, ValueError):
        raise InputError(f"stress must be a number or a 3 x 3 tensor (GPa), got {stress!r}") from None
    if not np.all(np.isfinite(s)):
        raise InputError(f"stress must be finite, got {stress!r}")
    if s.size and np.abs(s).max() > MAX_STRESS_GPA:
        raise InputError(f"stress must be in GPa; got max |stress| = {np.abs(s).max():.4g}, which looks like Pa "
                         "(divide by 1e9)")
    if s.shape == () or s.shape == (m,):
        return s[..., None, None] * x1[:, :, None] * x1[:, None, :]
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


def _elastic(A, rho, eps, sw_piezo) -> tuple[dict, np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """e = 0: the elastic Stroh solver's wave with a decoupled potential (phi = 0 at the surface).

    The potential's own Stroh root is that of eps_11 + 2 eps_12 p + eps_22 p^2 = 0 with Im p > 0.
    Returns the solver dict (c, wave_type, reason, method, polarisation (m, 4), decay (m, 4),
    power_flow_angle from the piezoelectric solver where subsonic, potential_share 0), c_free,
    c_metallized (both = c), K2 (0 where c is finite) and c_imag.
    """
    from surfwave.solvers.stroh import surface_wave

    el = surface_wave(A, rho)
    m = A.shape[0]
    e11, e12, e22 = eps[:, 0, 0], eps[:, 0, 1], eps[:, 1, 1]
    p_phi = (-e12 + 1j * np.sqrt(np.maximum(e11 * e22 - e12 ** 2, 0.0))) / e22
    found = np.isfinite(el["c"])
    sw = {"c": el["c"], "c_limit": el["c_limit"], "wave_type": el["wave_type"].astype(object),
          "reason": el["reason"].astype(object), "method": el["method"].astype(object),
          "polarisation": np.concatenate([el["polarisation"], np.where(found, 0.0, np.nan)[:, None]], axis=-1),
          "decay": np.concatenate([el["decay"], np.where(found, p_phi, np.nan)[:, None]], axis=-1),
          "power_flow_angle": np.where(np.isclose(sw_piezo["c"], el["c"], rtol=1e-9, atol=0),
                                       sw_piezo["power_flow_angle"], np.nan),
          "potential_share": np.where(found, 0.0, np.nan), "penetration_depth": el["penetration_depth"]}
    with np.errstate(invalid="ignore"):
        K2 = np.where(found, 0.0, np.nan) + np.zeros(m)
    return sw, el["c"], el["c"], K2, el["c_imag"]


def _supersonic(sw, c_free, c_met, lws, electrical):
    """Where no subsonic SAW exists but the leaky root has zero attenuation (|delta| <= DELTA_EXACT,
    e.g. GaAs (001)[110], whose mirror plane decouples the sagittal wave and the potential from
    the slower SH bulk wave), that root is an exact supersonic surface wave: it becomes c_free /
    c_metallized (and c_R, wave_type ``supersonic_decoupled``, its polarisation and decay; the
    power flow and potential share are not computed there, NaN)."""
    cs = {"free": c_free.copy(), "metallized": c_met.copy()}
    for el, lw in lws.items():
        exact = ~np.isfinite(cs[el]) & np.isfinite(lw["c_leaky"]) & (np.abs(lw["delta"]) <= DELTA_EXACT)
        cs[el] = np.where(exact, lw["c_leaky"], cs[el])
        if el == electrical and exact.any():
            sw = dict(sw)
            sw["c"] = cs[el]
            for key in ("wave_type", "reason"):
                sw[key] = sw[key].copy()
            sw["wave_type"][exact] = "supersonic_decoupled"
            sw["reason"][exact] = ""
            sw["polarisation"] = np.where(exact[:, None], lw["polarisation"], sw["polarisation"])
            sw["decay"] = np.where(exact[:, None], lw["decay"], sw["decay"])
    with np.errstate(invalid="ignore"):
        K2 = 2 * (cs["free"] - cs["metallized"]) / cs["free"]
    return sw, cs["free"], cs["metallized"], K2


def piezo_wave(material=None, axes=None, stress=0.0, *, electrical: str = "free", leaky: bool = True,
               tol: float = 1e-12, voigt=None, e=None, eps_r=None, rho=None) -> dict:
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
        orientation. Fixed-constants model (:data:`MODEL`).
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
        ``C`` (m, 3, 3, 3, 3) Pa, ``e`` (m, 3, 3, 3) C/m^2, ``eps`` (m, 3, 3) F/m, ``sigma`` (m, 3, 3)
        GPa (lab frame), ``rho`` (m,) kg/m^3, ``model`` (str).

    Raises
    ------
    InputError
        Bad constants (see :func:`resolve_piezo_material`), axes that are not rotations, stress
        not scalar or 3 x 3, non-finite or in Pa, unknown ``electrical``; all before any solve.

    Examples
    --------
    >>> from surfwave.real_crystals.piezo_materials import get_cut
    >>> cut = get_cut("Y-Z LiNbO3")
    >>> r = piezo_wave(cut.material, cut.lab_axes)
    >>> round(float(r["c_free"][0])), round(float(r["c_metallized"][0]))   # Slobodnik 1973: 3488 / 3404
    (3488, 3404)
    """
    if electrical not in ELECTRICAL:
        raise InputError(f"electrical must be 'free' or 'metallized', got {electrical!r}")
    mat = resolve_piezo_material(material, voigt=voigt, e=e, eps_r=eps_r, rho=rho)
    if axes is None:
        raise InputError("lab axes are missing: give Euler angles, a named cut or a surface and direction")
    R = _axes(axes)
    m = R.shape[0]
    sigma_c = _prestress(stress, R[:, 0])
    traction = np.abs(np.einsum("mij,mj->mi", sigma_c, R[:, 1])).max(axis=-1)
    loaded = traction > TRACTION_RTOL * max(np.abs(sigma_c).max(), 1e-300)
    C = rotate4(voigt_to_tensor(mat.voigt) * 1e9, R)
    ee = rotate3(piezo_voigt_to_tensor(mat.e), R)
    eps = rotate2(mat.eps_r * EPS0, R)
    sigma = rotate2(sigma_c, R)
    sigma[loaded] = 0.0                                              # placeholder, NaN below
    A = C + 1e9 * np.einsum("mjl,ik->mijkl", sigma, np.eye(3))
    rho_m = np.full(m, mat.rho)
    both = piezo_surface_wave(np.concatenate([A, A]), np.concatenate([ee, ee]), np.concatenate([eps, eps]),
                              np.concatenate([rho_m, rho_m]),
                              electrical=np.repeat(np.array(ELECTRICAL, dtype=object), m), tol=tol)
    k = 0 if electrical == "free" else 1
    sw = {key: v[k * m:(k + 1) * m] for key, v in both.items()}
    c_free, c_met = both["c"][:m], both["c"][m:]
    with np.errstate(invalid="ignore"):
        K2 = 2 * (c_free - c_met) / c_free
    c_imag = np.where(np.isfinite(sw["c"]), 0.0, np.nan)
    if not np.any(mat.e):                       # e = 0: the elastic solver, exactly (supersonic waves too)
        sw, c_free, c_met, K2, c_imag = _elastic(A, rho_m, eps, sw)
    im = np.where(np.isfinite(sw["decay"].imag), sw["decay"].imag, np.inf).min(axis=-1)
    with np.errstate(divide="ignore"):
        depth = np.where(np.isfinite(sw["c"]) & np.isfinite(im), 1.0 / (2 * np.pi * im), np.nan)
    depth = sw.get("penetration_depth", depth)
    c_leaky = np.full(m, np.nan)
    att = np.full(m, np.nan)
    leaky_reason = np.full(m, "not computed (leaky=False)", dtype=object)
    if leaky:
        from surfwave.solvers.leaky import leaky_wave

        piezo = bool(np.any(mat.e))
        lws = {el: leaky_wave(A, rho_m, ee, eps, electrical=el) for el in (ELECTRICAL if piezo else (electrical,))}
        lw = lws[electrical]
        c_leaky, att, leaky_reason = lw["c_leaky"], lw["leaky_attenuation"], lw["reason"].astype(object)
        if piezo:                       # exact supersonic waves (mirror directions): the leaky root, delta = 0
            sw, c_free, c_met, K2 = _supersonic(sw, c_free, c_met, lws, electrical)
    out = {"c_R": sw["c"], "c_free": c_free, "c_metallized": c_met, "K2": K2, "c_limit": sw["c_limit"],
           "c_leaky": c_leaky, "leaky_attenuation": att, "leaky_reason": leaky_reason,
           "power_flow_angle": sw["power_flow_angle"], "polarisation": sw["polarisation"],
           "potential_share": sw["potential_share"], "decay": sw["decay"], "penetration_depth": depth,
           "c_imag": c_imag,
           "wave_type": sw["wave_type"].copy(), "reason": sw["reason"].copy(), "method": sw["method"]}
    if loaded.any():
        for key in ("c_R", "c_imag", "c_free", "c_metallized", "K2", "c_limit", "c_leaky", "leaky_attenuation",
                    "power_flow_angle", "potential_share", "penetration_depth"):
            out[key] = np.where(loaded, np.nan, out[key])
        for key in ("polarisation", "decay"):
            out[key] = np.where(loaded[:, None], np.nan, out[key])
        out["wave_type"][loaded] = "none"
        out["reason"][loaded] = REASON_TRACTION
        out["leaky_reason"] = np.where(loaded, REASON_TRACTION, out["leaky_reason"]).astype(object)
    out.update(electrical=np.full(m, electrical, dtype=object), C=C, e=ee, eps=eps, sigma=sigma, rho=rho_m,
               model=MODEL)
    return out
