"""The layered-stack cube ``dispersion_layered.nc``: every mode of a stack against kh, film stress, electrical.

:func:`dispersion_cube` runs :func:`surfwave.layered` over a grid of equibiaxial film stresses and
electrical conditions and labels the result as an xarray Dataset with CF attributes (SI units).
Dimensions: ``film_stress`` (GPa, applied to every film, equibiaxial in the surface plane),
``electrical`` ("free", "metallized"), ``kh`` (wavenumber x total film thickness) and ``mode``
(the labels: "R", "S1", "L0", ..., sorted by their mean speed; an entry is NaN where that mode does
not exist at that point). Variables: ``c``, ``group_velocity``, ``K2``, ``attenuation``,
``frequency``, ``power_flow_angle``; ``c_limit`` (film_stress, electrical); ``mode_limit`` (film_stress,
electrical, mode: the limiting speed of the mode's family); ``reason`` (film_stress, electrical, kh);
``film_bulk_speed`` (film, sheet): the films' bulk speeds along x1 (unstressed), for figures.
"""
from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
import xarray as xr

from surfwave import validate
from surfwave.data.variables import CUBES, LAYERED_COORDS
from surfwave.errors import InputError
from surfwave.layers.modes import film_x1_speeds
from surfwave.layers.partial import scaled_blocks
from surfwave.layers.solve import checked_kh, layered
from surfwave.layers.stack import resolve_stack
from surfwave.solvers.boundary import Boundary, as_boundary

__all__ = ["dispersion_cube"]

#: The metadata of the cube's variables and coordinates (the one table: surfwave.data.variables).
VARIABLES = CUBES["dispersion_layered"]
COORDS = LAYERED_COORDS


def dispersion_cube(substrate, films: Sequence[Mapping], kh, *, film_stress=(0.0,), electrical=("free",),
                    leaky: bool = False, euler=None, surface: str = "(001)", direction="[100]",
                    stress=None, keep_film_stress: bool = False) -> xr.Dataset:
    """All modes of a stack over film stresses x electrical conditions x kh, as a labelled Dataset.

    Parameters
    ----------
    substrate, films, euler, surface, direction, stress, leaky
        As for :func:`surfwave.layered`; a film's own ``stress`` is replaced by each value of
        ``film_stress``.
    kh : array_like, shape (n,)
    film_stress : sequence of float
        Equibiaxial stresses (GPa) given to every film in turn.
    electrical : sequence of {"free", "metallized"} or Boundary
        Conditions of the top surface (piezoelectric stacks; elastic stacks take "free" only).
    keep_film_stress : bool
        True: a film that gives its own ``stress`` keeps it, and ``film_stress`` is given only to
        the films without one (False: every film's stress is replaced).

    Returns
    -------
    xarray.Dataset
        Dimensions (film_stress, electrical, kh, mode); see the module docstring. No global
        provenance attributes (the workflow script adds them with :func:`surfwave.data.cube.provenance`).
    """
    kh = checked_kh(kh)
    s = np.atleast_1d(validate.gpa_stress(film_stress, "film_stress"))   # the one Pa bound, before any run
    bounds = [as_boundary(e) for e in ([electrical] if isinstance(electrical, (str, Boundary)) else electrical)]
    el = [b.name for b in bounds]
    if s.ndim != 1 or s.size == 0 or not np.all(np.isfinite(s)):
        raise InputError(f"film_stress must be a list of finite GPa values, got {film_stress!r}")
    if not el or len(set(el)) != len(el):
        raise InputError(f"electrical must list distinct 'free'/'metallized', got {electrical!r}")
    runs: dict[tuple[int, int], dict[str, Any]] = {}
    for i, sig in enumerate(s):
        fs = [dict(f) if keep_film_stress and f.get("stress") is not None else {**dict(f), "stress": float(sig)}
              for f in films]
        for j in range(len(bounds)):
            runs[i, j] = dict(layered(substrate, fs, euler=euler, surface=surface, direction=direction, kh=kh,
                                      electrical=bounds[j], stress=stress, leaky=leaky))
    labels: dict[str, list[float]] = {}
    for r in runs.values():
        for row_c, row_l in zip(r["c"], r["mode"]):
            for c, lab in zip(row_c, row_l):
                if lab:
                    labels.setdefault(str(lab), []).append(float(c))
    modes = sorted(labels, key=lambda k: (float(np.mean(labels[k])), k))
    shape = (s.size, len(el), kh.size, len(modes))
    arrays = {k: np.full(shape, np.nan) for k in ("c", "group_velocity", "K2", "attenuation", "frequency",
                                                   "power_flow_angle")}
    c_lim = np.full((s.size, len(el)), np.nan)
    mode_lim = np.full((s.size, len(el), len(modes)), np.nan)
    reason = np.full((s.size, len(el), kh.size), "", dtype=object)
    pos = {m: q for q, m in enumerate(modes)}
    for (i, j), r in runs.items():
        c_lim[i, j] = r["c_limit"]
        reason[i, j] = r["reason"]
        rows, cols = np.nonzero(r["mode"] != "")
        q = np.array([pos[str(r["mode"][a, b])] for a, b in zip(rows, cols)], dtype=int)
        for key in arrays:
            arrays[key][i, j, rows, q] = r[key][rows, cols]
        mode_lim[i, j, q] = r["mode_limit"][rows, cols]          # one value per mode (its family's)
    stack = resolve_stack(substrate, [dict(f) for f in films], euler=euler, surface=surface, direction=direction)
    bulk = film_x1_speeds(scaled_blocks(stack)).reshape(len(films), 3) if films else np.zeros((0, 3))
    dims = ("film_stress", "electrical", "kh", "mode")
    data: dict[str, tuple] = {k: (dims, v, dict(VARIABLES[k])) for k, v in arrays.items()}
    data["c_limit"] = (("film_stress", "electrical"), c_lim, dict(VARIABLES["c_limit"]))
    data["mode_limit"] = (("film_stress", "electrical", "mode"), mode_lim, dict(VARIABLES["mode_limit"]))
    data["reason"] = (("film_stress", "electrical", "kh"), reason.astype(str), dict(VARIABLES["reason"]))
    data["film_bulk_speed"] = (("film", "sheet"), np.sort(bulk, axis=1), dict(VARIABLES["film_bulk_speed"]))
    coords = {"film_stress": ("film_stress", s, COORDS["film_stress"]),
              "electrical": ("electrical", np.array(el, dtype=str), COORDS["electrical"]),
              "kh": ("kh", kh, COORDS["kh"]), "mode": ("mode", np.array(modes, dtype=str), COORDS["mode"]),
              "film": ("film", np.arange(len(films)), COORDS["film"]),
              "sheet": ("sheet", np.arange(3), COORDS["sheet"])}
    return xr.Dataset(data, coords=coords)
