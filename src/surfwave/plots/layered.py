"""Figures of layered scenes (``dispersion_layered.nc`` of the ``layered`` rule).

:func:`dispersion` draws the phase speed of every mode against kh, one panel per substrate
orientation, with the substrate's limiting speed and the films' bulk speeds along the propagation
marked. :func:`coupling` draws K^2 against kh (piezoelectric stacks). :func:`stress_shift` draws,
for a film-stress sweep, the modes against kh for each stress and the shift of each mode's speed
from the unstressed (or least stressed) film.

Examples
--------
>>> from surfwave.data.cube import open_cube
>>> dispersion(open_cube("results/sio2_on_si/dispersion_layered.nc"), "a.png")   # doctest: +SKIP
"""
from __future__ import annotations

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from surfwave.layers.modes import label_family  # noqa: E402
from surfwave.plots.output import savefig  # noqa: E402

#: Names of a film's three bulk sheets along x1 (ascending speed).
SHEETS = ("slow shear", "fast shear", "longitudinal")
KH = r"$kh$ (wavenumber $\times$ total film thickness)"


def _reference(ds: xr.Dataset) -> int:
    """Index of the film stress nearest zero (the unstressed film where the grid has it)."""
    return int(np.argmin(np.abs(ds["film_stress"].values)))


def _panels(n: int, width: float = 5.6, height: float = 4.2):
    fig, axes = plt.subplots(1, n, figsize=(width * n, height), layout="constrained", squeeze=False)
    return fig, list(axes[0])


def _modes(ax, sub: xr.Dataset, var: str, scale: float = 1.0, modes=None) -> None:
    """One line per mode of ``sub`` (dims kh, mode) that has a value anywhere, labelled; a mode's
    colour is its place in ``sub["mode"]`` (the same in every figure of a cube), only ``modes`` drawn."""
    kh = sub["kh"].values
    for j, mode in enumerate(sub["mode"].values):
        y = sub[var].sel(mode=mode).values * scale
        if np.isfinite(y).any() and (modes is None or str(mode) in modes):
            ax.plot(kh, y, "-", color=f"C{j % 10}", marker="." if kh.size < 30 else None, ms=3, lw=1.4,
                    label=str(mode))


def bulk_marks(bulk: np.ndarray) -> list[tuple[float, str]]:
    """(speed, label) of each film's bulk sheets (``film_bulk_speed``, shape (n_film, 3), m/s);
    sheets within 0.1 % of each other (isotropic shear) share one label."""
    marks: list[tuple[float, str]] = []
    for f, speeds in enumerate(np.asarray(bulk, dtype=float)):
        names = list(SHEETS)
        if abs(speeds[1] - speeds[0]) <= 1e-3 * speeds[1]:
            names[0] = names[1] = "shear"
        for s, v in enumerate(speeds):
            lab = f"film {f} {names[s]}" if bulk.shape[0] > 1 else f"film {names[s]}"
            if np.isfinite(v) and not any(lab == m[1] for m in marks):
                marks.append((float(v), lab))
    return marks


FAMILY_NAMES = {"R": "sagittal", "L": "SH", "M": "coupled"}  # by family prefix (surfwave.layers.modes)


def limit_lines(sub: xr.Dataset) -> list[tuple[float, str]]:
    """(speed, label) of the substrate limits to draw for ``sub`` (dims kh, mode): one per family
    whose limit differs (``mode_limit``; sagittal and SH differ in a mirror plane), else the one
    ``c_limit`` ("substrate limit")."""
    c_lim = float(sub["c_limit"])
    if "mode_limit" not in sub:
        return [(c_lim, "substrate limit")]
    found: dict[float, list[str]] = {}
    for mode, v in zip(sub["mode"].values, sub["mode_limit"].values):
        if np.isfinite(v):
            key = next((k for k in found if abs(k - v) <= 5e-4 * v), float(v))
            name = FAMILY_NAMES.get(label_family(mode), "")
            if name not in found.setdefault(key, []):
                found[key].append(name)
    if len(found) <= 1:
        return [(c_lim, "substrate limit")]
    return [(v, f"limit, {' / '.join(names)} modes") for v, names in sorted(found.items())]


def _draw_limits(ax, limits: list[tuple[float, str]], lw: float) -> None:
    """Black horizontal lines at the limits of :func:`limit_lines` (dashed, then dash-dotted)."""
    for (v, lab), ls in zip(limits, ("--", "-.", ":")):
        ax.axhline(v, color="k", ls=ls, lw=lw, label=lab)


def dispersion(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Phase speed of every mode against kh, per orientation, at the film stress nearest zero.

    The substrate's limiting speed is a dashed black line (one per family where the sagittal and
    shear-horizontal limits differ, from ``mode_limit``); each film's bulk speeds along x1
    (``film_bulk_speed``) are dotted grey lines labelled on the right.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``dispersion_layered`` cube (dims orientation, film_stress, electrical, kh, mode).
    path : path
        PNG written.
    title : str
        Figure title (the scene).
    """
    i = _reference(ds)
    el = str(ds["electrical"].values[0])
    fig, axes = _panels(ds.sizes["orientation"])
    bulk = ds["film_bulk_speed"].values
    for ax, orient in zip(axes, ds["orientation"].values):
        sub = ds.sel(orientation=orient).isel(film_stress=i).sel(electrical=el)
        _modes(ax, sub, "c")
        limits = limit_lines(sub)
        c_lim = max(v for v, _ in limits)
        c = sub["c"].values
        top = max(np.nanmax(c) if np.isfinite(c).any() else c_lim, c_lim) * 1.06
        bottom = (np.nanmin(c) if np.isfinite(c).any() else c_lim) * 0.94
        marks = bulk_marks(bulk)
        shown = [(v, lab) for v, lab in marks if bottom * 0.9 <= v <= top * 1.15]
        top = max([top] + [v * 1.02 for v, _ in shown])
        bottom = min([bottom] + [v * 0.98 for v, _ in shown])
        _draw_limits(ax, limits, lw=1.2)
        groups: list[list[tuple[float, str]]] = []  # marks closer than 3.5 % of the axis share one label
        for v, lab in sorted(shown):
            if groups and v - groups[-1][-1][0] < 0.035 * (top - bottom):
                groups[-1].append((v, lab))
            else:
                groups.append([(v, lab)])
        for group in groups:
            for v, _ in group:
                ax.axhline(v, color="0.55", ls=":", lw=1.0)
            v = group[-1][0]
            lab = group[0][1] if len(group) == 1 else " / ".join(g[1] for g in group)
            below = 0 <= c_lim - v < 0.02 * c_lim  # just under the limit's line: label under the mark
            ax.annotate(lab, (1.0, v), xycoords=("axes fraction", "data"), xytext=(-3, -2 if below else 2),
                        textcoords="offset points", ha="right", va="top" if below else "bottom", fontsize=7,
                        color="0.35")
        ax.set_ylim(bottom, top)
        ax.set_xlim(float(ds["kh"].min()), float(ds["kh"].max()))
        ax.set_xlabel(KH)
        ax.set_ylabel("phase speed c (m/s)")
        ax.set_title(f"substrate {orient}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, title="mode", title_fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    sig = float(ds["film_stress"].values[i])
    fig.suptitle(f"{title}\nfilm stress {sig:g} GPa, {el} surface".strip(), fontsize=11)
    return savefig(fig, path)


def coupling(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """K^2 (percent) of every mode against kh, per orientation, at the film stress nearest zero.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``dispersion_layered`` cube of a piezoelectric stack.
    path : path
        PNG written.
    title : str
        Figure title (the scene).
    """
    i = _reference(ds)
    el = str(ds["electrical"].values[0])
    fig, axes = _panels(ds.sizes["orientation"])
    for ax, orient in zip(axes, ds["orientation"].values):
        sub = ds.sel(orientation=orient).isel(film_stress=i).sel(electrical=el)
        peak = abs(sub["K2"]).max("kh", skipna=True).fillna(0.0)
        zero = [str(m) for m in sub["mode"].values if sub["c"].sel(mode=m).notnull().any() and peak.sel(mode=m) < 1e-8]
        _modes(ax, sub, "K2", scale=100.0, modes=[str(m) for m in sub["mode"].values if str(m) not in zero])
        if zero:  # uncoupled modes (e.g. shear-horizontal ones of a decoupled family): named, not drawn
            ax.text(0.98, 0.97, f"K$^2$ = 0: {', '.join(zero)}", transform=ax.transAxes, ha="right", va="top",
                    fontsize=8, color="0.3")
        ax.axhline(0.0, color="k", lw=0.6)
        ax.set_xlim(float(ds["kh"].min()), float(ds["kh"].max()))
        ax.set_xlabel(KH)
        ax.set_ylabel(r"$K^2 = 2(c_\mathrm{free} - c_\mathrm{metallized})/c_\mathrm{free}$ (%)")
        ax.set_title(f"substrate {orient}", fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, title="mode", title_fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(f"{title}\nelectromechanical coupling, film stress {float(ds['film_stress'].values[i]):g} GPa"
                 .strip(), fontsize=11)
    return savefig(fig, path)


def stress_shift(ds: xr.Dataset, path: str | Path, title: str = "", max_modes: int = 3) -> Path:
    """For a film-stress sweep: every mode against kh per stress (left) and the shift of the lowest
    ``max_modes`` modes from the film stress nearest zero (right), first orientation and electrical.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``dispersion_layered`` cube with two or more film stresses.
    path : path
        PNG written.
    title : str
        Figure title (the scene).
    max_modes : int
        Modes whose shift is drawn (lowest mean speed first).
    """
    sub = ds.isel(orientation=0, electrical=0)
    i = _reference(ds)
    stresses = ds["film_stress"].values
    cmap = plt.get_cmap("coolwarm")
    norm = plt.Normalize(-np.abs(stresses).max(), np.abs(stresses).max())
    modes = [m for m in sub["mode"].values if np.isfinite(sub["c"].sel(mode=m).values).any()][:max_modes]
    styles = ("-", "--", ":", "-.")
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.6), layout="constrained")
    kh = sub["kh"].values
    for j, sig in enumerate(stresses):
        colour = cmap(norm(sig))
        for mode in sub["mode"].values:
            left.plot(kh, sub["c"].isel(film_stress=j).sel(mode=mode).values, color=colour, lw=1.2)
        for k, mode in enumerate(modes):
            shift = (sub["c"].isel(film_stress=j) - sub["c"].isel(film_stress=i)).sel(mode=mode).values
            right.plot(kh, shift, color=colour, ls=styles[k % len(styles)], lw=1.3)
    for mode in sub["mode"].values:  # each mode named at its first point (the reference stress)
        y = sub["c"].isel(film_stress=i).sel(mode=mode).values
        ok = np.flatnonzero(np.isfinite(y))
        if ok.size:
            left.annotate(str(mode), (kh[ok[0]], y[ok[0]]), xytext=(2, 4), textcoords="offset points", fontsize=8)
    _draw_limits(left, limit_lines(sub.isel(film_stress=i)), lw=1.0)
    left.set_ylabel("phase speed c (m/s)")
    left.legend(fontsize=8, loc="lower left")
    ref = float(stresses[i])
    right.set_ylabel(f"c(film stress) - c({ref:g} GPa) (m/s)")
    right.axhline(0.0, color="k", lw=0.6)
    for k, mode in enumerate(modes):
        right.plot([], [], color="0.3", ls=styles[k % len(styles)], label=f"mode {mode}")
    right.legend(fontsize=8, loc="best")
    for ax in (left, right):
        ax.set_xlabel(KH)
        ax.set_xlim(float(kh.min()), float(kh.max()))
        ax.grid(alpha=0.3)
    bar = fig.colorbar(plt.cm.ScalarMappable(norm=norm, cmap=cmap), ax=[left, right], pad=0.01)
    bar.set_label("equibiaxial film stress (GPa, < 0 compression)")
    fig.suptitle(f"{title}\nsubstrate {ds['orientation'].values[0]}, {sub['electrical'].values} surface".strip(),
                 fontsize=11)
    return savefig(fig, path)
