"""Euler angles of SAW cuts (ZXZ, engineering convention) -> our lab axes.

The SAW convention (Slobodnik et al., Microwave Acoustics Handbook 1973; Auld 1973; Morgan,
Surface Acoustic Wave Devices 2007): starting from the crystal axes X, Y, Z, rotate by ``phi``
about Z, then by ``theta`` about the new X, then by ``psi`` about the newest Z (passive
rotations of the axes, right-hand sense). The final axes are the SAW lab frame: x1 = propagation,
x3 = OUTWARD surface normal (substrate in x3 < 0). As a matrix whose rows are the final axes in
crystal coordinates::

    a = Rz(psi) @ Rx(theta) @ Rz(phi),
    Rz(t) = [[cos t, sin t, 0], [-sin t, cos t, 0], [0, 0, 1]],
    Rx(t) = [[1, 0, 0], [0, cos t, sin t], [0, -sin t, cos t]].

So theta about X turns +Y toward +Z and +Z toward -Y: (0, 90, 0) has the outward normal along
crystal -Y, and "rotated Y cut by angle A, X propagating" is (0, A - 90, 0): its outward normal
is ``sin(theta) (-Y) + cos(theta) Z``, i.e. Y rotated by A = theta + 90 degrees about +X from +Y
toward +Z. Our lab frame (docs/physics): x1 = propagation, x2 = INWARD normal, x3 = x1 x x2;
hence x1 = a[0], x2 = -a[2], x3 = +a[1].

Examples
--------
>>> euler_lab_axes(0, 0, 0)           # Z cut, X propagating: x2 = -Z points into the crystal
array([[ 1.,  0.,  0.],
       [ 0.,  0., -1.],
       [ 0.,  1.,  0.]])
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.validate import MAX_ANGLE, euler_angles


def saw_euler_matrix(phi: ArrayLike, theta: ArrayLike, psi: ArrayLike) -> np.ndarray:
    """The SAW-convention axes matrix a = Rz(psi) Rx(theta) Rz(phi) (rows: x1, x2, x3 of SAW frame).

    Parameters
    ----------
    phi, theta, psi : float or array_like, shape (m,)
        Euler angles, degrees (broadcast together).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        Rows: SAW lab x1 (propagation), x2 (in-plane), x3 (outward normal), in crystal axes.
    """
    p, t, s = (np.radians(np.asarray(a, dtype=float)) for a in np.broadcast_arrays(phi, theta, psi))
    cp, sp, ct, st, cs, ss = np.cos(p), np.sin(p), np.cos(t), np.sin(t), np.cos(s), np.sin(s)
    a = np.empty(p.shape + (3, 3))
    a[..., 0, 0] = cs * cp - ss * ct * sp
    a[..., 0, 1] = cs * sp + ss * ct * cp
    a[..., 0, 2] = ss * st
    a[..., 1, 0] = -ss * cp - cs * ct * sp
    a[..., 1, 1] = -ss * sp + cs * ct * cp
    a[..., 1, 2] = cs * st
    a[..., 2, 0] = st * sp
    a[..., 2, 1] = -st * cp
    a[..., 2, 2] = ct
    return a


def euler_lab_axes(phi: ArrayLike, theta: ArrayLike | None = None, psi: ArrayLike | None = None) -> np.ndarray:
    """Our lab axes (x1 propagation, x2 INWARD normal, x3 = x1 x x2) of a cut given by Euler angles.

    Parameters
    ----------
    phi, theta, psi : float or array_like, shape (m,)
        ZXZ Euler angles in degrees, SAW convention (module docstring). Alternatively pass one
        array of shape (m, 3) or (3,) as ``phi`` and leave ``theta`` and ``psi`` unset.

    Returns
    -------
    ndarray, shape (m, 3, 3), or (3, 3) for one triple of scalars (or a (3,) array)
        Rows are x1, x2, x3 in crystal coordinates; use with
        :func:`surfwave.solvers.tensors.rotate4` (C_lab = R R R R C).

    Raises
    ------
    InputError
        Non-finite angles, angles beyond :data:`surfwave.validate.MAX_ANGLE` degrees, or a shape that
        is not three angles.
    """
    if theta is None and psi is None:
        angles = euler_angles(phi, "Euler angles")
        phi, theta, psi = angles[..., 0], angles[..., 1], angles[..., 2]
    elif theta is None or psi is None:
        raise InputError("give all three Euler angles (phi, theta, psi) or one (m, 3) array")
    try:
        phi, theta, psi = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (phi, theta, psi)))
    except ValueError as exc:
        raise InputError(f"Euler angles do not broadcast together: {exc}") from None
    if phi.ndim > 1:
        raise InputError(f"Euler angles must be scalars or (m,) arrays, got shape {phi.shape}")
    bad = ~(np.isfinite(phi) & np.isfinite(theta) & np.isfinite(psi))
    if np.any(bad):
        i = int(np.flatnonzero(np.atleast_1d(bad))[0])
        trip = tuple(float(np.atleast_1d(a)[i]) for a in (phi, theta, psi))
        raise InputError(f"Euler angles must be finite, got (phi, theta, psi) = {trip} degrees")
    big = (np.abs(phi) > MAX_ANGLE) | (np.abs(theta) > MAX_ANGLE) | (np.abs(psi) > MAX_ANGLE)
    if np.any(big):
        i = int(np.flatnonzero(np.atleast_1d(big))[0])
        trip = tuple(float(np.atleast_1d(a)[i]) for a in (phi, theta, psi))
        raise InputError(f"Euler angles beyond {MAX_ANGLE:g} degrees lose precision in float64 (the angle "
                         f"computed would not be the angle given): (phi, theta, psi) = {trip}; reduce them "
                         "modulo 360")
    a = saw_euler_matrix(phi, theta, psi)
    return np.stack([a[..., 0, :], -a[..., 2, :], a[..., 1, :]], axis=-2) + 0.0  # no -0.0
