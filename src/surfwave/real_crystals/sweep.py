"""Surface waves of real crystals over a whole scene: materials x surfaces x angles, optionally
x loading x TOEC model x stress, in one labelled cube (``surface_wave.nc``).

Frames and units (docs/physics/general-solver.md): the lab frame of a surface has x1 along
the propagation direction, x2 along the inward surface normal and x3 = x1 x x2; ``angle`` is
measured in degrees from the surface's reference direction toward n x reference
(:mod:`surfwave.solvers.orientation`). Elastic constants and stresses are in GPa, densities
in kg/m^3, speeds in m/s.

Every applied stress lies in the surface plane (sigma . n = 0), so the free surface stays
traction-free at the prestressed state; loadings:

- ``along``: uniaxial sigma x1 x1 (along the propagation direction, turns with the angle);
- ``across``: uniaxial sigma x3 x3 (in-plane, perpendicular to the propagation);
- ``biaxial``: sigma (x1 x1 + x3 x3), equal in-plane biaxial stress;
- ``axis_<hkl>``: uniaxial along a fixed crystal direction lying in the surface
  (``axis_100``, ``axis_1-10``), the same for every angle.

With ``toec=False`` the second-order constants stay those of the natural state and the
stress enters only through the wave-propagation tensor A = C + sigma (the paper's Eq. A11
model); with ``toec=True`` the constants and the density are those of the stressed state,
from the third-order constants (:func:`surfwave.real_crystals.toec.stressed_state`).

Examples
--------
>>> from surfwave.real_crystals.materials import get_material
>>> ds = surface_wave_sweep([get_material("Cu")], ["(001)"], [0.0])   # doctest: +SKIP
>>> round(float(ds.c_R.sel(material="Cu", surface="(001)", angle=0.0)), 2)   # doctest: +SKIP
2012.12
"""
from __future__ import annotations

import itertools
from functools import partial
from typing import TYPE_CHECKING, NamedTuple, Sequence

import numpy as np

from surfwave.case import Case, make_case, solve
from surfwave.data.progress import solve_in_chunks
from surfwave.data.variables import CUBES, SURFACE_WAVE_COORDS
from surfwave.errors import InputError
from surfwave.real_crystals.loads import LOADINGS, axis_of_loading, stress_tensor
from surfwave.real_crystals.stressed_wave import BULK_KEYS, Constants
from surfwave.solvers.bulk_waves import BULK_POLARISATIONS
from surfwave.solvers.tensors import rotate4, voigt_to_tensor
from surfwave.validate import as_1d

if TYPE_CHECKING:  # xarray only for the Dataset builder: scene checks at workflow parse stay light
    import xarray as xr

__all__ = ["LOADINGS", "SceneGrid", "applied_stress", "axis_of_loading", "scene_cases", "surface_wave_sweep",
           "symmetry_reduced_range"]

#: Names of the three displacement components of the polarisation (lab frame).
COMPONENTS = ("u1", "u2", "u3")
#: Metadata of the trailing dimension of the bulk waves' polarisations (both real-crystal cubes).
BULK_COMPONENT = {"long_name": "lab-frame displacement component of a bulk wave (u1 along the propagation x1, "
                  "u2 along the inward normal x2, u3 = x1 x x2)"}
#: Trailing dimension of the vector variables.
TRAILING = {"polarisation": "component", "decay": "partial_wave",
            **{key: "bulk_component" for key in BULK_POLARISATIONS}}

#: The ``method`` attribute of the cube.
METHOD = ("general anisotropic surface-wave solver (Stroh formalism, surfwave.solvers.stroh) on "
          "A_ijkl = C_ijkl + sigma_jl delta_ik in the lab frame of each surface and angle; "
          "stressed-state constants and density from third-order constants where toec is true "
          "(surfwave.real_crystals.toec), natural-state constants otherwise; leaky SAW radiating into the "
          "slowest bulk sheet (surfwave.solvers.leaky) at every point")

#: The ``units_note`` attribute of the cube (SI, unlike the model-lattice cubes).
UNITS_NOTE = "SI units: speeds in m/s, stresses in GPa, densities in kg/m^3, angles in degrees"

#: Metadata of the cube's variables and coordinates: the one table, surfwave.data.variables.
VARIABLES = CUBES["surface_wave"]
COORDS = SURFACE_WAVE_COORDS


# --------------------------------------------------------------------------- symmetry


def _candidate_operations() -> np.ndarray:
    """Point operations to test against a stiffness: m-3m (cube axes) and 6/mmm (c along x3).

    Returns
    -------
    ndarray, shape (72, 3, 3)
    """
    ops = []
    for perm in itertools.permutations(range(3)):
        for signs in itertools.product((1.0, -1.0), repeat=3):
            R = np.zeros((3, 3))
            R[np.arange(3), perm] = signs
            ops.append(R)
    for k in range(6):
        c, s = np.cos(k * np.pi / 3), np.sin(k * np.pi / 3)
        rot = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
        for m in (np.eye(3), np.diag([1.0, -1.0, 1.0])):
            for inv in (1.0, -1.0):
                ops.append(inv * rot @ m)
    return np.array(ops)


def stiffness_symmetry(voigt) -> np.ndarray:
    """The candidate point operations that leave a stiffness unchanged.

    Parameters
    ----------
    voigt : array_like, shape (6, 6)
        Stiffness in crystal axes (any units).

    Returns
    -------
    ndarray, shape (n_ops, 3, 3)
        Orthogonal matrices R with R C R^T = C (m-3m and 6/mmm candidates only).
    """
    C = voigt_to_tensor(voigt)
    ops = _candidate_operations()
    rotated = rotate4(C[None], ops)
    scale = np.abs(C).max()
    keep = np.all(np.abs(rotated - C) <= 1e-9 * scale, axis=(1, 2, 3, 4))
    return ops[keep]


def symmetry_reduced_range(surface: str, voigts: Sequence) -> float:
    """Width (degrees) of the propagation-angle range that every other angle maps onto.

    The elastic point group of each crystal (found by testing m-3m and 6/mmm operations on
    its stiffness) restricted to operations that keep the surface normal (or reverse it: the
    stiffness is centrosymmetric), together with the reversal k -> -k (a wave and its reverse
    have the same speed), acts on the in-plane propagation directions as a set of mirror
    lines; with N lines in [0, 180) degrees the speeds repeat with mirror symmetry every
    180/N degrees. The reference direction lies on a mirror line for the low-index cubic
    surfaces, so the reduced range is [0, 180/N]: 45 for cubic (001), 90 for (110), 30 for
    (111). With unequally spaced lines (a transversely isotropic stiffness passes both the
    4- and the 6-fold tests) the smallest gap is returned, still a range every angle maps
    into; 180 when the reference direction is on no mirror line.

    Parameters
    ----------
    surface : str
        Miller indices, e.g. ``"(111)"``.
    voigts : sequence of array_like, shape (6, 6)
        Stiffnesses of the crystals concerned: the result is the widest of their ranges.

    Returns
    -------
    float
        Degrees (180 when the crystal has no in-plane symmetry besides k -> -k).
    """
    from surfwave.solvers import orientation

    axes = np.asarray(orientation.lab_axes(surface, 0.0), dtype=float).reshape(3, 3)
    e1, n, e3 = axes
    width = 0.0
    for voigt in voigts:
        R = stiffness_symmetry(voigt)  # (m, 3, 3)
        keeps_normal = np.abs(np.abs(R @ n @ n) - 1.0) <= 1e-9  # R n = +-n
        # the action on the in-plane directions (e1, e3)
        M = np.einsum("i,mij,j->m", e1, R, e1), np.einsum("i,mij,j->m", e1, R, e3), \
            np.einsum("i,mij,j->m", e3, R, e1), np.einsum("i,mij,j->m", e3, R, e3)
        # in-plane rotations (det > 0) have no mirror line; a reflection about the line at
        # angle phi is M = [[cos 2phi, sin 2phi], [sin 2phi, -cos 2phi]]
        reflect = keeps_normal & (M[0] * M[3] - M[1] * M[2] < 0)
        phi = 0.5 * np.degrees(np.arctan2(M[2][reflect], M[0][reflect]))
        both = np.concatenate([phi, phi + 90.0])  # -M is a reflection too (k -> -k)
        lines = set((np.round(both % 180.0, 6) % 180.0).tolist())
        ordered = np.sort(np.array(sorted(lines)))
        if ordered.size == 0 or ordered[0] > 1e-6:  # reference not on a mirror line
            return 180.0
        # Equally spaced lines (a finite group): the spacing. More lines (a transversely
        # isotropic stiffness has both 4- and 6-fold lines): the smallest gap, a safe range.
        gaps = np.diff(np.append(ordered, 180.0))
        width = max(width, float(gaps.min()))
    return width


# --------------------------------------------------------------------------- stress


def applied_stress(loading: str, axes, stress) -> np.ndarray:
    """Applied stress tensors in crystal axes
    (:func:`surfwave.real_crystals.loads.stress_tensor`).

    Parameters
    ----------
    loading : str
        ``along``, ``across``, ``biaxial`` or ``axis_<hkl>``.
    axes : array_like, shape (n_angle, 3, 3)
        Lab axes (rows x1, x2 = inward normal, x3) in crystal axes.
    stress : array_like, shape (n_stress,)
        Stress magnitudes, GPa.

    Returns
    -------
    ndarray, shape (n_angle, n_stress, 3, 3)
        sigma_ij in crystal axes, GPa; sigma . n = 0 for every entry.

    Raises
    ------
    InputError
        An ``axis_<hkl>`` loading whose axis is not in the surface plane.
    """
    return stress_tensor(loading, np.asarray(stress, dtype=float), np.asarray(axes, dtype=float))


# --------------------------------------------------------------------------- the cube


def surface_wave_sweep(
    materials: Sequence[str],
    surfaces: Sequence[str],
    angles,
    stress=None,
    loadings: Sequence[str] = ("along",),
    toec: Sequence[bool] = (False,),
    directions: Sequence[str] | None = None,
    tol: float | None = None,
    leaky: bool | None = True,
) -> xr.Dataset:
    """Surface waves of real crystals over a scene's whole grid, as one labelled cube.

    Parameters
    ----------
    materials : sequence of Material
        Records of :mod:`surfwave.real_crystals.materials` (``get_material(name)``) or any objects
        with ``name``, ``voigt`` (GPa), ``rho`` (kg/m^3) and ``toec`` (None or GPa): the
        caller looks the names up, so the physics does not depend on the database.
    surfaces : sequence of str
        Surface planes, e.g. ``["(001)", "(110)"]``.
    angles : array_like, shape (n_angle,)
        Propagation angles in degrees (the same for every surface).
    stress : array_like, shape (n_stress,), optional
        Applied stress magnitudes in GPa. None: unstressed, and the cube has no loading,
        toec and stress dims.
    loadings : sequence of str
        Stress kinds (see the module docstring); used only with ``stress``.
    toec : sequence of bool
        Models of the stressed state: False = fixed second-order constants, True = from the
        third-order constants (the material needs them); used only with ``stress``.
    directions : sequence of str, optional
        Miller labels of the angles (same length), stored as a ``direction`` coordinate.
    tol : float, optional
        Relative speed tolerance passed to the solver (its default when None).
    leaky : bool or None
        Where the leaky wave is solved (:func:`surfwave.real_crystals.stressed_wave.surface_wave`):
        True (default) at every point, so that the cube holds the whole leaky branch (also
        where it coexists with the subsonic wave); None only where no subsonic wave exists;
        False nowhere.

    Returns
    -------
    xarray.Dataset
        Dims (material, surface, angle) or (material, surface, angle, loading, toec, stress)
        for ``c_R``, ``c_R_imag``, ``c_limit`` (m/s), ``wave_type``, ``reason``,
        ``penetration_depth`` (wavelengths), ``rho`` (kg/m^3), and the same plus a trailing
        ``component`` (u1, u2, u3) for the complex ``polarisation`` (written to netCDF as real
        and imaginary parts by :func:`surfwave.data.cube.write`), ``c_leaky`` (m/s),
        ``leaky_attenuation`` (dB per wavelength) and ``leaky_reason`` (the leaky wave radiating
        into the slowest bulk sheet, NaN + reason where none), plus ``symmetric_range``
        (material, surface) in degrees.
        Every variable and coordinate has ``long_name`` (and ``units`` when numeric). No
        global attributes: the workflow adds provenance.

    Raises
    ------
    InputError
        Unknown surfaces, an ``axis_<hkl>`` loading outside a surface, or
        ``toec=True`` for a material without third-order constants.
    """
    grid = scene_cases(materials, surfaces, angles, stress, loadings, toec, tol=tol, leaky=leaky)
    mats, (nsf, na, nl, ns) = grid.materials, grid.sub
    shape = (len(mats), nsf, na, nl, len(grid.models), ns)
    keys = ("c_R", "c_R_imag", "c_limit", "penetration_depth", "rho", "polarisation", "decay", "wave_type",
            "reason", "c_leaky", "leaky_attenuation", "leaky_reason", "grazing") + BULK_KEYS
    out: dict = {}
    for im, mat in enumerate(mats):
        for it, use in enumerate(grid.models):
            # every value comes from this material and model's own solve (NaN where no state)
            case = grid.cases[im][it]
            res = solve_in_chunks(partial(_solve_points, case), case.size,
                                  f"surface_wave, {mat.name}" + (", toec" if use else ""))
            for name in keys:
                arr = res[name].reshape(grid.sub + res[name].shape[1:])
                if name not in out:
                    out[name] = np.empty(shape + arr.shape[len(grid.sub):], dtype=arr.dtype)
                out[name][im, :, :, :, it, :] = arr
    ds = _dataset(out, [m.name for m in mats], list(surfaces), grid.angles, grid.loadings, grid.models, grid.stress,
                  grid.stressed, directions)
    width = [[symmetry_reduced_range(sf, [m.voigt]) for sf in surfaces] for m in mats]
    return ds.assign(symmetric_range=(("material", "surface"), np.array(width),
                                      VARIABLES["symmetric_range"]))


class SceneGrid(NamedTuple):
    """The checked cases of a real-crystal scene (:func:`scene_cases`).

    ``cases[i][j]``: material i, model j, points in the order (surface, angle, loading, stress),
    whose sizes are ``sub``.
    """

    materials: list
    angles: np.ndarray
    loadings: list[str]
    models: list[bool]
    stress: np.ndarray
    stressed: bool
    sub: tuple[int, int, int, int]
    cases: list[list[Case]]


def scene_cases(materials: Sequence, surfaces: Sequence[str], angles, stress=None,
                loadings: Sequence[str] = ("along",), toec: Sequence[bool] = (False,), *, tol: float | None = None,
                leaky: bool | None = True) -> SceneGrid:
    """Every point of a real-crystal scene as checked cases (:func:`surfwave.case.make_case`), one per
    material and model: what :func:`surface_wave_sweep` solves and the scene check validates.

    Parameters
    ----------
    materials, surfaces, angles, stress, loadings, toec, tol, leaky
        As :func:`surface_wave_sweep`.

    Raises
    ------
    InputError
        Unknown surfaces, an ``axis_<hkl>`` loading outside a surface, ``toec`` true for a
        material without third-order constants, and every refusal of
        :func:`surfwave.case.make_case` (constants, density, the stress in GPa, sigma . n = 0).
    """
    from surfwave.solvers import orientation

    mats = list(materials)
    angles = as_1d(angles, "angles")
    stressed = stress is not None
    s = as_1d(stress if stressed else [0.0], "stress")
    loads = list(loadings) if stressed else ["along"]
    models = [bool(t) for t in toec] if stressed else [False]
    for m in mats:
        if any(models) and m.toec is None:
            raise InputError(f"material {m.name!r} has no third-order elastic constants "
                             "(toec: true needs C111, C112, C123, C144, C155, C456)")
    axes = np.stack([np.asarray(orientation.lab_axes(sf, angles), dtype=float).reshape(-1, 3, 3)
                     for sf in surfaces])                                # (nsf, na, 3, 3)
    nsf, na = axes.shape[:2]
    # Applied stress in crystal axes at every (surface, angle, loading, stress): (nsf*na, nl, ns, 3, 3)
    flat_axes = axes.reshape(nsf * na, 3, 3)
    sig = np.stack([applied_stress(ld, flat_axes, s) for ld in loads], axis=1)
    point_axes = np.broadcast_to(flat_axes[:, None, None], sig.shape).reshape(-1, 3, 3)
    sig = sig.reshape(-1, 3, 3)
    where = " ".join(surfaces)
    cases = [[make_case(Constants.from_material(m), point_axes, sig, toec=use, tol=tol, leaky=leaky, where=where)
              for use in models] for m in mats]
    return SceneGrid(mats, angles, loads, models, s, stressed, (nsf, na, len(loads), len(s)), cases)


def _solve_points(case: Case, start: int, stop: int) -> dict:
    """The one path on the points ``start:stop`` of a case (one chunk of the sweep)."""
    return solve(case, start, stop, bulk=False)[None]


def _dataset(out, materials, surfaces, angles, loads, models, s, stressed, directions) -> xr.Dataset:
    """Label the arrays of :func:`surface_wave_sweep` (drop the stress dims when unstressed)."""
    dims = ("material", "surface", "angle", "loading", "toec", "stress")
    data_vars = {}
    for name, arr in out.items():
        vdims = dims + ((TRAILING.get(name, "component"),) if arr.ndim == len(dims) + 1 else ())
        if arr.dtype == object:
            arr = arr.astype(str)
        data_vars[name] = (vdims, arr, dict(VARIABLES[name]))
    coords = {
        "material": ("material", np.asarray(materials, dtype=str), COORDS["material"]),
        "surface": ("surface", np.asarray(surfaces, dtype=str), COORDS["surface"]),
        "angle": ("angle", angles, COORDS["angle"]),
        "loading": ("loading", np.asarray(loads, dtype=str), COORDS["loading"]),
        "toec": ("toec", np.asarray(models, dtype=bool), COORDS["toec"]),
        "stress": ("stress", s, COORDS["stress"]),
        "component": ("component", np.asarray(COMPONENTS), {"long_name": "lab-frame displacement "
                      "component (u1 along the propagation, u2 along the inward normal)"}),
        "partial_wave": ("partial_wave", np.arange(1, 4), {"long_name": "partial wave of the Stroh "
                         "solution (1 = fastest decaying)", "units": "1"}),
        "bulk_component": ("bulk_component", np.asarray(COMPONENTS), BULK_COMPONENT),
    }
    import xarray as xr

    ds = xr.Dataset(data_vars, coords=coords)
    if directions is not None:
        ds = ds.assign_coords(direction=("angle", np.asarray(directions, dtype=str), COORDS["direction"]))
    if not stressed:
        ds = ds.isel(loading=0, toec=0, stress=0, drop=True)
    return ds
