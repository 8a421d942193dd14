"""Brackets of a sampled branch omega H(kh) (surfwave.layers.crossings), on closed-form curves.

References: a cubic w(kh) = (kh - 1)^3 - 3 (kh - 1) + 10, whose cubic Hermite model on any cell is the curve itself
(extrema at kh = 0 and 2, w = 12 and 8; roots of w = t from numpy.roots); a smooth dispersive curve c(kh) =
c_0 / (1 + kh) (w = c_0 kh / (1 + kh), slope c_0 / (1 + kh)^2) with one sample replaced by another branch's value.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.crossings import brackets, stray_samples, turning_points


def _cubic(kh):
    return (kh - 1) ** 3 - 3 * (kh - 1) + 10, 3 * (kh - 1) ** 2 - 3


def test_turning_points_of_a_cubic_are_exact():
    """Cells holding the cubic's extrema kh = 0 and 2 (not at samples) give them to rounding; cells without none."""
    kh = np.linspace(-1.3, 3.1, 12)
    w, v = _cubic(kh)
    np.testing.assert_allclose(turning_points(kh, w, v), [0.0, 2.0], atol=1e-12)
    # only where a target is met more often than the cell's ends show: 11.99 (both crossings near the maximum in
    # the cell -0.1 ... 0.3, whose ends are at 11.969 and 11.757), not 10 or 11.9 (one crossing per cell there)
    assert turning_points(kh, w, v, np.array([10.0])).size == 0
    assert turning_points(kh, w, v, np.array([11.9])).size == 0
    np.testing.assert_allclose(turning_points(kh, w, v, np.array([11.99])), [0.0], atol=1e-12)


def test_every_crossing_is_bracketed_with_the_extrema_sampled():
    """With the extrema added as samples, every real root of w = t in the sampled range is in exactly one bracket,
    the start inside it; t = 12 (the maximum) is a touch at a sample: one root, a bracket of zero width."""
    kh = np.linspace(-1.3, 3.1, 12)
    kh = np.sort(np.concatenate([kh, [0.0, 2.0]]))
    w, v = _cubic(kh)
    targets = np.array([7.0, 8.5, 10.0, 11.9, 12.0, 14.0])
    row, lo, hi, sign_lo, start = brackets(kh, w, v, targets)
    for i, t in enumerate(targets):
        r = np.roots([1.0, -3.0, 0.0, 12.0 - t])                  # (kh - 1)^3 - 3 (kh - 1) + 10 - t in kh
        r = np.sort(r[(np.abs(r.imag) < 1e-9) & (r.real >= kh[0]) & (r.real <= kh[-1])].real)
        if t == 12.0:
            r = np.unique(np.round(r, 6))                          # the double root at the maximum: one touch
        mine = row == i
        assert mine.sum() == r.size, (t, r)
        for x in r:
            inside = mine & (lo - 1e-9 <= x) & (x <= hi + 1e-9)
            assert inside.sum() == 1, (t, x)
        assert np.all((start[mine] >= lo[mine]) & (start[mine] <= hi[mine]))
        wl = _cubic(lo[mine])[0] - t
        assert np.all((np.sign(wl) == sign_lo[mine]) | (lo[mine] == hi[mine]))


def test_a_sample_of_another_branch_is_dropped_and_nothing_else():
    """A smooth curve is left whole, also where it bends strongly (kh 0 ... 0.1 of c = c_0 / (1 + 50 kh)); one sample
    replaced by a faster branch's value (c x 1.45, with that branch's slope) is flagged, alone."""
    c0 = 13000.0
    for a in (1.0, 50.0):
        kh = np.linspace(0.0, 3.0, 40)
        w, v = c0 * kh / (1 + a * kh), c0 / (1 + a * kh) ** 2
        assert not stray_samples(kh, w, v).any()
        w2, v2 = w.copy(), v.copy()
        w2[17], v2[17] = 1.45 * w[17], 1.45 * v[17] + 0.45 * c0 / (1 + a * kh[17])
        np.testing.assert_array_equal(np.flatnonzero(stray_samples(kh, w2, v2)), [17])
