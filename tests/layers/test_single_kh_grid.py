"""The general path's speed grid at one kh: a film much slower than its substrate, one kh per call.

The grid of a call is set by its largest kh. A film far slower than its substrate holds many modes below the
substrate's limiting speed already at small kh (about kh q_max / pi per sheet, q_max = sqrt(c_lim^2 / v^2 - 1)
for a film bulk speed v), and its slowest modes lie far below the grid's uniform steps. Reference: the isotropic
fast path (compound matrices, its own root search), against the general path forced on the same isotropic stack
(solve.FAST_ISOTROPIC = False): the same labels (ranks within each family) and speeds to 1e-8.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
import surfwave.layers.isotropic_guard as guard
from surfwave.layers import solve
from surfwave.layers.modes import film_bulk_speeds, lowest_speed, speed_grid
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import resolve_stack

H = 1.0e-6


def _isotropic(vs: float, rho: float, nu: float) -> dict:
    """An isotropic layer of shear speed vs (m/s), density rho (kg/m^3) and Poisson ratio nu (E in GPa)."""
    return {"E": 2.0 * (1.0 + nu) * rho * vs ** 2 / 1e9, "nu": nu, "rho": rho}


#: The very slow heavy film of test_backward_waves (shear 156 m/s, 12 times denser than its ~15000 m/s substrate).
SLOW_SUB = {"E": 645.8731811250179, "nu": 0.0944253498173546, "rho": 1319.73508333182}
SLOW_FILM = {"E": 1.0507174046061092, "nu": 0.328625655480177, "rho": 16321.33118120104, "thickness": H}
#: A film of shear speed 200 m/s on a substrate of shear speed 11871 m/s: its Rayleigh mode (~196 m/s at large kh)
#: lies below every point of the grid's uniform parts (the floor is 10 m/s, the first uniform step ~260 m/s).
FAST_SUB = _isotropic(11871.0, 19059.0, 0.427)
FAST_FILM = dict(_isotropic(200.0, 10725.0, 0.065), thickness=H)


def _both_paths(monkeypatch: pytest.MonkeyPatch, sub: dict, film: dict, kh: float) -> tuple[dict, dict]:
    """{label: speed} of the isotropic path and of the general path, for one call at this kh alone."""
    monkeypatch.setattr(guard, "ALWAYS", False, raising=False)
    out = []
    for fast in (True, False):
        monkeypatch.setattr(solve, "FAST_ISOTROPIC", fast)
        r = surfwave.layered(sub, [film], kh=[kh])
        out.append({str(m): float(c) for m, c in zip(r["mode"][0], r["c"][0]) if m})
    return out[0], out[1]


@pytest.mark.parametrize("kh", [0.6, 1.0, 1.488, 2.0])
def test_slow_heavy_film_one_small_kh_general_path_equals_isotropic_path(monkeypatch, kh):
    """One kh alone (phase kh q_max 58 ... 192 across the film's shear sheet): the general path finds every mode
    of the isotropic path with its label, speeds 1e-8; at kh 1.488 these include the S2, S3 and S4 at 586.15,
    808.97 and 1032.82 m/s that the isotropic path (and a general-path call with kh beyond 2) finds."""
    iso, gen = _both_paths(monkeypatch, SLOW_SUB, SLOW_FILM, kh)
    assert sorted(gen) == sorted(iso)
    np.testing.assert_allclose([gen[k] for k in iso], list(iso.values()), rtol=1e-8)
    if kh == 1.488:
        np.testing.assert_allclose([gen["S2"], gen["S3"], gen["S4"]], [586.15, 808.97, 1032.82], atol=0.01)


@pytest.mark.parametrize("kh", [1.488, 3.81, 6.0])
def test_slow_film_on_fast_substrate_keeps_its_sagittal_modes(monkeypatch, kh):
    """Film shear 200 m/s on a 11871 m/s substrate, one kh: the general path's modes (the sagittal family with its
    Rayleigh mode, below the film's shear speed at kh 3.81 and 6, included) equal the isotropic path's, labels and
    speeds 1e-8 (before the grid held its floor, a grid whose lowest point lay above R took R's count for the
    floor's, read it as an unstable row and dropped the whole family, with no reason given)."""
    iso, gen = _both_paths(monkeypatch, FAST_SUB, FAST_FILM, kh)
    assert "R" in iso and (kh < 3.0 or iso["R"] < 200.0)              # at kh 3.81 and 6 R is slower than the film
    assert sorted(gen) == sorted(iso)
    np.testing.assert_allclose([gen[k] for k in iso], list(iso.values()), rtol=1e-8)


def test_speed_grid_starts_at_the_floor_and_resolves_the_slow_sheet():
    """The grid's lowest speed is the floor (where the scan takes the stable count) to 1e-9, and at one small kh
    the film's shear sheet gets at least 8 grid points per mode (modes ~pi / kh apart in q, c = v sqrt(1 + q^2)):
    counted directly on the grid of the slow heavy film at kh 1.488, between the film's shear speed and c_lim."""
    b = scaled_blocks(resolve_stack(SLOW_SUB, [SLOW_FILM]))
    fam = families(b)[0]
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    c_lo = min(lowest_speed(b), 0.5 * c_lim)
    v = float(film_bulk_speeds(b).min())                                 # the film's shear speed, 156 m/s
    assert abs(v - np.sqrt(SLOW_FILM["E"] * 1e9 / (2 * (1 + SLOW_FILM["nu"])) / SLOW_FILM["rho"])) < 1e-6 * v
    kh = 1.488
    g = speed_grid(c_lim, c_lo, 71, [v], kh)
    assert abs(g[0] / c_lo - 1.0) <= 2e-9
    q = np.sqrt(np.clip((g[g > v] / v) ** 2 - 1.0, 0.0, None))
    n_modes = kh * np.sqrt((c_lim / v) ** 2 - 1.0) / np.pi
    assert q.size >= 8 * n_modes
    assert np.max(np.diff(q[q < 0.9 * q.max()])) * kh <= np.pi / 8
