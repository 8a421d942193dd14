"""Soft surface modes of prestressed FCC before the bulk goes soft (surfwave.dynamics.fcc_soft_modes).

On (001) and (111) the first surface mode to go soft is the sagittal Rayleigh branch along a
line where it follows the sine law, so it softens as a whole, together with Eq. (17)'s c_R: the
long-wave theory sees it. On the (unrelaxed) (110) surface a zone-corner mode goes soft while
c_R stays positive in every direction.
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
    (1.2640) the same mode is still positive. (Morse, (111) in-plane tension; the whole
    Gamma-M sagittal branch is soft here and the Stroh solver finds no surface wave along it.)"""
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


def test_001_x_point_softens_with_eq17():
    """Reference: Eq. (17) (surfwave.point along [110]). LJ (001) under in-plane tension: the
    X-point sagittal mode goes soft between d/d0 = 1.1189 and 1.1190, exactly where Eq. (17)
    loses its [110] root (the Gamma-X branch follows the sine law, so it softens as a whole),
    before the bulk (long-wave unstable at 1.1195)."""
    import surfwave

    r = surface_phonons("lj", "in_plane_hydrostatic", [1.1189, 1.1190], q=[[0.5, 0.0]])
    sag = np.where(r["sector"][:, 0] == 1, r["omega2"][:, 0], np.nan)
    low = np.nanmin(sag, axis=-1)
    assert low[0] > 0 > low[1] and r["bulk_stable"].all()
    c2 = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[110]", [1.1189, 1.1190])["c2_R"]
    assert c2[0] > 0 and np.isnan(c2[1])


def test_110_finite_q_soft_mode_unseen_by_long_wave():
    """References: a dense 120-plane slab at the zone corner S (same negative omega^2), phonopy's
    full-zone scan and the long-wave criterion (bulk stable), and the general Stroh solver
    (c_R^2 > 0 in every direction of the surface). LJ, (011) surface under uniaxial tension
    along [100], d/d0 = 1.204, unrelaxed bulk-terminated surface (the model of fcc_layers)."""
    pot = get_potential("lj")
    s = 1.204
    r = surface_phonons(pot, "uniaxial", s, surface="(110)", q=[[0.5, 0.5]], load_direction="[100]")
    assert r["omega2"][0, 0, 0] < -0.01 and r["bulk_stable"][0]
    sc = layers.surface_crystal("(110)", "uniaxial", pot, [s], "[100]")
    blk = layers.plane_blocks(sc, pot, r["q_cartesian"][0][None])
    dj, n = blk["D"][:, 0, 0], 120
    h = np.zeros((3 * n, 3 * n), complex)
    for layer in range(n):
        h[3 * layer:3 * layer + 3, 3 * layer:3 * layer + 3] = dj[0] - (blk["missing"][layer, 0, 0] if layer < 2 else 0)
        for j in (1, 2):
            if layer + j < n:
                h[3 * layer:3 * layer + 3, 3 * (layer + j):3 * (layer + j) + 3] = dj[j]
                h[3 * (layer + j):3 * (layer + j) + 3, 3 * layer:3 * layer + 3] = dj[j].conj().T
    w = eigh(h, eigvals_only=True, subset_by_index=[0, 0])
    assert abs(w[0] - r["omega2"][0, 0, 0]) < 1e-9
    phonon, _ = make_phonopy(sc.crystal, 0, pot, 2, 3e-5)
    assert zone_scan(phonon, sc.crystal.cell[0], 3, 8)[0] > 0
    from surfwave.solvers.stroh import surface_wave

    c2 = []
    for ang in np.arange(0.0, 180.0, 15.0):
        t = np.radians(ang)
        d3 = np.array([np.cos(t), 0.0, np.sin(t)])
        frame = np.array([d3, [0.0, 1.0, 0.0], np.cross(d3, [0.0, 1.0, 0.0])])
        b = sc.bonds[0] @ frame.T
        c2.append(float(surface_wave(elastic_constants(b, pot) + np.einsum("jl,ik->ijkl", stress(b, pot), np.eye(3)),
                                     1.0)["c"]) ** 2)
    assert min(c2) > 1e-3


def test_walk_finds_the_project_bulk_limits():
    """Reference: surfwave.model_crystals.stability.instability_limits (the analytic long-wave
    criterion, walked and bisected by the project's own code): the soft-mode walk's bulk limits
    of LJ (001) in-plane hydrostatic agree to its tolerance, and the tension side reports the
    X-point surface softening first (test_001_x_point_softens_with_eq17)."""
    from surfwave.dynamics.fcc_soft_modes import first_instabilities
    from surfwave.model_crystals.stability import instability_limits

    r = first_instabilities("lj", "in_plane_hydrostatic", "(001)", step=0.075, tol=2e-4, n_mesh=2,
                            search=(0.85, 1.15))
    ref = instability_limits("fcc", "in_plane_hydrostatic", "lj", "[100]", kind="long_wave", tol=1e-4)
    assert abs(r["d_bulk"][0] - ref[0]) < 3e-4 and r["first"][0] == "bulk"
    assert r["first"][1] == "surface" and r["d_surface"][1] < ref[1]
