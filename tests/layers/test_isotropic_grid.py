"""The speed grid of the isotropic path (surfwave.layers.isotropic_modes.speed_grid) at and below c_lo.

Reference: the general Stroh solver of surfwave.layers (forced with ``solve.FAST_ISOTROPIC = False``).
"""
from __future__ import annotations

import numpy as np
from general_path import layered_general

import surfwave
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.isotropic_modes import Rows, slowest_speed, speed_grid
from surfwave.layers.stack import resolve_stack


def _general(sub, films, kh):
    return layered_general(sub, films, kh=kh)

SUB = {"E": 573.25, "nu": 0.1077, "rho": 8614.9}
FILMS = [{"E": 294.41, "nu": 0.1905, "rho": 16726.3, "thickness": 0.848e-6},
         {"E": 503.64, "nu": 0.0124, "rho": 15316.7, "thickness": 1.099e-6}]


def test_rayleigh_mode_just_above_the_grid_floor():
    """A heavy top film: at large kh its Rayleigh wave (the slowest of any layer) is the R mode, 5 %
    above the floor c_lo of the grid and below its next point; c_lo is a grid point, so the mode is
    bracketed: labels and speeds (1e-10) as the general solver's."""
    kh = np.array([30.0, 38.8, 39.2])
    st = iso_stack(resolve_stack(SUB, FILMS))
    grid = speed_grid(st, Rows(kh, freq=False))
    c_lo = 0.95 * slowest_speed(st)
    assert c_lo in grid
    fast, gen = surfwave.layered(SUB, FILMS, kh=kh), _general(SUB, FILMS, kh)
    assert (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
    nxt = grid[grid > c_lo * (1 + 1e-9)][0]                               # the next distinct grid speed
    assert c_lo < fast["c"][0, 0] < nxt


def test_mass_loading_below_every_rayleigh_speed():
    """A dense, stiff film (10900 kg/m^3) on a slower substrate: at kh ~ 1 its mass takes the R mode
    below the Rayleigh speed of every layer (0.93 x the slowest), under the dense part of the grid;
    the grid reaches down to 0.05 x the slowest shear speed: labels and speeds as the general
    solver's (1e-10)."""
    sub = {"E": 391.4, "nu": 0.3817, "rho": 5235.4}
    films = [{"E": 629.4, "nu": 0.1526, "rho": 10933.7, "thickness": 0.4716e-6}]
    kh = np.array([0.27, 0.8, 1.5, 4.0])
    fast, gen = surfwave.layered(sub, films, kh=kh), _general(sub, films, kh)
    assert (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
    st = iso_stack(resolve_stack(sub, films))
    assert np.nanmin(fast["c"][:, 0]) < 0.95 * slowest_speed(st)            # below c_lo


def _reference_grid(st, rows_of, fine=1):
    """The speed grid written out as the module docstring defines it (unique points of all parts)."""
    import math

    import surfwave.layers.isotropic_modes as im
    c_lim = st.c_lim
    c_lo = 0.95 * slowest_speed(st)
    t_hi = math.sqrt(1.0 - (c_lo / c_lim) ** 2)
    top = np.geomspace(1e-7, 0.02, im.N_TOP, endpoint=False)
    t = np.linspace(0.02, t_hi, im.N_BASE * fine)
    base = np.concatenate([c_lim * np.sqrt(1.0 - t * t), np.linspace(c_lo, c_lim, im.N_BASE * fine)])
    c_floor = im.FLOOR * float(st.shear.min())
    low = np.geomspace(c_floor, c_lo, im.N_LOW, endpoint=False) if c_floor < c_lo else np.zeros(0)
    parts = [c_lim * np.sqrt(1.0 - top * top), np.array([c_lo]), low]
    aux = np.linspace(c_lo, c_lim, 4000)
    # and above each film's bulk speed v in (c_lo, c_lim): v (1 + d), d = 1e-12 ... 1e-2, 10 per decade
    onset = [v[i] * (1.0 + np.geomspace(1e-12, 1e-2, 101)) for v in (st.shear, st.longitudinal)
             for i in range(st.frac.size) if c_lo < v[i] < c_lim]
    aux = np.unique(np.concatenate([aux, *onset]))
    aux = aux[aux <= c_lim]
    nu = sum(st.frac[i] * np.sqrt(np.maximum((aux / v[i]) ** 2 - 1.0, 0.0))
             for v in (st.shear, st.longitudinal) for i in range(st.frac.size))
    phase = rows_of.kh_max(aux) * nu
    levels = np.arange(im.PHASE_STEP / fine, float(phase[-1]), im.PHASE_STEP / fine)
    if levels.size:
        pts = np.interp(levels, phase, aux)
        parts.append(pts)
        t_base = np.sqrt(np.maximum(1.0 - (base / c_lim) ** 2, 0.0))
        dc = np.minimum((c_lim - c_lo) / (im.N_BASE * fine), c_lim * c_lim * t_base * t_hi / (base * im.N_BASE * fine))
        k = np.clip(np.searchsorted(pts, base), 1, pts.size - 1) if pts.size > 1 else np.zeros(base.size, int)
        near = np.minimum(np.abs(pts[k] - base), np.abs(pts[np.maximum(k - 1, 0)] - base))
        base = base[near > 0.5 * dc]
    g = np.unique(np.concatenate(parts + [base]))
    g = g[(g == c_lo) | (np.abs(g - c_lo) > 1e-12 * c_lo)]
    return g[(g >= min(c_floor, c_lo)) & (g < c_lim)]


def test_speed_grid_equals_its_definition():
    """speed_grid (its cheaper evaluation: phase terms only above their bulk speed, remembered
    constants, its own geometric spacing and de-duplication) gives bit for bit the points of the
    grid written out as the module docstring defines it (numpy's geomspace and unique, every phase
    term everywhere), for 12 seeded random stacks (1-3 films), rows at kh and at frequency, and the
    rescan's fine grid."""
    rng = np.random.default_rng(7)
    for _ in range(12):
        def mat(E, rho):
            return {"E": float(rng.uniform(*E)), "nu": float(rng.uniform(0.05, 0.42)), "rho": float(rng.uniform(*rho))}
        films = [{**mat((40.0, 600.0), (1800.0, 20000.0)), "thickness": float(rng.uniform(0.1, 1.0)) * 1e-6}
                 for _ in range(int(rng.integers(1, 4)))]
        st = iso_stack(resolve_stack(mat((150.0, 600.0), (2000.0, 5000.0)), films))
        top = float(rng.choice([0.5, 5.0, 60.0]))
        for rows_of in (Rows(np.linspace(0.0, top, 7), freq=False), Rows(np.linspace(0.0, top * st.c_lim, 7), freq=True)):
            for fine in (1, 4):
                np.testing.assert_array_equal(speed_grid(st, rows_of, fine), _reference_grid(st, rows_of, fine))


def test_love_modes_packed_above_a_heavy_films_shear_speed(monkeypatch):
    """A heavy soft film (E 24 GPa, rho 19950, shear speed 687.1 m/s) on a stiff half-space at fixed
    frequencies up to kh = 100: the first Love modes lie within 0.2 m/s above the film's shear
    speed, where the vertical phase rises as sqrt(c - v) (about 9 rad there at the top row). One
    film is not checked against the count by default; reference: the same call with every row
    checked against the Wittrick-Williams count of the general path and repaired from it
    (isotropic_guard.ALWAYS = True). Every mode (labels, counts, speeds to 1e-12) must agree.
    The grid placed by a chord across the phase curve's first uniform cell above the onset missed
    two Love modes in the top row."""
    import surfwave.layers.isotropic_guard as guard
    half = {"E": 455.396, "nu": 0.17402, "rho": 4037.84}
    film = {"E": 24.2128, "nu": 0.28544, "rho": 19946.99, "thickness": 1e-6}
    kh = np.geomspace(10.0, 100.0, 12)
    freq = kh * 3000.0 / (2 * np.pi * 1e-6)
    for modes in (2, None):
        monkeypatch.setattr(guard, "ALWAYS", False)
        got = surfwave.layered(half, [film], frequency=freq, modes=modes)
        monkeypatch.setattr(guard, "ALWAYS", True)
        ref = surfwave.layered(half, [film], frequency=freq, modes=modes)
        assert np.array_equal(np.asarray(got["mode"], dtype=str), np.asarray(ref["mode"], dtype=str))
        assert got["c"].shape == ref["c"].shape
        np.testing.assert_allclose(got["c"], ref["c"], rtol=1e-12, atol=0.0)
