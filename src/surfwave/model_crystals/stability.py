"""Long-wave and full-zone stability of prestressed crystals, and the first instabilities.

The long-wave criterion is the analytic acoustic tensor over all directions
(``surfwave.point(...)["stable"]``, Eq. A11); the full-zone criterion is phonopy's
(:func:`surfwave.model_crystals.phonons.bulk_speeds`: no imaginary frequency on the zone mesh nor in the
long-wave limit of the force constants).

Only a :class:`~surfwave.errors.GeometryError` (the crystal cannot be built, or has
collapsed) ends a stable range here; any other exception is a bug and propagates.
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import GeometryError, InputError
from surfwave.model_crystals.elastic import properties
from surfwave.model_crystals.lattices import build_checked
from surfwave.model_crystals.phonons import (
    DEFAULT_DISPLACEMENT,
    DEFAULT_SUPERCELL,
    DEFAULT_ZONE_MESH,
    bulk_speeds,
)
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.validate import as_1d
from surfwave.vocab import Direction, Lattice, Loading


def _long_wave_flags(lattice, loading, potential, direction, s: np.ndarray) -> np.ndarray:
    """Analytic long-wave stability per point (``surfwave.point(...)["stable"]``, i.e.
    :func:`surfwave.model_crystals.elastic.properties`; the Rayleigh solve of ``point`` is not needed).

    Vectorised when every point can be built; otherwise point by point, a point whose
    geometry cannot be built (or has collapsed) being reported as False. Each point's value
    is independent of the others (the long-wave search runs per strain).
    """
    pot = get_potential(potential)
    try:
        build_checked(lattice, loading, pot, direction, s)
    except GeometryError:
        flags = np.zeros(s.size, bool)
        for i, si in enumerate(s):
            try:
                build_checked(lattice, loading, pot, direction, [si])
            except GeometryError:  # the geometry ends: not stable there
                continue
            flags[i] = bool(properties(lattice, loading, pot, direction, [si], min_eig=False)["stable"][0])
        return flags
    return np.asarray(properties(lattice, loading, pot, direction, s, min_eig=False)["stable"], bool)


def stability_scan(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential,
    direction: Direction,
    d_over_d0: ArrayLike,
    supercell: int = DEFAULT_SUPERCELL,
    displacement: float = DEFAULT_DISPLACEMENT,
    zone_mesh: int = DEFAULT_ZONE_MESH,
) -> dict[str, np.ndarray]:
    """Long-wave and full-zone stability flags at each strain.

    Parameters
    ----------
    lattice, loading, potential, direction : str
    d_over_d0 : array_like, shape (n,)
    supercell, displacement, zone_mesh
        Phonopy knobs, as in :func:`bulk_speeds`.

    Returns
    -------
    dict
        ``stable_long_wave`` (n,) bool: analytic acoustic tensor Q(n) positive for every
        direction (:func:`surfwave.point`); ``stable_full_zone`` (n,) bool: phonopy's
        ``stable_phonon`` (zone mesh and long-wave limit of the force constants);
        ``min_omega2`` (n,) K/m, ``min_omega2_q`` (n, 3) rad/d0, ``min_c2_phonopy`` (n,)
        K d0^2/m, ``reason`` (n,) str. Points that cannot be built are False in both flags.
    """
    s = as_1d(d_over_d0, finite=False)  # per point, as bulk_speeds: a non-finite point is NaN
    bulk = bulk_speeds(
        lattice,
        loading,
        potential,
        direction,
        s,
        supercell=supercell,
        displacement=displacement,
        zone_mesh=zone_mesh,
    )
    return {
        "d_over_d0": s,
        "stable_long_wave": _long_wave_flags(lattice, loading, potential, direction, s),
        "stable_full_zone": bulk["stable_phonon"] & (bulk["reason"] == ""),
        "min_omega2": bulk["min_omega2"],
        "min_omega2_q": bulk["min_omega2_q"],
        "min_c2_phonopy": bulk["min_c2_phonopy"],
        "reason": bulk["reason"],
    }


def _flag(lattice, loading, potential, direction, kind, d, knobs) -> bool | None:
    """Stability flag at one d/d0; None if the geometry cannot be built there."""
    try:
        build_checked(lattice, loading, potential, direction, [d])
    except GeometryError:
        return None
    if kind == "long_wave":
        return bool(_long_wave_flags(lattice, loading, potential, direction, np.array([d]))[0])
    r = bulk_speeds(lattice, loading, potential, direction, [d], **knobs)
    return bool(r["stable_phonon"][0] and r["reason"][0] == "")


def instability_limits(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential,
    direction: Direction,
    kind: Literal["long_wave", "full_zone"] = "long_wave",
    step: float = 0.01,
    tol: float = 1e-4,
    search: tuple[float, float] = (0.3, 2.0),
    **knobs: Any,
) -> tuple[float, float]:
    """First unstable d/d0 in compression and in tension, walking out from d/d0 = 1.

    Steps of ``step`` from 1 until the flag turns False, then bisection of the last
    stable / first unstable bracket down to ``tol``; the unstable end is returned. NaN if
    the crystal stays stable up to the ``search`` bound or up to where its geometry ends
    (in-plane hydrostatic FCC at sqrt 2, triangular at 2, the collapse t_y -> 0 of
    harmonic uniaxial FCC [110] at sqrt 3; see :func:`geometry_limit`).

    Parameters
    ----------
    kind : {"long_wave", "full_zone"}
        Analytic acoustic-tensor criterion, or phonopy's full-zone criterion.
    step, tol : float
        Walk step and bisection tolerance in d/d0.
    search : (float, float)
        Lowest and highest d/d0 examined.
    **knobs
        Phonopy knobs for ``kind="full_zone"`` (supercell, displacement, zone_mesh).

    Returns
    -------
    (d_compress, d_tension) : tuple of float
        d/d0 of the first instability below and above 1 (accurate to ``tol``).
    """
    if kind not in ("long_wave", "full_zone"):
        raise InputError(f"kind must be 'long_wave' or 'full_zone', got {kind!r}")
    return _walk_and_bisect(
        lambda d: _flag(lattice, loading, potential, direction, kind, d, knobs), step, tol, search
    )


def _walk_and_bisect(flag, step: float, tol: float, search: tuple[float, float]) -> tuple[float, float]:
    """First d/d0 (below and above 1) where ``flag(d)`` is False, to ``tol``.

    ``flag`` returns True (good), False (bad) or None (stop: NaN for that side).
    """
    limits = []
    for sign, bound in ((-1.0, search[0]), (1.0, search[1])):
        good, bad = 1.0, None
        for j in range(1, int(np.floor(abs(bound - 1.0) / step + 1e-9)) + 1):
            d = 1.0 + sign * j * step
            f = flag(d)
            if f is None:
                break
            if not f:
                bad = d
                break
            good = d
        if bad is None:
            limits.append(np.nan)
            continue
        while abs(bad - good) > tol:
            mid = 0.5 * (good + bad)
            good, bad = (mid, bad) if flag(mid) is True else (good, mid)
        limits.append(float(bad))
    return limits[0], limits[1]


def geometry_limit(
    lattice: Lattice,
    loading: Loading,
    potential: str | PairPotential,
    direction: Direction,
    step: float = 0.01,
    tol: float = 1e-4,
    search: tuple[float, float] = (0.3, 2.0),
) -> tuple[float, float]:
    """First d/d0 below and above 1 (to ``tol``) at which the geometry can no longer be built.

    A collapsed geometry (a lab stretch or the volume below 1e-6) counts as not built.
    NaN where it still exists at the ``search`` bound. Same walk-and-bisect as
    :func:`instability_limits`, with "buildable and not collapsed" as the flag.
    """
    pot = get_potential(potential)

    def ok(d):
        try:
            build_checked(lattice, loading, pot, direction, [d])
            return True
        except GeometryError:
            return False

    return _walk_and_bisect(ok, step, tol, search)
