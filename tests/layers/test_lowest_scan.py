"""The slowest mode of a family by a scan that stops above it (family_modes(..., lowest=True)).

Reference: the full scan of the speed grid (family_modes without ``lowest``, what surfwave.layered uses): its
column 0 must come out bit for bit, NaN at the same kh, for sagittal, shear-horizontal and coupled
(piezoelectric) families, a slow heavy film, a stiff film and a film under strong compression; and the scan
must actually stop early for a slow film (fewer speeds evaluated).
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from surfwave.layers import scan as scan_module
from surfwave.layers.modes import family_modes
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.solve import mode_speeds
from surfwave.layers.stack import resolve_stack

SIO2 = {"E": 70.0, "nu": 0.17, "rho": 2200.0, "thickness": 1.0e-6, "stress": -0.3}
NITRIDE = {"E": 200.0, "nu": 0.24, "rho": 3200.0, "thickness": 3.0e-7}
STACKS = {
    "SiO2 over nitride on Si": ("Si", [SIO2, NITRIDE], {}),
    "gold on Si": ("Si", [{"name": "Au", "thickness": 2e-7}], {}),
    "diamond on Si": ("Si", [{"name": "diamond", "thickness": 1e-6}], {}),
    "SiO2 at -3 GPa on Si": ("Si", [dict(SIO2, stress=-3.0)], {}),
    "ZnO on sapphire": ("sapphire", [{"name": "ZnO", "thickness": 1e-6}], {}),
}


@pytest.mark.parametrize("name", list(STACKS))
def test_slowest_mode_is_the_full_scans(name):
    """Column 0 of the stopped scan equals the full scan's at kh 0-6 and 1e-6-100 (log), every family."""
    sub, films, opts = STACKS[name]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # constants notes of database films
        b = scaled_blocks(resolve_stack(sub, films, **opts))
    for kh in (np.linspace(0.0, 6.0, 25), np.geomspace(1e-6, 100.0, 12)):
        for fam in families(b):
            full = family_modes(b, fam, kh)
            low = family_modes(b, fam, kh, lowest=True)
            assert low.shape[1] <= 1
            want = full[:, 0] if full.shape[1] else np.full(kh.size, np.nan)
            got = low[:, 0] if low.shape[1] else np.full(kh.size, np.nan)
            np.testing.assert_array_equal(got, want)


def test_scan_stops_above_the_slowest_mode(monkeypatch):
    """SiO2 over nitride on Si, sagittal family at kh 0.2-5: the slowest mode (R, below 4830 m/s with the
    family's limit at 5649 m/s) is found with at most 70 % of the full scan's speed evaluations, and
    mode_speeds(..., "R") (which takes this route) equals the full scan's R."""
    b = scaled_blocks(resolve_stack("Si", [SIO2, NITRIDE]))
    fam = next(f for f in families(b) if f.prefix == "R")
    kh = np.linspace(0.2, 5.0, 30)
    counted = []
    scan = scan_module._grid_eigenvalues

    def counting(b_, fam_, c, kh_, electrical):
        counted.append(np.size(c))
        return scan(b_, fam_, c, kh_, electrical)

    monkeypatch.setattr(scan_module, "_grid_eigenvalues", counting)
    full = family_modes(b, fam, kh)
    n_full = sum(counted)
    counted.clear()
    family_modes(b, fam, kh, lowest=True)
    assert sum(counted) <= 0.7 * n_full
    monkeypatch.undo()
    np.testing.assert_array_equal(mode_speeds(resolve_stack("Si", [SIO2, NITRIDE]), kh, "R"), full[:, 0])
