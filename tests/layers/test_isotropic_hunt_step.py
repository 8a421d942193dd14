"""The hunt's parabolic step (surfwave.layers.isotropic_hunt) against closed forms of parabolas.

References: the vertex and minimum of g(c) = (c - 2)^2 + m sampled at three points, written out by hand;
the golden-section point cm - 0.382 x (the wider side's length) of a bracket written out by hand.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.isotropic_hunt import near_miss, shrink, trial_point, vertex


def _samples(m: float, c: tuple[float, float, float] = (1.0, 2.1, 3.5)) -> tuple[np.ndarray, ...]:
    cs = np.array(c)
    g = (cs - 2.0) ** 2 + m
    return tuple(np.array([v]) for v in (*cs, *g))


def test_vertex_of_a_parabola():
    """Three samples of (c - 2)^2 + m: the vertex is c = 2 whatever m."""
    for m in (-0.3, 0.0, 0.4):
        assert abs(vertex(*_samples(m))[0] - 2.0) < 1e-12


def test_near_miss_threshold():
    """The parabola's minimum m against 0.7 x the middle sample gm = 0.01 + m: a near miss only above it."""
    for m, expected in ((0.5, True), (0.02, False), (-0.1, False)):
        cl, cm, ch, gl, gm, gh = _samples(m)
        # gm = 0.01 + m: m = 0.02 gives a minimum at 0.67 gm (not a near miss), m = 0.5 at 0.98 gm
        assert bool(near_miss(cl, cm, ch, gl, gm, gh, vertex(cl, cm, ch, gl, gm, gh))[0]) is expected


def test_trial_point_falls_back_to_the_wider_side():
    """A vertex outside (cl, ch) is replaced by cm - 0.382 x the wider side: 1 + 0.382 x 2 on (0, 1, 3),
    1 - 0.382 x 2 on (-1, 1, 2); a vertex inside and away from cm is kept."""
    one = np.array([1.0])
    assert trial_point(np.array([5.0]), np.array([0.0]), one, np.array([3.0]))[0] == 1.0 + 0.382 * 2.0
    assert trial_point(np.array([-5.0]), np.array([-1.0]), one, np.array([2.0]))[0] == 1.0 - 0.382 * 2.0
    assert trial_point(np.array([1.5]), np.array([0.0]), one, np.array([3.0]))[0] == 1.5


def test_shrink_keeps_the_lowest_point_in_the_middle():
    """A lower value left of the middle becomes the middle of (cl, x, cm); a higher one becomes the left end."""
    cl, cm, ch, gl, gm, gh = (np.array([v]) for v in (0.0, 1.0, 2.0, 3.0, 1.0, 3.0))
    out = shrink(cl, cm, ch, gl, gm, gh, np.array([0.5]), np.array([0.5]))
    assert [float(v[0]) for v in out] == [0.0, 0.5, 1.0, 3.0, 0.5, 1.0]
    out = shrink(cl, cm, ch, gl, gm, gh, np.array([0.5]), np.array([2.0]))
    assert [float(v[0]) for v in out] == [0.5, 1.0, 2.0, 2.0, 1.0, 3.0]
