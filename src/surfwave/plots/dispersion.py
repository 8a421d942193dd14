"""Figures of the triangular-lattice surface waves (matplotlib, Agg backend, PNG files).

Every function takes either the dict returned by :func:`surfwave.dynamics.dispersion.solve` /
:func:`surfwave.dynamics.dispersion.displacements` together with the coordinates (``d_over_d0``,
``theta``), or an xarray Dataset holding the same variables with coordinates ``theta`` and
``d_over_d0`` (or ``strain`` = d/d0 - 1) and no other dimension (select a potential first),
plus the output path. They return the path written.
"""
from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Sequence

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.collections import LineCollection  # noqa: E402
from numpy.typing import ArrayLike  # noqa: E402

from surfwave.errors import InputError  # noqa: E402
from surfwave.plots.labels import OMEGA, THETA_OVER_PI, potential_label  # noqa: E402
from surfwave.plots.output import savefig  # noqa: E402
from surfwave.validate import as_1d  # noqa: E402

if TYPE_CHECKING:
    import xarray as xr


def _get(data, name: str):
    if isinstance(data, dict):
        if name not in data:
            raise InputError(f"missing {name!r} in the data; have {sorted(data)}")
        return np.asarray(data[name])
    if name in data.variables:
        return np.asarray(data[name].values)
    raise InputError(f"missing {name!r} in the Dataset; have {sorted(data.variables)}")


def _coords(data, d_over_d0=None, theta=None):
    """(d_over_d0 (n,), theta (m,)) from the arguments, dict keys or Dataset coordinates."""
    if isinstance(data, dict):
        d_over_d0 = data.get("d_over_d0", d_over_d0) if d_over_d0 is None else d_over_d0
        theta = data.get("theta", theta) if theta is None else theta
    if d_over_d0 is None and not isinstance(data, dict):
        if "d_over_d0" in data.variables:
            d_over_d0 = data["d_over_d0"].values
        elif "strain" in data.coords:
            d_over_d0 = 1.0 + data["strain"].values
    if theta is None and not isinstance(data, dict) and "theta" in data.coords:
        theta = data["theta"].values
    if d_over_d0 is None or theta is None:
        raise InputError("pass d_over_d0 and theta (or a Dataset with those coordinates)")
    return as_1d(d_over_d0), as_1d(theta, "theta")


def _save(fig, path) -> Path:
    return savefig(fig, path, dpi=130)


def plot_dispersion(data: xr.Dataset | dict[str, Any], path: str | Path, *, d_over_d0: ArrayLike | None = None,
                    theta: ArrayLike | None = None, numerical: xr.Dataset | dict[str, Any] | None = None,
                    max_curves: int = 5, title: str = "") -> Path:
    """omega(theta) of the surface wave at several strains with the bulk band edges.

    Parameters
    ----------
    data : dict or xarray.Dataset
        ``omega``, ``omega_L``, ``omega_T`` of shape (strain, theta), (K/m)^(1/2); optional
        ``omega_bulk_min`` (bottom of the bulk continuum) and ``omega_lattice`` (numerical check).
    path : str or Path
        PNG file to write.
    d_over_d0, theta : array_like, shapes (n,), (m,), optional with a Dataset.
    numerical : dict, optional
        Output of :func:`surfwave.dynamics.triangular_surface.surface_mode` on the same grid (its
        ``omega_lattice`` is drawn as markers and ``omega_bulk_min`` shades the continuum).
    max_curves : int
        At most this many strains are drawn (evenly picked; among the strains the lattice
        dynamics checked, where ``omega_lattice`` is given, so every panel has its markers).
    """
    d, th = _coords(data, d_over_d0, theta)
    omega, wl, wt = _get(data, "omega"), _get(data, "omega_L"), _get(data, "omega_T")
    bottom = lattice = None
    src = numerical if numerical is not None else data
    names = src if isinstance(src, dict) else src.variables
    if "omega_bulk_min" in names:
        bottom = _get(src, "omega_bulk_min")
    if "omega_lattice" in names:
        lattice = _get(src, "omega_lattice")
    rows = np.arange(d.size)
    if lattice is not None and np.isfinite(lattice).any():  # draw checked strains (markers)
        rows = rows[np.isfinite(np.asarray(lattice, dtype=float)).reshape(d.size, -1).any(axis=1)]
    pick = rows[np.unique(np.linspace(0, rows.size - 1, min(max_curves, rows.size)).round().astype(int))]
    fig, axes = plt.subplots(1, len(pick), figsize=(3.2 * len(pick), 3.4), sharey=True, squeeze=False,
                             layout="constrained")
    for ax, i in zip(axes[0], pick):
        x = th / np.pi
        if bottom is not None:
            ax.fill_between(x, bottom[i], np.nanmax(wl) * 1.05, color="0.9", label="bulk continuum")
        ax.plot(x, wl[i], "C1--", lw=1, label=r"$\omega_L$ (Eq. 4a)")
        ax.plot(x, wt[i], "C2--", lw=1, label=r"$\omega_T$ (Eq. 4a)")
        ax.plot(x, omega[i], "C0-", lw=1.8, label=r"$\omega = (c_R/d_x)\sin\theta$")
        if lattice is not None:
            every = max(1, th.size // 25)
            ax.plot(x[::every], lattice[i, ::every], "k.", ms=4, label="lattice dynamics")
        ax.set_title(rf"$d/d_0 = {d[i]:.3g}$", fontsize=9)
        ax.set_xlabel(THETA_OVER_PI)
        ax.set_xlim(0, 1)
    axes[0, 0].set_ylabel(OMEGA)
    axes[0, 0].legend(fontsize=7, loc="upper left")
    if title:
        fig.suptitle(title, fontsize=10)
    return _save(fig, path)


def _identical_potentials(data, potential, i) -> list[str]:
    """Other potentials of ``data`` whose u, v at strain index ``i`` equal ``potential``'s."""
    if isinstance(data, dict) or "potential" not in getattr(data, "dims", ()):
        return []
    ref = data.sel(potential=potential)
    same = []
    for other in data["potential"].values:
        if str(other) == str(potential):
            continue
        o = data.sel(potential=other)
        if all(np.allclose(np.asarray(o[n].values)[i], np.asarray(ref[n].values)[i], rtol=0, atol=1e-9)
               for n in ("u", "v")):
            same.append(str(other))
    return same


def plot_displacements(data: xr.Dataset | dict[str, Any], path: str | Path, *, d_over_d0: ArrayLike | None = None,
                       theta: ArrayLike | None = None, strain_index: int | None = None, n_columns: int = 6,
                       scale: float = 0.35, title: str = "", potential: str | None = None) -> Path:
    """Fig. 3 of the paper: displacement patterns of the surface wave, one panel per theta.

    Atoms of rows I = 0 (surface, top) downwards sit at x = (I + 2J) d_x, y = I d_y (grey
    crosses); each atom's trajectory Re[(u_I, v_I) exp(i theta (I + 2J) - i omega t)] over one
    period is drawn as an ellipse, magnified so that the largest amplitude (1 by the
    normalisation of :func:`surfwave.dynamics.dispersion.displacements`) is ``scale`` d0 long
    (scale bar in the first panel); y into the crystal is drawn downwards; the dot marks
    t = 0. Rows are labelled on the left axis, x along the surface in units of d0 below.

    Parameters
    ----------
    data : dict or xarray.Dataset
        ``u``, ``v`` of shape (strain, theta, row) (from
        :func:`surfwave.dynamics.dispersion.displacements`), or a Dataset with a
        ``potential`` dimension together with ``potential``.
    path : str or Path
    d_over_d0, theta : array_like, optional with a Dataset.
    strain_index : int, optional
        Which strain to draw; default the one closest to d/d0 = 1 (zero stress, as the paper).
    n_columns : int
        Atoms per row drawn.
    scale : float
        Drawn length (units of d0) of a unit displacement.
    title : str, optional
        Default: "Fig. 3: ... <potential>, d/d0 = ...".
    potential : str, optional
        With a Dataset over potentials: the one to draw. The figure then says which other
        potentials give the identical pattern (at zero stress only K = phi''(d0) enters).
    """
    full = data
    if potential is not None and not isinstance(data, dict) and "potential" in data.dims:
        data = data.sel(potential=potential)
    elif potential is None and not isinstance(data, dict) and "potential" in data.coords \
            and data["potential"].ndim == 0:
        potential = str(data["potential"].values)
    d, th = _coords(data, d_over_d0, theta)
    u, v = _get(data, "u"), _get(data, "v")
    i = int(np.argmin(np.abs(d - 1.0))) if strain_index is None else strain_index
    dx, dy = 0.5 * d[i], np.sqrt(1 - (0.5 * d[i]) ** 2)
    rows = np.arange(u.shape[-1])
    width = 2 * dx * n_columns
    height = (rows[-1] + 1.2) * dy
    panel_w = 2.3
    fig, axes = plt.subplots(1, th.size, figsize=(panel_w * th.size + 0.6, panel_w * height / (width + 0.6) + 1.5),
                             sharey=True, squeeze=False, layout="constrained")
    t = np.linspace(0, 2 * np.pi, 41)
    for n, (ax, k) in enumerate(zip(axes[0], range(th.size))):
        # atoms with 0 <= x < width in every row (J shifted so that the panel is rectangular)
        I = np.repeat(rows, n_columns + 1)
        JJ = np.tile(np.arange(n_columns + 1), rows.size) - (I + 1) // 2
        x, y = (I + 2 * JJ) * dx, I * dy
        keep = (x > -1e-9) & (x < width - 1e-9)
        I, JJ, x, y = I[keep], JJ[keep], x[keep], y[keep]
        phase = np.exp(1j * th[k] * (I + 2 * JJ))
        cu, cv = u[i, k][I] * phase, v[i, k][I] * phase
        # trajectory over one period (ellipse) and the position at t = 0 (dot)
        tx = x[:, None] + scale * (cu[:, None] * np.exp(-1j * t)).real
        ty = -y[:, None] - scale * (cv[:, None] * np.exp(-1j * t)).real
        ax.plot(x, -y, "+", color="0.55", ms=4, mew=0.8, label="equilibrium site")
        # one segment per site, shape (sites, times, 2); the stubs want a sequence, the array is one
        ax.add_collection(LineCollection(np.stack([tx, ty], axis=-1),  # type: ignore[arg-type]
                                         colors="C0", linewidths=0.8,
                                         label=f"trajectory over one period (amplitude 1 drawn as {scale:g} $d_0$)"))
        ax.plot(tx[:, 0], ty[:, 0], "o", color="C3", ms=2.5, label="position at $t = 0$")
        ax.set_title(rf"$\theta = k d_x = {th[k] / np.pi:.3g}\,\pi$", fontsize=10)
        ax.set_aspect("equal")
        ax.set_xlim(-0.5, width)
        ax.set_ylim(-(rows[-1] + 0.8) * dy, 1.25)
        ax.set_xlabel(r"$x / d_0$ along the surface")
        ax.tick_params(labelsize=8)
        if n == 0:  # displacement scale bar: the largest amplitude (1) as drawn
            x0, y0 = 0.0, 0.85
            ax.plot([x0, x0 + scale], [y0, y0], "k-", lw=2)
            ax.text(x0 + scale + 0.15, y0, "scale: amplitude 1", ha="left", va="center", fontsize=7)
    step = max(1, rows.size // 8)
    axes[0, 0].set_yticks(-rows[::step] * dy)
    axes[0, 0].set_yticklabels(["0 (surface)"] + [str(r) for r in rows[::step][1:]])
    axes[0, 0].set_ylabel("row below the surface")
    handles, labels = axes[0, 0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, frameon=False, fontsize=8)
    who = potential_label(potential) if potential is not None else ""
    stress = "zero stress" if abs(d[i] - 1.0) < 1e-12 else f"$d/d_0 = {d[i]:.3g}$"
    head = title or f"Fig. 3: surface-wave displacements, triangular lattice, {who + ', ' if who else ''}{stress}"
    same = _identical_potentials(full, potential, i) if potential is not None else []
    if same:
        head += ("\nidentical for " + ", ".join(potential_label(p) for p in same)
                 + r": at zero stress only $K = \phi''(d_0)$ enters, the same for every potential"
                 if abs(d[i] - 1.0) < 1e-12 else "\nidentical for " + ", ".join(map(potential_label, same)))
    fig.suptitle(head, fontsize=10)
    return _save(fig, path)


def plot_theta_c(data: xr.Dataset | dict[str, Any] | Sequence[xr.Dataset | dict[str, Any]], path: str | Path, *,
                 d_over_d0: ArrayLike | None = None, title: str = "",
                 potential_labels: Sequence[str | None] | None = None) -> Path:
    """Crossover theta_c (q complex above it) against d/d0.

    Parameters
    ----------
    data : dict, xarray.Dataset, or a list of them (one curve each, e.g. per potential)
        Holding ``theta_c`` of shape (strain,) (a dict may also hold ``d_over_d0``).
    path : str or Path
    d_over_d0 : array_like, shape (n,), optional with a Dataset.
    potential_labels : list of str, optional
        Legend labels when ``data`` is a list.
    """
    items = data if isinstance(data, (list, tuple)) else [data]
    labels = potential_labels or [None] * len(items)
    fig, ax = plt.subplots(figsize=(4.5, 3.4), layout="constrained")
    for item, label in zip(items, labels):
        d, _ = _coords(item, d_over_d0, theta=[0.0])
        ax.plot(d, _get(item, "theta_c") / np.pi, ".-", label=potential_label(label) if label else None)
    ax.axhline(1 / 8, color="0.5", lw=0.8, ls=":", label=r"$\pi/8$ (paper, zero stress)")
    ax.set_xlabel(r"$d/d_0 = 2 d_x/d_0$")
    ax.set_ylabel(r"$\theta_c / \pi$")
    ax.legend(fontsize=8)
    if title:
        ax.set_title(title, fontsize=10)
    return _save(fig, path)
