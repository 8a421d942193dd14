"""The case record of a real-crystal question, checked once, and its solve.

A :class:`Case` holds everything that determines the surface waves of m points of a real
crystal, in fixed units and frames: the natural-state constants (C and C3 in GPa, rho in
kg/m^3, e in C/m^2, relative eps), the lab axes of each point, the Cauchy prestress of each
point, the surface's boundary object (:mod:`surfwave.solvers.boundary`; piezoelectric
constants switch the electrical part on) and the model choices (third-order constants, leaky
wave, tolerance). :func:`make_case` is the one place where a case is checked (units and the Pa
guard, density bounds, sigma . n = 0, the third-order set, the piezoelectric magnitudes, the
boundary): every door builds its cases through it, the API and the CLI through
:func:`surfwave.resolve.resolve_material`, the sweeps and the scene checks through
:func:`surfwave.real_crystals.sweep.scene_cases` and
:func:`surfwave.real_crystals.piezo_sweep.scene_cases`. :func:`solve` runs the one real-crystal
path (:func:`surfwave.real_crystals.stressed_wave.surface_wave_conditions`) on a checked case;
Born stability of the (stressed) crystal is a per-point outcome there (NaN with its reason).

Examples
--------
>>> from surfwave.real_crystals.materials import get_material
>>> from surfwave.real_crystals.stressed_wave import Constants, stress_tensor
>>> from surfwave.solvers.orientation import lab_axes
>>> R = lab_axes("(001)", [0.0, 45.0])
>>> case = make_case(Constants.from_material(get_material("Cu")), R, stress_tensor("along", 0.1, R), toec=True)
>>> [round(float(c), 2) for c in solve(case)[None]["c_R"]]   # material("Cu", direction=[100] and [110], ...)
[2019.06, 2332.96]
>>> make_case(Constants.from_material(get_material("Cu")), R[:1], [[0, 0, 0], [0, 0, 0], [0, 0, 0.1]])
Traceback (most recent call last):
...
surfwave.errors.InputError: prestress must lie in the surface plane (001): its traction sigma . n = [0.0, 0.0, 0.1] GPa (crystal axes) is not zero
"""  # noqa: E501 (a doctest's expected message)
from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.real_crystals.loads import check_stress
from surfwave.real_crystals.piezo_wave import stress_model
from surfwave.real_crystals.stressed_wave import Constants, require_toec, surface_wave_conditions
from surfwave.real_crystals.wallace import born_lowest, born_reason
from surfwave.solvers.boundary import FREE, Boundary, as_boundary
from surfwave.solvers.tensors import rotate2, voigt_to_tensor

__all__ = ["INTERNAL_KEYS", "Case", "born_reason_natural", "check_constants", "check_stress", "make_case",
           "material_result", "solve"]

#: Keys of the one path's per-point output that stay inside the library (the state's bookkeeping).
INTERNAL_KEYS = ("ok", "F", "axes")


@dataclass(frozen=True, eq=False)
class Case:
    """m points of one real crystal, checked (:func:`make_case` builds it).

    Attributes
    ----------
    constants : Constants
        Natural-state constants: ``voigt`` (6, 6) GPa, ``rho`` kg/m^3, ``toec`` (6, 6, 6) GPa or
        None, ``piezo`` (3, 6) C/m^2 and ``permittivity`` (3, 3) relative, or None.
    axes : ndarray, shape (m, 3, 3)
        Lab axes of the natural crystal, rows (x1 propagation, x2 inward normal, x3), crystal axes.
    stress : ndarray, shape (m, 3, 3)
        Cauchy prestress, crystal axes, GPa; sigma . n = 0 on each point's surface.
    boundaries : tuple of Boundary
        Electrical conditions solved (piezoelectric constants; one solve gives all): empty
        for a crystal without piezoelectric constants.
    toec : bool
        Stressed state from the third-order constants (True) or fixed constants (False).
    leaky : bool or None
        Where the leaky wave is solved (:func:`surfwave.real_crystals.stressed_wave.surface_wave`).
    tol : float or None
        Relative accuracy of rho c^2 (the solver's default when None).
    where : str
        The orientation in words, for messages (``"(001)"``, ``"of the Euler angles"``).
    angle : ndarray, shape (m,), or None
        Propagation angle of each point, degrees (from the surface's reference direction, or
        Euler psi), for the result's labels.
    euler : ndarray, shape (m, 3), or None
        SAW Euler angles (phi, theta, psi) of each point, degrees, where the orientation was
        given by them (or by a named cut).
    scalar : bool
        The question asked for one orientation (the API returns numbers, not arrays).
    """

    constants: Constants
    axes: np.ndarray
    stress: np.ndarray
    boundaries: tuple[Boundary, ...] = ()
    toec: bool = False
    leaky: bool | None = None
    tol: float | None = None
    where: str = "(001)"
    angle: np.ndarray | None = None
    euler: np.ndarray | None = None
    scalar: bool = False

    @property
    def boundary(self) -> Boundary | None:
        """The (first) electrical condition; None without piezoelectric constants."""
        return self.boundaries[0] if self.boundaries else None

    @property
    def piezo(self) -> bool:
        """True when the piezoelectric part is switched on (the constants carry e and eps)."""
        return self.constants.is_piezo

    @property
    def size(self) -> int:
        """m, the number of points."""
        return int(self.axes.shape[0])

    @property
    def stress_lab(self) -> np.ndarray:
        """The prestress in each point's lab frame, GPa, shape (m, 3, 3) (row and column 2: zero)."""
        return rotate2(self.stress, self.axes)


def check_constants(constants: Constants, toec: bool) -> None:
    """Units and bounds of natural-state constants; InputError naming the value.

    Elastic constants and third-order constants in GPa (:func:`surfwave.validate.gpa_constants`),
    density in [1, 1e12] kg/m^3, piezoelectric constants in C/m^2 with eps_r >= 1
    (:func:`surfwave.validate.piezo_constants`); ``toec`` needs a third-order set.
    """
    validate.gpa_constants(constants.voigt)
    validate.density(constants.rho)
    if constants.toec is not None:
        validate.gpa_constants(constants.toec, "third-order constants")
    if constants.is_piezo:
        validate.piezo_constants(constants.piezo, constants.permittivity)
    require_toec(constants, toec)


def born_reason_natural(constants: Constants) -> str:
    """Why the natural-state stiffness is not Born-stable, in the one wording; "" when it is.

    The criterion and the words of the stressed-state check
    (:func:`surfwave.real_crystals.wallace.born_lowest`, :func:`surfwave.real_crystals.wallace.born_reason`)
    at zero stress, where Wallace's B is C: the lowest eigenvalue of the Voigt matrix must be
    positive (a value within 1e-12 of the largest counts as zero). :func:`surfwave.material`
    answers such a crystal with NaN and this reason (after "no stressed state: "); a door that
    cannot answer per point (the layered solver) refuses it with the same words.

    Examples
    --------
    >>> from surfwave.solvers.tensors import cubic_voigt
    >>> born_reason_natural(Constants(cubic_voigt(50.0, -80.0, 30.0), 5000.0))
    "stressed crystal not Born-stable (lowest eigenvalue of Wallace's B = C* + stress terms: -110 GPa)"
    """
    C = voigt_to_tensor(constants.voigt)
    lowest = float(born_lowest(C, np.zeros((3, 3))))
    if lowest > 1e-12 * float(np.abs(constants.voigt).max(initial=0.0)):
        return ""
    return born_reason(lowest)


def make_case(constants: Constants, axes, stress, *, electrical: Any = None, toec: bool = False,
              leaky: bool | np.bool_ | None = None, tol: float | None = None, where: str = "(001)",
              angle: np.ndarray | None = None, euler: np.ndarray | None = None, scalar: bool = False) -> Case:
    """A checked :class:`Case`: the one place where a real-crystal question is checked.

    Parameters
    ----------
    constants : Constants
        Natural-state constants; piezoelectric constants (possibly zero) switch the electrical
        part on.
    axes : array_like, shape (m, 3, 3) or (3, 3)
        Lab axes of the natural crystal (rows x1, x2 inward normal, x3), crystal axes.
    stress : array_like, shape (m, 3, 3) or (3, 3)
        Cauchy prestress, crystal axes, GPa.
    electrical : None, str, Boundary or sequence of them
        The condition(s) (:mod:`surfwave.solvers.boundary`; default free with piezoelectric
        constants). Given without piezoelectric constants: InputError.
    toec, leaky, tol
        As :class:`Case`.
    where : str
        The surface in words, for messages.
    angle, euler, scalar
        Labels of the points (:class:`Case`).

    Raises
    ------
    InputError
        One line naming the value: constants not in GPa, density out of [1, 1e12] kg/m^3,
        piezoelectric constants not in C/m^2 or eps_r < 1, ``toec`` without a set, a stress that
        is not numbers, not finite, in Pa, not symmetric or loads a surface, an unknown or
        misplaced ``electrical``, ``leaky`` not None/True/False, axes that are not rotations.
    """
    if leaky is not None and not isinstance(leaky, (bool, np.bool_)):
        raise InputError(f"leaky must be None, True or False, got {leaky!r}")
    check_constants(constants, bool(toec))
    R = np.asarray(axes, dtype=float)
    if R.shape[-2:] != (3, 3) or R.ndim not in (2, 3):
        raise InputError(f"lab axes must have shape (3, 3) or (m, 3, 3), got {R.shape}")
    R = R.reshape(-1, 3, 3)
    if not np.all(np.isfinite(R)) or np.abs(R @ np.swapaxes(R, -1, -2) - np.eye(3)).max(initial=0.0) > 1e-9:
        raise InputError("lab axes must be finite rotation matrices (rows x1, x2, x3 in crystal axes)")
    sigma = check_stress(stress, R, where)
    if constants.is_piezo:
        given = (FREE,) if electrical is None else electrical
        asked = tuple(given) if isinstance(given, (tuple, list)) else (given,)
        bounds = tuple(as_boundary(b) for b in asked)
        if not bounds or len({b.name for b in bounds}) != len(bounds):
            raise InputError(f"electrical: each condition once, at least one, got {electrical!r}")
    elif electrical is not None:
        raise InputError(f"electrical={electrical!r} needs piezoelectric constants (piezo=, permittivity=)")
    else:
        bounds = ()
    return Case(constants, R, sigma, bounds, bool(toec), None if leaky is None else bool(leaky),
                None if tol is None else float(tol), where, angle, euler, bool(scalar))


def solve(case: Case, start: int = 0, stop: int | None = None, *, bulk: bool = True) -> dict:
    """The one real-crystal path on the points ``start:stop`` of a checked case.

    Returns
    -------
    dict
        Condition name (None without piezoelectric constants) -> the per-point dict of
        :func:`surfwave.real_crystals.stressed_wave.surface_wave` (every key the path gives,
        passed through; :data:`INTERNAL_KEYS` included).
    """
    sl = slice(start, stop)
    conditions: tuple = case.boundaries or (None,)
    return surface_wave_conditions(case.constants, case.axes[sl], case.stress[sl], conditions=conditions,
                                   toec=case.toec, tol=case.tol, bulk=bulk, leaky=case.leaky)


def material_result(case: Case) -> dict:
    """The :func:`surfwave.material` result of a checked case: every per-point key of the one
    path (:func:`solve`) but :data:`INTERNAL_KEYS`, plus ``toec``, ``angle`` and, with the
    piezoelectric part, ``euler`` (NaN for a surface/direction orientation) and ``model``; numbers
    (not arrays of one) for a scalar question."""
    r = solve(case)[case.boundary.name if case.boundary is not None else None]
    out = {key: value for key, value in r.items() if key not in INTERNAL_KEYS}
    out["toec"] = np.full(case.size, case.toec)
    out["angle"] = case.angle if case.angle is not None else np.full(case.size, np.nan)
    if case.piezo:
        out["euler"] = case.euler if case.euler is not None else np.full((case.size, 3), np.nan)
    if case.scalar:
        out = {k: _first(v) for k, v in out.items()}
    if case.piezo:
        out["model"] = stress_model([case.toec])
    return out


def _first(v: np.ndarray) -> Any:
    """The first point's value of a per-point array: an array (its trailing axes) or a Python
    scalar (float, bool, str: ``np.asarray(v[0]).item()``)."""
    x = v[0]
    if isinstance(x, np.ndarray):
        return x
    return x.item() if isinstance(x, np.generic) else np.asarray(x).item()
