"""The forward model of a film stack on a crystal, through :func:`surfwave.layered`, for the fitter.

:func:`layered_model` turns a stack (substrate and films, as :func:`surfwave.layered` takes them)
plus the names of one film's free parameters into a callable ``model(params, x) -> c`` of one
guided mode, which :func:`surfwave.metrology.fit.fit` fits. Free parameters of the film
``films[layer]``:

- ``E`` (GPa), ``nu``, ``rho`` (kg/m^3), ``thickness`` (m): the keys of an isotropic film;
- ``C11`` ... ``C66`` (GPa): entries of the film's Voigt stiffness (``voigt``; C_ij and C_ji
  move together);
- ``stress`` (GPa): the film's equibiaxial residual stress in the surface plane.

``x`` is kh (wavenumber times the total film thickness, as :func:`surfwave.layered` defines it)
or frequency in Hz. :func:`surfwave.layered` is imported when the model is first called, so this
module imports without it. Sensitivities: central differences (the fitter's default).
"""
from __future__ import annotations

import copy
import re
from collections.abc import Mapping, Sequence
from typing import Any, Literal

import numpy as np

from surfwave.errors import InputError

__all__ = ["FILM_PARAMETERS", "LayeredModel", "film_value", "layered_model"]

#: Names of film parameters the adapter sets besides C_ij.
FILM_PARAMETERS = ("E", "nu", "rho", "thickness", "stress")
_CIJ = re.compile(r"^C([1-6])([1-6])$")


def _check_name(name: str) -> None:
    if name not in FILM_PARAMETERS and not _CIJ.match(name):
        raise InputError(f"unknown film parameter {name!r}: use {', '.join(FILM_PARAMETERS)} or C11 ... C66")


def film_value(film: Mapping[str, Any], name: str) -> float:
    """The current value of parameter ``name`` in a film mapping (the fit's starting value).

    ``stress`` defaults to 0 (no residual stress) and must be a scalar; C_ij reads ``voigt``.
    """
    _check_name(name)
    m = _CIJ.match(name)
    if m:
        if "voigt" not in film:
            raise InputError(f"{name} is free but the film has no 'voigt' stiffness (it has {sorted(film)})")
        return float(np.asarray(film["voigt"], dtype=float)[int(m[1]) - 1, int(m[2]) - 1])
    if name == "stress":
        s = film.get("stress", 0.0)
        if np.ndim(s) != 0:
            raise InputError("a free 'stress' must be the film's scalar (equibiaxial) stress, got a tensor")
        return float(s)
    if name not in film:
        raise InputError(f"{name} is free but the film has no {name!r} (it has {sorted(film)})")
    return float(film[name])


def _apply(film: dict[str, Any], name: str, value: float) -> None:
    m = _CIJ.match(name)
    if m:
        v = np.array(film["voigt"], dtype=float)
        i, j = int(m[1]) - 1, int(m[2]) - 1
        v[i, j] = v[j, i] = value
        film["voigt"] = v
    else:
        film[name] = value


class LayeredModel:
    """``model(params, x) -> c`` of one guided mode of a stack, through :func:`surfwave.layered`.

    Build it with :func:`layered_model`. Calling it sets the named parameters of
    ``films[layer]``, calls :func:`surfwave.layered` once for all ``x`` and returns the chosen
    mode's phase speed (m/s), shape (n,), NaN where that mode does not exist.
    """

    def __init__(self, substrate: Any, films: Sequence[Mapping[str, Any]], layer: int,
                 mode: Any, variable: Literal["kh", "frequency"], options: Mapping[str, Any]) -> None:
        self.substrate = substrate
        self.films = [dict(f) for f in films]
        self.layer, self.mode, self.variable = layer, mode, variable
        self.options = dict(options)

    def stack(self, params: Mapping[str, float]) -> list[dict[str, Any]]:
        """The film list with ``params`` applied to ``films[layer]`` (a copy)."""
        films = copy.deepcopy(self.films)
        for name, value in params.items():
            _apply(films[self.layer], name, float(value))
        return films

    def __call__(self, params: Mapping[str, float], x: np.ndarray) -> np.ndarray:
        """Phase speed (m/s) of the chosen mode at each x, shape (n,)."""
        import surfwave

        solver = getattr(surfwave, "layered", None)
        if solver is None:
            raise InputError("model='layered' needs surfwave.layered, which this version of surfwave lacks; "
                             "use the closed-form Love model (model='love') for an isotropic film")
        xs = np.atleast_1d(np.asarray(x, dtype=float))
        if not isinstance(self.mode, (int, np.integer, str)) and len(self.mode) != xs.size:
            raise InputError(f"a mode per point needs {len(self.mode)} points, got {xs.size}")
        where = {"kh": xs} if self.variable == "kh" else {"frequency": xs}
        result = solver(self.substrate, self.stack(params), **where, **self.options)
        return select_mode(result, self.mode, xs.size)

    def __repr__(self) -> str:  # noqa: D105
        return (f"LayeredModel(layer={self.layer}, mode={self.mode!r}, variable={self.variable!r}, "
                f"{len(self.films)} film(s))")


def select_mode(result: Mapping[str, Any], mode: Any, n: int) -> np.ndarray:
    """The phase speed of one mode from a :func:`surfwave.layered` result, shape (n,).

    ``mode`` is a column index of ``c`` (ascending speeds at each kh) or a label of ``mode``
    (per kh when the labels are per point), or a sequence of them, one per point; NaN where
    the mode is absent.
    """
    c = np.asarray(result["c"], dtype=float).reshape(n, -1)
    if not isinstance(mode, (int, np.integer, str)):
        out = np.full(n, np.nan)
        for m in dict.fromkeys(list(mode)):
            rows = np.flatnonzero(np.array([v == m for v in mode]))
            out[rows] = select_mode({"c": c[rows], "mode": _rows(result["mode"], rows, c.shape)}, m, rows.size)
        return out
    if isinstance(mode, (int, np.integer)):
        if mode >= c.shape[1]:
            return np.full(n, np.nan)
        return c[:, int(mode)].copy()
    labels = np.asarray(result["mode"], dtype=object)
    labels = np.broadcast_to(labels, c.shape) if labels.ndim <= 1 else labels.reshape(c.shape)
    out = np.full(n, np.nan)
    for i in range(n):
        hit = np.flatnonzero(labels[i] == mode)
        if hit.size:
            out[i] = c[i, hit[0]]
    return out


def _rows(labels: Any, rows: np.ndarray, shape: tuple[int, ...]) -> np.ndarray:
    """The label rows ``rows`` (labels per point) or the labels themselves (one row for all)."""
    lab = np.asarray(labels, dtype=object)
    return lab if lab.ndim <= 1 else lab.reshape(shape)[rows]


def layered_model(substrate: Any, films: Sequence[Mapping[str, Any]], free: Sequence[str], *, layer: int = 0,
                  mode: Any = 0, variable: Literal["kh", "frequency"] = "kh",
                  **options: Any) -> LayeredModel:
    """The forward model of one guided mode of a film stack, for :func:`surfwave.metrology.fit.fit`.

    Parameters
    ----------
    substrate : str or mapping
        As :func:`surfwave.layered` takes it: a material name, {voigt (GPa), rho[, piezo,
        permittivity]} or isotropic {E (GPa), nu, rho}.
    films : sequence of mapping
        The films from the top down, as :func:`surfwave.layered` takes them (material keys,
        ``thickness`` in m, optional ``euler`` and ``stress`` in GPa).
    free : sequence of str
        The free parameters of ``films[layer]``: ``E``, ``nu``, ``rho``, ``thickness``,
        ``stress`` (equibiaxial, GPa) or ``C11`` ... ``C66`` (checked here, before any solve).
    layer : int
        Which film the parameters belong to (0 = top).
    mode : int or str, or sequence of them
        Column of the ascending speeds (0 = slowest guided mode) or a mode label of the result;
        or one per measured point (the model then takes exactly that many points, and one solver
        call serves every mode).
    variable : {"kh", "frequency"}
        What ``x`` is: kh (wavenumber x total film thickness) or frequency (Hz).
    **options
        Passed to :func:`surfwave.layered` unchanged (``euler``, ``surface``, ``direction``,
        ``electrical``, ``stress``, ``leaky``).

    Returns
    -------
    LayeredModel
        ``model(params, x) -> c`` (m/s, shape (n,)).

    Raises
    ------
    InputError
        Unknown parameter names, a layer out of range, a free parameter the film lacks.
    """
    films = list(films)
    if not films:
        raise InputError("films must hold at least one film")
    if not (isinstance(layer, (int, np.integer)) and 0 <= layer < len(films)):
        raise InputError(f"layer must index one of the {len(films)} films, got {layer!r}")
    if variable not in ("kh", "frequency"):
        raise InputError(f"variable must be 'kh' or 'frequency', got {variable!r}")
    for m in [mode] if isinstance(mode, (int, np.integer, str)) else list(mode):
        if not isinstance(m, (int, np.integer, str)) or (isinstance(m, (int, np.integer)) and m < 0):
            raise InputError(f"mode must be a column >= 0 or a label, got {m!r}")
    for name in free:
        film_value(films[layer], name)  # every name known and present
    bad = [k for k in options if k in ("kh", "frequency")]
    if bad:
        raise InputError(f"pass the abscissa as the data's x (variable={variable!r}), not as {bad}")
    return LayeredModel(substrate, films, int(layer), mode, variable, options)
