"""Surfaces, propagation directions and the lab frame of a surface-wave calculation.

Lab frame (docs/physics/paper.md): x1 = propagation direction, x2 = surface normal pointing INTO the
crystal, x3 = x1 x x2 (right-handed); the surface is the x1 x3 plane. :func:`lab_axes`
returns the three lab axes as the rows of a rotation matrix R written in crystal (cube)
axes, so that lab components of a tensor are ``rotate4(C, R)`` (:mod:`surfwave.solvers.tensors`).

Conventions
-----------
* The surface "(hkl)" has the inward normal x2 = +(h, k, l)/|(h, k, l)|: the crystal fills
  the half space n . r > 0. For (001) this is the crystal [001], as in the FCC frames of
  :mod:`surfwave.model_crystals.lattices` (y = [001] into the crystal).
* Reference direction of a surface (angle 0), see :func:`reference_direction`:
  (001): [100]; (110): [001]; (111): [1-10]. General rule: a normal along [001] (+ or -)
  takes [100]; a surface containing [001] (l = 0) takes [001]; any other takes
  n x [001] = [k, -h, 0] (the in-plane direction that lies in the (001) plane).
* An angle theta (degrees) turns from the reference r toward n x r:
  x1 = cos(theta) r + sin(theta) (n x r). On (001): from [100] toward [010].

Examples
--------
>>> lab_axes("(001)", "[110]").round(4)
array([[ 0.7071,  0.7071,  0.    ],
       [ 0.    ,  0.    ,  1.    ],
       [ 0.7071, -0.7071,  0.    ]])
>>> lab_axes("(111)", 90.0)[0].round(4)          # [11-2]/sqrt 6
array([ 0.4082,  0.4082, -0.8165])
"""
from __future__ import annotations

import re
from functools import lru_cache
from typing import Sequence

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError
from surfwave.solvers.tensors import cross

#: Largest |Miller index| accepted (larger ones overflow int64 or resolve angles below
#: float64 precision; real surfaces and directions have small indices).
MAX_INDEX = 10**6

_MILLER = re.compile(r"^\s*([\[(<{])\s*(.*?)\s*([\])>}])\s*$")


def _parse_indices(text: str, brackets: str, kind: str) -> np.ndarray:
    if not isinstance(text, str):
        raise InputError(f"{kind} must be a string like {brackets[0]}1-10{brackets[1]}, got {text!r}")
    m = _MILLER.match(text)
    if m is None or m.group(1) != brackets[0] or m.group(3) != brackets[1]:
        raise InputError(f"cannot read the {kind} {text!r}: write it as {brackets[0]}hkl{brackets[1]}, "
                         f"e.g. {brackets[0]}1-10{brackets[1]} or {brackets[0]}1, -1, 0{brackets[1]}")
    body = m.group(2)
    if re.search(r"[\s,]", body):
        parts = [p for p in re.split(r"[\s,]+", body) if p]
    else:  # compact form: one digit per index, each with an optional minus sign
        parts = re.findall(r"-?\d", body)
        if "".join(parts) != body:
            parts = []
    try:
        values = [int(p) for p in parts]
    except ValueError:
        values = []
    if len(values) != 3:
        raise InputError(f"the {kind} {text!r} must have three integer indices")
    big = [v for v in values if abs(v) > MAX_INDEX]
    if big:
        raise InputError(f"the {kind} {text!r} has the index {big[0]}: Miller indices must not exceed "
                         f"{MAX_INDEX} in magnitude (angles between such directions are below float64 "
                         "resolution)")
    idx = np.array(values, dtype=int)
    if not idx.any():
        raise InputError(f"the {kind} {text!r} is the zero vector")
    return idx


def parse_direction(text: str) -> np.ndarray:
    """Miller indices of a direction "[uvw]" (compact "[1-10]" or separated "[1, -1, 0]").

    Returns
    -------
    ndarray of int, shape (3,)

    Raises
    ------
    InputError
        Not of the form [uvw] with three integers, or the zero vector.
    """
    return _parse_indices(text, "[]", "direction")


def parse_plane(text: str) -> np.ndarray:
    """Miller indices of a surface "(hkl)"; ndarray of int, shape (3,). InputError as above."""
    return _parse_indices(text, "()", "surface")


def _normal(surface) -> np.ndarray:
    if isinstance(surface, str):
        return surface_frame(surface)[0]
    return _plane_normal(surface)


def _plane_normal(surface) -> np.ndarray:
    hkl = parse_plane(surface) if isinstance(surface, str) else np.asarray(surface)
    hkl = np.asarray(hkl, dtype=float)
    if hkl.shape != (3,) or not np.all(np.isfinite(hkl)) or not hkl.any():
        raise InputError(f"surface must be '(hkl)' or a non-zero 3-vector, got {surface!r}")
    return hkl / np.linalg.norm(hkl)


def _reference(n: np.ndarray) -> np.ndarray:
    """Unit reference direction of the surface of unit normal n (rule in the module docstring)."""
    if abs(abs(n[2]) - 1.0) < 1e-12:
        r = np.array([1.0, 0.0, 0.0])
    elif abs(n[2]) < 1e-12:
        r = np.array([0.0, 0.0, 1.0])
    else:
        r = np.cross(n, [0.0, 0.0, 1.0])
    return r / np.linalg.norm(r)


@lru_cache(maxsize=256)
def surface_frame(surface: str) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Unit normal n, reference direction r and n x r of a surface "(hkl)", each shape (3,), crystal axes.

    Computed once per surface string (the same numbers as :func:`surface_normal`,
    :func:`reference_direction` and ``np.cross(n, r)``); the arrays are read-only.

    Raises
    ------
    InputError
        Not a surface "(hkl)" with three integers, or the zero vector.
    """
    n = _plane_normal(surface)
    r = _reference(n)
    nr = np.cross(n, r)
    for v in (n, r, nr):
        v.setflags(write=False)
    return n, r, nr


def surface_normal(surface: str | Sequence[float] | np.ndarray) -> np.ndarray:
    """Unit inward normal x2 = (h, k, l)/|(h, k, l)| of "(hkl)", crystal axes, shape (3,)."""
    return _normal(surface).copy()


def reference_direction(surface: str | Sequence[float] | np.ndarray) -> np.ndarray:
    """Unit reference direction (angle 0) of a surface, crystal axes, shape (3,).

    (001): [100]; (110): [001]; (111): [1-10]; rule for any (hkl) in the module docstring.
    """
    return surface_frame(surface)[1].copy() if isinstance(surface, str) else _reference(_normal(surface))


def _frames(x1: np.ndarray, n: np.ndarray) -> np.ndarray:
    x3 = cross(x1, n)
    return np.stack([x1, np.broadcast_to(n, x1.shape), x3], axis=-2)


def direction_angle(surface: str | Sequence[float] | np.ndarray, direction: str) -> float:
    """Angle (degrees, in (-180, 180]) of a Miller direction in the surface from the reference."""
    R = lab_axes(surface, direction)
    n = _normal(surface)
    r = reference_direction(surface)
    return float(np.degrees(np.arctan2(R[0] @ np.cross(n, r), R[0] @ r)))


def lab_axes(surface: str | Sequence[float] | np.ndarray, direction: str | ArrayLike) -> np.ndarray:
    """Lab axes (rows x1, x2, x3) in crystal axes for a surface and a propagation direction.

    Parameters
    ----------
    surface : str or array_like, shape (3,)
        "(hkl)" (or its Miller indices).
    direction : str or float or array_like of float
        A Miller direction "[uvw]" lying in the surface, or an angle in degrees from
        :func:`reference_direction` toward n x reference (scalar or array, any shape).

    Returns
    -------
    ndarray, shape (3, 3) for a string or a scalar angle, (*angle.shape, 3, 3) for an array
        Orthonormal rows x1 = propagation, x2 = inward normal, x3 = x1 x x2.

    Raises
    ------
    InputError
        A direction not in the surface plane (naming both), a bad Miller string or angle.
    """
    n = _normal(surface)
    if isinstance(direction, str):
        uvw = parse_direction(direction)
        hkl = parse_plane(surface) if isinstance(surface, str) else np.asarray(surface, dtype=float)
        dot = float(np.dot(uvw, hkl))
        if abs(dot) > 1e-9 * np.linalg.norm(uvw) * np.linalg.norm(hkl):
            raise InputError(f"direction {direction} does not lie in the surface {surface}: "
                             f"[uvw].(hkl) = {dot:g}, not 0")
        x1 = uvw / np.linalg.norm(uvw)
        return _frames(x1, n)
    theta = np.asarray(direction, dtype=float)
    if not np.all(np.isfinite(theta)):
        raise InputError(f"angle must be finite degrees, got {direction!r}")
    if isinstance(surface, str):
        _, r, nr = surface_frame(surface)
    else:
        r = reference_direction(surface)
        nr = np.cross(n, r)
    t = np.radians(theta)[..., None]
    x1 = np.cos(t) * r + np.sin(t) * nr
    return _frames(x1, n)
