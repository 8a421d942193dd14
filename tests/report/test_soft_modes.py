"""The soft-surface-mode claim of a surface_phonons.nc summary (surfwave.report.soft_modes).

References: hand-built cubes whose answer is known by construction (a negative omega^2 where the
bulk is stable, one only where it is unstable, a grid with no stable strain), and the claim on
a real cube of surfwave.surface_phonons (LJ (001) in-plane hydrostatic at d/d0 = 1.0 and 1.1:
bulk stable, every surface omega^2 positive, the softest one next to Gamma: the long-wave
Rayleigh branch, whose slope is Eq. (17)'s c_R).
"""
from __future__ import annotations

import numpy as np
import xarray as xr

from surfwave.report.soft_modes import soft_mode_lines


def _cube(stable, softest):
    n = len(stable)
    low = np.stack([np.array(softest, dtype=float) + 0.5, np.array(softest, dtype=float)], axis=-1)
    return xr.Dataset(
        {"bulk_stable": (("potential", "cut", "strain"), [[stable]]),
         "softest_omega2": (("potential", "cut", "strain"), [[softest]]),
         "lowest_omega2": (("potential", "cut", "strain", "q"), [[low]]),
         "q_reduced": (("potential", "cut", "strain", "q", "axis2"),
                       np.broadcast_to([[0.0, 0.0], [0.5, 0.0]], (1, 1, n, 2, 2)))},
        coords={"potential": ["lj"], "cut": ["(001)"], "d_over_d0": ("strain", np.linspace(0.9, 1.1, n))})


def test_soft_only_where_the_bulk_is_stable_counts():
    """A negative omega^2 at an unstable-bulk strain is no surface instability; at a stable one it is."""
    lines = soft_mode_lines(_cube([False, True, True], [-1.0, 0.2, 0.1]))
    assert "no surface mode goes soft while the bulk is stable" in lines[2]
    assert "d/d0 = 1 ... 1.1" in lines[2]
    lines = soft_mode_lines(_cube([True, True, True], [0.3, 0.2, -0.1]))
    assert "a surface mode goes soft while the bulk is stable, at d/d0 = 1.1" in lines[2]
    assert "q = (0.5, 0)" in lines[2]                      # the q of the smallest lowest_omega2
    assert "bulk is unstable at every strain" in soft_mode_lines(_cube([False] * 3, [np.nan] * 3))[2]


def test_claim_on_a_real_cube():
    """On a surfwave.surface_phonons result the claim names the strain range and the softest
    mode's q, which equals the library's own softest_q (next to Gamma: the Rayleigh branch)."""
    import surfwave

    r = surfwave.surface_phonons("lj", "in_plane_hydrostatic", [1.0, 1.1], surface="(001)", q="GXMG",
                                 path_density=2.0)
    low = np.fmin.reduce(np.asarray(r["omega2"]), axis=-1)             # (strain, q); NaN where no mode
    ds = xr.Dataset(
        {"bulk_stable": (("potential", "cut", "strain"), [[np.asarray(r["bulk_stable"])]]),
         "softest_omega2": (("potential", "cut", "strain"), [[np.asarray(r["softest_omega2"])]]),
         "lowest_omega2": (("potential", "cut", "strain", "q"), [[low]]),
         "q_reduced": (("potential", "cut", "strain", "q", "axis2"),
                       [[np.broadcast_to(np.asarray(r["q"]), low.shape + (2,))]])},
        coords={"potential": ["lj"], "cut": ["(001)"], "d_over_d0": ("strain", [1.0, 1.1])})
    line = soft_mode_lines(ds)[2]
    assert "no surface mode goes soft" in line and "d/d0 = 1 ... 1.1" in line
    for q, w2 in zip(np.asarray(r["softest_q"]), np.asarray(r["softest_omega2"])):
        assert f"{w2:.3g} K/m" in line and f"q = ({q[0]:.3g}, {q[1]:.3g})" in line
