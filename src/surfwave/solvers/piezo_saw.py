"""The piezoelectric SAW of m points in one call: free and metallized speeds, K^2, leaky wave, power flow.

Tensors in (lab frame, SI), waves out: the piezoelectric branch of the one real-crystal path
(:func:`surfwave.real_crystals.stressed_wave.surface_wave`) calls :func:`piezo_saw` where a
crystal has piezoelectric constants. It combines :func:`surfwave.solvers.piezo.piezo_surface_wave`
(subsonic SAW, both electrical conditions in one batch), :func:`surfwave.solvers.leaky.leaky_wave`
(the leaky wave radiating into the slowest bulk sheet) and, for e = 0, the elastic Stroh solver
(:func:`surfwave.solvers.stroh.surface_wave`, so that a non-piezoelectric crystal gets exactly
the elastic answer, supersonic waves included).
"""
from __future__ import annotations

from typing import Sequence

import numpy as np

from surfwave.solvers.boundary import BOUNDARIES, Boundary, as_boundary
from surfwave.solvers.leaky import leaky_wave
from surfwave.solvers.piezo import piezo_surface_wave
from surfwave.solvers.stroh import surface_wave
from surfwave.vocab import ELECTRICAL

__all__ = ["DELTA_EXACT", "ELECTRICAL", "PIEZO_KEYS", "piezo_saw", "piezo_saw_conditions"]

#: Extra per-point float outputs of a piezoelectric crystal.
PIEZO_KEYS = ("c_free", "c_metallized", "K2", "c_leaky", "leaky_attenuation", "power_flow_angle",
              "potential_share", "c_leaky_free", "c_leaky_metallized", "K2_leaky")
#: |delta| (Im k / Re k) of a leaky root at or below which it is an exact (non-radiating) supersonic wave.
DELTA_EXACT = 1e-10


def piezo_saw(A: np.ndarray, rho: np.ndarray, e: np.ndarray, eps: np.ndarray, *, electrical: str = "free",
              tol: float = 1e-12, leaky: bool = True) -> dict:
    """Free and metallized SAW, K^2, leaky wave and power flow of m piezoelectric points (lab, SI).

    Parameters
    ----------
    A : ndarray, shape (m, 3, 3, 3, 3)
        Wave-propagation tensor C + sigma delta, Pa, lab frame (x1 propagation, x2 inward normal).
    rho : ndarray, shape (m,)
        Density, kg/m^3.
    e : ndarray, shape (m, 3, 3, 3)
        Piezoelectric stress tensor e_kij, C/m^2, lab frame.
    eps : ndarray, shape (m, 3, 3)
        Clamped permittivity, F/m, lab frame.
    electrical : {"free", "metallized"}
        Condition of ``c``, the polarisation, the power flow and the leaky wave.
    tol : float
        Relative accuracy of rho c^2 of the subsonic wave.
    leaky : bool
        Also the leaky wave (NaN and "not computed (leaky=False)" otherwise).

    Returns
    -------
    dict of ndarray, leading shape (m,)
        ``c``, ``c_imag``, ``c_limit`` (stiffened), ``penetration_depth``, ``wave_type``,
        ``reason``, ``method``, ``polarisation`` (m, 4), ``decay`` (m, 4), and :data:`PIEZO_KEYS`
        plus ``leaky_reason``. ``c_leaky_free``, ``c_leaky_metallized`` (m/s) and ``K2_leaky``
        (2 (c_leaky_free - c_leaky_metallized) / c_leaky_free, a fraction) are the leaky wave's
        pair and coupling, the same for either ``electrical`` (NaN where either root is missing,
        and everywhere with ``leaky=False``); ``c_leaky`` is the member of the pair for
        ``electrical``.

    Notes
    -----
    :func:`surfwave.solvers.piezo.piezo_surface_wave` for both conditions in one call; e = 0
    (every point): the elastic Stroh solver (:func:`_elastic_piezo_keys`); leaky:
    :func:`surfwave.solvers.leaky.leaky_wave` (both conditions in one call), and where no
    subsonic SAW exists but the leaky root does not attenuate (a mirror direction) that root is
    the SAW (:func:`_supersonic`).
    """
    return piezo_saw_conditions(A, rho, e, eps, conditions=(electrical,), tol=tol, leaky=leaky)[electrical]


def piezo_saw_conditions(A: np.ndarray, rho: np.ndarray, e: np.ndarray, eps: np.ndarray, *,
                         conditions: Sequence[str | Boundary] = ELECTRICAL, tol: float = 1e-12,
                         leaky: bool = True) -> dict[str, dict]:
    """:func:`piezo_saw` for several electrical conditions from one set of solves.

    The subsonic search always solves both conditions (K^2 needs both) and, for a piezoelectric
    point, the leaky search too (an exact supersonic root fixes c_free / c_metallized); asking for
    both conditions therefore costs what one costs.

    Parameters
    ----------
    A, rho, e, eps, tol, leaky
        As :func:`piezo_saw`.
    conditions : sequence of {"free", "metallized"} or of :class:`surfwave.solvers.boundary.Boundary`
        The conditions wanted, each once (results keyed by their names). Free and metallized
        are always solved (K^2); another boundary object is added to the same batch.

    Returns
    -------
    dict
        Condition -> the dict :func:`piezo_saw` returns for it.
    """
    asked = {b.name: b for b in (as_boundary(c) for c in conditions)}    # name -> boundary object
    names_asked = tuple(asked)
    # the batch: free and metallized always (K^2), then any other boundary asked, each once
    batch = tuple(BOUNDARIES[n] for n in ELECTRICAL) + tuple(b for n, b in asked.items() if n not in ELECTRICAL)
    m = A.shape[0]
    if m == 0:                           # no point with a state
        f, c = np.empty(0), np.empty((0, 4), dtype=complex)
        return {el: {**{k: f for k in ("c", "c_imag", "c_limit", "penetration_depth") + PIEZO_KEYS},
                     **{k: np.empty(0, dtype=object) for k in ("wave_type", "reason", "method", "leaky_reason")},
                     "polarisation": c, "decay": c} for el in names_asked}
    nb = len(batch)
    with np.errstate(invalid="ignore"):    # a point without a wave is NaN + reason, not a warning
        both = piezo_surface_wave(np.concatenate([A] * nb), np.concatenate([e] * nb), np.concatenate([eps] * nb),
                                  np.concatenate([rho] * nb),
                                  electrical=np.repeat(np.array(batch, dtype=object), m), tol=tol)
    piezo = bool(np.any(e))
    lws: dict = {}
    if leaky:
        with np.errstate(invalid="ignore"):
            # every condition in one call: the scan's eigen-decompositions are shared
            lws = leaky_wave(A, rho, e, eps, electrical=batch if piezo else tuple(asked.values()))
    names = tuple(b.name for b in batch)
    return {el: _one_condition(A, rho, e, eps, both, lws, el, tol, piezo, names) for el in names_asked}


def _one_condition(A, rho, e, eps, both, lws, electrical, tol, piezo, batch=ELECTRICAL) -> dict:
    """The :func:`piezo_saw` dict of one condition from the shared subsonic (``both``, the
    conditions ``batch`` one after the other, free and metallized first) and leaky (``lws``,
    empty without leaky) solves."""
    m = A.shape[0]
    k = batch.index(electrical)
    sw = {key: v[k * m:(k + 1) * m] for key, v in both.items()}
    c_free, c_met = both["c"][:m], both["c"][m:2 * m]
    with np.errstate(invalid="ignore"):
        K2 = 2 * (c_free - c_met) / c_free
    c_imag = np.where(np.isfinite(sw["c"]), 0.0, np.nan)
    if not piezo:                        # e = 0: the elastic solver, exactly (supersonic waves too)
        sw, c_free, c_met, K2, c_imag = _elastic_piezo_keys(A, rho, eps, sw, tol)
    # the smallest Im p > 0 of the partial waves carrying the wave (a NaN slot, e.g. the decoupled
    # potential of a mirror wave, carries none: NaN + 0j must not count as Im p = 0, depth inf)
    dec = sw["decay"]
    im = np.where(np.isfinite(dec) & (dec.imag > 0), dec.imag, np.inf).min(axis=-1)
    with np.errstate(divide="ignore"):
        depth = np.where(np.isfinite(sw["c"]) & np.isfinite(im), 1.0 / (2 * np.pi * im), np.nan)
    depth = sw.get("penetration_depth", depth)
    c_leaky, att = np.full(m, np.nan), np.full(m, np.nan)
    leaky_reason = np.full(m, "not computed (leaky=False)", dtype=object)
    pair = {el: np.full(m, np.nan) for el in ELECTRICAL}
    if lws:
        lw = lws[electrical]
        c_leaky, att, leaky_reason = lw["c_leaky"], lw["leaky_attenuation"], lw["reason"].astype(object)
        # e = 0 solves one condition: the potential is decoupled, so the other has the same root
        pair = {el: np.asarray(lws.get(el, lw)["c_leaky"], dtype=float) for el in ELECTRICAL}
        if piezo:
            sw, c_free, c_met, K2 = _supersonic(sw, c_free, c_met, lws, electrical)
    with np.errstate(invalid="ignore"):
        K2_leaky = 2 * (pair["free"] - pair["metallized"]) / pair["free"]
    return {"c": sw["c"], "c_imag": c_imag, "c_limit": sw["c_limit"], "wave_type": sw["wave_type"],
            "reason": sw["reason"], "method": sw["method"], "polarisation": sw["polarisation"],
            "decay": sw["decay"], "penetration_depth": depth, "c_free": c_free, "c_metallized": c_met,
            "K2": K2, "c_leaky": c_leaky, "leaky_attenuation": att, "leaky_reason": leaky_reason,
            "power_flow_angle": sw["power_flow_angle"], "potential_share": sw["potential_share"],
            "c_leaky_free": pair["free"], "c_leaky_metallized": pair["metallized"], "K2_leaky": K2_leaky}


def _elastic_piezo_keys(A, rho, eps, sw_piezo, tol) -> tuple:
    """e = 0: the elastic Stroh solver's wave with a decoupled potential (phi = 0 at the surface).

    The potential's own Stroh root is that of eps_11 + 2 eps_12 p + eps_22 p^2 = 0 with Im p > 0.
    Returns the solver dict (polarisation and decay with a 4th component; the power flow of the
    piezoelectric solver where it found the same wave, potential share 0), c_free, c_metallized
    (both = c), K2 (0 where c is finite) and c_imag.
    """
    el = surface_wave(A, rho)
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
    K2 = np.where(found, 0.0, np.nan)
    return sw, el["c"], el["c"], K2, el["c_imag"]


def _supersonic(sw, c_free, c_met, lws, electrical):
    """Where no subsonic SAW exists but the leaky root has zero attenuation (|delta| <=
    :data:`DELTA_EXACT`, e.g. GaAs (001)[110], whose mirror plane decouples the sagittal wave and
    the potential from the slower SH bulk wave), that root is an exact supersonic surface wave:
    it becomes c_free / c_metallized (and c_R, wave_type ``supersonic_decoupled``, its
    polarisation and decay; the power flow and potential share are not computed there, NaN)."""
    cs = {"free": c_free.copy(), "metallized": c_met.copy()}
    for el, lw in lws.items():
        if el not in cs:                 # another boundary: only where it is the condition asked
            if el != electrical:
                continue
            cs[el] = sw["c"].copy()
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
