"""Figures of the reproduction: Fig. 2 (sound speeds and c_R^2 versus stress) and helpers.

All functions read result cubes (paths or Datasets), draw with matplotlib's Agg backend and
write a PNG; they return the path written.

Examples
--------
>>> from surfwave.plots.speeds import fig2
>>> fig2("results/fig2/elastic.nc", "results/fig2/rayleigh.nc",
...      "results/fig2/speeds_vs_stress.png")  # doctest: +SKIP
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Iterable

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
import xarray as xr  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from numpy.typing import ArrayLike  # noqa: E402

from surfwave.data.cube import open_cube  # noqa: E402
from surfwave.plots.output import savefig  # noqa: E402

SPEED_UNITS = r"$K d_0^2/m$"
STRESS_LABEL = r"applied stress $\sigma^0_{xx} V/(K d_0^2)$"
from surfwave.plots.labels import POTENTIAL_NAMES, potential_label  # noqa: E402,F401

if TYPE_CHECKING:
    from matplotlib.axes import Axes

# quantity -> (legend label, colour, line width)
CURVES = {
    "c2_L_par": (r"$c_{L\parallel}^2$", "tab:blue", 1.2),
    "c2_T_par": (r"$c_{T\parallel}^2$", "tab:orange", 1.2),
    "c2_L_perp": (r"$c_{L\perp}^2$", "tab:green", 1.2),
    "c2_T_perp": (r"$c_{T\perp}^2$", "tab:red", 1.2),
    "c2_SH": (r"$c_{SH}^2$", "tab:gray", 1.0),
    "c2_R": (r"$c_R^2$ (Rayleigh)", "black", 2.2),
}
DIRECTION_STYLES = {"[100]": "-", "[110]": "--"}


def _dataset(obj) -> xr.Dataset | None:
    if obj is None or isinstance(obj, xr.Dataset):
        return obj
    return open_cube(obj) if Path(obj).is_file() else None


def curve_window(strain: np.ndarray, ok: np.ndarray | None,
                 stress: np.ndarray | None = None) -> tuple[np.ndarray, list[float]]:
    """Indices of the contiguous range around zero strain where ``ok`` holds and the stress
    rises with strain, plus one grid point beyond each end, and the strains midway to the
    first excluded points (the limits).

    Beyond a stress extremum the crystal cannot be held at a given stress, and a plot versus
    stress would fold back.

    Parameters
    ----------
    strain : ndarray, shape (n,)
    ok : ndarray of bool, shape (n,), or None (all fine)
    stress : ndarray, shape (n,), optional

    Returns
    -------
    (indices sorted by strain, list of limit strains)
    """
    order = np.argsort(strain)
    s = strain[order]
    ok = np.ones(s.size, bool) if ok is None else np.asarray(ok, bool)[order]
    i0 = int(np.argmin(np.abs(s)))
    if stress is not None:
        x = np.asarray(stress, float)[order]
        rising = np.concatenate([[True], np.diff(x) > 0])  # rising into point i from i-1
        for i in range(i0 + 1, s.size):
            ok[i] &= bool(rising[i]) and bool(ok[i - 1])
        for i in range(i0 - 1, -1, -1):
            ok[i] &= bool(rising[i + 1]) and bool(ok[i + 1])
    lo = i0
    while lo > 0 and ok[lo - 1]:
        lo -= 1
    hi = i0
    while hi < s.size - 1 and ok[hi + 1]:
        hi += 1
    limits = []
    if lo > 0:
        limits.append(0.5 * (s[lo - 1] + s[lo]))
    if hi < s.size - 1:
        limits.append(0.5 * (s[hi] + s[hi + 1]))
    return order[max(lo - 1, 0): hi + 2], limits


def _unstable_spans(x: np.ndarray, stable: np.ndarray) -> list[tuple[float, float]]:
    """Intervals of ``x`` (sorted) covered by unstable points, extended half a grid step."""
    order = np.argsort(x)
    x, ok = x[order], np.asarray(stable, bool)[order]
    spans, i = [], 0
    while i < x.size:
        if ok[i]:
            i += 1
            continue
        j = i
        while j + 1 < x.size and not ok[j + 1]:
            j += 1
        lo = x[i] if i == 0 else 0.5 * (x[i - 1] + x[i])
        hi = x[j] if j == x.size - 1 else 0.5 * (x[j] + x[j + 1])
        spans.append((float(lo), float(hi)))
        i = j + 1
    return spans


#: Curves closer than this (K d0^2/m, everywhere drawn) are one curve to the eye: drawn
#: dashed over each other and named together in the legend.
COINCIDE = 1e-9


def speeds_panel(ax: Axes, elastic: xr.Dataset, rayleigh: xr.Dataset | None, potential: str,
                 ymax: float = 1.6) -> set:
    """Draw sound speeds squared and c_R^2 versus stress for one potential on ``ax``.

    Bulk speeds come from ``elastic`` (c2_L_par, c2_T_par, c2_L_perp, c2_T_perp, c2_SH),
    c_R^2 from ``rayleigh``; [100] solid, [110] dashed. As in the paper, the curves run up
    to the shear instability (c_T,par^2 = 0) or the stress extremum (dotted lines, one grid
    point beyond drawn); where our full long-wave check finds the bulk lattice unstable
    (``stable`` False) the background is shaded grey. Points where ``wave_type`` is
    ``supersonic_decoupled`` are marked with open circles. A curve that coincides with one
    drawn before (c_SH^2 = c_T,par^2 along [100] under uniaxial stress: y and z are
    equivalent) is drawn with gaps so that both colours show.

    Returns
    -------
    set
        What was drawn, for the legend: curve names, directions, ``"supersonic"``,
        ``"limit"`` (dotted lines), ``"unstable"`` (shading) and ``("same", a, b)`` for
        coinciding curves.
    """
    drawn: set = set()
    el = elastic.sel(potential=potential)
    ra = None if rayleigh is None else rayleigh.sel(potential=potential)
    directions = [d for d in DIRECTION_STYLES if d in [str(v) for v in el["direction"].values]]
    xmin, xmax, edges, spans = np.inf, -np.inf, [], []
    for direction in directions:
        e = el.sel(direction=direction)
        stress = np.asarray(e["stress"].values, float)
        strain = np.asarray(e["strain"].values, float)
        shear_ok = np.asarray(e["c2_T_par"].values) > 0 if "c2_T_par" in e else None
        idx, limits = curve_window(strain, shear_ok, stress)
        xs = stress[idx]
        xmin, xmax = min(xmin, np.nanmin(xs)), max(xmax, np.nanmax(xs))
        srt = np.argsort(strain)
        edges += [float(np.interp(lim, strain[srt], stress[srt])) for lim in limits]
        if "stable" in e:
            spans += _unstable_spans(xs, np.asarray(e["stable"].values)[idx])
        ls = DIRECTION_STYLES[direction]
        drawn.add(direction)
        done: dict[str, np.ndarray] = {}
        for name, (_, colour, lw) in CURVES.items():
            if name == "c2_R":
                if ra is None:
                    continue
                y = np.asarray(ra.sel(direction=direction)["c2_R"].values, float)
            elif name in e:
                y = np.asarray(e[name].values, float)
            else:
                continue
            twin = next((o for o, yo in done.items() if yo.shape == y[idx].shape
                         and np.all(np.abs(yo - y[idx]) <= COINCIDE)), None)
            if twin is not None:  # on top of an earlier curve: gaps let that one show
                ax.plot(xs, y[idx], color=colour, lw=lw, dashes=(3, 3))
                drawn.add(("same", twin, name))
            else:
                ax.plot(xs, y[idx], ls=ls, color=colour, lw=lw)
            done[name] = y[idx]
            drawn.add(name)
            if name == "c2_R" and ra is not None and "wave_type" in ra:
                wt = np.asarray(ra.sel(direction=direction)["wave_type"].values).astype(str)[idx]
                m = np.flatnonzero(wt == "supersonic_decoupled")[::3]
                if m.size:
                    ax.plot(xs[m], y[idx][m], "o", mfc="white", mec=colour, ms=3.5, mew=0.8)
                    drawn.add("supersonic")
    pad = 0.03 * (xmax - xmin)
    ax.set_xlim(xmin - pad, xmax + pad)
    for lo, hi in spans:
        ax.axvspan(lo, hi, color="0.8", alpha=0.35, lw=0, zorder=0)
        drawn.add("unstable")
    for edge in edges:
        if xmin - pad <= edge <= xmax + pad:
            ax.axvline(edge, color="0.2", ls=":", lw=1.4)
            drawn.add("limit")
    ax.axhline(0, color="0.6", lw=0.6)
    ax.axvline(0, color="0.6", lw=0.6)
    ax.set_ylim(-0.05, ymax)
    ax.set_xlabel(STRESS_LABEL)
    ax.set_ylabel(f"sound speed squared $c^2$ ({SPEED_UNITS})")
    ax.set_title(potential_label(potential))
    ax.grid(alpha=0.3)
    return drawn


def _legend_handles(drawn: set) -> list:
    """Legend entries for exactly what :func:`speeds_panel` drew (union over the panels)."""
    # artists, and (artist, artist, label) triples of coinciding curves (drawn by HandlerTuple)
    handles: list[Any] = [Line2D([], [], color=c, lw=lw, label=lab) for name, (lab, c, lw) in CURVES.items()
               if name in drawn]
    for _, a, b in sorted(x for x in drawn if isinstance(x, tuple)):
        (la, ca, wa), (lb, cb, wb) = CURVES[a], CURVES[b]
        handles.append((Line2D([], [], color=ca, lw=wa), Line2D([], [], color=cb, lw=wb, dashes=(3, 3)),
                        f"{lb} = {la} (curves coincide)"))
    handles += [Line2D([], [], color="k", ls=ls, label=d) for d, ls in DIRECTION_STYLES.items() if d in drawn]
    if "supersonic" in drawn:
        handles.append(Line2D([], [], ls="none", marker="o", mfc="none", mec="k",
                              label="supersonic, decoupled by symmetry"))
    if "limit" in drawn:
        handles.append(Line2D([], [], color="0.2", ls=":", lw=1.4,
                              label="shear instability ($c_{T\\parallel}^2=0$) or stress extremum"))
    if "unstable" in drawn:
        handles.append(plt.Rectangle((0, 0), 1, 1, color="0.8", alpha=0.35,
                                     label="bulk lattice unstable (full long-wave check)"))
    return handles


def fig2(elastic: str | Path | xr.Dataset, rayleigh: str | Path | xr.Dataset | None, out_png: str | Path,
         title: str | None = None, ymax: float = 1.6) -> Path:
    """Fig. 2: sound speeds squared and c_R^2 versus in-plane stress, one panel per potential.

    Parameters
    ----------
    elastic, rayleigh : path or xr.Dataset
        Cubes of an FCC scene (dims potential, direction, strain); ``rayleigh`` may be
        missing (None or a non-existent path): then only bulk speeds are drawn.
    out_png : path
    title : str, optional
    ymax : float
        Upper y limit in K d0^2/m (longitudinal speeds under strong compression leave the
        frame; the interesting curves are below ~1.3).

    Returns
    -------
    Path of the PNG.
    """
    el, ra = _dataset(elastic), _dataset(rayleigh)
    if el is None:
        raise FileNotFoundError(f"no elastic cube at {elastic}")
    pots = [str(p) for p in el["potential"].values]
    order = [p for p in ("harmonic", "lj") if p in pots] + [p for p in pots if p not in ("harmonic", "lj")]
    ncol = 5 if len(order) > 1 else 3     # the legend spans the figure: as wide as the panels allow
    fig, axes = plt.subplots(1, len(order), figsize=(max(6.2 * len(order), 7.0), 5.0 if len(order) > 1 else 6.0),
                             squeeze=False, layout="constrained")
    drawn: set = set()
    for k, (ax, pot) in enumerate(zip(axes[0], order)):
        drawn |= speeds_panel(ax, el, ra, pot, ymax=ymax)
        ax.set_title(f"({chr(ord('a') + k)}) {ax.get_title()}")
    entries = _legend_handles(drawn)
    handles: list[Any] = [h if not isinstance(h, tuple) else h[:2] for h in entries]
    labels = [h.get_label() if not isinstance(h, tuple) else h[2] for h in entries]
    from matplotlib.legend_handler import HandlerTuple

    fig.legend(handles, labels, loc="outside lower center", ncol=ncol, frameon=False, fontsize=9,
               handler_map={tuple: HandlerTuple(ndivide=1, pad=0)})
    if title:
        fig.suptitle(title)
    return savefig(fig, out_png)


def table1_figure(csv_path: str | Path, out_png: str | Path) -> Path:
    """Ours - paper for every Table I entry (in units of the printed last digit)."""
    import csv

    rows = list(csv.DictReader(open(csv_path)))
    keys = list(dict.fromkeys(r["quantity"] for r in rows))
    fig, ax = plt.subplots(figsize=(8, 4))
    markers = "osD^vP*X"
    for n, k in enumerate(keys):
        sub = [r for r in rows if r["quantity"] == k and r["difference"]]
        offset = (n - (len(keys) - 1) / 2) * 0.0008  # spread the 8 columns within a row
        ax.plot([float(r["d_over_d0"]) + offset for r in sub],
                [float(r["difference"]) * 1e4 for r in sub], markers[n % len(markers)],
                ms=4, label=sub[0]["label"] if sub else k)
    ax.axhspan(-0.5, 0.5, color="tab:green", alpha=0.15, label="within printed rounding")
    ax.set_xlabel(r"in-plane spacing $d/d_0$")
    ax.set_ylabel(r"ours $-$ paper (units of $10^{-4}$)")
    ax.set_title("Table I: our values minus the printed ones")
    lim = max(0.7, *(abs(float(r["difference"])) * 1.1e4 for r in rows if r["difference"]))
    ax.set_ylim(-lim, lim)
    ax.legend(fontsize=8, loc="center left", bbox_to_anchor=(1.01, 0.5))
    ax.grid(alpha=0.3)
    return savefig(fig, out_png)


#: theta values of the Fig. 3 panels (the paper discusses pi/20, pi/8, ~1 and pi/2)
FIG3_THETA = (np.pi / 20, np.pi / 8, np.pi / 4, np.pi / 2)  # the paper's Fig. 3 (docs/physics/paper.md)
#: rows drawn in Fig. 3 (surface row 0 and the next 13: "noticeable nine layers deep")
FIG3_ROWS = 14


def nearest_indices(grid: ArrayLike, wanted: Iterable[float]) -> list[int]:
    """Sorted unique indices of the grid points nearest to each wanted value."""
    grid = np.asarray(grid, float)
    return sorted({int(np.argmin(np.abs(grid - w))) for w in wanted})


LOADING_TITLES = {"in_plane_hydrostatic": r"in-plane hydrostatic stress $\sigma_{xx}=\sigma_{zz}$",
                  "uniaxial": r"uniaxial stress $\sigma_{xx}$ along the propagation direction"}
