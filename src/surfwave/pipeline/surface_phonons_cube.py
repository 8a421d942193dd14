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
from surfwave.data.variables import CUBES
from surfwave.dynamics.fcc_layers import LOAD_DIRECTIONS
from surfwave.dynamics.fcc_surface_entropy import surface_entropy
from surfwave.dynamics.fcc_surface_phonons import DEFAULT_PATHS, surface_phonons

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
        for name, meta in CUBES["surface_phonons"].items():
            dims = meta["dims"][1:]
            if "q" in dims:
                b[name] = _pad(b[name], 1, nq)
            if "mode" in dims:
                b[name] = _pad(b[name], 2, nm)
    labels = [cut_label(s, ld) for s, ld in cuts(job)]
    ds = cube.build(blocks, {"potential": list(job["potentials"]), "cut": labels}, d, CUBES["surface_phonons"],
                    coords={"q": np.arange(nq), "mode": np.arange(nm),
                            "component": ["longitudinal", "normal", "shear_horizontal"],
                            "branch": np.arange(N_BRANCH), "edge": ["min", "max"], "axis2": ["b1", "b2"],
                            "frequency": omega})
    ds = ds.assign_coords(surface=("cut", [s for s, _ in cuts(job)]),
                          load_direction=("cut", [ld or "none" for _, ld in cuts(job)]))
    ds.coords["frequency"].attrs.update(long_name="angular frequency omega of the spectral density",
                                        units="(K/m)^(1/2)")
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
