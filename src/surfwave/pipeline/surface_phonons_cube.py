"""The ``surface_phonons`` cube of an FCC scene: surface phonons, soft modes and surface entropy.

One block per (potential, cut), a cut being a surface with, for uniaxial loading, one load
direction of the scene that lies in it ((001): [100], [110]; (111): [110]; (110): [110],
[100]). Per block :func:`surfwave.surface_phonons` along the surface's default path of
high-symmetry points (with the spectral density) and
:func:`surfwave.dynamics.fcc_surface_entropy.surface_entropy`; paths of different surfaces
have different lengths and are NaN-padded along ``q``.
"""
from __future__ import annotations

import json
from typing import Any

import numpy as np
import xarray as xr

from surfwave.data import cube
from surfwave.dynamics.fcc_layers import LOAD_DIRECTIONS
from surfwave.dynamics.fcc_surface_entropy import surface_entropy
from surfwave.dynamics.fcc_surface_phonons import DEFAULT_PATHS, surface_phonons

#: Variables: name -> (long_name, units, inner dims after strain).
VARIABLES: dict[str, tuple[str, str | None, tuple[str, ...]]] = {
    "omega": ("surface-mode angular frequency, sign(omega^2) sqrt|omega^2| (negative: imaginary, "
              "an unstable surface mode), ascending, NaN-padded", "sqrt(K/m)", ("q", "mode")),
    "decay": ("amplitude ratio of the surface mode between successive lattice planes", "1", ("q", "mode")),
    "polarisation": ("share of the top plane's |U|^2 along q (longitudinal), the inward normal and "
                     "q x n (shear horizontal)", "1", ("q", "mode", "component")),
    "sector": ("mirror sector: +1 sagittal (even), -1 shear horizontal (odd), 0 no mirror", "1", ("q", "mode")),
    "band_edges": ("projected bulk band: min and max over the normal wavevector of each bulk branch, "
                   "signed omega", "sqrt(K/m)", ("q", "branch", "edge")),
    "q_reduced": ("in-plane wavevector in reduced coordinates of the deformed surface reciprocal lattice",
                  "1", ("q", "axis2")),
    "q_distance": ("length along the path of high-symmetry points", "rad/d0", ("q",)),
    "spectral_density": ("spectral density of the top plane's displacements, -(2 omega/pi) Im Tr G_00, "
                         "integrating to 3 over omega", "(K/m)^-1/2", ("q", "frequency")),
    "lowest_omega2": ("omega^2 of the lowest surface mode at each q (NaN: none)", "K/m", ("q",)),
    "softest_omega2": ("lowest surface omega^2 along the path (negative: a soft surface mode)", "K/m", ()),
    "bulk_stable": ("bulk stable over the zone mesh and in the long-wave limit", None, ()),
    "reason": ("why values are NaN at this strain (empty if all are valid)", None, ()),
    "S_surface_exact": ("exact classical harmonic surface entropy per surface atom of the semi-infinite "
                        "crystal (log-determinant route)", "k_B", ()),
    "S_surface_exact_error": ("error estimate of S_surface_exact (Richardson over q grids)", "k_B", ()),
    "S_surface_estimate": ("Eq. (25)-type estimate <ln omega_1 omega_2 omega_3> - <ln omega_R> - "
                           "2 <ln omega>_bulk (see docs/physics/surface-phonons.md)", "k_B", ()),
    "bulk_mean_log_omega": ("mean of ln(omega/omega0) over all bulk modes, omega0 = (K/m)^(1/2)", "1", ()),
}
#: Branches stored (3 per plane, up to two planes per principal layer: (110)).
N_BRANCH = 6


def cuts(job: dict) -> list[tuple[str, str | None]]:
    """(surface, load direction or None) of every block of the scene (job parameters)."""
    out: list[tuple[str, str | None]] = []
    for surface in job["surfaces"]:
        if job["loading"] == "in_plane_hydrostatic":
            out.append((surface, None))
        else:
            out += [(surface, d) for d in job["directions"] if d in LOAD_DIRECTIONS[surface]]
    return out


def cut_label(surface: str, load_direction: str | None) -> str:
    """Label of a cut along the ``cut`` dimension, e.g. "(001)" or "(001) load [110]"."""
    return surface if load_direction is None else f"{surface} load {load_direction}"


def _block(pot: str, loading: str, d: np.ndarray, surface: str, ld: str | None, acc: dict) -> tuple[dict, dict]:
    omega = np.linspace(0.0, acc["omega_max"], acc["n_omega"])
    r = surface_phonons(pot, loading, d, surface=surface, q=DEFAULT_PATHS[surface],
                        path_density=acc["path_density"], omega=omega, eta=acc["eta"], load_direction=ld)
    e = surface_entropy(pot, loading, d, surface=surface, load_direction=ld, n_grid=acc["entropy_grid"])
    n, nq = r["omega"].shape[:2]
    edges = np.full((n, nq, N_BRANCH, 2), np.nan)
    edges[:, :, :r["band_edges"].shape[2]] = r["band_edges"]
    block = {
        "omega": r["omega"], "decay": r["decay"], "polarisation": r["polarisation"],
        "sector": r["sector"].astype(float), "band_edges": edges,
        "q_reduced": np.broadcast_to(r["q"], (n, nq, 2)).copy(), "q_distance": r["q_distance"],
        "spectral_density": r["spectral_density"], "lowest_omega2": r["omega2"][..., 0],
        "softest_omega2": r["softest_omega2"], "bulk_stable": r["bulk_stable"],
        "reason": np.asarray(r["reason"], dtype=str),
        "S_surface_exact": e["S_surface_exact"], "S_surface_exact_error": e["S_surface_exact_error"],
        "S_surface_estimate": e["S_surface_estimate"], "bulk_mean_log_omega": e["bulk_mean_log_omega"],
    }
    path = {"labels": r["path_labels"], "index": [int(i) for i in r["path_index"]]}
    return block, {"path": path, "omega": omega}


def _pad(a: np.ndarray, axis: int, n: int) -> np.ndarray:
    if a.shape[axis] == n:
        return a
    width = [(0, 0)] * a.ndim
    width[axis] = (0, n - a.shape[axis])
    return np.pad(a.astype(float), width, constant_values=np.nan)


def surface_phonons_cube(job: dict[str, Any]) -> xr.Dataset:
    """Build the cube of a scene's ``surface_phonons`` stage (job from :func:`job_params`).

    Returns
    -------
    xarray.Dataset
        dims (potential, cut, strain, q, mode, component, branch, edge, axis2, frequency); CF
        attributes on every variable; ``path_labels`` (JSON: per cut the labels and their
        q indices) and ``eta`` as attributes.
    """
    acc = job["accuracy"]
    d = np.asarray(job["d_over_d0"], float)
    blocks: dict[tuple[str, str], dict] = {}
    paths: dict[str, dict] = {}
    omega = np.zeros(0)
    for pot in job["potentials"]:
        for surface, ld in cuts(job):
            block, extra = _block(pot, job["loading"], d, surface, ld, acc)
            blocks[(pot, cut_label(surface, ld))] = block
            paths[cut_label(surface, ld)] = extra["path"]
            omega = extra["omega"]
    nq = max(b["omega"].shape[1] for b in blocks.values())
    nm = max(b["omega"].shape[2] for b in blocks.values())
    for b in blocks.values():
        for name, (_, _, dims) in VARIABLES.items():
            if "q" in dims:
                b[name] = _pad(b[name], 1, nq)
            if "mode" in dims:
                b[name] = _pad(b[name], 2, nm)
    meta = {k: {"long_name": v[0], **({"units": v[1]} if v[1] else {}), "dims": v[2]} for k, v in VARIABLES.items()}
    labels = [cut_label(s, ld) for s, ld in cuts(job)]
    ds = cube.build(blocks, {"potential": list(job["potentials"]), "cut": labels}, d, meta,
                    coords={"q": np.arange(nq), "mode": np.arange(nm),
                            "component": ["longitudinal", "normal", "shear_horizontal"],
                            "branch": np.arange(N_BRANCH), "edge": ["min", "max"], "axis2": ["b1", "b2"],
                            "frequency": omega})
    ds = ds.assign_coords(surface=("cut", [s for s, _ in cuts(job)]),
                          load_direction=("cut", [ld or "none" for _, ld in cuts(job)]))
    ds.coords["frequency"].attrs.update(long_name="angular frequency omega of the spectral density",
                                        units="sqrt(K/m)")
    for name, long_name in (("q", "index along the sampled path"), ("mode", "surface mode index (ascending omega)"),
                            ("branch", "bulk branch index (ascending)"), ("cut", "surface (and load direction)"),
                            ("surface", "surface plane of the cubic crystal"),
                            ("load_direction", "uniaxial load direction (none: in-plane hydrostatic)"),
                            ("component", "polarisation component"), ("edge", "band edge"),
                            ("axis2", "reduced axis")):
        ds.coords[name].attrs.setdefault("long_name", long_name)
        if ds.coords[name].dtype.kind in "iuf":
            ds.coords[name].attrs.setdefault("units", "1")
    ds.attrs["path_labels"] = json.dumps(paths, sort_keys=True)
    ds.attrs["eta"] = float(acc["eta"])
    return ds
