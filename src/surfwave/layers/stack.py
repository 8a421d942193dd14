"""Resolve a substrate and a list of films into one checked stack of lab-frame tensors.

:func:`resolve_stack` is the single place where the inputs of :func:`surfwave.layered`
(and of the ``surfwave layered`` command) are read and checked, before anything is computed.
Everything a layer shares with a crystal of :func:`surfwave.material` goes through the one door
of the real-crystal questions, so the same input gives the same refusal in the same words
(after the layer's name, "substrate: ..."): names and aliases of both crystal databases with
their did-you-mean (:mod:`surfwave.real_crystals.catalog`, the film database added), constants
(:func:`surfwave.resolve.resolve_constants`: units and the one Pa bound, density bounds,
piezoelectric magnitudes, eps_r >= 1), Born stability of C
(:func:`surfwave.case.born_reason_natural`), Euler angles and directions
(:func:`surfwave.validate.euler_angles`, :func:`surfwave.validate.angle_values`), stress units
and sigma . n = 0 at the surface and at every interface (:func:`surfwave.validate.gpa_stress`,
:func:`surfwave.case.check_stress`). What only a layer has stays here: thickness in metres,
isotropic {E, nu, rho} with -1 < nu < 0.5, the film list, electrodes and conductors.

Remembered. Resolving a material and building a layer's lab-frame tensor cost far more than the
waves of a small isotropic stack; both are remembered by the values of their inputs (a material
mapping of plain scalars, and the Voigt matrix, axes and stress of a layer; :data:`MEMO_SIZE`
entries each). Only successful resolutions are remembered, so a refusal is the same line every
time, and every caller receives its own copy of a layer's tensor.

Frames
------
The solver works in the project's lab frame: x1 = propagation, x2 = INWARD normal (into the
substrate), x3 = x1 x x2. The public frame of a film stress is the SAW frame of the issue:
x1 = propagation, x2' = in-plane normal to it, x3' = OUTWARD normal; hence our x2 = -x3' and
our x3 = x2' (:data:`SAW_TO_LAB`). A film's crystal axes are given by SAW Euler angles
(:func:`surfwave.solvers.euler.euler_lab_axes`, default (0, 0, 0): crystal Z along the outward
normal, crystal X along the propagation).
"""
from __future__ import annotations

import functools
from collections.abc import Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, replace

import numpy as np

from surfwave import validate
from surfwave.case import born_reason_natural, check_stress
from surfwave.errors import InputError
from surfwave.resolve import resolve_constants
from surfwave.solvers.euler import euler_lab_axes
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.piezo_tensors import EPS0, piezo_voigt_to_tensor, rotate3
from surfwave.solvers.stroh import wave_propagation_tensor
from surfwave.solvers.tensors import cubic_voigt, rotate2, rotate4, voigt_to_tensor

__all__ = ["GPA", "Layer", "MAX_THICKNESS", "SAW_TO_LAB", "Stack", "isotropic_voigt", "resolve_stack"]

#: GPa -> Pa.
GPA = 1.0e9
#: Rows: our lab axes (x1, x2 inward, x3) in the SAW frame (x1, x2' in-plane, x3' outward).
SAW_TO_LAB = np.array([[1.0, 0.0, 0.0], [0.0, 0.0, -1.0], [0.0, 1.0, 0.0]])
#: A film thicker than this (m) is refused: a thickness given in micrometres (e.g. 1.0 for 1 um)
#: instead of metres. 1 cm is far beyond any deposited film.
MAX_THICKNESS = 1.0e-2
#: Largest |stress| in GPa (larger looks like Pa): the one bound, :data:`surfwave.validate.MAX_STRESS_GPA`.
MAX_STRESS_GPA = validate.MAX_STRESS_GPA
#: Largest |constant| in GPa (larger looks like Pa): the one bound, :data:`surfwave.validate.MAX_CONSTANT_GPA`.
MAX_GPA = validate.MAX_CONSTANT_GPA
#: The axes of a layer's stress as given (the message of a loaded surface names them).
SAW_FRAME = "SAW frame: x1 propagation, x2 in-plane, x3 outward normal"
_MATERIAL_KEYS = {"name", "voigt", "rho", "piezo", "permittivity", "E", "nu", "conductor"}
_FILM_KEYS = _MATERIAL_KEYS | {"thickness", "euler", "stress", "material", "electrode_below"}


@dataclass(frozen=True, eq=False)
class Layer:
    """One layer (or the substrate) in the lab frame, SI units.

    Attributes
    ----------
    name : str
        What the caller called it.
    A : ndarray, shape (3, 3, 3, 3)
        Wave-propagation tensor C + sigma delta in the lab frame, Pa.
    rho : float
        Density, kg/m^3.
    e : ndarray, shape (3, 3, 3), or None
        Piezoelectric stress tensor e_kij, lab frame, C/m^2.
    eps : ndarray, shape (3, 3), or None
        Clamped permittivity, lab frame, F/m.
    thickness : float
        m (0 for the substrate, which is semi-infinite).
    sigma : ndarray, shape (3, 3)
        In-plane prestress in the lab frame, Pa.
    electrode_below : bool
        A thin grounded electrode (phi = 0, no mass) on the interface under this film.
    """

    name: str
    A: np.ndarray
    rho: float
    e: np.ndarray | None
    eps: np.ndarray | None
    thickness: float
    sigma: np.ndarray
    electrode_below: bool = False


@dataclass(frozen=True, eq=False)
class Stack:
    """A substrate and its films, top film first.

    Attributes
    ----------
    substrate : Layer
    films : tuple of Layer
        From the top (free surface) down to the substrate.
    piezo : bool
        True when any layer carries piezoelectric constants (the potential is then solved in
        every layer).
    """

    substrate: Layer
    films: tuple[Layer, ...]
    piezo: bool

    @property
    def total_thickness(self) -> float:
        """Sum of the film thicknesses, m."""
        return float(sum(f.thickness for f in self.films))


def isotropic_voigt(E, nu) -> np.ndarray:
    """Voigt stiffness (6, 6) of an isotropic solid from Young's modulus E (GPa) and Poisson's ratio nu.

    Raises
    ------
    InputError
        E <= 0 or non-finite, nu outside (-1, 0.5) (the stiffness would not be positive definite).
    """
    E = _number(E, "E (GPa)")
    nu = _number(nu, "nu")
    if E <= 0:
        raise InputError(f"Young's modulus E must be positive (GPa), got {E!r}")
    validate.gpa_constants(E, "Young's modulus E")
    if not -1.0 < nu < 0.5:
        raise InputError(f"Poisson's ratio nu must lie in (-1, 0.5) for a stable isotropic solid, got {nu!r}")
    lam = E * nu / ((1 + nu) * (1 - 2 * nu))
    mu = E / (2 * (1 + nu))
    return cubic_voigt(lam + 2 * mu, lam, mu)   # isotropic: a cubic stiffness with C11 - C12 = 2 C44


def _number(value, what: str) -> float:
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        raise InputError(f"{what} must be one number, got {value!r}")
    v = float(value)
    if not np.isfinite(v):
        raise InputError(f"{what} must be finite, got {value!r}")
    return v


@contextmanager
def _at(where: str) -> Iterator[None]:
    """Prefix an InputError of the one door's checks with the layer it concerns ("substrate: ...")."""
    try:
        yield
    except InputError as exc:
        raise InputError(f"{where}: {exc}") from None


def _eps_matrix(value):
    """A relative permittivity as given, a number standing for eps_r times the identity."""
    if np.ndim(value) == 0 and not isinstance(value, (bool, np.bool_, str)):
        return float(validate.real_array(value, "permittivity (eps_r)")[0]) * np.eye(3)
    return value


def _checked_eps(e6, value, where: str) -> np.ndarray:
    """eps_r (3, 3) of a layer, checked with its e (zeros when None) by :func:`surfwave.validate.piezo_constants`."""
    with _at(where):
        return validate.piezo_constants(np.zeros((3, 6)) if e6 is None else e6, _eps_matrix(value))[1]


#: Types of the values of a material mapping whose resolution is remembered (immutable scalars).
_PLAIN = (int, float, str, bool, type(None))
#: Entries of each remembered resolution (materials, layer tensors) at most; the oldest go first.
MEMO_SIZE = 64
#: Keys of a film mapping that its material does not depend on (read by :func:`resolve_stack` itself).
_LAYER_ONLY_KEYS = frozenset({"thickness", "euler", "stress", "electrode_below"})
_MATERIALS: dict[tuple, dict] = {}
_TENSORS: dict[tuple, np.ndarray] = {}


def _remember(memo: dict, key: tuple, value) -> None:
    """Store ``value`` under ``key``, dropping the oldest entry beyond :data:`MEMO_SIZE`."""
    if len(memo) >= MEMO_SIZE:
        memo.pop(next(iter(memo)), None)
    memo[key] = value


def _material_key(spec, film: bool) -> tuple | None:
    """A key of a material mapping by value, or None when its resolution is not remembered.

    Only mappings whose keys are all accepted ones and whose values other than a layer's own
    (thickness, euler, stress, electrode_below) are immutable scalars of exactly the :data:`_PLAIN`
    types (the isotropic {E, nu, rho} and a name with a density are the common cases) have a key;
    the type is part of it (1 and 1.0 and True differ).
    """
    if not isinstance(spec, Mapping):
        return None
    items = []
    for k, v in spec.items():
        if not isinstance(k, str) or k not in _FILM_KEYS:
            return None
        if k not in _LAYER_ONLY_KEYS:                                   # every key _resolved_material reads
            if type(v) not in _PLAIN:
                return None
            items.append((k, type(v).__name__, v))
    return (film, *sorted(items))


def _material(spec, where: str, film: bool = True) -> dict:
    """:func:`_resolved_material`, remembered by value for plain mappings (:func:`_material_key`).

    A remembered record is returned as a new dict whose arrays are read-only (they are shared);
    only successful resolutions are remembered, so a refusal is raised anew each time.
    """
    key = _material_key(spec, film)
    if key is not None and key in _MATERIALS:
        return dict(_MATERIALS[key])
    rec = _resolved_material(spec, where, film)
    if key is not None:
        for v in rec.values():
            if isinstance(v, np.ndarray):
                v.setflags(write=False)
        _remember(_MATERIALS, key, rec)
        rec = dict(rec)
    return rec


def _resolved_material(spec, where: str, film: bool = True) -> dict:
    """Voigt C (GPa, crystal axes), rho, e (3, 6) or None, eps_r (3, 3) or None from a name or a mapping.

    Names: :func:`surfwave.layers.films.lookup`; constants: :func:`surfwave.resolve.resolve_constants`
    (the checks and words of :func:`surfwave.material`), then Born stability of C
    (:func:`surfwave.case.born_reason_natural`), refused here: a layer has no per-point answer.
    """
    from surfwave.layers.films import lookup

    if isinstance(spec, str):
        return lookup(spec, where, film=film)
    if not isinstance(spec, Mapping):
        raise InputError(f"{where} must be a material name or a mapping (voigt/rho, E/nu/rho, name), got {spec!r}")
    extra = sorted(set(spec) - _FILM_KEYS)
    if extra:
        raise InputError(f"{where}: unknown keys {extra}; accepted: {sorted(_FILM_KEYS)}")
    name = spec.get("name", spec.get("material"))
    if name is not None:
        rec = lookup(str(name), where, film=film)
        if "rho" in spec:
            with _at(where):
                rec["rho"] = validate.density(spec["rho"])
        for key in ("voigt", "E", "nu", "piezo"):
            if key in spec:
                raise InputError(f"{where}: material {name!r} given by name: do not also give {key!r}")
        if "permittivity" in spec:
            rec["eps_r"] = _checked_eps(rec.get("e"), spec["permittivity"], where)
        if "conductor" in spec:
            rec["conductor"] = bool(spec["conductor"])
        return rec
    if "voigt" in spec and ("E" in spec or "nu" in spec):
        raise InputError(f"{where}: give either voigt or E and nu, not both")
    if "voigt" in spec:
        voigt, label = spec["voigt"], "voigt"
    elif "E" in spec or "nu" in spec:
        if "E" not in spec or "nu" not in spec:
            raise InputError(f"{where}: an isotropic material needs both E (GPa) and nu")
        with _at(where):
            voigt, label = isotropic_voigt(spec["E"], spec["nu"]), "isotropic"
    else:
        raise InputError(f"{where}: give a material name, voigt (GPa) and rho, or E (GPa), nu and rho")
    if "rho" not in spec:
        raise InputError(f"{where}: the density rho (kg/m^3) is missing")
    e6, eps = spec.get("piezo"), spec.get("permittivity")
    if e6 is not None and eps is None:
        raise InputError(f"{where}: piezo given without permittivity (relative, 3 x 3)")
    with _at(where):
        c = resolve_constants(voigt=voigt, rho=spec["rho"], piezo=None if eps is None and e6 is None else
                              (np.zeros((3, 6)) if e6 is None else e6),
                              permittivity=None if eps is None else _eps_matrix(eps))
        born = born_reason_natural(c)
        if born:
            raise InputError(born)
    return {"name": label, "voigt": c.voigt, "rho": c.rho, "e": None if e6 is None else c.piezo,
            "eps_r": c.permittivity, "conductor": bool(spec.get("conductor", False))}


def _stress(stress, where: str, surface: str) -> np.ndarray:
    """In-plane prestress in our lab frame (3, 3), GPa, from a scalar (equibiaxial) or a 3 x 3 SAW-frame tensor.

    Units, finiteness, symmetry and sigma . n = 0 by the one door's checks
    (:func:`surfwave.validate.gpa_stress`, :func:`surfwave.case.check_stress`); ``surface``
    names the plane in the message.
    """
    if stress is None:
        return np.zeros((3, 3))
    with _at(where):
        s = validate.gpa_stress(stress)
        if s.shape == ():
            sig = float(s) * np.diag([1.0, 1.0, 0.0])            # equibiaxial in the surface plane (SAW frame)
        elif s.shape == (3, 3):
            sig = s
        else:
            raise InputError(f"stress must be a scalar (equibiaxial) or a 3 x 3 tensor in GPa ({SAW_FRAME}), got "
                             f"shape {s.shape}")
        check_stress(sig, SAW_TO_LAB[None], surface, frame=SAW_FRAME)   # row 1: the inward normal, SAW frame
    return SAW_TO_LAB @ sig @ SAW_TO_LAB.T


def _propagation_tensor(voigt: np.ndarray, R: np.ndarray, sigma: np.ndarray, where: str) -> np.ndarray:
    """Wave-propagation tensor (3, 3, 3, 3), Pa, of Voigt C (GPa) in lab axes R under sigma (Pa).

    Remembered by the values of its inputs (a new copy is returned each time).
    """
    v, r, s = (np.ascontiguousarray(a, dtype=float) for a in (voigt, R, sigma))
    key = (v.tobytes(), r.tobytes(), s.tobytes())
    A = _TENSORS.get(key)
    if A is None:
        C = rotate4(voigt_to_tensor(v), r) * GPA
        try:
            A = wave_propagation_tensor(C, s)
        except InputError as exc:
            raise InputError(f"{where}: {exc}") from None
        _remember(_TENSORS, key, A)
    return A.copy()


def _layer(rec: dict, R: np.ndarray, thickness: float, sigma_gpa: np.ndarray, piezo_stack: bool, where: str) -> Layer:
    sigma = sigma_gpa * GPA
    A = _propagation_tensor(rec["voigt"], R, sigma, where)
    e = eps = None
    if piezo_stack:
        if rec.get("conductor"):
            raise InputError(f"{where}: a conducting (metal) film in a piezoelectric stack is not supported yet; "
                             "use electrical='metallized' for a metallized top surface")
        if rec.get("eps_r") is None:
            raise InputError(f"{where}: in a piezoelectric stack every layer needs a permittivity (relative); "
                             f"{rec['name']!r} has none")
        e6 = np.zeros((3, 6)) if rec.get("e") is None else np.asarray(rec["e"], dtype=float)
        e = rotate3(piezo_voigt_to_tensor(e6), R)
        eps = rotate2(np.asarray(rec["eps_r"], dtype=float) * EPS0, R)
    return Layer(name=str(rec["name"]), A=A, rho=float(rec["rho"]), e=e, eps=eps, thickness=thickness, sigma=sigma)


def _euler_axes(euler, where: str) -> np.ndarray:
    """Lab axes (3, 3) of SAW Euler angles (degrees), checked by :func:`surfwave.validate.euler_angles`."""
    with _at(where):
        a = validate.euler_angles(euler)
        if a.shape != (3,):
            raise InputError(f"euler must be three angles (phi, theta, psi) in degrees, got shape {a.shape}")
    return np.asarray(euler_lab_axes(a), dtype=float)


@functools.lru_cache(maxsize=1)
def _default_film_axes() -> np.ndarray:
    """Lab axes of a film without Euler angles (crystal axes = lab axes), remembered (read-only)."""
    R = np.asarray(euler_lab_axes(0, 0, 0), dtype=float)
    R.setflags(write=False)
    return R


@functools.lru_cache(maxsize=64)
def _named_axes(surface: str, direction: str) -> np.ndarray:
    """:func:`lab_axes` of a named surface and direction, remembered (read-only; errors are not cached)."""
    R = np.asarray(lab_axes(surface, direction), float)
    R.setflags(write=False)
    return R


def _substrate_axes(euler, surface: str, direction) -> tuple[np.ndarray, str]:
    """Lab axes (3, 3) of the substrate and its surface in words (as :func:`surfwave.material` names it)."""
    if euler is not None:
        return _euler_axes(euler, "substrate"), "of the Euler angles"
    with _at("substrate"):
        if isinstance(surface, str) and isinstance(direction, str):
            R = _named_axes(surface, direction).copy()
        else:
            which = direction if isinstance(direction, str) else validate.angle_values(direction, "direction")
            R = np.asarray(lab_axes(surface, which), float)
    if R.ndim != 2:
        raise InputError(f"substrate: one propagation direction at a time, got {direction!r}")
    return R, str(surface)


def _thickness(value, where: str) -> float:
    if value is None:
        raise InputError(f"{where}: the thickness (m) is missing")
    t = _number(value, f"{where} thickness (m)")
    if t < 0:
        raise InputError(f"{where}: the thickness must be >= 0 m, got {t!r}")
    if t > MAX_THICKNESS:
        raise InputError(f"{where}: thickness {t!r} m is thicker than {MAX_THICKNESS:g} m; film thicknesses are "
                         "in metres (1 um = 1e-6)")
    return t


def resolve_stack(substrate, films: Sequence = (), *, euler=None, surface: str = "(001)", direction="[100]",
                  stress=None) -> Stack:
    """Check and resolve a substrate and films into lab-frame tensors (no computation of waves).

    Parameters
    ----------
    substrate : str or mapping
        A material name (elastic, piezoelectric or film database), or a mapping
        ``{voigt (6, 6) GPa, rho[, piezo (3, 6) C/m^2, permittivity (3, 3) relative]}`` or
        ``{E (GPa), nu, rho}``, crystal axes.
    films : sequence of str or mapping
        From the top down. Each: a material as for ``substrate`` (``name`` or ``material`` for a
        database entry) plus ``thickness`` (m), optional ``euler`` (SAW Euler angles of the film's
        crystal axes, degrees; default (0, 0, 0)) and ``stress`` (GPa; scalar: equibiaxial in the
        surface plane; 3 x 3: SAW frame x1 propagation, x2 in-plane, x3 outward normal) and, in a
        piezoelectric stack, ``electrode_below`` (a grounded electrode on the interface under it).
    euler : array_like, shape (3,), optional
        SAW Euler angles of the substrate (wins over ``surface`` and ``direction``).
    surface, direction : str
        Substrate surface "(hkl)" and propagation direction "[uvw]" or angle (degrees).
    stress : float or array_like (3, 3), optional
        Substrate prestress, as for a film.

    Returns
    -------
    Stack

    Raises
    ------
    InputError
        Unknown names or keys, bad thicknesses (negative, non-finite, above :data:`MAX_THICKNESS`),
        nu outside (-1, 0.5), a stiffness not positive definite, constants or stresses in Pa,
        a stress that loads the surface or an interface, missing permittivities in a
        piezoelectric stack. One line, before anything is computed.
    """
    if isinstance(films, (str, Mapping)):
        films = [films]
    if not isinstance(films, Sequence):
        raise InputError(f"films must be a list of mappings (top film first), got {films!r}")
    R_sub, plane = _substrate_axes(euler, surface, direction)    # orientation, constants, stress: material()'s order
    sub = _material(substrate, "substrate", film=False)
    if isinstance(substrate, Mapping) and "thickness" in substrate:
        raise InputError("the substrate is semi-infinite: do not give it a thickness")
    s_sub = _stress(stress, "substrate", plane)
    recs = []
    for i, f in enumerate(films):
        where = f"film {i} (from the top)"
        if isinstance(f, str):
            raise InputError(f"{where}: give a mapping with a thickness, e.g. {{'name': {f!r}, 'thickness': 1e-6}}")
        if not isinstance(f, Mapping):
            raise InputError(f"{where} must be a mapping (a material and its thickness), got {f!r}")
        R = _euler_axes(f["euler"], where) if f.get("euler") is not None else _default_film_axes().copy()
        rec = _material(f, where)
        t = _thickness(f.get("thickness"), where)
        sig = _stress(f.get("stress"), where, "of the film and its interfaces")
        recs.append((rec, R, t, sig, where, f.get("electrode_below", False)))
    piezo = sub.get("e") is not None or any(r[0].get("e") is not None for r in recs)
    for r in recs:
        if not isinstance(r[5], (bool, np.bool_)):
            raise InputError(f"{r[4]}: electrode_below must be True or False, got {r[5]!r}")
        if r[5] and not piezo:
            raise InputError(f"{r[4]}: electrode_below needs a piezoelectric layer or substrate")
    layers = tuple(replace(_layer(*r[:4], piezo, r[4]), electrode_below=bool(r[5])) for r in recs)
    return Stack(substrate=_layer(sub, R_sub, 0.0, s_sub, piezo, "substrate"), films=layers, piezo=piezo)
