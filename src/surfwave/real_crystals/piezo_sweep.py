"""Surface waves of piezoelectric crystals over a whole scene, one labelled cube (``surface_wave.nc``).

Grid: materials x (named cuts | Euler angles phi x theta x psi) x electrical condition
[x toec x stress]. The cube keeps the public layout of ``surface_wave.nc`` (dims ``material``,
``surface``, ``angle``): a surface is a plate (a named cut, or one Euler pair (phi, theta)),
the angle the propagation direction psi in it from the plate's reference psi0; coordinates
``cut``, ``euler_phi``, ``euler_theta`` (per surface) and ``euler_psi`` (surface, angle) say
which Euler angles each point has (:func:`surfwave.data.cube.open_cube` indexes ``euler_phi``,
``euler_theta`` and ``cut``, so ``ds.sel(euler_theta=38.0)`` selects by them). Each point
is :func:`surfwave.real_crystals.piezo_wave.piezo_wave`, i.e. the one real-crystal
path :func:`surfwave.real_crystals.stressed_wave.surface_wave` (uniaxial stress along the
propagation x1; prestress model per ``toec`` coordinate: fixed constants,
:data:`surfwave.real_crystals.piezo_wave.MODEL`, or the stressed state from third-order
constants, :data:`~surfwave.real_crystals.piezo_wave.MODEL_TOEC`; e and eps at natural values
in both; a point without a Born-stable stressed state is NaN with the reason that
:func:`surfwave.material` gives).

Examples
--------
>>> ds = piezo_wave_sweep(["LiNbO3-Warner1967"], cuts=["Y-Z LiNbO3"])   # doctest: +SKIP
>>> round(float(ds.c_R.sel(electrical="free").squeeze()))               # doctest: +SKIP
3488
"""
from __future__ import annotations

from functools import partial
from typing import TYPE_CHECKING, Any, NamedTuple, Sequence

import numpy as np

from surfwave import validate
from surfwave.case import Case, make_case, solve
from surfwave.data.progress import solve_in_chunks
from surfwave.data.variables import CUBES, PIEZO_WAVE_COORDS
from surfwave.errors import InputError
from surfwave.real_crystals.piezo_materials import note_status
from surfwave.real_crystals.stressed_wave import BULK_KEYS
from surfwave.real_crystals.sweep import BULK_COMPONENT
from surfwave.solvers.bulk_waves import BULK_POLARISATIONS
from surfwave.vocab import ELECTRICAL

if TYPE_CHECKING:
    import xarray as xr

#: The ``method`` attribute of the cube.
METHOD = ("piezoelectric Stroh solver (8 x 8, surfwave.solvers.piezo) for the subsonic SAW with a free "
          "(open-circuit) and a metallized surface, leaky SAW radiating into the slowest bulk sheet "
          "(surfwave.solvers.leaky); A_ijkl = C_ijkl + sigma_jl delta_ik with the natural-state C^E (toec "
          "false) or the stressed-state constants and density from third-order constants (toec true, "
          "surfwave.real_crystals.toec), piezoelectric constants e and clamped permittivity eps at their "
          "natural values; SAW Euler "
          "angles (ZXZ) -> lab frame x1 propagation, x2 inward normal (surfwave.solvers.euler)")
UNITS_NOTE = ("SI units: speeds in m/s, stresses in GPa, angles in degrees, attenuation in dB per "
              "wavelength, potential in V per m of surface displacement")
#: Components of the generalised polarisation.
COMPONENTS = ("u1", "u2", "u3", "phi")

#: Metadata of the cube's variables and coordinates: the one table, surfwave.data.variables.
VARIABLES = CUBES["piezo_wave"]
COORDS = PIEZO_WAVE_COORDS
#: Per-point variables (material, orientation, [stress]) that do not depend on the electrical condition.
NO_ELECTRICAL = ("K2", "c_limit", "rho", "K2_leaky", "c_leaky_free", "c_leaky_metallized") + BULK_KEYS


def _orientations(cuts, euler) -> tuple[np.ndarray, dict, tuple[int, int]]:
    """Euler angles (n_surface * n_angle, 3), surface/angle coords, (n_surface, n_angle).

    The public cube layout has dims ``surface`` and ``angle`` (docs/cubes.md): a surface is a
    plate, Euler (phi, theta), and the angle is the propagation direction psi in it, measured
    from the surface's reference psi0 (a named cut's own psi, else 0): psi = psi0 + angle.
    """
    from surfwave.real_crystals.piezo_materials import get_cut

    if (cuts is None) == (euler is None):
        raise InputError("give either cuts or euler angles")
    if cuts is not None:
        found = [get_cut(c) for c in cuts]
        e = np.array([c.euler for c in found], dtype=float)
        angle = np.array([0.0])
        coords: dict[str, Any] = {"surface": [c.name for c in found], "cut": [c.name for c in found]}
    else:
        phi, theta, angle = (np.atleast_1d(np.asarray(euler[k], dtype=float)) for k in ("phi", "theta", "psi"))
        pt = np.stack(np.meshgrid(phi, theta, indexing="ij"), axis=-1).reshape(-1, 2)
        e = np.column_stack([pt, np.zeros(len(pt))])
        coords = {"surface": [f"Euler ({p:g}, {t:g})" for p, t in pt]}
    coords.update(euler_phi=e[:, 0], euler_theta=e[:, 1], psi0=e[:, 2], angle=angle)
    full = np.repeat(e, angle.size, axis=0)
    full[:, 2] += np.tile(angle, len(e))
    return full, coords, (len(e), angle.size)


def piezo_wave_sweep(materials: Sequence[str], *, cuts: Sequence[str] | None = None, euler: dict | None = None,
                     electrical: Sequence[str] = ELECTRICAL, stress: Sequence[float] | None = None,
                     toec: Sequence[bool] = (False,), toec_constants=None, tol: float = 1e-12) -> xr.Dataset:
    """SAW, K^2, leaky wave and power flow of piezoelectric crystals over a scene's grid.

    Parameters
    ----------
    materials : sequence of str
        Piezoelectric database names.
    cuts : sequence of str, optional
        Named cuts (their Euler angles are applied to every material).
    euler : dict, optional
        ``{"phi": ..., "theta": ..., "psi": ...}``, each a number or a 1-D sequence, degrees
        (the grid is their product). Exactly one of ``cuts`` and ``euler``.
    electrical : sequence of {"free", "metallized"}
    stress : sequence of float, optional
        Uniaxial stress along the propagation, GPa; None: unstressed, no ``toec`` and
        ``stress`` dims.
    toec : sequence of bool
        Models of the stressed state (as :func:`surfwave.real_crystals.sweep.surface_wave_sweep`):
        False = fixed constants, True = stressed state from the third-order constants (the
        material's own set, GaAs, or ``toec_constants``); used only with ``stress``.
    toec_constants : mapping or array_like, optional
        The caller's third-order constants for every material (GPa): a mapping of the class's
        named constants (:data:`surfwave.real_crystals.toec_classes.TOEC_NAMES`, a ``source``
        key allowed) or a (6, 6, 6) Voigt array, checked as ``surfwave.material(..., toec=...)``
        checks it (:func:`surfwave.real_crystals.piezo_materials.with_toec`).
    tol : float
        Relative accuracy of rho c^2.

    Returns
    -------
    xarray.Dataset
        Dims ``material``, ``surface``, ``angle``, ``electrical``, [``toec``, ``stress``] (coordinates
        ``cut``, ``euler_phi``, ``euler_theta``, ``euler_psi``; module docstring), with
        ``component`` (u1, u2, u3, phi) for
        ``polarisation`` and ``partial_wave`` (1..4) for ``decay``; variables of
        :data:`VARIABLES` (``K2``, ``c_limit`` and ``rho`` without ``electrical``).

    Raises
    ------
    InputError
        ``toec`` true for a material without third-order constants (and no ``toec_constants``),
        or ``toec_constants`` not a valid set for a material's class.
    """
    g = scene_cases(materials, cuts=cuts, euler=euler, electrical=electrical, stress=stress, toec=toec,
                    toec_constants=toec_constants, tol=tol)
    mats, models, el = g.materials, g.models, g.electrical
    out: dict[str, np.ndarray] = {}
    for i, m in enumerate(mats):
        note_status(m)                                                  # one line for an unverified set
        for t, use in enumerate(models):
            case = g.cases[i][t]
            rs = solve_in_chunks(partial(_solve_case, case), case.size,
                                 f"piezo_wave, {m.name}" + (", toec" if use else ""))
            for j, cond in enumerate(el):                               # both conditions from one solve
                r = rs[cond]
                for key in VARIABLES:
                    v = np.asarray(r[key])
                    if key not in out:
                        out[key] = np.empty((len(mats), len(el), len(models)) + v.shape, dtype=v.dtype)
                    out[key][i, j, t] = v
    return _dataset(out, g, stressed=stress is not None)


def _dataset(out: dict[str, np.ndarray], g: PiezoSceneGrid, stressed: bool) -> xr.Dataset:
    """Label the arrays of :func:`piezo_wave_sweep` (``out[key]``: (material, electrical, toec, point, ...))
    as the cube; without a stress grid the ``toec`` and ``stress`` dims are dropped."""
    import xarray as xr

    mats, models, el, oc, oshape, s = g.materials, g.models, g.electrical, g.coords, g.shape, g.stress
    grid = (len(mats), len(el), len(models)) + oshape + (s.size,)
    dims = ("material", "electrical", "toec", "surface", "angle", "stress")
    data_vars = {}
    for key, arr in out.items():
        trailing = arr.shape[4:]
        arr = arr.reshape(grid + trailing)
        vdims = dims + (("component",) if key == "polarisation" else ("partial_wave",) if key == "decay"
                        else ("bulk_component",) if key in BULK_POLARISATIONS else ())
        if key in NO_ELECTRICAL:
            arr, vdims = arr[:, 0], tuple(d for d in vdims if d != "electrical")
        if arr.dtype == object:
            arr = arr.astype(str)
        data_vars[key] = (vdims, arr, dict(VARIABLES[key]))
    coords: dict[str, Any] = {"material": ("material", np.array([m.name for m in mats], dtype=str), COORDS["material"]),
              "electrical": ("electrical", np.array(el, dtype=str), COORDS["electrical"]),
              "toec": ("toec", np.asarray(models, dtype=bool), COORDS["toec"]),
              "stress": ("stress", s, COORDS["stress"]),
              "component": ("component", np.array(COMPONENTS), {"long_name": "u1 along the propagation, u2 "
                            "along the inward normal, u3 in plane; phi the electric potential"}),
              "partial_wave": ("partial_wave", np.arange(1, 5), {"long_name": "partial wave of the Stroh "
                               "solution (1 = fastest decaying)", "units": "1"}),
              "bulk_component": ("bulk_component", np.array(COMPONENTS[:3]), BULK_COMPONENT)}
    coords.update(surface=("surface", np.asarray(oc["surface"], dtype=str), COORDS["surface"]),
                  angle=("angle", oc["angle"], COORDS["angle"]),
                  euler_phi=("surface", oc["euler_phi"], COORDS["euler_phi"]),
                  euler_theta=("surface", oc["euler_theta"], COORDS["euler_theta"]),
                  euler_psi=(("surface", "angle"), oc["psi0"][:, None] + oc["angle"][None, :], COORDS["euler_psi"]))
    if "cut" in oc:
        coords["cut"] = ("surface", np.asarray(oc["cut"], dtype=str), COORDS["cut"])
    ds = xr.Dataset(data_vars, coords=coords).transpose("material", "surface", "angle", "electrical", "toec",
                                                        "stress", ...)
    if not stressed:
        ds = ds.isel(toec=0, stress=0, drop=True)
    return ds


def _with_toec(material, constants, needed: bool):
    """``material`` carrying ``constants`` (the caller's set, checked for its class) as its
    third-order set; InputError where a set is ``needed`` and there is none."""
    from surfwave.real_crystals.piezo_materials import with_toec

    if constants is not None:
        return with_toec(material, constants)
    if needed and material.toec_voigt is None:
        raise InputError(f"material {material.name!r} has no third-order elastic constants (toec: true needs "
                         f"a set: give toec_constants, the class-{material.crystal_class} names)")
    return material


def _solve_case(case: Case, start: int, stop: int) -> dict:
    """The one path on the points ``start:stop`` of a case (one chunk): condition -> dict."""
    return solve(case, start, stop, bulk=False)


class PiezoSceneGrid(NamedTuple):
    """The checked cases of a piezoelectric scene (:func:`scene_cases`).

    ``cases[i][j]``: material i, model j; points orientation-major (``shape`` = (n_surface,
    n_angle)), stress inner.
    """

    materials: list
    models: list[bool]
    electrical: list[str]
    coords: dict
    shape: tuple[int, int]
    stress: np.ndarray
    cases: list[list[Case]]


def scene_cases(materials: Sequence[str], *, cuts: Sequence[str] | None = None, euler: dict | None = None,
                electrical: Sequence[str] = ELECTRICAL, stress: Sequence[float] | None = None,
                toec: Sequence[bool] = (False,), toec_constants=None, tol: float = 1e-12) -> PiezoSceneGrid:
    """Every point of a piezoelectric scene as checked cases (:func:`surfwave.case.make_case`), one per
    material and model: what :func:`piezo_wave_sweep` solves and the scene check validates.

    Parameters
    ----------
    materials, cuts, euler, electrical, stress, toec, toec_constants, tol
        As :func:`piezo_wave_sweep`.

    Raises
    ------
    InputError
        Unknown names, repeated ``toec`` values, a missing or invalid third-order set, and
        every refusal of :func:`surfwave.case.make_case` (constants, density, the stress in
        GPa, sigma . n = 0, the electrical conditions, non-finite Euler angles).
    """
    from surfwave.real_crystals.piezo_materials import get_piezo_material
    from surfwave.real_crystals.stressed_wave import Constants, stress_tensor
    from surfwave.solvers.euler import euler_lab_axes

    angles, oc, oshape = _orientations(cuts, euler)
    if not np.all(np.isfinite(angles)):
        raise InputError(f"Euler angles must be finite, got {angles[~np.all(np.isfinite(angles), axis=1)][0].tolist()}")
    R0 = euler_lab_axes(angles).reshape(-1, 3, 3)
    s = np.array([0.0]) if stress is None else validate.gpa_stress(stress).reshape(-1)
    models = [bool(t) for t in toec] if stress is not None else [False]
    if len(set(models)) < len(models) or not models:
        raise InputError(f"toec must be distinct booleans, got {list(toec)!r}")
    n_o, n_s = R0.shape[0], s.size
    R = np.repeat(R0, n_s, axis=0)                                   # orientation-major, stress inner
    S = np.tile(s, n_o)
    sigma = stress_tensor("along", 1.0, R) * S[..., None, None]      # uniaxial along each x1
    mats = [_with_toec(get_piezo_material(m), toec_constants, any(models)) for m in materials]
    el = list(electrical)
    cases = [[make_case(Constants.from_piezo_material(m), R, sigma, electrical=tuple(el), toec=use, tol=tol,
                        leaky=True, where="of the Euler angles") for use in models] for m in mats]
    return PiezoSceneGrid(mats, models, el, oc, oshape, s, cases)


def scene_points(n_materials: int, cuts, euler, electrical, stress, toec=(False,)) -> int:
    """Number of solver points of a scene (for the grid cap), without building anything."""
    n_o = len(cuts) if cuts is not None else int(np.prod([np.size(euler[k]) for k in ("phi", "theta", "psi")]))
    return n_materials * n_o * len(electrical) * (len(stress) * len(toec) if stress else 1)


__all__ = ["COMPONENTS", "METHOD", "UNITS_NOTE", "VARIABLES", "PiezoSceneGrid", "piezo_wave_sweep", "scene_cases",
           "scene_points"]
