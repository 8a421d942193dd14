"""The fit figure (surfwave.plots.fit): drawn from the fit result alone.

Reference: the result it is given (points, curve, residuals, table rows must be the result's).
"""
from __future__ import annotations

import numpy as np

import surfwave
from surfwave.metrology.love import love_speed
from surfwave.plots.fit import plot_fit


def test_figure_shows_the_result(tmp_path):
    kh = np.linspace(0.2, 5, 15)
    c = love_speed(kh, {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0})
    c = c * (1 + 1e-3 * np.random.default_rng(0).standard_normal(kh.size))
    r = surfwave.fit_film(kh, c, model="love", film={"mu": 30.0, "rho": 2200.0}, substrate={"mu": 66.25, "rho": 2650.0},
                          free=["mu", "substrate_mu"])
    fig = plot_fit(r)
    ax, axr, axt = fig.axes
    line = [ln for ln in ax.get_lines() if ln.get_label() == "fit"][0]
    np.testing.assert_array_equal(line.get_ydata(), r["curve_c"])
    np.testing.assert_allclose(axr.get_lines()[-1].get_ydata(), r["residuals"])
    cells = [t.get_text().get_text() for t in axt.tables[0].get_celld().values()]
    v, s = (float(t) for t in cells[cells.index("mu") + 1].split(" ± "))
    assert abs(v - r["values"]["mu"]) <= 0.01 * s + 1e-9 * v and abs(s / r["uncertainties"]["mu"] - 1) < 0.03
    text = axt.texts[0].get_text()
    assert "noise estimated from the scatter" in text and "fixed: rho = 2200 kg/m³, substrate_rho = 2650" in text
    path = plot_fit(r, tmp_path / "fit.png")
    assert path.stat().st_size > 10_000
