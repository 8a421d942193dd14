"""Figures of real-crystal scenes (``surface_wave.nc``): the classic c_R(angle) and v_L(angle)
per surface, and c_R against the applied stress per material and direction.

Both functions take the cube (a Dataset from :func:`surfwave.data.cube.open_cube`), draw with
matplotlib's Agg backend and return the PNG path written.

Examples
--------
>>> from surfwave.data.cube import open_cube
>>> ds = open_cube("results/crystals/surface_wave.nc")          # doctest: +SKIP
>>> speeds_vs_angle(ds, "angles.png")                           # doctest: +SKIP
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.legend_handler import HandlerTuple  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

from surfwave.plots.output import savefig  # noqa: E402

#: Line styles of the wave types (the pseudo surface wave is leaky: dashed).
TYPE_STYLES = {"surface": "-", "supersonic_decoupled": "-", "pseudo": "--"}
LOADING_COLOURS = {"along": "tab:blue", "across": "tab:orange", "biaxial": "tab:green"}


def _unstressed(ds: xr.Dataset) -> tuple[xr.Dataset, str]:
    """The unstressed (or least stressed), fixed-constant slice of a cube, and a note."""
    if "stress" not in ds.dims:
        return ds, ""
    i = int(np.argmin(np.abs(ds.stress.values)))
    sub = ds.isel(stress=i, loading=0)
    if "toec" in sub.dims:
        sub = sub.sel(toec=False) if False in sub.toec.values else sub.isel(toec=0)
    s = float(ds.stress[i])
    return sub, ("" if s == 0 else f", stress {s:g} GPa ({str(ds.loading[0].values)})")


def speeds_vs_angle(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """c_R(angle), the leaky wave and the limiting speed v_L(angle), one column per surface.

    Each material has one colour: its surface wave is a solid line, the limiting speed v_L a
    thin dotted line; open circles mark sagittal waves above v_L that exist only on mirror
    directions (``supersonic_decoupled``). A cube with ``c_leaky`` (the leaky SAW radiating
    into the slowest bulk sheet) draws it as a thin dashed line with dots in the top row and
    its attenuation (dB per wavelength) in a second row below; without it, a pseudo surface
    wave with a speed is dashed and one without is an x on v_L. Each panel covers the
    symmetry-reduced angle range of its surface (``symmetric_range`` in the cube) when the
    cube's angles span it.

    Parameters
    ----------
    ds : xarray.Dataset
        ``surface_wave.nc`` with dims (material, surface, angle[, loading, toec, stress]);
        stressed cubes are drawn at the stress closest to zero, fixed-constant model.
    path : str or Path
        PNG to write.
    title : str
        Figure title suffix.

    Returns
    -------
    pathlib.Path
    """
    ds, note = _unstressed(ds)
    surfaces = [str(s) for s in ds.surface.values]
    leaky = "c_leaky" in ds
    if leaky:
        fig, grid = plt.subplots(2, len(surfaces), figsize=(4.2 * len(surfaces), 6.6), squeeze=False,
                                 sharey="row", sharex="col", layout="constrained",
                                 gridspec_kw={"height_ratios": [2.2, 1.0]})
        axes, att_axes = grid[:1], grid[1]
    else:
        fig, axes = plt.subplots(1, len(surfaces), figsize=(4.2 * len(surfaces), 4.2), squeeze=False,
                                 sharey=True, layout="constrained")
    colours = plt.get_cmap("tab10")
    angle = ds.angle.values
    for k, (ax, sf) in enumerate(zip(axes[0], surfaces)):
        width = float(ds.symmetric_range.sel(surface=sf).max()) if "symmetric_range" in ds else angle.max()
        inside = angle <= width + 1e-9 if angle.min() < width < angle.max() else np.ones(angle.size, bool)
        for i, mat in enumerate(ds.material.values):
            point = ds.sel(material=mat, surface=sf)
            col = colours(i % 10)
            c, wt = point.c_R.values, point.wave_type.values.astype(str)
            x = angle[inside]
            ax.plot(x, point.c_limit.values[inside], ":", color=col, lw=1.0)
            for kind in ("surface", "pseudo"):
                ax.plot(x, np.where(wt == kind, c, np.nan)[inside], TYPE_STYLES[kind], color=col,
                        lw=1.8 if kind == "surface" else 1.4)
            sup = (wt == "supersonic_decoupled") & inside
            ax.plot(angle[sup], c[sup], "o", mfc="none", color=col, ms=5)
            # a pseudo wave whose complex speed the solver does not give: x on v_L, where it leaks
            leak = (wt == "pseudo") & ~np.isfinite(c) & inside
            ax.plot(angle[leak], point.c_limit.values[leak], "x", color=col, ms=4)
            if leaky:   # the leaky branch (dots: isolated points show too) and its attenuation
                ax.plot(x, point.c_leaky.values[inside], "--", marker=".", ms=3, color=col, lw=0.9)
                att_axes[k].plot(x, point.leaky_attenuation.values[inside], "--", marker=".", ms=3,
                                 color=col, lw=0.9)
        ax.set_title(f"{sf} surface")
        ax.set_xlim(x.min(), x.max())
        ax.grid(alpha=0.3)
        bottom = att_axes[k] if leaky else ax
        bottom.set_xlabel("propagation angle (degree)")
        if leaky:
            att_axes[k].grid(alpha=0.3)
    axes[0, 0].set_ylabel("speed (m/s)")
    axes[0, 0].set_ylim(bottom=0)
    if leaky:
        att_axes[0].set_ylabel("leaky-wave attenuation\n(dB per wavelength)")
        att_axes[0].set_ylim(bottom=0)
    handles = [Line2D([], [], color=colours(i % 10), lw=2, label=str(m)) for i, m in enumerate(ds.material.values)]
    pseudo = ds.wave_type == "pseudo"
    with_speed = bool((pseudo & np.isfinite(ds.c_R)).any())
    handles += [Line2D([], [], color="k", ls="-", lw=1.8, label=r"$c_R$ surface wave")]
    if leaky:
        handles.append(Line2D([], [], color="k", ls="--", marker=".", ms=3, lw=0.9,
                              label="leaky SAW (into the slowest\nbulk sheet), speed and\nattenuation"))
    if with_speed:
        handles.append(Line2D([], [], color="k", ls="--", lw=1.4, label="pseudo-SAW (leaky, real part)"))
    if bool((pseudo & ~np.isfinite(ds.c_R)).any()):
        handles.append(Line2D([], [], color="k", ls="", marker="x",
                              label="pseudo-SAW (leaky, speed not\ncomputed), marked on $v_L$"))
    handles += [
                Line2D([], [], color="k", ls="", marker="o", mfc="none", label="sagittal, above $v_L$ (mirror)"),
                Line2D([], [], color="k", ls=":", lw=1.0, label=r"$v_L$ limiting speed")]
    fig.legend(handles=handles, loc="outside right center", fontsize=8, frameon=False)
    fig.suptitle(f"Surface waves of cubic crystals against the propagation angle{note}"
                 + (f" ({title})" if title else ""), fontsize=10)
    return savefig(fig, path)


def _direction_labels(ds: xr.Dataset) -> list[str]:
    if "direction" in ds.coords:
        return [str(d) for d in ds.direction.values]
    return [f"{float(a):g} deg" for a in ds.angle.values]


def _coinciding_fixed(ds: xr.Dataset, a: str, b: str, rtol: float = 1e-9) -> tuple[str, str] | None:
    """(a, b) when the fixed-constants curves of loadings a and b agree everywhere (to ``rtol``), else None."""
    if "toec" not in ds.dims or False not in ds.toec.values or not {a, b} <= {str(v) for v in ds.loading.values}:
        return None
    fixed = ds.c_R.sel(toec=False)
    ca, cb = fixed.sel(loading=a).values, fixed.sel(loading=b).values
    both = np.isfinite(ca) & np.isfinite(cb)
    same = bool(both.any()) and np.array_equal(np.isfinite(ca), np.isfinite(cb)) and bool(
        np.all(np.abs(ca[both] - cb[both]) <= rtol * np.abs(ca[both])))
    return (a, b) if same else None


def speeds_vs_stress(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Relative change of c_R against the applied stress, one panel per material and direction.

    Colours: the loading kinds; solid lines: constants of the stressed state from the
    third-order constants (``toec`` true), dashed: fixed second-order constants. Points
    without a true surface wave (pseudo or none) are left out. The panel title gives
    c_R at zero stress.

    Parameters
    ----------
    ds : xarray.Dataset
        ``surface_wave.nc`` with dims (material, surface, angle, loading, toec, stress).
    path : str or Path
    title : str

    Returns
    -------
    pathlib.Path
    """
    labels = _direction_labels(ds)
    cols = [(sf, j) for sf in ds.surface.values for j in range(ds.sizes["angle"])]
    mats = list(ds.material.values)
    fig, axes = plt.subplots(len(mats), len(cols), figsize=(3.3 * len(cols), 2.6 * len(mats)),
                             squeeze=False, sharex=True, layout="constrained")
    s = ds.stress.values
    i0 = int(np.argmin(np.abs(s)))
    cmap = plt.get_cmap("tab10")
    n_load = ds.sizes["loading"]
    for r, mat in enumerate(mats):
        for k, (sf, j) in enumerate(cols):
            ax = axes[r, k]
            point = ds.sel(material=mat, surface=sf).isel(angle=j)
            for li, ld in enumerate(point.loading.values):
                col = LOADING_COLOURS.get(str(ld), cmap((li + 3) % 10))
                for tv in point.toec.values:
                    p = point.sel(loading=ld, toec=tv)
                    c = np.where(p.wave_type.values.astype(str) == "pseudo", np.nan, p.c_R.values)
                    # fixed constants: interleaved dashes, so that coinciding loadings (along
                    # and biaxial; across is flat) stay visible
                    style = "-" if tv else (2.5 * li, (2.5, 2.5 * (n_load - 1) or 2.5))
                    ax.plot(s, 100.0 * (c / c[i0] - 1.0), linestyle=style, color=col, lw=1.4)
            c0 = float(point.c_R.isel(loading=0, toec=0, stress=i0))
            ax.set_title(f"{mat} {sf} {labels[j]}: $c_R$ = {c0:.0f} m/s", fontsize=8)
            ax.axhline(0, color="0.6", lw=0.6)
            ax.grid(alpha=0.3)
            if r == len(mats) - 1:
                ax.set_xlabel("applied stress (GPa)")
            if k == 0:
                ax.set_ylabel(r"$c_R/c_R(0) - 1$ (%)")
    handles: list = [Line2D([], [], color=LOADING_COLOURS.get(str(ld), cmap((li + 3) % 10)), lw=2,
                            label=f"loading: {ld}") for li, ld in enumerate(ds.loading.values)]
    handles += [Line2D([], [], color="k", ls="-", label="stressed-state constants (TOEC)"),
                Line2D([], [], color="k", ls="--", label="fixed second-order constants")]
    labels = [str(h.get_label()) for h in handles]
    pair = _coinciding_fixed(ds, "along", "biaxial")
    if pair:     # say so: one dashed line would otherwise seem missing
        handles.append(tuple(Line2D([], [], color=LOADING_COLOURS.get(ld, "k"), lw=1.4, ls="--") for ld in pair))
        labels.append("fixed constants: along = biaxial, the curves\ncoincide (a stress across x1 does not enter)")
    fig.legend(handles, labels, loc="outside lower center", ncol=3 if len(cols) > 2 else 2, fontsize=8,
               frameon=False,
               handler_map={tuple: HandlerTuple(ndivide=None, pad=0)})
    fig.suptitle("Surface-wave speed against in-plane stress" + (f" ({title})" if title else ""),
                 fontsize=10)
    return savefig(fig, path)
