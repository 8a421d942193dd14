"""Prestress as the user gives it: loading kinds, the one load-to-stress function, the one stress check.

Stresses are Cauchy stresses in GPa (negative = compression) in the crystal axes of the natural
crystal unless a function says otherwise; ``axes`` are the lab axes (rows x1 = propagation, x2 =
inward normal, x3) in the same frame. :func:`stress_tensor` builds the tensor of a named loading,
:func:`check_stress` is the check every door runs on a given tensor (numbers, the Pa guard,
symmetry, no traction on the surface), with one wording.
"""
from __future__ import annotations

import re

import numpy as np
from numpy.typing import ArrayLike

from surfwave import validate
from surfwave.errors import InputError
from surfwave.vocab import STRESS_LOADINGS

__all__ = ["LOADINGS", "TRACTION_TOL", "axis_of_loading", "check_stress", "stress_tensor"]

#: The one tolerance of "the stress lies in the surface plane": |sigma . n| (lab components,
#: n the normal of the deformed surface) and |axis . n| of an axis loading, relative to
#: max |sigma| (to 1 for a unit axis).
TRACTION_TOL = 1e-9
#: Loading kinds: uniaxial along / across the propagation direction (in the surface),
#: equi-biaxial in the surface plane; ``axis_<hkl>`` (or ``axis`` with ``axis=``) uniaxial
#: along a fixed crystal direction in the surface.
LOADINGS = tuple(k for k in STRESS_LOADINGS if k != "axis")
_AXIS = re.compile(r"^axis_(-?\d)(-?\d)(-?\d)$")


def axis_of_loading(loading: str) -> np.ndarray | None:
    """Unit crystal direction of an ``axis_<hkl>`` loading, or None for the other kinds.

    Raises
    ------
    InputError
        An unknown loading name (the message lists the kinds).
    """
    if loading in LOADINGS:
        return None
    m = _AXIS.match(loading)
    if not m:
        raise InputError(f"unknown loading {loading!r}; choose one of {list(LOADINGS)} or "
                         "axis_<hkl> (e.g. axis_100, axis_1-10)")
    d = np.array([float(g) for g in m.groups()])
    if not np.any(d):
        raise InputError(f"loading {loading!r}: the axis [000] has no direction")
    return d / np.linalg.norm(d)


def stress_tensor(loading: str, magnitude: ArrayLike, axes: ArrayLike, *,
                  axis: str | ArrayLike | None = None) -> np.ndarray:
    """Cauchy stress of a loading in crystal axes, GPa: the one load-to-stress function.

    Parameters
    ----------
    loading : str
        ``along``: sigma = s x1 x1 (uniaxial along the propagation direction);
        ``across``: sigma = s x3 x3 (uniaxial, in the surface, normal to the propagation);
        ``biaxial``: sigma = s (x1 x1 + x3 x3); ``axis_<hkl>``, or ``axis`` with ``axis=``:
        sigma = s a a along a fixed crystal direction a in the surface.
    magnitude : float or array_like, shape (k,)
        s, GPa (negative = compression).
    axes : array_like, shape (3, 3) or (m, 3, 3)
        Lab axes of the natural crystal, rows (x1, x2 = inward normal, x3), crystal axes.
    axis : str or array_like, shape (3,), optional
        The crystal direction of ``loading="axis"`` ("[hkl]" or a vector).

    Returns
    -------
    ndarray, shape axes.shape[:-2] + magnitude.shape + (3, 3)
        sigma . n = 0 for every entry.

    Raises
    ------
    InputError
        Unknown loading, non-finite magnitude, an axis not in the surface plane (|a . n| >
        :data:`TRACTION_TOL`).
    """
    from surfwave.solvers.orientation import parse_direction

    axes = np.asarray(axes, dtype=float)
    s = np.asarray(magnitude, dtype=float)
    if not np.all(np.isfinite(s)):
        raise InputError(f"stress magnitude must be finite, got {magnitude!r}")
    x1, n, x3 = axes[..., 0, :], axes[..., 1, :], axes[..., 2, :]
    d: np.ndarray | None
    if loading == "axis":
        if axis is None:
            raise InputError("loading 'axis' needs axis= (a crystal direction in the surface)")
        d = parse_direction(axis) if isinstance(axis, str) else np.asarray(axis, dtype=float)
        d = d / np.linalg.norm(d)
        name = f"axis {axis!r}"
    else:
        d = axis_of_loading(loading)
        name = f"loading {loading!r}: the axis"
    if loading == "along":
        unit = np.einsum("...i,...j->...ij", x1, x1)
    elif loading == "across":
        unit = np.einsum("...i,...j->...ij", x3, x3)
    elif loading == "biaxial":
        unit = np.einsum("...i,...j->...ij", x1, x1) + np.einsum("...i,...j->...ij", x3, x3)
    else:
        assert d is not None  # an axis loading: axis_of_loading refused every other name
        if np.any(np.abs(n @ d) > TRACTION_TOL):
            raise InputError(f"{name} is not in the surface plane (a stress with a normal component "
                             "cannot act on a free surface)")
        unit = np.broadcast_to(np.outer(d, d), axes.shape)
    lead = axes.shape[:-2]
    return unit.reshape(lead + (1,) * s.ndim + (3, 3)) * s[..., None, None]


def check_stress(stress, axes: np.ndarray, where: str, *, frame: str = "crystal axes") -> np.ndarray:
    """The prestress (m, 3, 3) in GPa: numbers, finite, the Pa guard, symmetric, sigma . n = 0.

    The one stress check of every door (:func:`surfwave.case.make_case`, where it is also
    exported, :func:`surfwave.real_crystals.piezo_wave.piezo_wave`,
    :func:`surfwave.real_crystals.acoustoelastic.surface_wave_speed`), in one wording.

    Parameters
    ----------
    stress : array_like, shape (m, 3, 3) or (3, 3)
        Cauchy stress, GPa, in the axes ``frame`` names.
    axes : ndarray, shape (m, 3, 3)
        Lab axes in the same frame (row 1: the inward normal).
    where : str
        The surface in words (the message names it).
    frame : str
        The axes of ``stress`` in words (the message names them).
    """
    s = validate.gpa_stress(stress)
    if s.shape[-2:] != (3, 3):
        raise InputError(f"stress must be 3 x 3 tensors (GPa), got shape {s.shape}")
    try:
        s = np.broadcast_to(s, axes.shape)
    except ValueError:
        raise InputError(f"stress must be one 3 x 3 tensor or one per point ({axes.shape[0]}), got shape "
                         f"{s.shape}") from None
    scale = max(float(np.abs(s).max()), 1e-300) if s.size else 1.0
    if not np.all(np.abs(s - np.swapaxes(s, -1, -2)) <= 1e-12 * scale):   # allclose(rtol=0): s is finite
        raise InputError(f"the stress tensor must be symmetric, got {s[0].tolist()}")
    traction = np.einsum("mij,mj->mi", s, axes[:, 1])
    bad = np.abs(traction).max(axis=-1) > TRACTION_TOL * scale
    if bad.any():
        k = int(np.flatnonzero(bad)[0])
        raise InputError(f"prestress must lie in the surface plane {where}: its traction sigma . n = "
                         f"{np.round(traction[k], 12).tolist()} GPa ({frame}) is not zero")
    return s
