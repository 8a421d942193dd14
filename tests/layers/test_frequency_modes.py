"""Named modes at given frequencies, their families and modes alone (surfwave.layers.frequency.mode_speeds_at_frequency).

References: surfwave.layered(frequency=...) (every mode of every family, each solved on its own: the numbers must
be identical); and the kh route, surfwave.layers.solve.mode_speeds at kh = 2 pi f H / c (a different search: no
start curve, no Newton in kh), which must give back c to 2e-12 (the Newton iteration stops at steps of 1e-11 kh).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.layers.frequency import mode_speeds_at_frequency
from surfwave.layers.solve import mode_speeds
from surfwave.layers.stack import resolve_stack

FILM = {"E": 70.0, "nu": 0.17, "rho": 2200.0, "thickness": 1.0e-6, "stress": -0.3}
UNDER = {"E": 200.0, "nu": 0.24, "rho": 3200.0, "thickness": 3.0e-7}


def column(result, lab):
    """The speed of mode ``lab`` per row of a layered() result (NaN where absent)."""
    return np.array([row_c[list(row_m).index(lab)] if lab in list(row_m) else np.nan
                     for row_c, row_m in zip(result["c"], result["mode"])])


@pytest.mark.parametrize("films, labels", [([FILM], ["R", "S1", "L0", "L1"]), ([FILM, UNDER], ["R"])])
def test_same_numbers_as_layered_at_frequency(films, labels):
    """SiO2-like film(s) on Si (001), 12 frequencies 0.1-2 GHz: R, S1 (cut off below ~1 GHz), L0 and L1 (absent)
    equal layered(frequency=)'s columns bit for bit, NaN at the same points; a per-point list of labels too."""
    f = np.linspace(1e8, 2e9, 12)
    full = surfwave.layered("Si", films, frequency=f)
    stack = resolve_stack("Si", films)
    for lab in labels:
        np.testing.assert_array_equal(mode_speeds_at_frequency(stack, f, lab), column(full, lab))
    mixed = ["R", "L0"] * 6 if len(films) == 1 else ["R"] * 12
    want = np.array([column(full, lab)[i] for i, lab in enumerate(mixed)])
    np.testing.assert_array_equal(mode_speeds_at_frequency(stack, f, mixed), want)


def test_agrees_with_the_kh_route():
    """c of R and S1 at frequency f equals the kh search's speed at kh = 2 pi f H / c (2e-12)."""
    f = np.linspace(2e8, 2e9, 8)
    stack = resolve_stack("Si", [FILM])
    for lab in ("R", "S1"):
        c = mode_speeds_at_frequency(stack, f, lab)
        ok = np.isfinite(c)
        assert ok.sum() >= 3
        kh = 2 * np.pi * f[ok] * FILM["thickness"] / c[ok]
        np.testing.assert_allclose(mode_speeds(stack, kh, lab), c[ok], rtol=2e-12)


def test_layered_model_at_frequency_takes_the_short_route():
    """The fitter's forward model at frequency (mode by label) gives layered(frequency=)'s numbers without calling
    layered() (a stand-in that counts calls is not reached: the short route serves labels)."""
    from surfwave.metrology.layered_model import layered_model

    f = np.linspace(3e8, 1.5e9, 6)
    model = layered_model("Si", [FILM], ["E"], mode="R", variable="frequency")
    want = column(surfwave.layered("Si", [dict(FILM, E=75.0)], frequency=f), "R")
    np.testing.assert_array_equal(model({"E": 75.0}, f), want)
    by_index = layered_model("Si", [FILM], ["E"], mode=0, variable="frequency")  # an index: the full solve
    np.testing.assert_array_equal(by_index({"E": 75.0}, f), want)


def test_isotropic_stack_named_modes_take_the_fast_path(monkeypatch):
    """An isotropic unstressed stack (SiO2-like film on an isotropic fast half-space): the named modes at frequency come
    from the isotropic path (compound matrices) and equal the general path's search (Stroh blocks, eigenvalue counting;
    solve.FAST_ISOTROPIC = False) to 1e-10, NaN at the same points; both equal their own layered(frequency=) column."""
    from surfwave.layers import solve

    half = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
    films = [{"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1.0e-6}]
    f = np.linspace(1e8, 2.5e9, 9)
    stack = resolve_stack(half, films)
    assert solve.use_fast_path(stack)
    fast = {lab: mode_speeds_at_frequency(stack, f, lab) for lab in ("R", "S1", "L0", "L1")}
    for lab, c in fast.items():
        np.testing.assert_array_equal(c, column(surfwave.layered(half, films, frequency=f), lab))
    monkeypatch.setattr(solve, "FAST_ISOTROPIC", False)
    for lab, c in fast.items():
        slow = mode_speeds_at_frequency(stack, f, lab)
        np.testing.assert_array_equal(np.isnan(c), np.isnan(slow))
        assert np.isfinite(c).sum() >= 3 or lab == "L1"
        np.testing.assert_allclose(c, slow, rtol=1e-10)
