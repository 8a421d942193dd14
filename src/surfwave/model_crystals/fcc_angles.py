"""Model FCC crystals with propagation at any angle in the (001) surface.

Under in-plane hydrostatic loading (sigma_xx = sigma_zz, the paper's Table I and Fig. 2) the
prestressed FCC crystal is tetragonal about the surface normal and the stress is invariant
under rotations about it, so the lab frame for an angle theta (degrees from [100] toward
[010]) is the [100] lab frame turned about the normal y: the new propagation axis is
x' = cos(theta) x - sin(theta) z, and z' = sin(theta) x + cos(theta) z (at theta = 45 this is
exactly the [110] frame of :mod:`surfwave.model_crystals.lattices`). Elastic constants, stress
derivatives and sound speeds are rotated from the [100] results; the Rayleigh speed uses
Eq. (17) on the mirror directions (theta a multiple of 45 degrees) and the general
anisotropic solver (:mod:`surfwave.solvers.stroh`) elsewhere, where the sagittal and
shear-horizontal motions couple.

Units are the reduced units of docs/physics/paper.md (tensors times the volume per atom, m = 1).

Examples
--------
>>> out = properties_at_angles("lj", [0.0, 45.0], [1.0])
>>> out["C"].shape
(2, 1, 3, 3, 3, 3)
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.model_crystals import elastic
from surfwave.solvers import rayleigh
from surfwave.solvers.tensors import rotate4
from surfwave.validate import as_1d
from surfwave.vocab import WAVE_TYPES  # noqa: F401 (the wave types the rayleigh cube may hold)

#: The only loading whose stressed crystal is the same for every in-plane angle.
LOADING = "in_plane_hydrostatic"


def lab_rotation(angles: ArrayLike) -> np.ndarray:
    """Rotations about the surface normal from the [100] lab frame to the frame at each angle.

    Parameters
    ----------
    angles : array_like, shape (n,)
        Degrees from [100] toward [010].

    Returns
    -------
    ndarray, shape (n, 3, 3)
        Rows: the new lab axes x', y' = y, z' written in the [100] lab axes.
    """
    t = np.radians(as_1d(angles, "angles"))
    c, s, z, o = np.cos(t), np.sin(t), np.zeros_like(t), np.ones_like(t)
    return np.stack([np.stack([c, z, -s], -1), np.stack([z, o, z], -1), np.stack([s, z, c], -1)], -2)


def is_mirror(angles: ArrayLike) -> np.ndarray:
    """True where the sagittal plane is a mirror of the tetragonal crystal (multiples of 45 degrees)."""
    a = np.asarray(angles, dtype=float)
    return np.isclose(np.mod(a + 1e-9, 45.0), 0.0, atol=1e-6)


def properties_at_angles(potential: str, angles: ArrayLike, d_over_d0: ArrayLike, loading: str = LOADING) -> dict:
    """:func:`surfwave.model_crystals.elastic.properties` at every angle.

    Parameters
    ----------
    potential : str
    angles : array_like, shape (na,)
        Degrees from [100] toward [010].
    d_over_d0 : array_like, shape (n,)
    loading : {"in_plane_hydrostatic"}

    Returns
    -------
    dict
        The keys of :func:`surfwave.model_crystals.elastic.properties`, each with a leading
        angle axis: shape (na, n) or (na, n, 3, 3, 3, 3) for ``C`` and ``S``.

    Raises
    ------
    InputError
        Another loading (the uniaxial crystal depends on the angle and is not built).
    """
    if loading != LOADING:
        raise InputError(f"loading {loading!r} at arbitrary angles is not supported: only "
                         f"{LOADING!r} leaves the stressed crystal the same for every direction")
    base = elastic.properties("fcc", loading, potential, "[100]", d_over_d0)
    R = lab_rotation(angles)[:, None]                      # (na, 1, 3, 3)
    C = rotate4(base["C"][None], R)
    S = rotate4(base["S"][None], R)
    na = R.shape[0]
    out = {k: np.broadcast_to(v, (na,) + np.shape(v)).copy()
           for k, v in base.items() if k not in ("C", "S")}
    out.update(elastic.sound_speeds(S))
    out["C"], out["S"] = C, S
    return out


def rayleigh_at_angles(C: ArrayLike, stress: ArrayLike, S: ArrayLike, angles: ArrayLike) -> dict:
    """Rayleigh speed at every angle: Eq. (17) on mirrors, the general solver elsewhere.

    Parameters
    ----------
    C, S : array_like, shape (na, n, 3, 3, 3, 3)
        V C and V S in the lab frame of each angle (reduced units).
    stress : array_like, shape (na, n)
        V sigma0_xx (= V sigma0_zz, in-plane hydrostatic).
    angles : array_like, shape (na,)

    Returns
    -------
    dict
        ``c2_R`` (K d0^2/m; for a leaky pseudo surface wave the square of the real part of
        its speed), ``wave_type`` (:data:`WAVE_TYPES`), ``reason``; shape (na, n).
    """
    from surfwave.solvers import stroh

    C, S = np.asarray(C, dtype=float), np.asarray(S, dtype=float)
    s = np.asarray(stress, dtype=float)
    mirror = is_mirror(angles)
    shape = s.shape
    c2 = np.full(shape, np.nan)
    wave_type = np.full(shape, "none", dtype=object)
    reason = np.full(shape, "", dtype=object)
    if mirror.any():
        r = rayleigh.solve(S[mirror], 1.0)
        c2[mirror], wave_type[mirror], reason[mirror] = r["c2_R"], r["wave_type"], r["reason"]
    if (~mirror).any():
        sigma = np.zeros(shape + (3, 3))
        sigma[..., 0, 0] = sigma[..., 2, 2] = s
        A = stroh.wave_propagation_tensor(C[~mirror], sigma[~mirror])
        r = stroh.surface_wave(A.reshape((-1,) + A.shape[-4:]), np.ones(A[..., 0, 0, 0, 0].size))
        sub = (int((~mirror).sum()),) + shape[1:]
        c = np.asarray(r["c"], dtype=float).reshape(sub)
        c2[~mirror] = c * c
        wave_type[~mirror] = np.asarray(r["wave_type"]).astype(object).reshape(sub)
        reason[~mirror] = np.asarray(r["reason"]).astype(object).reshape(sub)
    return {"c2_R": c2, "wave_type": wave_type, "reason": reason}


