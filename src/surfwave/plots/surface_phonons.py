"""Figures of the ``surface_phonons`` cube: dispersion over the bulk bands, soft-mode map, entropy.

Matplotlib with the Agg backend; every function takes the cube (one potential selected) and an
output path and returns the path written.
"""
from __future__ import annotations

import json
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402

from surfwave.plots.output import savefig  # noqa: E402

_LABELS = {"G": "$\\bar\\Gamma$", "X": "$\\bar X$", "M": "$\\bar M$", "K": "$\\bar K$", "Y": "$\\bar Y$",
           "S": "$\\bar S$"}
_SECTOR_COLOURS = {1: "tab:red", -1: "tab:blue", 0: "k"}


def three_strains(d: np.ndarray, computed: np.ndarray | None = None) -> list[int]:
    """Indices of three strains to draw: the smallest, the one nearest d/d0 = 1 and the largest
    of those with an answer (``computed``, shape like ``d``; all strains when none has one),
    fewer if there are fewer.

    >>> three_strains(np.array([0.9, 0.95, 1.0, 1.05, 1.1]), np.array([False, True, True, True, False]))
    [1, 2, 3]
    """
    ok = np.flatnonzero(computed) if computed is not None and np.any(computed) else np.arange(d.size)
    return sorted({int(ok[0]), int(ok[np.argmin(np.abs(d[ok] - 1.0))]), int(ok[-1])})


def _path_axis(ax, ds: xr.Dataset, cut: str, x: np.ndarray) -> None:
    path = json.loads(ds.attrs["path_labels"])[cut]
    for i in path["index"]:
        if i < x.size and np.isfinite(x[i]):
            ax.axvline(x[i], color="0.6", lw=0.6)
    ax.set_xticks([x[i] for i in path["index"]])
    ax.set_xticklabels([_LABELS.get(c, c) for c in path["labels"]])
    ax.set_xlim(np.nanmin(x), np.nanmax(x))


def plot_dispersion(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Surface modes over the shaded projected bulk bands, one row per cut, three strains.

    Parameters
    ----------
    ds : xarray.Dataset
        The cube with one potential selected (dims cut, strain, q, ...).
    path : path
    title : str
    """
    cuts = [str(c) for c in ds["cut"].values]
    d = ds["d_over_d0"].values
    other = [dim for dim in ds["band_edges"].dims if dim != "strain"]
    cols = three_strains(d, ds["band_edges"].notnull().any(other).values)   # strains whose bulk is stable
    fig, axes = plt.subplots(len(cuts), len(cols), figsize=(3.6 * len(cols), 3.0 * len(cuts)),
                             squeeze=False, sharey=True)
    for r, cut in enumerate(cuts):
        sub = ds.sel(cut=cut)
        for c, i in enumerate(cols):
            ax = axes[r, c]
            one = sub.isel(strain=i)
            x = one["q_distance"].values
            good = np.isfinite(x)
            edges = one["band_edges"].values[good]
            for b in range(edges.shape[1]):
                lo, hi = edges[:, b, 0], edges[:, b, 1]
                if np.isfinite(lo).any():
                    ax.fill_between(x[good], lo, hi, color="0.82", lw=0)
            w = one["omega"].values[good]
            sec = one["sector"].values[good]
            for s, colour in _SECTOR_COLOURS.items():
                m = (sec == s) & np.isfinite(w)
                xs = np.broadcast_to(x[good][:, None], w.shape)[m]
                ax.plot(xs, w[m], ".", ms=2.5, color=colour,
                        label={1: "sagittal", -1: "shear horizontal", 0: "no mirror"}[s])
            _path_axis(ax, ds, cut, x)
            if not bool(one["bulk_stable"].values):
                ax.text(0.5, 0.5, "bulk unstable", transform=ax.transAxes, ha="center")
            ax.set_title(f"{cut}, d/d0 = {d[i]:.3g}", fontsize=9)
            if c == 0:
                ax.set_ylabel("omega (K/m)^1/2")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    if handles:
        uniq = dict(zip(labels, handles))
        fig.legend(uniq.values(), uniq.keys(), loc="lower center", ncol=3, fontsize=8, frameon=False)
    fig.suptitle(title or "surface phonons (grey: projected bulk bands)", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    return savefig(fig, path)


def _first_unstable(d: np.ndarray, stable: np.ndarray) -> tuple[float, float]:
    """Midpoints between the last stable and first unstable strain below and above d/d0 = 1."""
    lo = hi = np.nan
    order = np.argsort(d)
    d, stable = d[order], stable[order]
    below = np.flatnonzero((d < 1) & ~stable)
    above = np.flatnonzero((d > 1) & ~stable)
    if below.size and below.max() + 1 < d.size:
        lo = 0.5 * (d[below.max()] + d[below.max() + 1])
    if above.size and above.min() > 0:
        hi = 0.5 * (d[above.min()] + d[above.min() - 1])
    return lo, hi


def plot_soft_map(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Lowest surface omega^2 over strain and q along the path, bulk stability limits marked."""
    cuts = [str(c) for c in ds["cut"].values]
    fig, axes = plt.subplots(1, len(cuts), figsize=(4.6 * len(cuts), 3.6), squeeze=False)
    d = ds["d_over_d0"].values
    for k, cut in enumerate(cuts):
        ax = axes[0, k]
        sub = ds.sel(cut=cut)
        x = sub["q_distance"].values[0]
        good = np.isfinite(x)
        w2 = sub["lowest_omega2"].values[:, good]
        scale = np.nanmax(np.abs(w2)) if np.isfinite(w2).any() else 1.0
        half = 0.5 * (d[1] - d[0]) if d.size > 1 else 0.01
        edges_y = np.concatenate([[d[0] - half], 0.5 * (d[1:] + d[:-1]), [d[-1] + half]])
        xg = x[good]
        edges_x = np.concatenate([[xg[0]], 0.5 * (xg[1:] + xg[:-1]), [xg[-1]]])
        mesh = ax.pcolormesh(edges_x, edges_y, w2, cmap="RdBu", vmin=-scale, vmax=scale, shading="flat")
        stable = sub["bulk_stable"].values.astype(bool)
        for i in np.flatnonzero(~stable):
            ax.axhspan(edges_y[i], edges_y[i + 1], color="0.7", hatch="///", alpha=0.6, lw=0)
        lo, hi = _first_unstable(d, stable)
        for v in (lo, hi):
            if np.isfinite(v):
                ax.axhline(v, color="k", lw=1.2, ls="--")
        ax.text(0.02, 0.02, "hatched: bulk unstable; dashed: bulk limit", transform=ax.transAxes, fontsize=7)
        _path_axis(ax, ds, cut, x)
        ax.set_ylabel("d/d0")
        ax.set_title(f"{cut}: lowest surface omega^2", fontsize=9)
        fig.colorbar(mesh, ax=ax, label="omega^2 (K/m)")
    fig.suptitle(title or "soft surface modes", fontsize=10)
    fig.tight_layout()
    return savefig(fig, path)


def plot_entropy(ds: xr.Dataset, path: str | Path, title: str = "") -> Path:
    """Exact surface entropy against strain, with its Eq. (25)-type estimate, per cut."""
    fig, ax = plt.subplots(figsize=(5.2, 3.8))
    d = ds["d_over_d0"].values
    for k, cut in enumerate(str(c) for c in ds["cut"].values):
        sub = ds.sel(cut=cut)
        colour = f"C{k}"
        ax.errorbar(d, sub["S_surface_exact"].values, yerr=sub["S_surface_exact_error"].values, color=colour,
                    marker="o", ms=3, label=f"{cut} exact")
        ax.plot(d, sub["S_surface_estimate"].values, color=colour, ls="--", marker="x", ms=4,
                label=f"{cut} Eq. (25)-type estimate")
    ax.set_xlabel("d/d0")
    ax.set_ylabel("surface entropy per surface atom (k_B)")
    ax.legend(fontsize=7)
    ax.set_title(title or "surface entropy", fontsize=10)
    fig.tight_layout()
    return savefig(fig, path)


def draw_all(ds: xr.Dataset, outputs: dict[str, str], scene: str) -> set[str]:
    """Draw the outputs named ``surface_phonons_{dispersion,soft,entropy}_<potential>``.

    Returns
    -------
    set of str
        The output keys written.
    """
    draw = {"dispersion": plot_dispersion, "soft": plot_soft_map, "entropy": plot_entropy}
    done = set()
    for key, path in outputs.items():
        kind, pot = key[len("surface_phonons_"):].split("_", 1)
        one = ds.sel(potential=pot)
        what = {"dispersion": "surface phonons over the projected bulk bands (grey)",
                "soft": "lowest surface-mode omega^2 along the path", "entropy": "surface entropy"}[kind]
        draw[kind](one, path, title=f"FCC {what}, {pot} (scene {scene})")
        done.add(key)
    return done
