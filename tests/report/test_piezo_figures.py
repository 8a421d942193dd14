"""Piezoelectric figures of a user scene fit their page: titles and labels inside the image, the
x axis fitted to the swept range (not 0-180 deg for a 30-50 deg scene), legends clear of the
curves (one figure legend outside every panel).

Reference: the rendered matplotlib figure itself (artist extents after a draw), for a tiny
scene computed by surfwave.real_crystals.piezo_sweep.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.plots import piezo
from surfwave.real_crystals.piezo_sweep import piezo_wave_sweep


@pytest.fixture
def drawn(monkeypatch, tmp_path):
    """Draw with the project's savefig replaced by one that keeps the figure (drawn, not closed)."""
    figs = []

    def keep(fig, path, dpi=150):
        fig.canvas.draw()
        figs.append(fig)
        return path

    monkeypatch.setattr(piezo, "savefig", keep)
    return figs


def _inside(fig, artist) -> bool:
    box = artist.get_window_extent(fig.canvas.get_renderer())
    w, h = fig.canvas.get_width_height()
    return box.x0 >= -0.5 and box.y0 >= -0.5 and box.x1 <= w + 0.5 and box.y1 <= h + 0.5


@pytest.mark.parametrize("thetas, full", [(np.arange(-60, -39, 10), False), (np.arange(-90, 91, 45), True)])
def test_single_panel_rotated_cut_figure_fits(drawn, tmp_path, thetas, full):
    ds = piezo_wave_sweep(["LiNbO3"], euler={"phi": 0, "theta": [float(t) for t in thetas], "psi": 0})
    piezo.speeds_vs_euler(ds, tmp_path / "a.png", title="scene my_cuts_with_a_long_name")
    fig = drawn[0]
    axes = fig.axes
    texts = [fig._suptitle, *(ax.title for ax in axes), *(ax.xaxis.label for ax in axes), *(ax.yaxis.label
                                                                                           for ax in axes)]
    for t in texts:
        if t is not None and t.get_text():
            assert _inside(fig, t), t.get_text()
    lo, hi = axes[-1].get_xlim()
    x = thetas + 90.0
    assert (lo, hi) == ((0.0, 180.0) if full else (x.min(), x.max()))
    assert all(ax.get_legend() is None for ax in axes)        # no legend over the curves
    (legend,) = fig.legends
    r = fig.canvas.get_renderer()
    lb = legend.get_window_extent(r)
    assert _inside(fig, legend)
    assert all(not lb.overlaps(ax.get_window_extent(r)) for ax in axes)


def test_stress_figure_marks_the_third_order_model_with_dots(drawn, tmp_path):
    """Free lines solid, metallized dashed; the third-order model's lines carry dots on the same
    line style (the format "-." drew a dash-dot line instead)."""
    ds = piezo_wave_sweep(["GaAs"], euler={"phi": 45, "theta": 0, "psi": 0}, stress=[-0.5, 0.0, 0.5],
                          toec=[False, True])
    piezo.speeds_vs_stress(ds, tmp_path / "s.png")
    lines = {ln.get_label(): ln for ln in drawn[0].axes[0].get_lines() if not ln.get_label().startswith("_")}
    assert len(lines) == 4
    for label, ln in lines.items():
        assert ln.get_linestyle() == ("-" if ", free," in label else "--"), label
        assert ln.get_marker() == ("." if "third-order" in label else "None"), label
