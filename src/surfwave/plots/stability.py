"""Stability map of prestressed FCC: long-wave vs full-zone, as a cube and a figure.

The long-wave criterion is the analytic acoustic tensor over all directions
(``surfwave.point(...)["stable"]``); the full-zone criterion is phonopy's
(:func:`surfwave.continuum.phonons.bulk_speeds`: zone mesh plus the long-wave limit of the force
constants). Run ``python -m surfwave.plots.stability OUTDIR`` to write
OUTDIR/stability_map.nc and OUTDIR/stability_map.png.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import xarray as xr

from surfwave import __version__
from surfwave.continuum.phonons import DEFAULT_DISPLACEMENT, DEFAULT_SUPERCELL, DEFAULT_ZONE_MESH, TOLERANCE
from surfwave.continuum.stability import geometry_limit, instability_limits, stability_scan

#: The paper's claim: "maximum compressive strains about 10% (LJ) and 40% (harmonic)".
PAPER_CLAIM = {"lj": 0.90, "harmonic": 0.60}
STATES = {-1: "no_geometry", 0: "long_wave_unstable", 1: "short_wave_unstable", 2: "stable"}


def stability_map(
    potentials=("harmonic", "lj"),
    loadings=("in_plane_hydrostatic", "uniaxial"),
    directions=("[100]", "[110]"),
    d_over_d0=None,
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
    grid = np.round(np.arange(0.50, 1.4101, 0.01), 4) if d_over_d0 is None else np.asarray(d_over_d0, float)
    knobs = dict(supercell=supercell, displacement=displacement, zone_mesh=zone_mesh)
    shape = (len(potentials), len(loadings), len(directions))
    state = np.full(shape + (grid.size,), -1, np.int8)
    fields = {k: np.full(shape + (grid.size,), np.nan) for k in ("min_omega2", "min_c2_phonopy")}
    flags = {
        k: np.zeros(shape + (grid.size,), bool)
        for k in ("stable_long_wave", "stable_full_zone", "stable_zone_mesh")
    }
    qmin = np.full(shape + (grid.size, 3), np.nan)
    limits = np.full(shape + (2, 2), np.nan)
    geom = np.full(shape + (2,), np.nan)
    for idx in np.ndindex(shape):
        pot, load, d = potentials[idx[0]], loadings[idx[1]], directions[idx[2]]
        scan = stability_scan("fcc", load, pot, d, grid, **knobs)
        built = np.array([("GeometryError" not in r) for r in scan["reason"]])
        flags["stable_long_wave"][idx] = scan["stable_long_wave"]
        flags["stable_full_zone"][idx] = scan["stable_full_zone"]
        flags["stable_zone_mesh"][idx] = scan["min_omega2"] > -TOLERANCE
        fields["min_omega2"][idx] = scan["min_omega2"]
        fields["min_c2_phonopy"][idx] = scan["min_c2_phonopy"]
        qmin[idx] = scan["min_omega2_q"]
        state[idx] = np.where(
            ~built, -1, np.where(~scan["stable_long_wave"], 0, np.where(~scan["stable_full_zone"], 1, 2))
        )
        for k, kind in enumerate(("long_wave", "full_zone")):
            limits[idx + (k,)] = instability_limits(
                "fcc", load, pot, d, kind, tol=tol, **(knobs if k else {})
            )
        geom[idx] = geometry_limit("fcc", load, pot, d, tol=tol)
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
                flags["stable_long_wave"],
                {
                    "long_name": "acoustic tensor Q(n) positive for every direction n (analytic, Eq. A11)",
                    "units": "1",
                },
            ),
            "stable_full_zone": (
                dims + ("strain",),
                flags["stable_full_zone"],
                {
                    "long_name": "no imaginary phonon frequency: zone mesh and long-wave limit (phonopy)",
                    "units": "1",
                },
            ),
            "stable_zone_mesh": (
                dims + ("strain",),
                flags["stable_zone_mesh"],
                {
                    "long_name": "no imaginary phonon frequency on the zone mesh alone (Gamma excluded)",
                    "units": "1",
                },
            ),
            "min_omega2": (
                dims + ("strain",),
                fields["min_omega2"],
                {"long_name": "lowest omega^2 on the zone mesh (refined when negative)", "units": "K / m"},
            ),
            "min_omega2_q": (
                dims + ("strain", "xyz"),
                qmin,
                {"long_name": "Cartesian lab-frame wave vector of min_omega2", "units": "rad / d0"},
            ),
            "min_c2_phonopy": (
                dims + ("strain",),
                fields["min_c2_phonopy"],
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
            "Conventions": "CF-1.8",
            "title": "stability map of prestressed nearest-neighbour FCC",
            "source": f"surfwave {__version__} (surfwave.plots.stability.stability_map)",
            "history": f"{time.strftime('%Y-%m-%dT%H:%M:%SZ', time.gmtime())} stability_map",
            "method": "long wave: analytic acoustic tensor; full zone: phonopy finite displacements",
            "supercell": supercell,
            "displacement": displacement,
            "zone_mesh": zone_mesh,
            "units_note": "reduced units d0 = K = m = 1",
        },
    )
    return ds


def plot_stability_map(ds: xr.Dataset, path) -> None:
    """One panel per potential; a coloured band per (loading, direction) over d/d0.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`stability_map` (``state``, ``d_limit`` and the d/d0 coordinate).
    path : str or Path
        PNG file to write.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.colors import ListedColormap

    cmap = ListedColormap(["lightgrey", "tab:red", "tab:orange", "tab:green"])
    pots = list(ds.potential.values)
    fig, axes = plt.subplots(len(pots), 1, figsize=(9, 2.2 + 1.1 * len(pots) * 2), squeeze=False)
    x = ds.d_over_d0.values
    for ax, pot in zip(axes[:, 0], pots):
        rows, labels = [], []
        for load in ds.loading.values:
            for d in ds.direction.values:
                rows.append(ds.state.sel(potential=pot, loading=load, direction=d).values)
                labels.append(f"{load} {d}")
        dx = x[1] - x[0] if x.size > 1 else 0.01
        ax.imshow(
            np.array(rows) + 1,
            aspect="auto",
            cmap=cmap,
            vmin=0,
            vmax=3,
            interpolation="nearest",
            extent=(x[0] - dx / 2, x[-1] + dx / 2, len(rows) - 0.5, -0.5),
        )
        i = 0
        for load in ds.loading.values:
            for d in ds.direction.values:
                for kind, mk in (("long_wave", "|"), ("full_zone", "x")):
                    for side in ("compression", "tension"):
                        v = float(
                            ds.d_limit.sel(potential=pot, loading=load, direction=d, kind=kind, side=side)
                        )
                        if np.isfinite(v):
                            ax.plot(v, i, mk, color="k", ms=10)
                            if kind == "long_wave":
                                ax.annotate(
                                    f"{v:.4f}",
                                    (v, i),
                                    textcoords="offset points",
                                    xytext=(0, 8),
                                    ha="center",
                                    fontsize=7,
                                )
                i += 1
        ax.axvline(
            PAPER_CLAIM.get(str(pot), np.nan),
            color="b",
            ls="--",
            lw=1.2,
            label=f"paper: max compression {1 - PAPER_CLAIM.get(str(pot), np.nan):.0%}",
        )
        ax.axvline(1.0, color="k", lw=0.5)
        ax.set_yticks(range(len(labels)), labels, fontsize=8)
        ax.set_title(f"FCC, {pot}", fontsize=10)
        ax.legend(loc="lower right", fontsize=7)
    axes[-1, 0].set_xlabel("d/d0 (stretch along propagation direction x)")
    handles = [plt.Rectangle((0, 0), 1, 1, color=cmap(k)) for k in range(4)]
    fig.legend(
        handles,
        ["no geometry", "long-wave unstable", "short-wave only unstable", "stable"],
        loc="upper center",
        ncol=4,
        fontsize=8,
    )
    fig.text(
        0.01, 0.005, "| first long-wave instability, x first full-zone instability (phonopy)", fontsize=7
    )
    fig.tight_layout(rect=(0, 0.02, 1, 0.94))
    fig.savefig(path, dpi=120)
    plt.close(fig)


def main(outdir: str) -> xr.Dataset:
    """Compute the default map and write ``stability_map.nc`` and ``stability_map.png``."""
    out = Path(outdir)
    out.mkdir(parents=True, exist_ok=True)
    ds = stability_map()
    ds.to_netcdf(out / "stability_map.nc", engine="h5netcdf")
    plot_stability_map(ds, out / "stability_map.png")
    return ds


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: python -m surfwave.plots.stability OUTDIR")
    main(sys.argv[1])
