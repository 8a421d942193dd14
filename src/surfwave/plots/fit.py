"""The figure of a film fit: measured points with the fitted curve, residuals, parameter table.

Drawn from a :class:`surfwave.metrology.fit.FitResult` alone (it carries the data, the fitted
curve and the table), so the figure never recomputes physics.
"""
from __future__ import annotations

import math
import textwrap
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib.transforms import Bbox  # noqa: E402

from surfwave.plots.output import savefig  # noqa: E402

__all__ = ["noise_line", "plot_fit"]

_UNITS = {"mu": "GPa", "E": "GPa", "substrate_mu": "GPa", "stress": "GPa", "nu": "", "rho": "kg/m³",
          "substrate_rho": "kg/m³", "thickness": "m"}
_X_LABELS = {"kh": r"$kh$ (wavenumber × film thickness)", "frequency_Hz": "frequency (MHz)"}


def _value(v: float, s: float) -> str:
    """value ± uncertainty with two significant digits of the uncertainty."""
    if not math.isfinite(s):
        return f"{v:.5g} ± ∞"
    if s <= 0 or abs(v) >= 1e6 or abs(v) < 1e-3:
        return f"{v:.5g} ± {s:.2g}"
    d = max(0, 1 - int(math.floor(math.log10(s))))
    return f"{v:.{d}f} ± {s:.{d}f}"


def noise_line(r) -> str:
    """chi^2 and the basis of the uncertainties, in words (for the figure and the CLI)."""
    if r["noise"] == "sigma":
        return (f"χ² = {r['chi2']:.4g}, dof = {r['dof']}, χ²/dof = {r['reduced_chi2']:.3g}"
                + (f", p = {r['p_value']:.2g}" if math.isfinite(r["p_value"]) else "")
                + "; uncertainties from the given σ")
    s = math.sqrt(r["reduced_chi2"]) if math.isfinite(r["reduced_chi2"]) else math.nan
    est = f"{100 * s:.3g} % of c" if r["noise"] == "relative" else f"{s:.3g} m/s"
    return f"no σ given: noise estimated from the scatter {est} (dof = {r['dof']}); uncertainties scaled by it"


def plot_fit(result, path: str | Path | None = None, *, title: str | None = None):
    """Draw data + fit, residuals and the parameter table of a fit.

    Parameters
    ----------
    result : FitResult
        From :func:`surfwave.fit_film` or :func:`surfwave.metrology.fit.fit`.
    path : str or Path, optional
        Write a PNG there (and close the figure); otherwise return the open figure.
    title : str, optional
        Default: the model in words.

    Returns
    -------
    matplotlib.figure.Figure or Path
        The figure, or the path written.
    """
    r = result
    freq = r["x_name"] == "frequency_Hz"
    sx = 1e-6 if freq else 1.0
    x, c = np.asarray(r["x"]) * sx, np.asarray(r["c"])
    sigma = np.asarray(r["sigma"])
    fig = plt.figure(figsize=(11.0, 6.2), layout="constrained")
    gs = fig.add_gridspec(2, 2, height_ratios=[3, 1.3], width_ratios=[1.6, 1])
    ax = fig.add_subplot(gs[0, 0])
    axr = fig.add_subplot(gs[1, 0], sharex=ax)
    axt = fig.add_subplot(gs[:, 1])
    given = r["uncertainty_basis"] == "sigma"
    lab = "measured (±1σ given)" if given else "measured (±1σ estimated from the scatter)"
    ax.errorbar(x, c, yerr=sigma, fmt="o", ms=4, color="k", ecolor="0.5", capsize=2, label=lab, zorder=3)
    if np.size(r["curve_x"]):
        ax.plot(np.asarray(r["curve_x"]) * sx, r["curve_c"], "-", color="tab:red", lw=1.6, label="fit", zorder=2)
    ax.set_ylabel("phase speed c (m/s)")
    ax.legend(loc="best", fontsize=9)
    ax.grid(alpha=0.3)
    ax.tick_params(labelbottom=False)
    res = np.asarray(r["residuals"])
    axr.axhline(0.0, color="tab:red", lw=1)
    order = np.argsort(x)
    axr.fill_between(x[order], -sigma[order], sigma[order], color="0.85", label="±1σ", step="mid")
    axr.plot(x, res, "o", ms=4, color="k")
    axr.set_ylabel("fit − data (m/s)")
    axr.set_xlabel(_X_LABELS.get(r["x_name"], r["x_name"]))
    axr.grid(alpha=0.3)
    axr.legend(loc="upper right", fontsize=8)
    axt.axis("off")
    rows = []
    for k in r["names"]:
        f, unit = (1e6, "µm") if k == "thickness" else (1.0, _UNITS.get(k, "GPa" if k.startswith("C") else ""))
        rows.append([k, _value(f * r["values"][k], f * r["uncertainties"][k]), unit])
    height = 0.07 * (len(rows) + 1)
    tab = axt.table(cellText=rows, colLabels=["parameter", "value ± 1σ", "unit"], loc="upper center",
                    cellLoc="left", colLoc="left", bbox=Bbox.from_bounds(0.0, 1.0 - height, 1.0, height))
    tab.auto_set_font_size(False)
    tab.set_fontsize(9)
    lines = []
    n = len(r["names"])
    if n > 1:
        pairs = [(r["names"][i], r["names"][j], r["correlation"][i, j]) for i in range(n) for j in range(i + 1, n)]
        lines.append("correlations: " + ", ".join(
            f"{a}–{b} {v:+.3f}" if math.isfinite(v) else f"{a}–{b} n/a" for a, b, v in pairs))
    lines.append(noise_line(r))
    fixed = [f"{k} = {v:.5g} {_UNITS.get(k, '')}".rstrip() for k, v in r["values"].items() if k not in r["names"]]
    lines.append(f"rms residual {float(np.sqrt(np.mean(res ** 2))):.3g} m/s, {r['x'].size} points")
    if fixed:
        lines.append("fixed: " + ", ".join(fixed))
    for w in r["warnings"]:
        lines.append("⚠ " + w)
    text = "\n".join(textwrap.fill(t, 58, subsequent_indent="   ") for t in lines)
    axt.text(0.0, 1.0 - height - 0.04, text, va="top", ha="left", fontsize=8.5,
             transform=axt.transAxes)
    fig.suptitle(title if title is not None else r["model"], fontsize=11)
    if path is None:
        return fig
    return savefig(fig, path)
