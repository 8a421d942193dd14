"""Figures of piezoelectric scenes (``surface_wave.nc`` of the ``piezo_wave`` rule).

:func:`speeds_vs_euler`: the classic pair of rotated-cut plots, velocity (SAW free and
metallized, leaky SAW free and metallized, limiting speed), leaky attenuation and K^2 against the
swept Euler angle (for rotated Y cuts, X propagating: the rotation angle theta + 90), named cuts
marked. :func:`speeds_vs_stress`: SAW velocity (free, metallized) and its fractional change
against the uniaxial stress along the propagation.

Examples
--------
>>> from surfwave.data.cube import open_cube
>>> speeds_vs_euler(open_cube("results/rotated_y_cuts/surface_wave.nc"), "a.png")   # doctest: +SKIP
"""
from __future__ import annotations

import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from surfwave.plots.output import savefig  # noqa: E402

EULER = ("euler_phi", "euler_theta", "euler_psi")
STYLES = {"free": "-", "metallized": "--"}


def _short(material: str) -> str:
    return material.split("-")[0]


def _cut_marks(material: str, xdim: str, fixed: dict) -> list[tuple[float, str]]:
    """Named cuts of ``material``'s crystal on the plotted line (Euler ``xdim`` free, ``fixed`` fixed)."""
    from surfwave.real_crystals.piezo_materials import available_cuts, get_cut, get_piezo_material

    formula = get_piezo_material(material).formula
    marks = []
    for name in available_cuts():
        c = get_cut(name)
        if get_piezo_material(c.material).formula != formula:
            continue
        e = dict(zip(EULER, c.euler))
        if all(abs(e[d] - v) < 1e-9 for d, v in fixed.items()):
            marks.append((e[xdim], name.split()[0]))
    return marks


def _line(ds: xr.Dataset) -> tuple[xr.Dataset, str, dict]:
    """The cube along its one swept Euler angle: dim ``point``, the Euler name swept, the fixed ones."""
    if ds.sizes["angle"] >= 3 and ds.sizes["surface"] == 1:           # psi swept in one plate
        line = ds.isel(surface=0).rename(angle="point")
        line = line.assign_coords(x=("point", line.euler_psi.values))
        return line, "euler_psi", {"euler_phi": float(line.euler_phi), "euler_theta": float(line.euler_theta)}
    line = ds.isel(angle=0).rename(surface="point")
    phi, theta = line.euler_phi.values, line.euler_theta.values
    xdim = "euler_theta" if np.ptp(theta) >= np.ptp(phi) else "euler_phi"
    other = "euler_phi" if xdim == "euler_theta" else "euler_theta"
    keep = np.flatnonzero(line[other].values == line[other].values[0])   # first value of the other angle
    line = line.isel(point=keep)
    line = line.assign_coords(x=("point", line[xdim].values))
    return line, xdim, {other: float(line[other].values[0]), "euler_psi": float(line.euler_psi.values[0])}


def speeds_vs_euler(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Velocity, leaky attenuation and K^2 against the swept Euler angle, one column per material.

    Parameters
    ----------
    ds : xarray.Dataset
        Piezoelectric cube (dims material, surface, angle, electrical[, stress]; coordinates
        euler_phi, euler_theta per surface, euler_psi). The swept Euler angle is the x axis
        (psi when one plate has three or more angles, else theta or phi over the plates, the
        other taken at its first value); the stress nearest zero.
    path : str or Path
        PNG to write.
    title : str

    Returns
    -------
    Path
    """
    if "stress" in ds.dims:
        ds = ds.isel(stress=int(np.argmin(np.abs(ds.stress.values))))
    if "toec" in ds.dims:                                           # the fixed-constants model where present
        ds = ds.sel(toec=False) if False in ds.toec.values else ds.isel(toec=0)
    ds, dim, fixed = _line(ds)
    rotated_y = dim == "euler_theta" and fixed["euler_phi"] == 0 and fixed["euler_psi"] == 0
    x = ds.x.values + (90.0 if rotated_y else 0.0)
    xlabel = ("rotation angle of the rotated Y cut, X propagation (deg) = Euler theta + 90" if rotated_y
              else f"Euler {dim.split('_')[1]} (deg); " + ", ".join(f"{d.split('_')[1]} = {v:g}"
                                                                    for d, v in fixed.items()))
    mats = [str(m) for m in ds.material.values]
    width = max(5.2 * len(mats), 7.0)                 # one panel: room for its title and x label
    fig, axes = plt.subplots(3, len(mats), figsize=(width, 9.6), sharex=True, squeeze=False,
                             gridspec_kw={"height_ratios": [2.2, 1, 1]})
    chars = int(12 * width / len(mats))               # characters of a 10-pt line across one panel
    for j, mat in enumerate(mats):
        d = ds.sel(material=mat)
        av, aa, ak = axes[:, j]
        for el in [str(e) for e in d.electrical.values]:
            e = d.sel(electrical=el)
            av.plot(x, e.c_R, STYLES.get(el, "-"), color="tab:blue", label=f"SAW, {el}")
            av.plot(x, e.c_leaky, STYLES.get(el, "-"), color="tab:red", label=f"leaky SAW, {el}")
            aa.plot(x, e.leaky_attenuation, STYLES.get(el, "-"), color="tab:red", label=f"leaky SAW, {el}")
        av.plot(x, d.c_limit, ":", color="0.4", lw=1, label="limiting speed (stiffened bulk)")
        if "c_SH" in d:          # cubes before the bulk waves lack them; sorted: the names swap where
            shear = np.sort(np.stack([d.c_T_par.values, d.c_SH.values]), axis=0)   # the polarisations cross
            av.plot(x, shear[1], "--", color="0.6", lw=0.8, label="fast bulk shear along x1")
            av.plot(x, shear[0], "-.", color="0.6", lw=0.8, label="slow bulk shear along x1")
        ak.plot(x, 100 * d.K2, "-", color="tab:blue", label="SAW")
        els = [str(e) for e in d.electrical.values]
        if "K2_leaky" in d:
            ak.plot(x, 100 * d.K2_leaky, "-", color="tab:red", label="leaky SAW")
        elif {"free", "metallized"} <= set(els):
            vf, vm = d.c_leaky.sel(electrical="free"), d.c_leaky.sel(electrical="metallized")
            ak.plot(x, 100 * 2 * (vf - vm) / vf, "-", color="tab:red", label="leaky SAW")
        for xm, label in _cut_marks(mat, dim, fixed):
            xm = xm + (90.0 if rotated_y else 0.0)
            xm = xm % 180 if rotated_y else xm
            if x.min() - 1e-9 <= xm <= x.max() + 1e-9:
                for ax in (av, aa, ak):
                    ax.axvline(xm, color="0.75", lw=0.8, zorder=0)
                av.annotate(label, (xm, 1.0), xycoords=("data", "axes fraction"), xytext=(0, 2),
                            textcoords="offset points", fontsize=7, color="0.3", rotation=90, ha="center",
                            va="bottom")
        av.set_title(textwrap.fill(f"{_short(mat)} ({mat}); grey lines: named cuts", chars), fontsize=10, pad=34)
        av.set_ylabel("phase velocity (m/s)")
        aa.set_ylabel("leaky attenuation (dB/$\\lambda$)")
        aa.set_ylim(bottom=0)
        ak.set_ylabel("$K^2$ = 2 (v$_f$ - v$_m$)/v$_f$ (%)")
        ak.set_ylim(bottom=0)
        ak.set_xlabel(textwrap.fill(xlabel if len(mats) == 1 or j == 0 else
                                    "rotation angle (deg)" if rotated_y else xlabel, chars))
        for ax in (av, aa, ak):
            ax.grid(alpha=0.3)
    # one legend for every panel, below them (inside, it hid curves): the K^2 panel uses the
    # same colours (blue SAW, red leaky SAW)
    h, lab = axes[0, 0].get_legend_handles_labels()
    fig.legend(h, lab, loc="lower center", ncol=3, fontsize=8, frameon=False)
    span = float(np.ptp(x)) if x.size else 0.0
    if rotated_y and span >= 120:                     # the classic full 0-180 degree picture
        axes[-1, 0].set_xlim(0, 180)
        axes[-1, 0].set_xticks(np.arange(0, 181, 30))
    elif span > 0:                                    # a user's range fills the width
        axes[-1, 0].set_xlim(x.min(), x.max())
    head = (("Rotated Y-cut, X-propagating SAW: velocity, leaky attenuation and coupling $K^2$"
             if rotated_y else "SAW against the Euler angle") + (f" ({title})" if title else ""))
    fig.suptitle(textwrap.fill(head, int(12 * width)), fontsize=10)
    fig.tight_layout(rect=(0, 0.06, 1, 1))
    return savefig(fig, path)


def speeds_vs_stress(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """SAW velocity (free, metallized) and its fractional change against uniaxial stress.

    One line per (material, orientation, electrical condition[, prestress model]); the fractional
    change is (v(sigma) - v(0)) / v(0) with v(0) interpolated at zero stress. With a ``toec`` dim,
    the third-order model's lines carry dots.

    Parameters
    ----------
    ds : xarray.Dataset
        Piezoelectric cube with a ``stress`` dim (GPa, uniaxial along the propagation)[ and
        ``toec``].
    path : str or Path
    title : str

    Returns
    -------
    Path
    """
    s = ds.stress.values
    models = [bool(t) for t in ds.toec.values] if "toec" in ds.dims else [None]
    stacked = ds.stack(orientation=("surface", "angle"), create_index=False)   # surface has the plate indexes
    fig, (av, ar) = plt.subplots(1, 2, figsize=(10.5, 4.2))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    k = 0
    for mat in [str(m) for m in ds.material.values]:
        for i in range(stacked.sizes["orientation"]):
            o = stacked.sel(material=mat).isel(orientation=i)
            label_o = (str(o.cut.values) if "cut" in o.coords else
                       "Euler (" + ", ".join(f"{float(o[d]):g}" for d in EULER) + ")")
            colour = colours[k % len(colours)]
            k += 1
            for el, t in [(str(e), t) for e in o.electrical.values for t in models]:
                p = o.sel(electrical=el) if t is None else o.sel(electrical=el, toec=t)
                v = p.c_R.values
                v0 = np.interp(0.0, s, v)
                lab = f"{label_o}, {_short(mat)}, {el}" if len(ds.material) > 1 else f"{label_o}, {el}"
                lab += "" if t is None else ", third-order constants" if t else ", fixed constants"
                # the third-order model's lines carry dots ("-." would be a dash-dot line)
                style = {"linestyle": STYLES.get(el, "-"), "marker": "." if t else None}
                av.plot(s, v, color=colour, label=lab, **style)
                ar.plot(s, 1e6 * (v / v0 - 1), color=colour, label=lab, **style)
    av.set_xlabel("uniaxial stress along the propagation (GPa, < 0 compression)")
    ar.set_xlabel("uniaxial stress along the propagation (GPa, < 0 compression)")
    av.set_ylabel("SAW phase velocity (m/s)")
    ar.set_ylabel("fractional change (v - v$_0$)/v$_0$ (ppm)")
    for ax in (av, ar):
        ax.grid(alpha=0.3)
        ax.axvline(0, color="0.7", lw=0.8)
    av.legend(fontsize=8, loc="best")
    model = ("third-order constants where marked" if any(models) and len(models) > 1 else
             "third-order constants" if models == [True] else "fixed constants: A = C + $\\sigma$")
    fig.suptitle(f"SAW velocity under prestress ({model}; e, $\\varepsilon$ at natural values)"
                 + (f" ({title})" if title else ""), fontsize=10)
    fig.tight_layout()
    return savefig(fig, path)
