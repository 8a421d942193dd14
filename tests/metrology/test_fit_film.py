"""surfwave.fit_film, the front door of the inverse problem.

References: synthetic data from the closed-form Love wave (surfwave.metrology.love, itself checked
against finite elements in test_love_waves.py); physical limits of the parameters (moduli and
densities > 0, -1 < nu < 0.5).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.metrology.love import love_speed

FILM = {"mu": 31.2, "rho": 2200.0, "thickness": 1.0e-6}
SUB = {"mu": 66.25, "rho": 2650.0}
P = {**FILM, "substrate_mu": 66.25, "substrate_rho": 2650.0}


def test_four_parameters_from_frequency_data_and_the_scaling_degeneracy():
    """Film (mu, rho, thickness) and substrate mu from 50 noiseless points of one mode against frequency:
    recovered to 1e-6 from 10 % off. Freeing the substrate density too makes the problem degenerate: scaling
    every modulus and density by the same factor leaves b1, b2 and mu_s/mu, hence c, unchanged; the fitter
    must say that these four are not separable and report infinite uncertainties."""
    f = np.linspace(2e7, 3e9, 50)
    c = love_speed(f, P, variable="frequency")
    start = {"mu": 34.0, "rho": 2000.0, "thickness": 1.1e-6}
    free = ["mu", "rho", "thickness", "substrate_mu"]
    r = surfwave.fit_film(f, c, model="love", film=start, substrate={"mu": 60.0, "rho": 2650.0}, free=free,
                          variable="frequency", sigma=1.0)
    for k in free:
        assert r["values"][k] == pytest.approx(P[k], rel=1e-6), k
        assert 0 < r["uncertainties"][k] < np.inf
    assert r["x_name"] == "frequency_Hz" and r["model"].startswith("Love mode 0")
    r = surfwave.fit_film(f, c, model="love", film=start, substrate={"mu": 60.0, "rho": 2800.0},
                          free=free + ["substrate_rho"], variable="frequency", sigma=1.0)
    assert r["chi2"] < 1e-12 and np.isinf(r["condition_number"])
    assert r["uncertainties"]["mu"] == np.inf and np.isfinite(r["uncertainties"]["thickness"])
    assert any(w.startswith("mu, rho, substrate_mu and substrate_rho are not separable") for w in r["warnings"])
    ratio = [r["values"][k] / P[k] for k in ("mu", "rho", "substrate_mu", "substrate_rho")]
    np.testing.assert_allclose(ratio, ratio[0], rtol=1e-6)  # the fit moved along the scaling only


def test_e_and_nu_film_and_warning_context():
    """(E, nu) of the film: a Love wave sees only mu = E / 2(1 + nu), so fitting both is refused in words that
    name the data (one mode, its kh range)."""
    kh = np.linspace(0.05, 0.3, 15)
    c = love_speed(kh, {"E": 73.0, "nu": 0.17, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0})
    r = surfwave.fit_film(kh, c, model="love", film={"E": 70.0, "nu": 0.17, "rho": 2200.0}, substrate=SUB,
                          free=["E", "nu"], sigma=1.0)
    assert any(w.startswith("E and nu are not separable from one mode (Love mode 0) at kh 0.05-0.3") for w in r["warnings"])
    r = surfwave.fit_film(kh, c, model="love", film={"E": 70.0, "nu": 0.17, "rho": 2200.0}, substrate=SUB,
                          free=["E", "rho"], sigma=1e-3 * c)
    assert any(w.startswith("E and rho are not separable from one mode (Love mode 0) at kh 0.05-0.3")
               and "fix one" in w for w in r["warnings"])


def test_bounds_keep_parameters_physical():
    """Default bounds: nu stays in (-1, 0.5); a starting value outside the bounds is refused."""
    kh = np.linspace(0.2, 5, 15)
    c = love_speed(kh, P)
    r = surfwave.fit_film(kh, c * 1.02, model="love", film={"E": 70.0, "nu": 0.3, "rho": 2200.0}, substrate=SUB,
                          free=["nu"], sigma=1.0)
    assert -1 < r["values"]["nu"] < 0.5
    with pytest.raises(InputError, match="outside its bounds"):
        surfwave.fit_film(kh, c, model="love", film=FILM, substrate=SUB, free=["mu"], bounds={"mu": (40.0, 50.0)})


@pytest.mark.parametrize("kw, text", [
    (dict(model="lovely"), "model must be"),
    (dict(film={"mu": 31.2}), "film as"),
    (dict(film={"mu": 31.2, "rho": -1.0}), "must be > 0"),
    (dict(film={"E": 70.0, "nu": 0.6, "rho": 2200.0}, free=["E"]), "Poisson"),
    (dict(substrate="Si"), "isotropic mapping"),
    (dict(free=["C11"]), "not in the Love model"),
    (dict(free=[]), "at least one"),
    (dict(variable="frequency", film={"mu": 31.2, "rho": 2200.0}), "thickness"),
    (dict(film={"mu": 31.2, "rho": 2200.0, "thickness": float("nan")}), "thickness"),
    (dict(mode=-1), "mode"),
    (dict(film=dict(FILM, stress=-0.5)), "unstressed"),
    (dict(film=[FILM, FILM]), "one film"),
])
def test_bad_input_is_one_line(kw, text):
    args = dict(model="love", film=FILM, substrate=SUB, free=["mu"]) | kw
    with pytest.raises(InputError, match=text):
        surfwave.fit_film(np.linspace(0.2, 5, 10), np.full(10, 4500.0), **args)


def test_negative_x_refused():
    with pytest.raises(InputError, match=">= 0"):
        surfwave.fit_film([-1.0, 1.0, 2.0], [4000.0, 4000, 4000], model="love", film=FILM, substrate=SUB, free=["mu"])


def test_points_of_two_modes_in_one_fit():
    """Points of Love modes 0 and 1 fitted together: the truth to 1e-8 from exact data, the curves of both modes
    (NaN between them) in the result, and refusals of a mode list of the wrong length or of negative modes."""
    kh0, kh1 = np.linspace(0.3, 8, 20), np.linspace(3.8, 8, 12)
    c = np.r_[love_speed(kh0, P), love_speed(kh1, P, mode=1)]
    modes = [0] * 20 + [1] * 12
    r = surfwave.fit_film(np.r_[kh0, kh1], c, model="love", film={"mu": 28.0, "rho": 2300.0}, substrate=SUB,
                          free=["mu", "rho"], mode=modes, sigma=1e-3 * c)
    assert r["values"]["mu"] == pytest.approx(31.2, rel=1e-8) and r["values"]["rho"] == pytest.approx(2200, rel=1e-8)
    assert r["model"].startswith("Love modes 0, 1") and any("from 2 modes (Love modes 0, 1)" in w for w in r["warnings"])
    gap = np.flatnonzero(np.isnan(r["curve_x"]))
    assert gap.size == 1 and np.all(np.diff(r["curve_x"][gap[0] + 1:]) > 0)
    np.testing.assert_allclose(r["curve_c"][gap[0] + 1:], love_speed(r["curve_x"][gap[0] + 1:], P, mode=1))
    for bad, text in (([0] * 5, "one per point"), ([0] * 31 + [-1], "integer >= 0")):
        with pytest.raises(InputError, match=text):
            surfwave.fit_film(np.r_[kh0, kh1], c, model="love", film=FILM, substrate=SUB, free=["mu"], mode=bad)
