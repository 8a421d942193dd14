"""Free-surface leaky wave of rotated Y-cut LiNbO3 just off 41Y-X: no holes in a smooth branch
(issue 28 item 7).

Before this change, on a 0.01-degree grid of theta (Euler (0, theta, 0), Warner 1967 constants)
from -53.30 to -50.80 deg, 22 of 251 points were NaN with "no leaky root found" (REASON_LOW) in
8 short runs, inside a branch whose attenuation falls smoothly from 4.4e-4 to 4e-5 dB/lambda
(delta 8e-6 to 7e-7; it touches zero at about -49.42 deg). Cause: the root lies just below v_L2,
above the highest point of the real-speed grid, and so close to the real axis that the grid's
|det| minimum sits one point lower; the secant from there wandered off. The searches from above
v_L2 (w = pi/2 + i y) did converge to the root and pass every validation, but only roots above
v_L2 were kept from them.

Reference: the independent continuation in the rotation angle of tests/solvers/test_leaky_rotated_y.py
(own 8 x 8 Stroh matrix, nearest-root matching, own secant in X at each angle), started from the
solver's root at -53.30 deg, which the old code found as well.
"""
from __future__ import annotations

import numpy as np
from test_leaky_rotated_y import _continue, _solve

from surfwave.solvers.leaky import PROBE_DECAY


def test_no_holes_in_the_free_branch_near_41y():
    theta = np.round(np.arange(-53.30, -50.80 + 1e-9, 0.01), 2)
    rots = theta + 90.0
    ref = _continue(rots, "free")
    r = _solve(rots, "free")
    holes = theta[r["reason"] != ""]
    assert holes.size == 0, (holes, set(r["reason"]))
    assert np.allclose(r["c_leaky"], ref[:, 0], rtol=1e-9, atol=0)
    assert np.allclose(r["delta"], ref[:, 1], rtol=0, atol=1e-10)  # solver tol 1e-10 in X
    # the branch is smooth: no jump between neighbours beyond the local trend
    assert np.max(np.abs(np.diff(r["c_leaky"], 2))) < 1e-3            # m/s
    # and it is the nearly real root the relaxed probe rule admits: decaying waves well inside
    assert np.all(r["decay"][:, 1:].imag > 10 * PROBE_DECAY)
    assert np.all(r["c_leaky"] < r["c_limits"][:, 1])


def test_through_the_zero_of_the_attenuation():
    """Across -49.42 deg, where the attenuation touches zero (delta 9e-12 by the continuation),
    every 0.05-degree point is found and matches the continuation."""
    theta = np.round(np.arange(-50.80, -48.60 + 1e-9, 0.05), 2)
    ref = _continue(theta + 90.0, "free")
    r = _solve(theta + 90.0, "free")
    assert np.all(r["reason"] == ""), theta[r["reason"] != ""]
    assert np.allclose(r["c_leaky"], ref[:, 0], rtol=1e-9, atol=0)
    assert np.allclose(r["delta"], ref[:, 1], rtol=0, atol=1e-10)
    assert ref[:, 1].min() < 1e-9 < ref[:, 1].max()
