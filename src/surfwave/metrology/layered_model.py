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
module imports without it. A film given by name (``{"name": "SiO2", "thickness": 1e-6}``) whose
free parameters it does not spell out is first written as explicit constants
(:func:`explicit_film`: E and nu if the database's stiffness is isotropic, else ``voigt``; rho).
Modes named by label are solved by their families' search alone (at kh:
:func:`surfwave.layers.solve.mode_speeds`; at frequency, those modes alone:
:func:`surfwave.layers.frequency.mode_speeds_at_frequency`; the same numbers as
:func:`surfwave.layered`).

Sensitivities: the model's :meth:`LayeredModel.jacobian` gives dc/dp of the guided modes by
implicit differentiation of the layered solver's secular equation
(:func:`surfwave.layers.sensitivity.mode_sensitivities`): two evaluations of the impedance
recursion per parameter instead of two full mode searches, so the fitter takes it as exact. Leaky
modes (``leaky=True``) have none (the fitter then uses central differences).
"""
from __future__ import annotations

import copy
import re
from collections.abc import Mapping, Sequence
from typing import Any, Literal

import numpy as np

from surfwave.errors import InputError

__all__ = ["FILM_PARAMETERS", "LayeredModel", "explicit_film", "film_value", "layered_model", "select_mode"]

#: Names of film parameters the adapter sets besides C_ij.
FILM_PARAMETERS = ("E", "nu", "rho", "thickness", "stress")
_CIJ = re.compile(r"^C([1-6])([1-6])$")
#: Relative step of the implicit sensitivities' central differences in a parameter ...
REL_STEP = 1e-6
#: ... and the smallest absolute step per kind (stress and C_ij, GPa, may start at 0).
MIN_STEP = {"stress": 1e-4, "nu": 1e-7, "C": 1e-4}
#: Options of :func:`surfwave.layered` that fix the stack (the others: electrical, leaky).
_STACK_OPTIONS = ("euler", "surface", "direction", "stress")


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


def explicit_film(film: Mapping[str, Any]) -> dict[str, Any]:
    """A film given by ``name`` (or ``material``) written as explicit constants, other keys kept.

    Isotropic database stiffness -> ``E`` (GPa) and ``nu``; otherwise ``voigt`` (GPa, the film's
    crystal axes); ``rho`` from the database unless given; a piezoelectric film keeps ``piezo``
    and ``permittivity``. A film without a name is returned as a copy.
    """
    from surfwave.layers.films import lookup
    from surfwave.solvers.tensors import cubic_voigt

    f = dict(film)
    name = f.pop("name", None)
    name = f.pop("material", None) if name is None else name
    if name is None:
        return f
    rec = lookup(str(name), "film")
    C = np.asarray(rec["voigt"], dtype=float)
    lam, mu = C[0, 1], C[3, 3]
    iso = cubic_voigt(lam + 2 * mu, lam, mu)                            # the isotropic stiffness of (lam, mu)
    if np.allclose(C, iso, rtol=1e-9, atol=1e-9 * np.abs(C).max()):
        f.update(E=float(mu * (3 * lam + 2 * mu) / (lam + mu)), nu=float(lam / (2 * (lam + mu))))
    else:
        f["voigt"] = C
    f.setdefault("rho", float(rec["rho"]))
    if rec.get("e") is not None:
        f.setdefault("piezo", np.asarray(rec["e"], dtype=float))
    if rec.get("eps_r") is not None:
        f.setdefault("permittivity", np.asarray(rec["eps_r"], dtype=float))
    if rec.get("conductor"):
        f.setdefault("conductor", True)
    return f


def _step(name: str, value: float) -> float:
    """Step of the central difference of the secular eigenvalue in parameter ``name`` at ``value``."""
    kind = "C" if _CIJ.match(name) else name
    return max(REL_STEP * abs(value), MIN_STEP.get(kind, 0.0), 1e-300)


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
    mode's phase speed (m/s), shape (n,), NaN where that mode does not exist. A bad stack at the
    first call is an InputError; after one valid call, parameters outside the physical domain (a
    fitter's trial step to a negative modulus) give NaN instead.

    Without ``leaky`` it also has ``jacobian(params, x, names) -> (n, m)``: dc/dp of the
    chosen guided modes by implicit differentiation of the secular equation
    (:func:`surfwave.layers.sensitivity.mode_sensitivities`), at the speeds of the last call
    when it was at the same parameters and points (the fitter's order), else after one solve.
    """

    def __init__(self, substrate: Any, films: Sequence[Mapping[str, Any]], layer: int,
                 mode: Any, variable: Literal["kh", "frequency"], options: Mapping[str, Any]) -> None:
        self.substrate = substrate
        self.films = [dict(f) for f in films]
        self.layer, self.mode, self.variable = layer, mode, variable
        self.options = dict(options)
        self._last: tuple[bytes, np.ndarray, np.ndarray] | None = None
        self._valid_once = False  # after one valid stack, parameters outside the domain give NaN
        if not self.options.get("leaky", False):
            self.jacobian = self._jacobian

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
        try:
            c, labels = self._solve(solver, params, xs)
        except InputError:
            if not self._valid_once:
                raise
            # a trial step of the fitter (or its profile check) left the physical domain (a negative
            # modulus, a stiffness not positive definite): no answer there, as for a missing mode
            c, labels = np.full(xs.size, np.nan), np.full(xs.size, "", dtype=object)
        self._valid_once = True
        self._last = (self._key(params, xs), c, labels)
        return c

    def _solve(self, solver: Any, params: Mapping[str, float], xs: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """(c, labels) of the chosen modes at the points xs."""
        if self._one_family_search(solver):
            from surfwave.layers.frequency import mode_speeds_at_frequency
            from surfwave.layers.solve import mode_speeds
            from surfwave.layers.stack import resolve_stack

            stack = resolve_stack(self.substrate, self.stack(params),
                                  **{k: self.options[k] for k in _STACK_OPTIONS if k in self.options})
            if self.options.get("electrical", "free") == "metallized" and not stack.piezo:
                raise InputError("electrical='metallized' needs a piezoelectric layer or substrate")
            modes = self.mode if isinstance(self.mode, str) else list(self.mode)
            if self.variable == "kh":
                c = mode_speeds(stack, xs, modes, self.options.get("electrical", "free"))
            else:
                c = mode_speeds_at_frequency(stack, xs, modes, self.options.get("electrical", "free"))
            labels = np.where(np.isfinite(c), np.broadcast_to(np.asarray(modes, dtype=object), c.shape), "")
        else:
            where = {"kh": xs} if self.variable == "kh" else {"frequency": xs}
            result = solver(self.substrate, self.stack(params), **where, **self.options)
            c, labels = select_mode(result, self.mode, xs.size, labels=True)
        return c, labels

    def _one_family_search(self, solver: Any) -> bool:
        """Whether a call may search only the measured modes' families (same numbers as the full solve).

        Guided modes named by label (at kh or at frequency), with the library's own solver (not a
        stand-in) and valid options; otherwise the full :func:`surfwave.layered` call (which also
        checks them).
        """
        from surfwave.layers.solve import layered

        modes = [self.mode] if isinstance(self.mode, (str, int, np.integer)) else list(self.mode)
        return (solver is layered and not self.options.get("leaky", False)
                and self.options.get("electrical", "free") in ("free", "metallized")
                and set(self.options) <= {*_STACK_OPTIONS, "electrical", "leaky"}
                and all(isinstance(m, str) and not m.endswith("~") for m in modes))

    @staticmethod
    def _key(params: Mapping[str, float], xs: np.ndarray) -> bytes:
        return repr(sorted((k, float(v)) for k, v in params.items())).encode() + xs.tobytes()

    def _jacobian(self, params: Mapping[str, float], x: np.ndarray, names: Sequence[str]) -> np.ndarray:
        """dc/dp (m/s per unit of each parameter), shape (n, len(names)), by implicit differentiation.

        NaN at points where the mode is absent. A replaced ``surfwave.layered`` (a stand-in with
        its own physics) gets central differences of its speeds instead.
        """
        import surfwave
        from surfwave.layers.sensitivity import family_prefix, mode_sensitivities
        from surfwave.layers.solve import layered
        from surfwave.layers.stack import resolve_stack
        from surfwave.metrology.fit import finite_difference_jacobian

        xs = np.atleast_1d(np.asarray(x, dtype=float))
        if getattr(surfwave, "layered", None) is not layered:
            return finite_difference_jacobian(self, params, xs, names)
        if self._last is None or self._last[0] != self._key(params, xs):
            self(params, xs)
        assert self._last is not None
        _, c, labels = self._last
        p = np.array([float(params[n]) for n in names])
        steps = np.array([_step(n, v) for n, v in zip(names, p)])
        found = np.isfinite(c)
        fams = np.array([family_prefix(lab) if ok else "" for lab, ok in zip(labels, found)], dtype=object)
        stack_opts = {k: self.options[k] for k in _STACK_OPTIONS if k in self.options}

        def stack_of(q: np.ndarray) -> Any:
            return resolve_stack(self.substrate, self.stack(dict(zip(names, q))), **stack_opts)

        J = np.full((xs.size, len(names)), np.nan)
        if found.any():
            J[found] = mode_sensitivities(stack_of, p, c[found], xs[found], steps, family=fams[found],
                                          variable=self.variable, electrical=self.options.get("electrical", "free"))
        return J

    def __repr__(self) -> str:  # noqa: D105
        return (f"LayeredModel(layer={self.layer}, mode={self.mode!r}, variable={self.variable!r}, "
                f"{len(self.films)} film(s))")


def select_mode(result: Mapping[str, Any], mode: Any, n: int, labels: bool = False) -> Any:
    """The phase speed of one mode from a :func:`surfwave.layered` result, shape (n,).

    ``mode`` is a column index of ``c`` (ascending speeds at each kh) or a label of ``mode``
    (per kh when the labels are per point), or a sequence of them, one per point; NaN where
    the mode is absent. With ``labels=True``: ``(c, label)``, the second the mode label of each
    point (object array, shape (n,); "" where absent).
    """
    c = np.asarray(result["c"], dtype=float).reshape(n, -1)
    lab = np.asarray(result["mode"], dtype=object)
    lab = np.broadcast_to(lab, c.shape) if lab.ndim <= 1 else lab.reshape(c.shape)
    out = np.full(n, np.nan)
    which = np.full(n, "", dtype=object)
    if not isinstance(mode, (int, np.integer, str)):
        for m in dict.fromkeys(list(mode)):
            rows = np.flatnonzero(np.array([v == m for v in mode]))
            out[rows], which[rows] = select_mode({"c": c[rows], "mode": lab[rows]}, m, rows.size, labels=True)
    elif isinstance(mode, (int, np.integer)):
        if mode < c.shape[1]:
            out = c[:, int(mode)].copy()
            which = np.array(lab[:, int(mode)], dtype=object)
    else:
        for i in range(n):
            hit = np.flatnonzero(lab[i] == mode)
            if hit.size:
                out[i], which[i] = c[i, hit[0]], mode
    return (out, which) if labels else out


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
        A film given by name is first written as explicit constants (:func:`explicit_film`)
        when a free parameter is a material constant.
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
        ``model(params, x) -> c`` (m/s, shape (n,)); ``model.films`` holds the stack it varies
        (the starting values: :func:`film_value` of ``model.films[layer]``).

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
    named = isinstance(films[layer], Mapping) and ("name" in films[layer] or "material" in films[layer])
    if named and any(n not in ("thickness", "stress") for n in free):
        films[layer] = explicit_film(films[layer])
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
