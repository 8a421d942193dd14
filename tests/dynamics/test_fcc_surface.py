"""Numerical FCC (001) surface lattice dynamics versus the analytic long-wave Rayleigh speed.

The slab solve of :mod:`surfwave.dynamics.fcc_surface` uses only the bond force constants; it shares
no formula with Eq. (17), the S tensor (A11) or the root selection of :func:`surfwave.point`.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.sparse.linalg import eigsh

import surfwave
from surfwave.dynamics.fcc_surface import (
    layer_matrices,
    long_wave_c2,
    sagittal_blocks,
    slab_matrix,
    surface_mode,
    tail_ratio,
)
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import get_potential

#: Richardson over k = 0.8, 0.4, ..., 0.05 (1/d0): measured error ~1e-8 relative.
K_MAX, LEVELS = 0.8, 5
RTOL = 1e-6


@pytest.mark.parametrize("direction, gamma", [
    ("[100]", (3 - np.sqrt(3)) / 2),
    ("[110]", (7 - np.sqrt(17)) / 4),
])
def test_zero_stress_closed_forms(direction, gamma):
    """Reference: docs/physics/paper.md "Checks that need no paper": nearest-neighbour FCC at zero stress,
    rho c_R^2 / C44 = (3 - sqrt 3)/2 along [100] and (7 - sqrt 17)/4 along [110];
    V C44 = 1/2 (K d0^2) and m = 1, so c_R^2 = gamma / 2."""
    res = long_wave_c2("fcc", "in_plane_hydrostatic", "lj", direction, 1.0, k=K_MAX, levels=LEVELS)
    assert res["c2_R"] == pytest.approx(gamma / 2, rel=RTOL)
    assert res["error"] < 1e-5


PRESTRESSED = [
    ("in_plane_hydrostatic", "lj", "[100]", 0.93),
    ("in_plane_hydrostatic", "lj", "[100]", 0.97),
    ("in_plane_hydrostatic", "lj", "[100]", 1.06),
    ("in_plane_hydrostatic", "lj", "[110]", 0.93),
    ("in_plane_hydrostatic", "lj", "[110]", 0.97),
    ("in_plane_hydrostatic", "lj", "[110]", 1.03),
    ("uniaxial", "lj", "[100]", 0.95),
    ("uniaxial", "lj", "[100]", 1.05),
    ("uniaxial", "lj", "[110]", 0.95),
    ("uniaxial", "lj", "[110]", 1.04),
    ("uniaxial", "harmonic", "[100]", 0.9),
    ("uniaxial", "harmonic", "[100]", 1.1),
    ("uniaxial", "harmonic", "[110]", 0.9),
    ("uniaxial", "harmonic", "[110]", 1.1),
]


@pytest.mark.parametrize("loading, potential, direction, s", PRESTRESSED)
def test_prestressed_matches_eq17(loading, potential, direction, s):
    """Reference: surfwave.point(...)["c2_R"], the root of Eq. (17) with S of Eq. (A11) selected
    by the unsquared boundary condition (docs/physics/paper.md "Rayleigh velocity"). The lattice solve
    tests the prestressed free-surface condition independently."""
    ref = float(surfwave.point("fcc", loading, potential, direction, s)["c2_R"][0])
    res = long_wave_c2("fcc", loading, potential, direction, s, k=K_MAX, levels=LEVELS)
    assert res["c2_R"] == pytest.approx(ref, rel=RTOL)


def test_supersonic_decoupled_110_is_sagittal_and_localised():
    """Reference: docs/physics/paper.md: along [110] the sagittal surface wave is faster than the
    shear-horizontal bulk wave (c_R > c_SH, "supersonic_decoupled") and exists because the
    z -> -z mirror decouples it. Checked on the full 3x3-block slab: the xz, yz blocks vanish,
    SH modes lie below the surface wave, and the eigenvector at the surface-wave frequency
    has no z component and is localised at layer 0."""
    k = 0.4
    pt = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.0)
    assert pt["wave_type"][0] == "supersonic_decoupled"
    sag = surface_mode("fcc", "in_plane_hydrostatic", "lj", "[110]", 1.0, k)
    assert sag["c2"] > float(pt["c2_SH"][0])
    assert sag["tail"] < 1e-6 and sag["surface_weight"] > 0.1

    crystal = build("fcc", "in_plane_hydrostatic", None, "[110]", 1.0)
    a0, a0s, a1, _ = (m[0] for m in layer_matrices(crystal, "lj", k))
    sagittal_blocks(a0[None], a0s[None], a1[None])  # raises unless the z coupling vanishes
    h = slab_matrix(a0, a0s, a1, sag["n_layers"])
    v0 = np.ones(h.shape[0], dtype=complex)
    lowest, lv = eigsh(h, k=1, sigma=0.0, which="LM", v0=v0)
    z_weight_low = np.sum(np.abs(lv[2::3, 0]) ** 2)
    assert lowest[0] < sag["omega2"] and z_weight_low > 0.999  # an SH mode lies lower
    w, v = eigsh(h, k=1, sigma=sag["omega2"] * (1 - 1e-9), which="LM", v0=v0)
    assert w[0] == pytest.approx(sag["omega2"], rel=1e-10)
    mode = v[:, 0].reshape(-1, 3)
    assert np.sum(np.abs(mode[:, 2]) ** 2) < 1e-16
    assert tail_ratio(mode) < 1e-6


def test_layer_blocks_bulk_limit_and_surface_equilibrium():
    """Reference: docs/physics/paper.md (A7, A11) and "with sigma_yy = 0 the free surface is in equilibrium".
    Translation invariance: A0 + A1 + A1^H = 0 at k = 0; the bulk matrix
    A0 + A1 + A1^H at small k (normal wavenumber 0) gives rho c^2 = S_xxxx and S_xyyx;
    the bonds a surface atom lacks carry no net force (uniaxial LJ, orthorhombic [110])."""
    loading, pot, direction, s = "uniaxial", "lj", "[110]", 1.04
    crystal = build("fcc", loading, pot, direction, s)
    a0, _, a1, _ = (m[0] for m in layer_matrices(crystal, pot, 0.0))
    np.testing.assert_allclose(a0 + a1 + a1.conj().T, 0, atol=1e-13)
    k = 1e-4
    a0, _, a1, _ = (m[0] for m in layer_matrices(crystal, pot, k))
    c2 = np.sort(np.linalg.eigvalsh(a0 + a1 + a1.conj().T)) / k**2
    pt = surfwave.point("fcc", loading, pot, direction, s)
    expect = np.sort([pt["c2_L_par"][0], pt["c2_T_par"][0], pt["c2_SH"][0]])
    np.testing.assert_allclose(c2, expect, rtol=1e-6)
    b = crystal.bonds[0]
    up = np.concatenate([b, -b])[np.concatenate([b, -b])[:, 1] > 1e-9]
    ru = np.linalg.norm(up, axis=-1)
    force = (get_potential(pot).dphi(ru) / ru)[:, None] * up
    np.testing.assert_allclose(force.sum(axis=0), 0, atol=1e-12)


@pytest.mark.parametrize("loading, d_over_d0, load_direction", [
    ("in_plane_hydrostatic", 1.0, None),
    ("uniaxial", 1.03, "[100]"),
])
def test_non_mirror_angle_matches_general_solver(loading, d_over_d0, load_direction):
    """Reference: the general Stroh/impedance solver (surfwave.point at 20 deg from [100],
    A_ijkl = C_ijkl + sigma_jl delta_ik, nominal-traction condition). The slab solve uses only
    the bond force constants, rotated about the (001) normal, with the full coupled 3 x 3
    blocks; zero stress and uniaxial LJ prestress along [100] (monoclinic lab frame)."""
    ref = float(surfwave.point("fcc", loading, "lj", 20.0, d_over_d0, load_direction=load_direction)["c2_R"][0])
    res = long_wave_c2("fcc", loading, "lj", 20.0, d_over_d0, k=K_MAX, levels=LEVELS,
                       load_direction=load_direction)
    assert res["c2_R"] == pytest.approx(ref, rel=RTOL)
