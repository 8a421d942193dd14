"""``surfwave.fit_film``: a film's parameters from measured surface-wave dispersion points.

One door for the inverse problem: it checks the stack and the names once, builds the forward
model (the closed-form Love wave, :mod:`surfwave.metrology.love`, or a guided mode of
:func:`surfwave.layered`, :mod:`surfwave.metrology.layered_model`), sets physical bounds and
calls the fitter (:func:`surfwave.metrology.fit.fit`).
"""
from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import TYPE_CHECKING, Any, Literal

import numpy as np

from surfwave.errors import InputError

if TYPE_CHECKING:  # the fitter imports scipy.optimize: loaded on first use, not with `import surfwave`
    from surfwave.metrology.fit import FitResult

__all__ = ["DEFAULT_BOUNDS", "fit_film"]

#: Physical bounds of each kind of parameter (open ends kept off the singular values).
DEFAULT_BOUNDS: dict[str, tuple[float, float]] = {
    "E": (1e-6, math.inf), "mu": (1e-6, math.inf), "rho": (1e-3, math.inf), "thickness": (1e-15, math.inf),
    "nu": (-0.999, 0.499), "substrate_mu": (1e-6, math.inf), "substrate_rho": (1e-3, math.inf),
}
_LOVE_FILM = ("mu", "E", "nu", "rho", "thickness")
_LOVE_SUBSTRATE = ("substrate_mu", "substrate_rho")


def _shear(m: Mapping[str, Any], what: str) -> dict[str, float]:
    """{mu (GPa), rho} or {E, nu, rho} of an isotropic medium, checked."""
    if not isinstance(m, Mapping):
        raise InputError(f"model='love' needs the {what} as an isotropic mapping {{mu, rho}} or {{E, nu, rho}}, "
                         f"got {m!r}")
    if "stress" in m or "voigt" in m:
        raise InputError(f"model='love' is an isotropic, unstressed {what}: drop "
                         f"{[k for k in ('stress', 'voigt') if k in m]} or use model='layered'")
    keys = set(m) - {"thickness", "name"}
    if keys not in ({"mu", "rho"}, {"E", "nu", "rho"}):
        raise InputError(f"model='love' needs the {what} as {{mu, rho}} or {{E, nu, rho}} (GPa, kg/m^3), "
                         f"got keys {sorted(m)}")
    out = {k: float(m[k]) for k in keys}
    for k, v in out.items():
        if not math.isfinite(v):
            raise InputError(f"{what} {k} must be finite, got {v!r}")
    if out["rho"] <= 0 or out.get("mu", 1.0) <= 0 or out.get("E", 1.0) <= 0:
        raise InputError(f"{what}: moduli and density must be > 0, got {out}")
    if "nu" in out and not -1.0 < out["nu"] < 0.5:
        raise InputError(f"{what}: Poisson's ratio must lie in (-1, 0.5), got {out['nu']!r}")
    return out


def _love_setup(film: Mapping[str, Any], substrate: Any, free: Sequence[str],
                variable: str) -> dict[str, float]:
    params = _shear(film, "film")
    if "thickness" in film:
        h = float(film["thickness"])
        if not (math.isfinite(h) and h > 0):
            raise InputError(f"film thickness must be finite and > 0 (m), got {film['thickness']!r}")
        params["thickness"] = h
    elif variable == "frequency" or "thickness" in free:
        raise InputError("the film needs a 'thickness' (m) for frequency data or a free thickness")
    sub = _shear(substrate, "substrate")
    mu_s = sub["mu"] if "mu" in sub else sub["E"] / (2.0 * (1.0 + sub["nu"]))
    params.update(substrate_mu=mu_s, substrate_rho=sub["rho"])
    unknown = [n for n in free if n not in params]
    if unknown:
        allowed = [n for n in _LOVE_FILM + _LOVE_SUBSTRATE if n in params]
        raise InputError(f"free parameter(s) {unknown} are not in the Love model; it has {allowed}")
    return params


def fit_film(x, c, *, model: Literal["love", "layered"], film: Mapping[str, Any] | Sequence[Mapping[str, Any]],
             substrate: Any, free: Sequence[str], sigma=None, variable: Literal["kh", "frequency"] = "kh",
             mode: int | str | Sequence[int | str] = 0, layer: int = 0,
             bounds: Mapping[str, tuple[float, float]] | None = None,
             noise: Literal["relative", "absolute"] = "relative",
             jacobian_updates: Literal["auto", "exact", "broyden"] = "auto",
             check_linearity: bool | Literal["fast", "profile"] = True,
             layered_options: Mapping[str, Any] | None = None) -> FitResult:
    """Fit a film's parameters (E, nu, rho, thickness, C_ij, residual stress) to measured
    surface-wave dispersion points.

    Parameters
    ----------
    x : array_like, shape (n,)
        Where each speed was measured: kh (wavenumber x total film thickness) or frequency in
        Hz, per ``variable``.
    c : array_like, shape (n,)
        Measured phase speeds, m/s.
    model : {"love", "layered"}
        ``"love"``: the shear-horizontal guided (Love) wave of one isotropic film on an
        isotropic substrate, closed form with exact sensitivities (fast). ``"layered"``: a
        guided mode of any stack through :func:`surfwave.layered`, with sensitivities by
        implicit differentiation of its secular equation
        (:func:`surfwave.layers.sensitivity.mode_sensitivities`; leaky modes: central
        differences).
    film : mapping or sequence of mapping
        The film (or the films, top down) with the starting values of the free parameters and
        the values of the fixed ones. Love: {mu (GPa), rho (kg/m^3)} or {E (GPa), nu, rho},
        plus ``thickness`` (m; needed for frequency data). Layered: as :func:`surfwave.layered`
        takes films (``voigt`` or E/nu, ``rho``, ``thickness``, ``euler``, ``stress`` in GPa; or
        a film by ``name``, e.g. {"name": "SiO2", "thickness": 1e-6}, whose database constants
        are the starting values).
    substrate : str or mapping
        Love: an isotropic {mu, rho} or {E, nu, rho}. Layered: as :func:`surfwave.layered`
        (a material name or a mapping).
    free : sequence of str
        The parameters to fit. Love: ``mu`` or ``E``/``nu``, ``rho``, ``thickness``,
        ``substrate_mu``, ``substrate_rho``. Layered: ``E``, ``nu``, ``rho``, ``thickness``,
        ``stress`` (equibiaxial, GPa), ``C11`` ... ``C66`` of ``film[layer]``.
    sigma : float or array_like, shape (n,), optional
        1-sigma uncertainty of each c, m/s. Without it the uncertainties come from the
        scatter (covariance scaled by the reduced chi^2; see ``noise``).
    variable : {"kh", "frequency"}
        What ``x`` is. With kh data a single film's thickness does not enter (a warning says so
        if it is free).
    mode : int or str, or sequence of them (one per point)
        Which mode was measured: Love mode number (0 = fundamental); layered: column of the
        ascending speeds or a mode label of :func:`surfwave.layered`'s result. One per point to
        fit points of several modes together (a second mode often separates parameters that
        one mode ties together); ``curve_x``/``curve_c`` then hold each mode's curve,
        separated by NaN.
    layer : int
        Layered: which film's parameters are free (0 = top).
    bounds : mapping of str to (float, float), optional
        Override the physical bounds (:data:`DEFAULT_BOUNDS`: moduli, densities, thickness > 0,
        -1 < nu < 0.5; C_ij and stress unbounded).
    noise : {"relative", "absolute"}
        Without sigma: equal relative (default) or absolute uncertainty of every point.
    jacobian_updates : {"auto", "exact", "broyden"}
        How the fitter refreshes the sensitivities between iterations
        (:func:`surfwave.metrology.fit.fit`); ``auto``: exact whenever the forward model has
        its own sensitivities (the Love model; the layered model's guided modes), Broyden
        updates between finite-difference Jacobians otherwise (leaky layered modes: each
        finite-difference Jacobian costs 2 x the free parameters solver calls).
    check_linearity : bool or {"fast", "profile"}
        Check the linear uncertainties by holding each parameter one sigma off and refitting the
        others; a warning gives the profile's range where they disagree
        (:func:`surfwave.metrology.fit.fit`). ``True`` (= ``"fast"``): each refit stops once
        its chi^2 rise is known to be within range (2 model calls per free parameter where the
        model is linear over one sigma, up to 8); ``"profile"``: the full refit everywhere (8).
    layered_options : mapping, optional
        Extra keywords of :func:`surfwave.layered` (``euler``, ``surface``, ``direction``,
        ``electrical``, ``stress``, ``leaky``).

    Returns
    -------
    FitResult
        ``values``, 1-sigma ``uncertainties``, ``covariance``, ``correlation``, ``chi2``,
        ``dof``, ``residuals``, ``warnings`` (:class:`surfwave.metrology.fit.FitResult`).

    Raises
    ------
    InputError
        A stack, name, bound or data problem, in one line, before any solve.

    Examples
    --------
    >>> import numpy as np
    >>> import surfwave
    >>> from surfwave.metrology.love import love_speed
    >>> film = {"mu": 31.2, "rho": 2200.0}; sub = {"mu": 66.25, "rho": 2650.0}
    >>> kh = np.linspace(0.2, 5.0, 20)
    >>> c = love_speed(kh, {**film, "substrate_mu": 66.25, "substrate_rho": 2650.0})
    >>> r = surfwave.fit_film(kh, c, model="love", film={"mu": 28.0, "rho": 2200.0}, substrate=sub,
    ...                       free=["mu"], sigma=1.0)
    >>> round(r["values"]["mu"], 6), r["warnings"]
    (31.2, [])
    """
    from surfwave.metrology.fit import fit
    from surfwave.metrology.layered_model import film_value, layered_model
    from surfwave.metrology.love import LoveModel
    from surfwave.metrology.modes import PerPointModes, mode_curves

    if variable not in ("kh", "frequency"):
        raise InputError(f"variable must be 'kh' or 'frequency', got {variable!r}")
    free = list(free)
    if not free:
        raise InputError("free must name at least one parameter")
    xa = np.atleast_1d(np.asarray(x, dtype=float))
    if xa.size and np.all(np.isfinite(xa)) and np.any(xa < 0):
        raise InputError(f"{variable} must be >= 0, got {xa[xa < 0][:3].tolist()}")
    what = "kh" if variable == "kh" else "f"
    span = (f"{what} {xa.min():.3g}-{xa.max():.3g}" if variable == "kh"
            else f"{xa.min() / 1e6:.4g}-{xa.max() / 1e6:.4g} MHz") if xa.size else ""
    limits = {n: DEFAULT_BOUNDS[n] for n in free if n in DEFAULT_BOUNDS}
    limits.update(bounds or {})
    several = not isinstance(mode, (str, int, np.integer))
    modes: list[Any] = list(mode) if several else [mode]  # type: ignore[arg-type]
    if several and len(modes) != xa.size:
        raise InputError(f"mode must be one value or one per point ({xa.size}), got {len(modes)}")
    distinct = list(dict.fromkeys(modes))
    if model == "love":
        if not isinstance(film, Mapping):
            if len(film) != 1:
                raise InputError(f"model='love' takes one film, got {len(film)}; use model='layered'")
            film = film[0]
        bad = [m for m in distinct if not (isinstance(m, (int, np.integer)) and m >= 0)]
        if bad:
            raise InputError(f"Love mode must be an integer >= 0, got {bad[0]!r}")
        params = _love_setup(film, substrate, free, variable)

        def one(m: Any) -> Any:
            return LoveModel(int(m), variable)

        desc = (f"Love mode{'s' if len(distinct) > 1 else ''} {', '.join(str(m) for m in distinct)} "
                "(SH, isotropic film on isotropic substrate, closed form)")
    elif model == "layered":
        films: list[Mapping[str, Any]] = [film] if isinstance(film, Mapping) else list(film)
        opts = dict(layered_options or {})
        for m in distinct:
            checked = layered_model(substrate, films, free, layer=layer, mode=m, variable=variable, **opts)
        films = [*checked.films]  # a film given by name, as explicit constants

        def one(m: Any) -> Any:
            return layered_model(substrate, films, free, layer=layer, mode=m, variable=variable, **opts)

        params = {n: film_value(films[layer], n) for n in free}
        desc = (f"mode{'s' if len(distinct) > 1 else ''} {', '.join(map(str, distinct))} of surfwave.layered, "
                f"film {layer} of {len(films)}")
    else:
        raise InputError(f"model must be 'love' or 'layered', got {model!r}")
    per_mode = PerPointModes(one, modes, xa) if several else None
    if several and model == "layered":  # one solver call serves every mode
        fwd: Any = layered_model(substrate, films, free, layer=layer, mode=modes, variable=variable, **opts)
    else:
        fwd = per_mode if per_mode is not None else one(distinct[0])
    for n, (lo, hi) in limits.items():
        if n in params and not lo <= params[n] <= hi:
            raise InputError(f"starting value {params[n]!r} of {n!r} is outside its bounds ({lo}, {hi})")
    kind = "Love " if model == "love" else ""
    context = (f"from {len(distinct)} modes ({kind}modes {', '.join(map(str, distinct))}) at {span}"
               if len(distinct) > 1 else f"from one mode ({kind}mode {distinct[0]}) at {span}")
    if jacobian_updates == "auto":
        jacobian_updates = "exact" if hasattr(fwd, "jacobian") else "broyden"
    result = fit(fwd, xa, c, params, free=free, bounds={n: limits[n] for n in free if n in limits},
                 sigma=sigma, noise=noise, jacobian_updates=jacobian_updates, check_linearity=check_linearity,
                 context=context, x_name="kh" if variable == "kh" else "frequency_Hz", description=desc,
                 curve_points=0 if several else 200)
    if per_mode is not None:
        result["curve_x"], result["curve_c"] = mode_curves(per_mode, result["values"])
    return result
