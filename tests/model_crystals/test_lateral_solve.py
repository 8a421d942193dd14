"""The vectorised lateral-stretch solve of uniaxial FCC against independent references.

:func:`surfwave.model_crystals.lattices.solve_lateral_stretch` follows anchors by continuation
and starts Newton at every point from their cubic Hermite interpolant. References: a
per-point root (``scipy.optimize.brentq``, or MINPACK through ``scipy.optimize.root``) of
the stress of all 12 neighbours written out here (not the library's bond tables), the
marching route itself on single points, and the closed form of the harmonic [110] collapse.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.optimize import brentq, root

from surfwave.errors import GeometryError
from surfwave.model_crystals import lattices
from surfwave.model_crystals.potentials import get_potential
from surfwave.solvers.orientation import lab_axes


def _fcc_neighbours() -> np.ndarray:
    """All 12 vectors (+-1, +-1, 0)/sqrt 2 and permutations, shape (12, 3)."""
    out = []
    for i, j in ((0, 1), (0, 2), (1, 2)):
        for a in (1, -1):
            for b in (1, -1):
                v = np.zeros(3)
                v[i], v[j] = a, b
                out.append(v / np.sqrt(2.0))
    return np.array(out)


def _lateral_sigma(direction, pot, s, ty, tz):
    """(V sigma_yy, V sigma_zz) = 1/2 sum over the 12 neighbours of r_a^2 phi'(r)/r."""
    r = (_fcc_neighbours() @ lab_axes("(001)", direction).T) * np.array([s, ty, tz])
    length = np.linalg.norm(r, axis=1)
    w = 0.5 * pot.dphi(length) / length
    return float(w @ r[:, 1] ** 2), float(w @ r[:, 2] ** 2)


def _reference_stretch(direction, pot, s):
    """(t_y, t_z) at one s. [100]: the load axis is a four-fold axis, so t_y = t_z and one
    brentq on sigma_yy(t, t) in [0.8, 1.2] (the branch for 0.85 <= s <= 1.3) gives it.
    [110]: MINPACK's hybrid root finder (scipy.optimize.root) from the unstressed (1, 1)."""
    if direction == "[100]":
        t = brentq(lambda t: _lateral_sigma(direction, pot, s, t, t)[0], 0.8, 1.2, xtol=1e-15)
        return t, t
    sol = root(lambda t: _lateral_sigma(direction, pot, s, *t), [1.0, 1.0], method="hybr", tol=1e-12)
    assert sol.success and np.abs(sol.fun).max() < 1e-13
    return tuple(sol.x)


@pytest.mark.parametrize("direction", ["[100]", "[110]"])
@pytest.mark.parametrize("potential", ["lj", "morse", "harmonic"])
def test_anchored_solve_matches_a_per_point_root(direction, potential):
    """4000 strains (the anchored route: far more points than anchors): eight of them,
    spread over the range, agree with the per-point root (brentq or MINPACK) to 1e-11."""
    pot = get_potential(potential)
    s = np.linspace(0.85, 1.3, 4000)
    t = lattices.solve_lateral_stretch(direction, s, pot)
    for i in np.linspace(0, s.size - 1, 8).astype(int):
        np.testing.assert_allclose(t[i], _reference_stretch(direction, pot, s[i]), rtol=0, atol=1e-11)


def test_anchored_solve_equals_marching_each_point():
    """The anchored route on 3000 strains (LJ [110], through the long-wave instabilities)
    against the same solve on a few points alone, which marches each from s = 1 (the
    route used when there are fewer points than anchors): the same root to 1e-12."""
    s = np.linspace(0.8, 1.3, 3000)
    t = lattices.solve_lateral_stretch("[110]", s, "lj")
    pick = [0, 777, 1500, 2999]
    np.testing.assert_allclose(t[pick], lattices.solve_lateral_stretch("[110]", s[pick], "lj"),
                               rtol=0, atol=1e-12)
    # repeated strains are solved once and handed back in the input order
    rev = lattices.solve_lateral_stretch("[110]", np.concatenate([s[::-1], s[:5]]), "lj")
    np.testing.assert_array_equal(rev[:3000], t[::-1])
    np.testing.assert_array_equal(rev[3000:], t[:5])


def test_anchored_solve_names_the_first_collapsed_point():
    """Harmonic uniaxial [110]: t_y = sqrt((3 - s^2)/2) (out-of-plane bonds at rest), so the
    solve must fail first where t_y <= MIN_LATERAL_STRETCH; on 3001 strains crossing it
    (anchored route, some anchors failing) the error names that grid point."""
    s = np.linspace(1.6, 1.75, 3001)
    first = s[np.sqrt(np.clip((3 - s**2) / 2, 0, None)) <= lattices.MIN_LATERAL_STRETCH][0]
    with pytest.raises(GeometryError, match=f"d/d0 = {first:.6g}"):
        lattices.solve_lateral_stretch("[110]", s, "harmonic")
    ok = lattices.solve_lateral_stretch("[110]", s[s < first - 1e-3], "harmonic")
    np.testing.assert_allclose(ok[:, 0], np.sqrt((3 - s[s < first - 1e-3] ** 2) / 2),
                               rtol=0, atol=1e-10)
