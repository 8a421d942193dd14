"""The validators of the library's arguments: arrays (strains, angles, theta, stresses),
propagation angles, Euler angles, densities, Voigt stiffnesses and third-order constants. Each
error names the argument and value.

Examples
--------
>>> as_1d(0.95).tolist(), as_1d([0.9, 1.0]).tolist()
([0.95], [0.9, 1.0])
>>> as_1d([[1.0]], "theta")
Traceback (most recent call last):
...
surfwave.errors.InputError: theta must be a scalar or a 1-D array, got shape (1, 1)
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError


def as_1d(values, name: str = "d_over_d0", *, finite: bool = True) -> np.ndarray:
    """``values`` (scalar or 1-D) as a float array of shape (n,).

    Parameters
    ----------
    values : float or array_like, shape (n,)
    name : str
        The argument's name, for the error message.
    finite : bool
        Refuse NaN and infinities (default). ``False`` where the function's contract is
        per point: a non-finite entry gives a NaN result with its reason, the others are
        computed.

    Raises
    ------
    InputError
        Naming ``name``: for more than one dimension, for values that are not numbers, and
        (``finite``) for NaN or infinite entries.
    """
    a = real_array(values, name)
    if a.ndim != 1:
        raise InputError(f"{name} must be a scalar or a 1-D array, got shape {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite, got {a[~np.isfinite(a)][:5].tolist()}")
    return a


#: Largest |angle| (degrees) accepted: beyond 1e6 degrees the spacing of float64 values
#: (1.2e-10 degrees at 1e6, 16384 degrees at 1e20) starts to eat the decimals a grid is
#: rounded to, and the angle computed is no longer the angle labelled. Angles are not
#: reduced modulo 360 because the label must be the value the user gave.
MAX_ANGLE = 1.0e6
#: Densities accepted (kg/m^3): below 1 no solid exists (silica aerogel, the lightest, is
#: about 1 kg/m^3) and speeds can overflow (rho = 1e-300 gives c = inf); the upper end,
#: far above osmium (22,590), admits the scaled-units habit rho = 1e9 with constants in
#: GPa (speeds^2 then in units of C/rho) used in the docs and tests.
MIN_RHO, MAX_RHO = 1.0, 1.0e12


def huge_angle_error(what: str, detail: str = "") -> InputError:
    """The one refusal of an angle beyond :data:`MAX_ANGLE` degrees; ``what`` names it and its
    value (e.g. "angle = 1e+20"), ``detail`` is appended (e.g. the text given)."""
    return InputError(f"{what} degrees: angles beyond {MAX_ANGLE:g} degrees lose precision in float64 (the angle "
                      f"computed would not be the angle labelled); reduce it modulo 360{detail}")


def brief(value, limit: int = 80) -> str:
    """``repr(value)`` on one line, cut to ``limit`` characters (for error messages)."""
    text = " ".join(repr(value.tolist() if isinstance(value, np.ndarray) else value).split())
    return text if len(text) <= limit else text[:limit - 5] + " ...]"


def real_array(values, name: str) -> np.ndarray:
    """``values`` as a float array (at least 1-D); text, complex or ragged input refused."""
    try:
        raw = np.asarray(values)
    except (TypeError, ValueError) as exc:
        why = "rows of different lengths" if "inhomogeneous" in str(exc) else " ".join(str(exc).split())[:80]
        raise InputError(f"{name} must be numbers in a regular array, got {brief(values)} ({why})") from None
    if raw.dtype.kind in "USV":
        raise InputError(f"{name} must be numbers, got text: {brief(values)}")
    if raw.dtype.kind == "c":
        raise InputError(f"{name} must be real numbers, got complex values: {brief(values)}")
    try:
        return np.atleast_1d(np.asarray(raw, dtype=float))
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be numbers, got {brief(values)} ({exc})") from None


def angle_values(values, name: str = "angle"):
    """Propagation angle(s) in degrees: a float for a scalar, else a float array of shape (m,).

    Raises
    ------
    InputError
        Naming ``name`` and the value: not numbers, more than one dimension, empty, not
        finite, or larger in magnitude than :data:`MAX_ANGLE`.

    Examples
    --------
    >>> angle_values(30), angle_values([0, 45]).tolist()
    (30.0, [0.0, 45.0])
    >>> angle_values([])
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: angle must hold at least one angle (degrees), got []
    """
    a = as_1d(values, name)
    if a.size == 0:
        raise InputError(f"{name} must hold at least one angle (degrees), got {values!r}")
    big = np.abs(a) > MAX_ANGLE
    if big.any():
        raise huge_angle_error(f"{name} = {float(a[big][0])!r}")
    return float(a[0]) if np.ndim(values) == 0 else a


def density(rho, name: str = "rho") -> float:
    """A density in kg/m^3 as a float in [:data:`MIN_RHO`, :data:`MAX_RHO`].

    Examples
    --------
    >>> density(8960)
    8960.0
    >>> density(1e-300)
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: rho = 1e-300 kg/m^3 lies outside [1, 1e+12] kg/m^3 (no solid is lighter than 1 kg/m^3; is it in g/cm^3 or another unit?)
    """  # noqa: E501 (a doctest's expected message)
    if isinstance(rho, np.ndarray) and rho.ndim == 0:
        rho = rho.item()
    if isinstance(rho, (bool, np.bool_)) or not isinstance(rho, (int, float, np.integer, np.floating)):
        raise InputError(f"{name} must be one number (kg/m^3), got {rho!r}")
    value = float(rho)
    if not np.isfinite(value) or value <= 0:
        raise InputError(f"density {name} must be positive and finite, got {rho!r} kg/m^3")
    if not MIN_RHO <= value <= MAX_RHO:
        raise InputError(f"{name} = {rho!r} kg/m^3 lies outside [{MIN_RHO:g}, {MAX_RHO:g}] kg/m^3 (no solid "
                         "is lighter than 1 kg/m^3; is it in g/cm^3 or another unit?)")
    return value


def stiffness(voigt, name: str = "voigt") -> np.ndarray:
    """A Voigt stiffness (6, 6) of real, finite numbers, symmetric (GPa, not checked here).

    Raises
    ------
    InputError
        Naming ``name``: text or complex entries, a shape other than (6, 6), NaN or
        infinite entries (before the symmetry test, which NaN would fail misleadingly),
        an asymmetric matrix (the largest asymmetry named).
    """
    C6 = real_array(voigt, name)
    if C6.shape != (6, 6):
        raise InputError(f"{name} must be a 6 x 6 stiffness (GPa), got shape {np.shape(voigt)}")
    bad = ~np.isfinite(C6)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        raise InputError(f"{name} must be finite, got {float(C6[i, j])!r} at row {i + 1}, column {j + 1}")
    if not np.allclose(C6, C6.T, rtol=1e-10, atol=0):
        i, j = np.unravel_index(np.argmax(np.abs(C6 - C6.T)), C6.shape)
        raise InputError(f"the Voigt stiffness {name} must be symmetric: C{i + 1}{j + 1} = {float(C6[i, j])!r} but "
                         f"C{j + 1}{i + 1} = {float(C6[j, i])!r}")
    return C6


def euler_angles(euler, name: str = "euler") -> np.ndarray:
    """SAW Euler angles (degrees) as a float array of shape (3,) or (m, 3), m >= 1.

    Every way of giving Euler angles (API ``euler=``, the CLI's ``--euler``, a scene's grid)
    comes through here before any computation.

    Raises
    ------
    InputError
        Naming ``name`` and the value: text (``"0 38 0"``), complex, ragged or a mapping; a
        shape other than (3,) or (m, 3); no rows; NaN or infinite angles; angles beyond
        :data:`MAX_ANGLE` degrees.

    Examples
    --------
    >>> euler_angles((0, -52, 0)).tolist()
    [0.0, -52.0, 0.0]
    >>> euler_angles("0 38 0")
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: euler must be numbers, got text: '0 38 0'
    """
    if isinstance(euler, dict):
        raise InputError(f"{name} must be (phi, theta, psi) in degrees or an (m, 3) array, got a mapping "
                         f"{brief(euler)}; give the three angles in that order")
    e = real_array(euler, name)
    if e.ndim == 0 or (e.shape != (3,) and (e.ndim != 2 or e.shape[1] != 3)):
        raise InputError(f"{name} must be (phi, theta, psi) in degrees or an (m, 3) array, got shape "
                         f"{np.shape(euler)}: {brief(euler)}")
    if e.size == 0:
        raise InputError(f"{name} must hold at least one (phi, theta, psi) row, got shape {e.shape}")
    bad = ~np.isfinite(e)
    if bad.any():
        row = e.reshape(-1, 3)[np.flatnonzero(bad.reshape(-1, 3).any(axis=1))[0]]
        raise InputError(f"{name} angles must be finite, got (phi, theta, psi) = {tuple(row.tolist())} degrees")
    big = np.abs(e) > MAX_ANGLE
    if big.any():
        raise huge_angle_error(f"{name} = {float(e[big][0])!r}")
    return e


#: Largest |angle| of a set of Euler angles that all look like radians (2 pi).
_RADIANS = 2 * np.pi + 1e-9


def radians_note(euler, name: str = "Euler angles") -> str | None:
    """A one-line note when every Euler angle looks like radians, else None.

    "Looks like radians": every non-zero angle lies within 2 pi in magnitude (the largest at
    least 0.01) and at least one of them is not a whole number of degrees (0.663 is 38 degrees in radians; whole degrees
    such as (0, 1, 0) and the Z cut (0, 0, 0) are taken at their word). The angles are used as
    given (degrees); the note only says what they would be in radians.

    Parameters
    ----------
    euler : array_like, shape (3,) or (m, 3) or (n,)
        Angles in degrees (any shape: every value is looked at).
    name : str
        What the angles are called in the note ("--euler", "scene 's', key 'euler'").

    Examples
    --------
    >>> radians_note([0, 0.663, 0])
    'note: all Euler angles lie within 2 pi and 0.663 is not a whole number: they are taken as degrees (0.663 deg); if you meant radians, 0.663 rad = 37.99 deg'
    >>> radians_note([0, 38, 0]) is None, radians_note([0, 0, 0]) is None
    (True, True)
    """  # noqa: E501 (a doctest's expected message)
    a = np.asarray(euler, dtype=float).ravel()
    a = a[np.isfinite(a) & (a != 0)]
    if not a.size or not 0.01 <= np.abs(a).max() <= _RADIANS:
        return None
    frac = a[a != np.round(a)]
    if not frac.size:
        return None
    x = float(frac[np.argmax(np.abs(frac))])
    return (f"note: all {name} lie within 2 pi and {x:g} is not a whole number: they are taken as degrees "
            f"({x:g} deg); if you meant radians, {x:g} rad = {np.degrees(x):.2f} deg")


def toec_array(toec, name: str = "toec") -> np.ndarray:
    """Third-order constants given as numbers (GPa): a float array, text, ragged, complex refused.

    The shape is the caller's to check ((6,) cubic six or a (6, 6, 6) Voigt array).

    Examples
    --------
    >>> toec_array([-1271, -814, -50, -3, -780, -95]).shape
    (6,)
    >>> toec_array("abc")
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: toec must be numbers, got text: 'abc'
    """
    if isinstance(toec, (bool, np.bool_)):
        raise InputError(f"{name} must be True (the database's set) or numbers in GPa, got {toec!r}")
    t = real_array(toec, name)
    if t.ndim == 0 or t.size == 0:
        raise InputError(f"{name} must hold the third-order constants in GPa, got {brief(toec)}")
    return t


# --------------------------------------------------------------------------- units and magnitudes
# The one place of the unit guards of a real crystal (GPa, C/m^2, relative permittivity): every
# door (API, CLI, scene validation, sweeps) reaches them through surfwave.case.make_case.

#: Largest |elastic constant| accepted, second and third order, GPa: diamond's C11 is about
#: 1080 GPa and the largest measured third-order constants a few thousand GPa; a larger value
#: was almost surely given in Pa.
MAX_CONSTANT_GPA = 1.0e5
#: Largest |stress| accepted, GPa: no crystal carries a stress of 1 TPa (the ideal strength of
#: diamond is about 100 GPa); a larger value was almost surely given in Pa (0.1 GPa = 1e8 Pa).
MAX_STRESS_GPA = 1.0e3
#: Largest |piezoelectric stress constant| accepted, C/m^2: the strongest known (PZT ceramics,
#: e33 about 25 C/m^2; LiNbO3 e15 3.7 C/m^2) stay far below; a larger value is in another unit
#: (uC/cm^2 is 100 x smaller than C/m^2 per unit value) or mistyped.
MAX_PIEZO_E = 100.0
#: Smallest eigenvalue of a relative permittivity accepted: vacuum (1) is the floor.
MIN_EPS_R = 1.0


def _has_bool(values) -> bool:
    """True when ``values`` is or holds a bool (``True`` would silently count as 1)."""
    if isinstance(values, (bool, np.bool_)):
        return True
    if isinstance(values, np.ndarray):
        return values.dtype.kind == "b" or (values.dtype == object and any(_has_bool(v) for v in values.flat))
    if isinstance(values, (list, tuple)):
        return any(_has_bool(v) for v in values)
    return False


def _numbers(values, name: str, unit: str) -> np.ndarray:
    """``values`` as a real float array; booleans, text and complex refused (naming ``unit``)."""
    if type(values) is np.ndarray and values.dtype == np.float64:        # already real floats: a view
        a = values.reshape(values.shape)
        if not np.all(np.isfinite(a)):
            raise InputError(f"{name} must be finite, got {brief(values)}")
        return a
    if _has_bool(values):
        raise InputError(f"{name} must be numbers ({unit}), not True/False: got {brief(values)}")
    a = real_array(values, name).reshape(np.shape(values))
    if not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite, got {brief(values)}")
    return a


def gpa_constants(values, name: str = "elastic constants") -> np.ndarray:
    """Elastic constants (any shape) in GPa: real, finite, within :data:`MAX_CONSTANT_GPA`.

    Examples
    --------
    >>> gpa_constants([[168.4e9]])
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: elastic constants must be in GPa; the largest is 1.684e+11, which looks like Pa (divide by 1e9)
    """  # noqa: E501 (a doctest's expected message)
    a = _numbers(values, name, "GPa")
    big = float(np.abs(a).max()) if a.size else 0.0
    if big > MAX_CONSTANT_GPA:
        raise InputError(f"{name} must be in GPa; the largest is {big:.4g}, which looks like Pa (divide by 1e9)")
    return a


def gpa_stress(values, name: str = "stress") -> np.ndarray:
    """A prestress (any shape) in GPa: real numbers (not True), finite, within :data:`MAX_STRESS_GPA`.

    Examples
    --------
    >>> gpa_stress(0.1).tolist()
    0.1
    >>> gpa_stress(2000.0)
    Traceback (most recent call last):
    ...
    surfwave.errors.InputError: stress must be in GPa; got 2000.0, beyond 1000 GPa, which looks like Pa (divide by 1e9: 2e-06 GPa)
    """  # noqa: E501 (a doctest's expected message)
    a = _numbers(values, name, "GPa")
    big = float(a.flat[np.argmax(np.abs(a))]) if a.size else 0.0
    if abs(big) > MAX_STRESS_GPA:
        raise InputError(f"{name} must be in GPa; got {big!r}, beyond {MAX_STRESS_GPA:g} GPa, which looks like Pa "
                         f"(divide by 1e9: {big / 1e9:g} GPa)")
    return a


def piezo_constants(e, eps_r) -> tuple[np.ndarray, np.ndarray]:
    """Piezoelectric stress constants e (3, 6), C/m^2, and relative permittivity eps_r (3, 3), checked.

    Raises
    ------
    InputError
        Text, complex or boolean entries, wrong shapes, non-finite values, |e| beyond
        :data:`MAX_PIEZO_E` C/m^2, an eps_r that is not symmetric or has an eigenvalue below
        :data:`MIN_EPS_R` (vacuum is the floor; eps_r is relative, not in F/m).
    """
    e6 = _numbers(e, "piezo (e)", "C/m^2")
    er = _numbers(eps_r, "permittivity (eps_r)", "relative")
    if e6.shape != (3, 6) or er.shape != (3, 3):
        raise InputError(f"piezo must be 3 x 6 (C/m^2) and permittivity 3 x 3 (relative), got shapes {e6.shape} "
                         f"and {er.shape}")
    big = float(np.abs(e6).max())
    if big > MAX_PIEZO_E:
        raise InputError(f"piezo (e) must be in C/m^2; the largest is {big:.4g}, beyond {MAX_PIEZO_E:g} C/m^2 "
                         "(the strongest piezoelectrics have about 25)")
    if not np.allclose(er, er.T, rtol=0, atol=1e-12 * max(float(np.abs(er).max()), 1.0)):
        raise InputError(f"permittivity (eps_r) must be symmetric, got {er.tolist()}")
    low = float(np.linalg.eigvalsh(er)[0])
    if low < MIN_EPS_R:
        raise InputError(f"permittivity (eps_r) must be positive definite with eigenvalues >= 1 (relative to "
                         f"vacuum, eps / EPS0; not in F/m), the lowest is {low:.4g}")
    return e6, er
