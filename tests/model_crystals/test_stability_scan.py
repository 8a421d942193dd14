"""Long-wave stability against an independent brute-force direction scan.

Reference: docs/physics/paper.md (bulk stability) -- every bulk acoustic wave, in every direction n, needs a positive
eigenvalue of Q_ik(n) = (C_ijkl + sigma_jl delta_ik) n_j n_l. Here that minimum over n is
found without the library's search: a dense Fibonacci sphere (a fine angle grid in 2D),
refined by zooming local grids around the best few directions (scipy.optimize in 2D), with Q assembled here from V C and
V sigma (the library's bond sums, themselves checked against finite differences of the
lattice energy in test_elastic). The instability edges (where the minimum crosses zero)
are bracketed and bisected with this brute force only (scipy.optimize.brentq), never taken
from the code under test; the library's ``stable`` flag and ``min_acoustic_eig`` are then
checked just either side of each edge and on a grid of strains, for both loadings, three
potentials and both lattices.
"""
from __future__ import annotations

import numpy as np
import pytest
from acoustic_brute import EIG_ATOL, EIG_RTOL, SPHERE, brute_at, q_min, tensors
from scipy.optimize import brentq

from surfwave.model_crystals import elastic


def library(case, d):
    """The code under test: (stable, min_acoustic_eig) of elastic.properties."""
    lattice, loading, potential, direction = case
    r = elastic.properties(lattice=lattice, loading=loading, potential=potential,
                           direction=direction, d_over_d0=np.atleast_1d(d))
    return np.asarray(r["stable"]), np.asarray(r["min_acoustic_eig"])


# (lattice, loading, potential, direction), and brackets (lo, hi) of d/d0 that hold one
# instability edge each (a sign change of the brute-force minimum, asserted below).
EDGES = [
    (("fcc", "in_plane_hydrostatic", "harmonic", "[100]"), [(0.84, 0.85)]),
    (("fcc", "in_plane_hydrostatic", "lj", "[110]"), [(0.91, 0.92), (1.11, 1.12)]),
    (("fcc", "uniaxial", "lj", "[100]"), [(0.85, 0.86), (1.20, 1.21)]),
    (("fcc", "uniaxial", "harmonic", "[110]"), [(0.79, 0.805)]),  # edge at 0.8
    (("fcc", "uniaxial", "morse", "[110]"), [(0.87, 0.88), (1.29, 1.30)]),
    (("triangular", "uniaxial", "harmonic", "[10]"), [(0.69, 0.70)]),
    (("triangular", "uniaxial", "lj", "[10]"), [(0.89, 0.90), (1.11, 1.12)]),
]


@pytest.mark.parametrize("case, brackets", EDGES, ids=lambda v: "-".join(v) if isinstance(v[0], str) else None)
def test_stability_edges_and_minimum_eigenvalue_match_brute_force(case, brackets):
    """Just inside (stable) and just outside (unstable) each edge, 2e-4 in d/d0 away, the
    library's flag agrees with the brute force, and its minimum eigenvalue equals the brute
    force's to EIG_ATOL + EIG_RTOL |minimum| (it is a minimum over directions: a search that misses the worst
    direction reports a larger value); also at 3 strains across the crystal's range."""
    d_edges = []
    for lo, hi in brackets:
        f_lo, f_hi = brute_at(case, lo), brute_at(case, hi)
        assert f_lo * f_hi < 0, (case, lo, hi, f_lo, f_hi)
        d_edges.append(brentq(lambda d: brute_at(case, d), lo, hi, xtol=1e-6))
    probes = np.array([e + s for e in d_edges for s in (-2e-4, 2e-4)])
    lo, hi = min(b[0] for b in brackets) - 0.03, max(b[1] for b in brackets) + 0.03
    d = np.concatenate([probes, np.linspace(lo, hi, 3)])
    brute = np.array([brute_at(case, x) for x in d])
    stable, eig = library(case, d)
    np.testing.assert_array_equal(stable, brute > 0, err_msg=f"{case} at d/d0 {d}")
    np.testing.assert_allclose(eig, brute, rtol=EIG_RTOL, atol=EIG_ATOL, err_msg=f"{case} at d/d0 {d}")
    # the probes really sit on both sides of every edge
    for k in range(len(d_edges)):
        assert brute[2 * k] * brute[2 * k + 1] < 0, (case, d_edges[k])


def test_stable_flags_over_a_strain_grid_all_potentials():
    """On a 0.03-step grid through both edges, for both FCC loadings and both directions,
    harmonic, LJ and Morse: the flag agrees with a 1000-direction scan wherever that scan is
    decisive (|minimum| > 5e-3, beyond its grid error), and the library's minimum is never
    above the scan's."""
    d = np.round(np.arange(0.78, 1.32, 0.03), 2)
    sphere = SPHERE[::3]
    for loading in ("in_plane_hydrostatic", "uniaxial"):
        for pot in ("harmonic", "lj", "morse"):
            for direction in ("[100]", "[110]"):
                case = ("fcc", loading, pot, direction)
                sig, C = tensors(*case, d)
                brute = np.array([q_min(s, c, sphere).min() for s, c in zip(sig, C)])
                stable, eig = library(case, d)
                clear = np.abs(brute) > 5e-3
                np.testing.assert_array_equal(stable[clear], brute[clear] > 0, err_msg=str(case))
                assert np.all(eig <= brute + EIG_ATOL + EIG_RTOL * np.abs(brute)), case  # never (much) above a grid direction's value
