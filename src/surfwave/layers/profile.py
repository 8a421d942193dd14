"""Displacement (and potential) of one mode of a stack against depth.

:func:`mode_profile` resolves a stack as :func:`surfwave.layered` does, finds the requested mode at
each kh, and returns its fields U(x2) = (u1, u2, u3[, phi]) at the given depths, from the partial-wave
amplitudes of the impedance recursion (:func:`surfwave.layers.fields.mode_fields`).
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError
from surfwave.layers.fields import mode_fields
from surfwave.layers.modes import family_modes, label_family
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import resolve_stack
from surfwave.solvers.boundary import Boundary

__all__ = ["mode_profile"]


def mode_profile(substrate, films, kh, depth, *, mode: str = "R", euler=None, surface: str = "(001)",
                 direction="[100]", electrical: str | Boundary = "free", stress=None) -> dict:
    """Fields of one guided mode against depth.

    Parameters
    ----------
    substrate, films, euler, surface, direction, electrical, stress
        As for :func:`surfwave.layered`.
    kh : array_like, shape (k,)
        Wavenumber times total film thickness.
    depth : array_like, shape (d,)
        Depths below the free surface in units of the total film thickness (so k x2 = kh depth);
        1 is the film-substrate interface of a single film.
    mode : str
        Label ("R", "S1", "L0", "M0", ...).

    Returns
    -------
    dict
        ``c`` (k,) m/s; ``U`` (k, d, 3) complex displacement in the solver's lab frame (x1
        propagation, x2 inward normal, x3), normalised to max |u| = 1 per kh, phase such that the
        largest surface component is real and positive; ``phi`` (k, d) complex potential (V per m
        of displacement x 0 for elastic stacks), ``group_velocity`` (k,) m/s.

    Raises
    ------
    InputError
        Bad inputs (as :func:`surfwave.layered`), an unknown label, or the mode missing at some kh.
    """
    stack = resolve_stack(substrate, films, euler=euler, surface=surface, direction=direction, stress=stress)
    kh = np.atleast_1d(np.asarray(kh, dtype=float))
    depth = np.atleast_1d(np.asarray(depth, dtype=float))
    if not (np.all(np.isfinite(kh)) and np.all(kh >= 0) and np.all(np.isfinite(depth)) and np.all(depth >= 0)):
        raise InputError("kh and depth must be finite and >= 0")
    b = scaled_blocks(stack)
    prefix = label_family(mode)
    fam = next((f for f in families(b) if f.prefix == prefix), None)
    try:
        j = 0 if mode == "R" else int(mode[1:])
    except ValueError:
        j = -1
    if fam is None or j < 0:
        raise InputError(f"mode {mode!r} is not a label of this stack's families "
                         f"({[f.prefix for f in families(b)]})")
    c = family_modes(b, fam, kh, electrical=electrical)
    if c.shape[1] <= j or not np.all(np.isfinite(c[:, j])):
        raise InputError(f"mode {mode!r} does not exist at every kh given")
    r = mode_fields(b, fam, c[:, j], kh, electrical, depth=depth, check=False)
    U = np.zeros((kh.size, depth.size, 4), dtype=complex)
    U[:, :, list(fam.idx)] = r["U"]
    # potential back to V per m of displacement: phi was scaled by sqrt(se / sA)
    U[:, :, 3] *= np.sqrt(b.se / b.sA)
    surf = U[:, 0, :3]
    ref = np.take_along_axis(surf, np.argmax(np.abs(surf), axis=-1)[:, None], axis=-1)[:, 0]
    U *= (np.conj(ref) / np.where(np.abs(ref) > 0, np.abs(ref), 1.0))[:, None, None]
    scale = np.abs(U[:, :, :3]).max(axis=(1, 2))
    U /= np.where(scale > 0, scale, 1.0)[:, None, None]
    return {"c": c[:, j], "U": U[:, :, :3], "phi": U[:, :, 3], "group_velocity": r["group_velocity"]}
