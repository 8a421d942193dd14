"""Stability map of prestressed FCC: long-wave against full-zone stability over a strain grid.

The long-wave criterion is the analytic acoustic tensor over all directions
(``surfwave.point(...)["stable"]``); the full-zone criterion is phonopy's
(:func:`surfwave.model_crystals.phonons.bulk_speeds`: zone mesh plus the long-wave limit of the force
constants). :func:`stability_map` returns the map as a Dataset (per strain: a state and both
flags; per case: the first instabilities and the end of the geometry); the workflow writes it
with :func:`surfwave.data.cube.write` and :mod:`surfwave.plots.stability` draws it.
"""

from __future__ import annotations

from typing import Any, Literal, Sequence

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from surfwave.model_crystals.phonons import DEFAULT_DISPLACEMENT, DEFAULT_SUPERCELL, DEFAULT_ZONE_MESH, TOLERANCE
from surfwave.model_crystals.potentials import PairPotential
from surfwave.model_crystals.stability import geometry_limit, instability_limits, stability_scan
from surfwave.vocab import Direction, Loading

#: Values of the ``state`` variable.
STATES = {-1: "no_geometry", 0: "long_wave_unstable", 1: "short_wave_unstable", 2: "stable"}
#: Default strain grid: covers every first instability found.
DEFAULT_GRID = np.round(np.arange(0.50, 1.4101, 0.01), 4)
#: The two stability criteria of the limits (dimension ``kind``), in this order.
_KINDS: tuple[Literal["long_wave", "full_zone"], ...] = ("long_wave", "full_zone")


def stability_map(
    potentials: Sequence[str | PairPotential] = ("harmonic", "lj"),
    loadings: Sequence[Loading] = ("in_plane_hydrostatic", "uniaxial"),
    directions: Sequence[Direction] = ("[100]", "[110]"),
    d_over_d0: ArrayLike | None = None,
    supercell: int = DEFAULT_SUPERCELL,
    displacement: float = DEFAULT_DISPLACEMENT,
    zone_mesh: int = DEFAULT_ZONE_MESH,
    tol: float = 1e-4,
) -> xr.Dataset:
    """FCC stability over a strain grid, and the first instabilities from d/d0 = 1.

    Parameters
    ----------
    potentials, loadings, directions : sequence of str
    d_over_d0 : array_like, shape (n,), optional
        Grid; default 0.50 ... 1.41 by 0.01 (covers every first instability found).
    supercell, displacement, zone_mesh
        Phonopy knobs.
    tol : float
        Bisection tolerance of the limits, in d/d0.

    Returns
    -------
    xarray.Dataset
        dims (potential, loading, direction, strain): ``state`` (int8, see flag_meanings),
        ``stable_long_wave``, ``stable_full_zone``, ``stable_zone_mesh`` (mesh alone),
        ``min_omega2`` (K/m), ``min_omega2_q`` (+ xyz, rad/d0), ``min_c2_phonopy``
        (K d0^2/m); dims (potential, loading, direction, kind, side): ``d_limit``, the first
        unstable d/d0 (NaN: none before the geometry ends); dims (..., side):
        ``d_geometry_limit``.
    """
    grid = DEFAULT_GRID if d_over_d0 is None else np.asarray(d_over_d0, float)
    knobs: dict[str, Any] = dict(supercell=supercell, displacement=displacement, zone_mesh=zone_mesh)
    shape = (len(potentials), len(loadings), len(directions))
    arrays = _empty_map(shape, grid.size)
    for idx in np.ndindex(shape):
        _fill_case(arrays, idx, potentials[idx[0]], loadings[idx[1]], directions[idx[2]], grid, knobs, tol)
    return _map_dataset(arrays, potentials, loadings, directions, grid, knobs, tol)


def _empty_map(shape: tuple[int, int, int], n: int) -> dict[str, np.ndarray]:
    """The map's arrays before any case is scanned (state -1, flags False, values NaN).

    Parameters
    ----------
    shape : tuple of int
        (potential, loading, direction) sizes.
    n : int
        Number of strain points.

    Returns
    -------
    dict of ndarray
        ``state`` (*shape, n) int8; ``stable_long_wave``, ``stable_full_zone``,
        ``stable_zone_mesh`` (*shape, n) bool; ``min_omega2`` (K/m) and ``min_c2_phonopy``
        (K d0^2/m) (*shape, n); ``min_omega2_q`` (*shape, n, 3) rad/d0; ``d_limit`` (*shape, 2
        kind, 2 side); ``d_geometry_limit`` (*shape, 2 side).
    """
    out: dict[str, np.ndarray] = {"state": np.full(shape + (n,), -1, np.int8)}
    out.update({k: np.full(shape + (n,), np.nan) for k in ("min_omega2", "min_c2_phonopy")})
    out.update({k: np.zeros(shape + (n,), bool) for k in ("stable_long_wave", "stable_full_zone", "stable_zone_mesh")})
    out["min_omega2_q"] = np.full(shape + (n, 3), np.nan)
    out["d_limit"] = np.full(shape + (2, 2), np.nan)
    out["d_geometry_limit"] = np.full(shape + (2,), np.nan)
    return out


def _fill_case(arrays: dict[str, np.ndarray], idx: tuple[int, ...], pot: str | PairPotential, load: Loading,
               d: Direction, grid: np.ndarray, knobs: dict[str, Any], tol: float) -> None:
    """Scan one (potential, loading, direction) case and write it into ``arrays`` at ``idx``.

    Parameters
    ----------
    arrays : dict of ndarray
        From :func:`_empty_map` (written in place).
    idx : tuple of int
        (potential, loading, direction) index of the case.
    pot, load, d
        The case.
    grid : ndarray, shape (n,)
        d/d0 values.
    knobs : dict
        Phonopy knobs (``supercell``, ``displacement``, ``zone_mesh``).
    tol : float
        Bisection tolerance of the limits, in d/d0.
    """
    scan = stability_scan("fcc", load, pot, d, grid, **knobs)
    built = np.array([("GeometryError" not in r) for r in scan["reason"]])
    arrays["stable_long_wave"][idx] = scan["stable_long_wave"]
    arrays["stable_full_zone"][idx] = scan["stable_full_zone"]
    arrays["stable_zone_mesh"][idx] = scan["min_omega2"] > -TOLERANCE
    arrays["min_omega2"][idx] = scan["min_omega2"]
    arrays["min_c2_phonopy"][idx] = scan["min_c2_phonopy"]
    arrays["min_omega2_q"][idx] = scan["min_omega2_q"]
    arrays["state"][idx] = np.where(
        ~built, -1, np.where(~scan["stable_long_wave"], 0, np.where(~scan["stable_full_zone"], 1, 2))
    )
    for k, kind in enumerate(_KINDS):
        arrays["d_limit"][idx + (k,)] = instability_limits(
            "fcc", load, pot, d, kind, tol=tol, **(knobs if k else {})
        )
    arrays["d_geometry_limit"][idx] = geometry_limit("fcc", load, pot, d, tol=tol)


def _map_dataset(arrays: dict[str, np.ndarray], potentials: Sequence[str | PairPotential],
                 loadings: Sequence[Loading], directions: Sequence[Direction], grid: np.ndarray,
                 knobs: dict[str, Any], tol: float) -> xr.Dataset:
    """Label the arrays of :func:`_empty_map` as the map's Dataset (CF attributes, coordinates).

    Parameters
    ----------
    arrays : dict of ndarray
        Filled by :func:`_fill_case` (shapes in :func:`_empty_map`).
    potentials, loadings, directions : sequence
        Coordinates of the first three dims.
    grid : ndarray, shape (n,)
        d/d0 values.
    knobs : dict
        Phonopy knobs, stored as attributes.
    tol : float
        Bisection tolerance of the limits, stored with ``d_limit``.

    Returns
    -------
    xarray.Dataset
        As :func:`stability_map`.
    """
    state, qmin, limits, geom = (arrays[k] for k in ("state", "min_omega2_q", "d_limit", "d_geometry_limit"))
    supercell, displacement, zone_mesh = knobs["supercell"], knobs["displacement"], knobs["zone_mesh"]
    dims = ("potential", "loading", "direction")
    ds = xr.Dataset(
        {
            "state": (
                dims + ("strain",),
                state,
                {
                    "long_name": "stability state",
                    "units": "1",
                    "flag_values": np.array(list(STATES), np.int8),
                    "flag_meanings": " ".join(STATES.values()),
                },
            ),
            "stable_long_wave": (
                dims + ("strain",),
                arrays["stable_long_wave"],
                {
                    "long_name": "acoustic tensor Q(n) positive for every direction n (analytic, Eq. A11)",
                    "units": "1",
                },
            ),
            "stable_full_zone": (
                dims + ("strain",),
                arrays["stable_full_zone"],
                {
                    "long_name": "no imaginary phonon frequency: zone mesh and long-wave limit (phonopy)",
                    "units": "1",
                },
            ),
            "stable_zone_mesh": (
                dims + ("strain",),
                arrays["stable_zone_mesh"],
                {
                    "long_name": "no imaginary phonon frequency on the zone mesh alone (Gamma excluded)",
                    "units": "1",
                },
            ),
            "min_omega2": (
                dims + ("strain",),
                arrays["min_omega2"],
                {"long_name": "lowest omega^2 on the zone mesh (refined when negative)", "units": "K / m"},
            ),
            "min_omega2_q": (
                dims + ("strain", "xyz"),
                qmin,
                {"long_name": "Cartesian lab-frame wave vector of min_omega2", "units": "rad / d0"},
            ),
            "min_c2_phonopy": (
                dims + ("strain",),
                arrays["min_c2_phonopy"],
                {
                    "long_name": "lowest acoustic-tensor eigenvalue over all directions (phonopy)",
                    "units": "K d0^2 / m",
                },
            ),
            "d_limit": (
                dims + ("kind", "side"),
                limits,
                {
                    "long_name": "first unstable d/d0 walking out from 1 (NaN: none before the geometry ends)",
                    "units": "1",
                    "tolerance": tol,
                },
            ),
            "d_geometry_limit": (
                dims + ("side",),
                geom,
                {
                    "long_name": "d/d0 where the prestressed geometry ceases to exist (NaN: beyond 0.3 / 2.0)",
                    "units": "1",
                },
            ),
        },
        coords={
            "potential": list(potentials),
            "loading": list(loadings),
            "direction": list(directions),
            "strain": ("strain", grid - 1.0, {"long_name": "strain d/d0 - 1", "units": "1"}),
            "d_over_d0": (
                "strain",
                grid,
                {"long_name": "stretch along the propagation direction", "units": "1"},
            ),
            "kind": ["long_wave", "full_zone"],
            "side": ["compression", "tension"],
            "xyz": ["x", "y", "z"],
        },
        attrs={
            "method": "long wave: analytic acoustic tensor; full zone: phonopy finite displacements",
            "supercell": supercell,
            "displacement": displacement,
            "zone_mesh": zone_mesh,
            "units_note": "reduced units d0 = K = m = 1",
        },
    )
    return ds
