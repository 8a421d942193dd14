"""Figure of the FCC stability map (long-wave against full-zone stability).

Draws the Dataset of :func:`surfwave.model_crystals.stability_map.stability_map`; computing and
writing the map belong to the library and the workflow (rule ``figure_stability_map``).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import xarray as xr

from surfwave.data.paper import load_paper_values

#: Vertical offsets (in rows) of the two limit markers, so that coinciding limits stay apart.
_MARKERS = {"long_wave": ("|", -0.22, "first long-wave instability"),
            "full_zone": ("x", 0.22, "first full-zone instability (phonopy)")}


def paper_max_compression() -> dict[str, float]:
    """The paper's "maximum compressive strains" as d/d0 per potential (paper_values.yaml)."""
    claim = load_paper_values()["claims"]["max_compressive_strain"]["value"]
    return {pot: 1.0 - float(strain) for pot, strain in claim.items()}


def plot_stability_map(ds: xr.Dataset, path: str | Path) -> None:
    """One panel per potential; a coloured band per (loading, direction) over d/d0.

    Parameters
    ----------
    ds : xarray.Dataset
        From :func:`surfwave.model_crystals.stability_map.stability_map` (``state``, ``d_limit``
        and the d/d0 coordinate).
    path : str or Path
        PNG file to write.
    """
    import matplotlib.pyplot as plt
    from matplotlib.artist import Artist
    from matplotlib.colors import ListedColormap
    from matplotlib.lines import Line2D

    from surfwave.plots.output import savefig  # sets the Agg backend

    cmap = ListedColormap(["lightgrey", "tab:red", "tab:orange", "tab:green"])
    claim = paper_max_compression()
    pots = list(ds.potential.values)
    fig, axes = plt.subplots(len(pots), 1, figsize=(9, 2.2 + 2.2 * len(pots)), squeeze=False,
                             layout="constrained")
    x = ds.d_over_d0.values
    dx = x[1] - x[0] if x.size > 1 else 0.01
    cases = [(load, d) for load in ds.loading.values for d in ds.direction.values]
    for ax, pot in zip(axes[:, 0], pots):
        rows = [ds.state.sel(potential=pot, loading=load, direction=d).values for load, d in cases]
        ax.imshow(np.array(rows) + 1, aspect="auto", cmap=cmap, vmin=0, vmax=3, interpolation="nearest",
                  extent=(x[0] - dx / 2, x[-1] + dx / 2, len(rows) - 0.5, -0.5))
        for i, (load, d) in enumerate(cases):
            for kind, (mk, dy, _) in _MARKERS.items():
                for side in ("compression", "tension"):
                    v = float(ds.d_limit.sel(potential=pot, loading=load, direction=d, kind=kind, side=side))
                    if not np.isfinite(v):
                        continue
                    ax.plot(v, i + dy, mk, color="k", ms=8, mew=1.5)
                    if kind == "long_wave":
                        ax.annotate(f"{v:.4f}", (v, i + dy), textcoords="offset points", xytext=(4, 2),
                                    ha="left", va="bottom", fontsize=7)
        if str(pot) in claim:
            ax.axvline(claim[str(pot)], color="b", ls="--", lw=1.2,
                       label=f"paper: max compression {1 - claim[str(pot)]:.0%}")
            ax.legend(loc="lower right", fontsize=7)
        ax.axvline(1.0, color="k", lw=0.5)
        ax.set_yticks(range(len(cases)), [f"{load} {d}" for load, d in cases], fontsize=8)
        ax.set_title(f"FCC, {pot}", fontsize=10)
    axes[-1, 0].set_xlabel("d/d0 (stretch along propagation direction x)")
    handles: list[Artist] = [plt.Rectangle((0, 0), 1, 1, color=cmap(k)) for k in range(4)]
    labels = ["no geometry", "long-wave unstable", "short-wave only unstable", "stable"]
    for mk, _, label in _MARKERS.values():
        handles.append(Line2D([], [], ls="", marker=mk, color="k", ms=8, mew=1.5))
        labels.append(label)
    fig.legend(handles, labels, loc="outside upper center", ncol=3, fontsize=8, frameon=False)
    savefig(fig, path, dpi=120)
