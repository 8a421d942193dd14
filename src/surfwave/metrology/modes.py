"""Points of several modes in one fit: each measured point evaluated with the model of its mode.

A second mode measured over the same range often separates parameters that one mode ties
together (docs/physics/metrology.md). :class:`PerPointModes` wraps one forward model per mode
into the single ``model(params, x) -> c`` the fitter takes, for the measured points only.
"""
from __future__ import annotations

from collections.abc import Callable, Hashable, Mapping, Sequence
from typing import Any

import numpy as np

from surfwave.errors import InputError

__all__ = ["PerPointModes", "mode_curves"]


class PerPointModes:
    """``model(params, x) -> c`` for measured points of several modes.

    Parameters
    ----------
    model_for : callable
        ``model_for(mode)`` -> the forward model of one mode.
    modes : sequence, length n
        The mode of each measured point.
    x : ndarray, shape (n,)
        The measured abscissae; the wrapper evaluates exactly these points (the fitter's
        finite differences and checks call it with them).

    Notes
    -----
    Has a ``jacobian`` when every mode's model has one.
    """

    def __init__(self, model_for: Callable[[Any], Any], modes: Sequence[Hashable], x: np.ndarray) -> None:
        self.modes = np.asarray(list(modes), dtype=object)
        self.x = np.asarray(x, dtype=float)
        if self.modes.shape != self.x.shape:
            raise InputError(f"mode must be one value or one per point ({self.x.size}), got {self.modes.size}")
        self.groups = {m: np.flatnonzero(self.modes == m) for m in dict.fromkeys(self.modes.tolist())}
        self.models = {m: model_for(m) for m in self.groups}
        if all(hasattr(mod, "jacobian") for mod in self.models.values()):
            self.jacobian = self._jacobian

    def _check(self, x: np.ndarray) -> None:
        if x.shape != self.x.shape or not np.array_equal(x, self.x):
            raise InputError("a several-mode model evaluates only the measured points")

    def __call__(self, params: Mapping[str, float], x: np.ndarray) -> np.ndarray:
        """Phase speed of each point's mode, m/s, shape (n,)."""
        xs = np.asarray(x, dtype=float)
        self._check(xs)
        out = np.full(xs.shape, np.nan)
        for m, idx in self.groups.items():
            out[idx] = self.models[m](params, xs[idx])
        return out

    def _jacobian(self, params: Mapping[str, float], x: np.ndarray, names: Sequence[str]) -> np.ndarray:
        xs = np.asarray(x, dtype=float)
        self._check(xs)
        out = np.full((xs.size, len(names)), np.nan)
        for m, idx in self.groups.items():
            out[idx] = self.models[m].jacobian(params, xs[idx], names)
        return out

    def __repr__(self) -> str:  # noqa: D105
        return f"PerPointModes(modes={list(self.groups)})"


def mode_curves(model: PerPointModes, params: Mapping[str, float], points: int = 200) -> tuple[np.ndarray, np.ndarray]:
    """Each mode's model on a fine grid over its points' range, joined with NaN between modes.

    Returns ``(x, c)``, shape (k,) each, ready for one line plot (NaN breaks the line).
    """
    xs: list[np.ndarray] = []
    cs: list[np.ndarray] = []
    gap = np.array([np.nan])
    for m, idx in model.groups.items():
        grid = np.linspace(float(model.x[idx].min()), float(model.x[idx].max()), points)
        xs += [grid, gap]
        cs += [np.asarray(model.models[m](params, grid), dtype=float), gap]
    return np.concatenate(xs)[:-1], np.concatenate(cs)[:-1]
