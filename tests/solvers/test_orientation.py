"""Surfaces, directions and lab frames (solvers.orientation).

References: docs/physics/paper.md "Units and frames" (x = propagation, y = inward normal, z = x x y; the
FCC frames along [100] and [110] of the (001) surface), and issue 10's reference directions
((001): [100]; (110): [001]; (111): [1-10]), written out by hand below.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.model_crystals.lattices import _FCC_LAB_AXES
from surfwave.solvers.orientation import direction_angle, lab_axes, parse_direction, parse_plane, reference_direction

S2, S3, S6 = np.sqrt(2.0), np.sqrt(3.0), np.sqrt(6.0)


def test_fcc_frames_are_the_physics_md_frames():
    """docs/physics/paper.md: (001) surface, y = [001] into the crystal, z = x x y. By hand:
    [100] -> rows [100], [001], [0-10]; [110] -> [110]/sqrt2, [001], [1-10]/sqrt2. The lattice
    module takes its frames from lab_axes (one place for the convention)."""
    by_hand = {"[100]": np.array([[1, 0, 0], [0, 0, 1], [0, -1, 0]], float),
               "[110]": np.array([[1 / S2, 1 / S2, 0], [0, 0, 1], [1 / S2, -1 / S2, 0]])}
    for d, R in by_hand.items():
        np.testing.assert_allclose(lab_axes("(001)", d), R, atol=1e-15)
        np.testing.assert_allclose(_FCC_LAB_AXES[d], R, atol=1e-15)
        np.testing.assert_allclose(lab_axes("(001)", direction_angle("(001)", d)), R, atol=1e-15)


@pytest.mark.parametrize("surface, ref, toward", [
    ("(001)", [1, 0, 0], [0, 1, 0]),
    ("(110)", [0, 0, 1], [1 / S2, -1 / S2, 0]),
    ("(111)", [1 / S2, -1 / S2, 0], [1 / S6, 1 / S6, -2 / S6]),
])
def test_reference_directions_and_angle_sense(surface, ref, toward):
    """Issue 10: angles run from the reference toward n x reference; n x ref written by hand
    ((001): [010]; (110): [110]x[001] = [1-10]; (111): [111]x[1-10] = [11-2])."""
    np.testing.assert_allclose(reference_direction(surface), ref, atol=1e-15)
    np.testing.assert_allclose(lab_axes(surface, 90.0)[0], toward, atol=1e-15)


def test_frames_orthonormal_right_handed_vectorised():
    """Any (hkl) and angle array: rows orthonormal, det +1, x2 = (hkl)/|hkl|, shape (*angles, 3, 3)."""
    rng = np.random.default_rng(0)
    for hkl in rng.integers(-3, 4, size=(20, 3)):
        if not hkl.any():
            continue
        surface = "({}, {}, {})".format(*hkl)
        R = lab_axes(surface, rng.uniform(-180, 180, size=(4, 5)))
        assert R.shape == (4, 5, 3, 3)
        np.testing.assert_allclose(R @ np.swapaxes(R, -1, -2), np.broadcast_to(np.eye(3), R.shape), atol=1e-14)
        np.testing.assert_allclose(np.linalg.det(R), 1.0, atol=1e-14)
        np.testing.assert_allclose(R[..., 1, :], np.broadcast_to(hkl / np.linalg.norm(hkl), R.shape[:-2] + (3,)),
                                   atol=1e-15)


def test_miller_parsing():
    assert parse_direction("[1-10]").tolist() == [1, -1, 0]
    assert parse_direction("[1, -12, 0]").tolist() == [1, -12, 0]
    assert parse_plane("(111)").tolist() == [1, 1, 1]
    assert direction_angle("(111)", "[11-2]") == pytest.approx(90.0, abs=1e-12)
    assert direction_angle("(001)", "[210]") == pytest.approx(np.degrees(np.arctan(0.5)), abs=1e-12)
    for bad in ("[12]", "(111)", "[000]", "[1a0]", "110"):
        with pytest.raises(InputError):
            parse_direction(bad)


def test_direction_outside_the_surface_is_refused_naming_both():
    with pytest.raises(InputError, match=r"\[111\].*\(001\)"):
        lab_axes("(001)", "[111]")
    with pytest.raises(InputError, match=r"\[100\].*\(111\)"):
        lab_axes("(111)", "[100]")
