"""Grids of a scene (d/d0, theta) and the error every config check raises.

Shared by the checks of model-crystal scenes (:mod:`surfwave.pipeline.scenes`) and of
real-crystal scenes (:mod:`surfwave.pipeline.crystal_scenes`).
"""
from __future__ import annotations

from typing import Any, Sequence

import numpy as np

from surfwave.errors import SceneError
from surfwave.validate import MAX_STRESS_GPA as _MAX_STRESS_GPA

#: Decimals kept in d/d0 and theta values: grids land on the decimal values a user types.
DECIMALS = 12
#: Most points one grid, and one scene's product of grids, may hold: checked before any job
#: (a scene beyond it would run for hours or exhaust memory; split it into scenes).
MAX_POINTS = 100_000
#: Largest |stress| in GPa a scene may give: the one bound of every door,
#: :data:`surfwave.validate.MAX_STRESS_GPA` (1e3 GPa); larger values are almost surely in Pa
#: (1.0e+8 Pa = 0.1 GPa).
MAX_STRESS_GPA = _MAX_STRESS_GPA


def check_points(where: str, sizes: dict[str, int]) -> int:
    """The number of points of a scene (the product of its grid sizes), or SceneError.

    Parameters
    ----------
    where : str
        "scene 'name'", the start of the message.
    sizes : dict
        Grid name -> number of values, e.g. {"potentials": 2, "angles": 90001, "d/d0": 50001}.

    Raises
    ------
    SceneError
        The product exceeds :data:`MAX_POINTS`; the message names every factor.

    Examples
    --------
    >>> check_points("scene 's'", {"angles": 3, "d/d0": 4})
    12
    >>> check_points("scene 's'", {"angles": 90001, "d/d0": 50001})
    Traceback (most recent call last):
    ...
    surfwave.errors.SceneError: scene 's': 90001 angles x 50001 d/d0 = 4500140001 points exceed the limit of 100000 points per scene; split it into several scenes or use coarser grids
    """  # noqa: E501 (a doctest's expected message)
    n = 1
    for size in sizes.values():
        n *= int(size)
    if n > MAX_POINTS:
        factors = " x ".join(f"{size} {name}" for name, size in sizes.items())
        raise SceneError(f"{where}: {factors} = {n} points exceed the limit of {MAX_POINTS} points per "
                         "scene; split it into several scenes or use coarser grids")
    return n



def _rounded(values: np.ndarray) -> np.ndarray:
    """``values`` rounded to :data:`DECIMALS` decimals where that changes anything (|v| < 1e15);
    np.round would overflow to inf beyond ~1e296 (scaling by 10**DECIMALS) and call 1e308 infinite."""
    with np.errstate(over="ignore", invalid="ignore"):
        return np.where(np.abs(values) < 1e15, np.round(values, DECIMALS), values)


def expand_grid(spec: Sequence[float] | dict[str, Any], where: str = "grid") -> np.ndarray:
    """Values of a grid: a list (sorted, rounded), or {start, stop, step} with stop included.

    The values are start + i * step rounded to :data:`DECIMALS` decimals, so a grid from
    0.88 by 0.01 contains exactly the float 0.93 a user would type (no drift).

    Raises
    ------
    SceneError
        Malformed grid (stop before start, stop not on the grid, too many points,
        duplicate values); the message starts with ``where``.
    """
    if isinstance(spec, dict):
        start, stop, step = (float(spec[k]) for k in ("start", "stop", "step"))
        bad = {k: v for k, v in zip(("start", "stop", "step"), (start, stop, step)) if not np.isfinite(v)}
        if bad:
            key, value = next(iter(bad.items()))
            raise SceneError(f"{where}: {key} must be a finite number, got {value!r}")
        if not step > 0:
            raise SceneError(f"{where}: step must be positive, got {step!r}")
        if stop < start:
            raise SceneError(f"{where}: stop {stop!r} lies before start {start!r}")
        with np.errstate(over="ignore"):
            n = (stop - start) / step
        if not n + 1 <= MAX_POINTS + 0.5:  # before int(): a step of 5e-324 makes n infinite
            raise SceneError(f"{where}: {n + 1:.4g} points exceed the limit of {MAX_POINTS}")
        k = int(round(n))
        if abs(n - k) > 1e-9 * max(1.0, abs(n)):
            raise SceneError(
                f"{where}: stop - start = {stop - start:.12g} is not a multiple of step {step!r}"
            )
        values = _rounded(start + step * np.arange(k + 1))
    else:
        values = _rounded(np.sort(np.asarray(spec, dtype=float)))
        if values.ndim != 1 or values.size == 0:
            raise SceneError(f"{where}: expected a non-empty list of numbers, got {spec!r}")
        dup = values[1:][np.diff(values) == 0]
        if dup.size:
            raise SceneError(f"{where}: value {float(dup[0])!r} appears twice")
    if not np.all(np.isfinite(values)):
        raise SceneError(f"{where}: values must be finite, got {spec!r}")
    return values


def theta_grid(spec: Sequence[float] | dict[str, Any], where: str = "theta") -> np.ndarray:
    """theta values in radians: a list, or {n: N} = N midpoints (i + 1/2) pi / N inside (0, pi),
    optionally with ``pi_fractions: [f, ...]`` adding the exact values f * pi (e.g. 0.125 for pi/8)."""
    if isinstance(spec, dict):
        n = int(spec["n"])
        grid = (np.arange(n) + 0.5) * np.pi / n
        extra = np.asarray(spec.get("pi_fractions", []), dtype=float) * np.pi
        bad = extra[(extra <= 0) | (extra >= np.pi)]
        if bad.size:
            raise SceneError(f"{where}: pi_fractions value {bad[0] / np.pi!r} lies outside (0, 1)")
        # An added value replaces a midpoint it coincides with (no near-duplicate columns).
        keep = np.all(np.abs(grid[:, None] - extra[None, :]) > 1e-12, axis=1)
        return np.sort(np.concatenate([grid[keep], extra]))
    values = expand_grid(spec, where)
    bad = values[(values <= 0) | (values >= np.pi)]
    if bad.size:
        raise SceneError(f"{where}: theta = {bad[0]!r} lies outside (0, pi)")
    return values
