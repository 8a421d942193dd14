"""Triangular lattice where the long-wave crystal has no Rayleigh wave (issue 20, item 7).

Harmonic springs: at d/d0 = 0.5 the lattice is bulk unstable and at 0.7 Eq. (20)'s root is
negative (c2_T_par = 0.005, root -0.0072, from surfwave.dynamics.triangular.long_wave); the
dispersion cube stored that negative root as c2_R_long_wave and depth 0 (2^steps of a
decimation that never ran). Now both are NaN there and n_surface_modes is -1 where no scan
ran; at d/d0 = 1 the values are unchanged (c2_R = (3 - sqrt 3)/4, Eq. 16 at x = 1/2).
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.dynamics import triangular_surface


def test_no_long_wave_rayleigh_wave_is_nan_with_reason():
    r = triangular_surface.surface_mode("harmonic", [0.5, 0.7, 1.0], [0.5, 1.0])
    c2 = r["c2_R_long_wave"]
    assert np.isnan(c2[:2]).all()
    assert c2[2] == pytest.approx((3 - 3**0.5) / 4, rel=1e-12)
    assert np.isnan(r["depth"][:2]).all() and (r["depth"][2] >= 1).all()
    assert (r["n_surface_modes"][0] == -1).all() and (r["n_surface_modes"][1] == 0).all()
    assert (r["n_surface_modes"][2] == 1).all()
    assert all(r["reason_lattice"][0]) and all(r["reason_lattice"][1])  # each NaN has a reason
    assert "bulk unstable" in r["reason_lattice"][0, 0]
    assert "no bound surface mode" in r["reason_lattice"][1, 0]

