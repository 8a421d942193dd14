"""A soft surface mode of the prestressed FCC (111) surface before the bulk goes soft.

Morse, (111) in-plane hydrostatic tension: at d/d0 = 1.2647 the sagittal surface mode at the
zone-boundary point M has omega^2 < 0 while the bulk is still stable (found by
surfwave.dynamics.fcc_soft_modes; the bulk goes long-wave unstable at d/d0 ~ 1.26485).
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import eigh

from surfwave.dynamics import fcc_layers as layers
from surfwave.dynamics.fcc_soft_modes import surface_check
from surfwave.dynamics.fcc_surface_phonons import surface_phonons
from surfwave.model_crystals.elastic import elastic_constants, stress
from surfwave.model_crystals.phonons import make_phonopy, zone_scan
from surfwave.model_crystals.potentials import get_potential
from surfwave.solvers.long_wave import long_wave_stability

D_SOFT = 1.2647


def test_soft_surface_mode_at_m_before_the_bulk():
    """References: (1) a dense 300-plane slab (free top, clamped bottom) at q = M has the same
    negative omega^2 (1e-8) with a mode localised at the top; (2) the bulk is stable there by
    phonopy's full-zone scan of the same crystal (finite displacements, 8^3 mesh) and by the
    long-wave strong-ellipticity search of surfwave.point; (3) slightly less stretched
    (1.2640) the same mode is still positive."""
    pot = get_potential("morse")
    r = surface_phonons(pot, "in_plane_hydrostatic", [1.2640, D_SOFT], surface="(111)", q=[[0.5, 0.0]])
    assert r["omega2"][0, 0, 0] > 0 > r["omega2"][1, 0, 0]
    assert r["sector"][1, 0, 0] == 1 and r["bulk_stable"].all()
    sc = layers.surface_crystal("(111)", "in_plane_hydrostatic", pot, [D_SOFT])
    blk = layers.plane_blocks(sc, pot, r["q_cartesian"][1][None])
    dj, n = blk["D"][:, 0, 0], 300
    h = np.zeros((3 * n, 3 * n), complex)
    for layer in range(n):
        h[3 * layer:3 * layer + 3, 3 * layer:3 * layer + 3] = dj[0] - (blk["missing"][0, 0, 0] if layer == 0 else 0)
        if layer + 1 < n:
            h[3 * layer:3 * layer + 3, 3 * layer + 3:3 * layer + 6] = dj[1]
            h[3 * layer + 3:3 * layer + 6, 3 * layer:3 * layer + 3] = dj[1].conj().T
    w, v = eigh(h, subset_by_index=[0, 0])
    assert abs(w[0] - r["omega2"][1, 0, 0]) < 1e-8
    amp = np.linalg.norm(v[:, 0].reshape(n, 3), axis=1)
    assert amp[n // 2:].max() < 1e-2 * amp.max()
    phonon, _ = make_phonopy(sc.crystal, 0, pot, 2, 3e-5)
    zone_min, _ = zone_scan(phonon, sc.crystal.cell[0], 3, 8)
    assert zone_min > 0
    stable, _, _ = long_wave_stability(elastic_constants(sc.crystal.bonds, pot), stress(sc.crystal.bonds, pot))
    assert stable[0]


def test_surface_check_flags_it():
    """Reference: the test above; the walk's per-strain check sees the soft mode on its mesh
    plus path (the path contains M) and reports the bulk stable."""
    r = surface_check("morse", "in_plane_hydrostatic", [D_SOFT], "(111)", n_mesh=4)
    assert r["bulk_stable"][0] and r["softest_omega2"][0] < 0
