"""Independent derivations of the constants other tests take as given.

Several tests use instability edges and stability flags the code once produced itself
("found by bisection"): the triangular LJ surface limits 0.8937 / 1.1139 (test_dispersion,
test_entropy, test_lattice_dynamics), the harmonic surface limit 2(3 - sqrt 7), the LJ bulk
limits 0.8930277 / 1.1141848, the FCC edges quoted in the README (0.8477 harmonic, 0.9198
LJ) and the LJ stability flags of test_phonons. Each is derived here by a route that does
not go through the code that produced it:

- surface limits: c_R^2 = 0 of the Cauchy-case formula, Eq. (20), is equivalent to
  c_L,par^2 c_T,par^2 c_L,perp^2 = c_T,perp^6 (square both sides of Eq. 20 at c_R = 0).
  With the bond sums of Eq. (A12) written out by hand for the triangular lattice (in-row
  bond 2x, inclined bonds at rest length 1 with phi'(1) = 0, phi''(1) = 1; x = d_x/d0,
  y^2 = 1 - x^2):
      c_L,par^2 = 4x^2 phi''(2x) + 2x^4,   c_T,par^2 = 2x phi'(2x) + 2x^2 y^2,
      c_L,perp^2 = 2y^4,                   c_T,perp^2 = 2x^2 y^2,
  and the potentials typed from docs/physics/paper.md (not from surfwave.model_crystals.potentials). For
  Hooke springs the condition reduces to x^2 - 6x + 2 = 0, so d/d0 = 2x = 2(3 - sqrt 7).
- bulk limits and flags: the brute-force direction scan of tests/acoustic_brute.py, bisected
  with scipy.optimize.brentq.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from acoustic_brute import brute_at
from scipy.optimize import brentq

from surfwave.dynamics import dispersion as D


def lj_dphi(r):
    """phi_LJ'(r) for phi_LJ = (r^-12 - 2 r^-6)/72 (docs/physics/paper.md, reduced units)."""
    return (r**-7 - r**-13) / 6.0


def lj_d2phi(r):
    return (13.0 * r**-14 - 7.0 * r**-8) / 6.0


def cauchy_zero(d, dphi, d2phi):
    """c_L,par^2 c_T,par^2 c_L,perp^2 - c_T,perp^6 of the triangular lattice (module docstring)."""
    x = 0.5 * d
    y2 = 1.0 - x * x
    c_l_par = 4 * x * x * d2phi(2 * x) + 2 * x**4
    c_t_par = 2 * x * dphi(2 * x) + 2 * x * x * y2
    return c_l_par * c_t_par * (2 * y2**2) - (2 * x * x * y2) ** 3


#: LJ surface limits as used (rounded or in full) by test_dispersion, test_entropy and
#: test_lattice_dynamics (LJ_SURFACE there).
LJ_SURFACE = (0.89361985602, 1.11392551139)


def test_harmonic_surface_limit_is_2_3_minus_sqrt7():
    """Hooke springs: the Cauchy condition has its root at 2(3 - sqrt 7) = 0.7084973778708...
    to 1e-14, and the library's c_R^2 (surfwave.dynamics.dispersion) changes sign there."""
    edge = 2 * (3 - math.sqrt(7))
    root = brentq(cauchy_zero, 0.65, 0.75, args=(lambda r: r - 1.0, lambda r: 1.0 + 0 * r), xtol=1e-16)
    assert root == pytest.approx(edge, abs=1e-14)
    c2 = D.lattice_constants("harmonic", edge * np.array([1 - 1e-9, 1 + 1e-9]))["c2_R"]
    assert not c2[0] > 0 and 0 < c2[1] < 1e-7


def test_lj_surface_limits():
    """LJ: the two roots of the Cauchy condition are the constants the other tests use (to
    1e-10), and the library's c_R^2 is positive just inside and absent/non-positive just
    outside each of them."""
    lo = brentq(cauchy_zero, 0.85, 0.95, args=(lj_dphi, lj_d2phi), xtol=1e-15)
    hi = brentq(cauchy_zero, 1.05, 1.20, args=(lj_dphi, lj_d2phi), xtol=1e-15)
    np.testing.assert_allclose([lo, hi], LJ_SURFACE, rtol=0, atol=1e-10)
    assert round(lo, 4) == 0.8936 and round(hi, 4) == 1.1139  # the 0.8937 / 1.1139 of the tests
    d = np.array([lo * (1 - 1e-7), lo * (1 + 1e-7), hi * (1 - 1e-7), hi * (1 + 1e-7)])
    c2 = D.lattice_constants("lj", d)["c2_R"]
    inside = np.array([False, True, True, False])
    assert np.all(c2[inside] > 0) and not np.any(c2[~inside] > 0)


@pytest.mark.parametrize("case, bracket, quoted, digits", [
    # test_lattice_dynamics: "the LJ bulk goes unstable only beyond them (0.8930277 and 1.1141848)"
    (("triangular", "uniaxial", "lj", "[10]"), (0.88, 0.8935), 0.8930277, 6),
    (("triangular", "uniaxial", "lj", "[10]"), (1.1139, 1.13), 1.1141848, 6),
    # README "What we found": FCC in-plane hydrostatic unstable at 0.8477 (harmonic) and
    # 0.9198 (LJ) -- the LJ edge is 0.919866, truncated there (0.9199 when rounded)
    (("fcc", "in_plane_hydrostatic", "harmonic", "[100]"), (0.84, 0.85), 0.8477, 4),
    (("fcc", "in_plane_hydrostatic", "lj", "[100]"), (0.91, 0.92), 0.91987, 5),
])
def test_bulk_stability_limits(case, bracket, quoted, digits):
    """Long-wave bulk limits quoted in tests and README, recomputed by bisecting the
    brute-force minimum of the acoustic tensor over all directions."""
    edge = brentq(lambda d: brute_at(case, d), *bracket, xtol=1e-9)
    assert abs(edge - quoted) <= 0.5 * 10**-digits  # the quoted value is the edge, rounded


def test_lj_fcc_flags_of_test_phonons():
    """test_phonons.test_known_unstable_points_flagged expects LJ in-plane hydrostatic
    [False, False, True, False] at d/d0 = 0.88, 0.90, 0.95, 1.15: the sign of the
    brute-force minimum gives the same, and the soft direction at 0.90 is the in-plane
    diagonal (+-1, 0, +-1)/sqrt 2 (Q evaluated there is already negative)."""
    case = ("fcc", "in_plane_hydrostatic", "lj", "[100]")
    flags = [brute_at(case, d) > 0 for d in (0.88, 0.90, 0.95, 1.15)]
    assert flags == [False, False, True, False]
    from acoustic_brute import q_min, tensors

    sig, C = tensors(*case, 0.90)
    assert q_min(sig[0], C[0], np.array([[2**-0.5, 0.0, 2**-0.5]]))[0] < 0
