"""Acoustoelastic coefficients from a stressed cube (surfwave.report.acoustoelastic).

Reference: a closed form. For c(sigma) = c0 (1 + a sigma + b sigma^2 + d sigma^3) the central
difference over +/- h gives a + d h^2 and over +/- 2h gives a + 4 d h^2, so the coefficient
is a + d h^2 and Richardson's error estimate |K(2h) - K(h)|/3 equals its exact error d h^2.
"""
from __future__ import annotations

import numpy as np
import pytest
import xarray as xr

from surfwave.errors import InputError
from surfwave.report.acoustoelastic import PER_TPA, coefficients, write_table


def _cube(stress, a=0.02, b=0.3, d=0.5, wave_type="surface"):
    s = np.asarray(stress, dtype=float)
    c = 3000.0 * (1 + a * s + b * s ** 2 + d * s ** 3)
    shape = (1, 1, 1, 1, 2, s.size)
    dims = ("material", "surface", "angle", "loading", "toec", "stress")
    return xr.Dataset(
        {"c_R": (dims, np.broadcast_to(c, shape).copy()),
         "wave_type": (dims, np.full(shape, wave_type))},
        coords={"material": ["Cu"], "surface": ["(001)"], "angle": [0.0], "loading": ["along"],
                "toec": [False, True], "stress": s, "direction": ("angle", ["[100]"])})


def test_central_difference_and_error_estimate():
    h = 0.1
    K = coefficients(_cube(np.round(np.arange(-2, 3) * h, 12)))
    np.testing.assert_allclose(K.K.values, (0.02 + 0.5 * h ** 2) * PER_TPA, rtol=1e-10)
    np.testing.assert_allclose(K.K_error.values, 0.5 * h ** 2 * PER_TPA, rtol=1e-8)
    assert K.K.attrs["units"] == "TPa-1"


def test_no_surface_wave_gives_nan_and_bad_grids_are_refused(tmp_path):
    K = coefficients(_cube([-0.1, 0.0, 0.1], wave_type="pseudo"))
    assert np.isnan(K.K.values).all() and np.isnan(K.K_error.values).all()  # no +/- 2h points
    with pytest.raises(InputError, match="0 and one point"):
        coefficients(_cube([0.0, 0.1, 0.2]))
    md, csv = write_table(_cube([-0.2, -0.1, 0.0, 0.1, 0.2]), tmp_path / "a.md", tmp_path / "a.csv")
    text = md.read_text()
    assert "| Cu | (001) | [100] (0 deg) | along |" in text and "K TOEC (1/TPa)" in text
    assert csv.read_text().count("\n") == 2
