"""Surface phonons of the semi-infinite prestressed FCC crystal against independent routes.

The Green's-function solution (:mod:`surfwave.dynamics.fcc_surface_green`) is checked against
Eq. (17) and the general Stroh solver (continuum, no lattice sum), dense eigen-solves of thick
slabs built plane by plane (no decimation), direct elimination of a thick slab's Green's
function, an exact sum rule, and phonopy's bulk dynamical matrix.
"""
from __future__ import annotations

import numpy as np
import pytest
from scipy.linalg import eigh

import surfwave
from surfwave.dynamics import fcc_layers as layers
from surfwave.dynamics.fcc_surface_green import bulk_band_edges, decimate, inv
from surfwave.dynamics.fcc_surface_phonons import surface_phonons
from surfwave.errors import InputError
from surfwave.model_crystals.elastic import elastic_constants, stress
from surfwave.model_crystals.phonons import dynamical_matrix, make_phonopy
from surfwave.model_crystals.potentials import get_potential
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.stroh import surface_wave

#: Richardson over k = 0.2, 0.1, ..., 0.0125 rad/d0: measured error ~1e-11 relative.
K_MAX, LEVELS = 0.2, 5
RTOL_LONG_WAVE = 1e-8
#: Gauss-Legendre nodes of the sum rule (measured: 1e-10 at 1200).
N_SUM_RULE = 1200


def _long_wave_c2(surface, loading, pot, s, direction, load_direction=None, sagittal=False):
    """Richardson limit of omega^2/k^2 of the lowest surface mode along ``direction`` (e1, e3)
    (with ``sagittal``: the lowest of the even mirror sector)."""
    sc = layers.surface_crystal(surface, loading, pot, [s], load_direction)
    ks = K_MAX / 2.0 ** np.arange(LEVELS)
    q_red = np.einsum("ij,kj->ki", sc.cell2d[0], ks[:, None] * np.asarray(direction)) / (2 * np.pi)
    r = surface_phonons(pot, loading, s, surface=surface, q=q_red, load_direction=load_direction)
    w2 = np.where(r["sector"][0] == 1, r["omega2"][0], np.inf) if sagittal else r["omega2"][0]
    table = [np.nanmin(w2, axis=-1) / ks**2]
    for j in range(1, LEVELS):
        prev = table[-1]
        table.append((2.0**j * prev[1:] - prev[:-1]) / (2.0**j - 1.0))
    return float(table[-1][0]), sc


@pytest.mark.parametrize("loading, pot, lab_direction, s", [
    ("in_plane_hydrostatic", "lj", "[100]", 0.97),
    ("in_plane_hydrostatic", "harmonic", "[100]", 1.03),
    ("in_plane_hydrostatic", "morse", "[110]", 1.02),
    ("uniaxial", "lj", "[100]", 1.03),
    ("uniaxial", "harmonic", "[110]", 0.96),
])
def test_long_wave_slope_is_eq17(loading, pot, lab_direction, s):
    """Reference: surfwave.point(...)["c2_R"], Eq. (17) with S of Eq. (A11) for the same
    crystal and propagation direction (lab x). The [110] in-plane hydrostatic case is
    "supersonic_decoupled": found only through the mirror-sector split."""
    ld = lab_direction if loading == "uniaxial" else None
    sc = layers.surface_crystal("(001)", loading, pot, [s], ld)
    crystal_dir = {"[100]": np.array([1.0, 0.0, 0.0]), "[110]": np.array([1.0, 1.0, 0.0]) / np.sqrt(2)}
    lab = lab_axes("(001)", ld or "[100]") @ crystal_dir[lab_direction]
    d = sc.rotation[0] @ lab
    pt = surfwave.point("fcc", loading, pot, lab_direction, s)
    sagittal = pt["wave_type"][0] == "supersonic_decoupled"
    c2, _ = _long_wave_c2("(001)", loading, pot, s, d[[0, 2]] / np.linalg.norm(d[[0, 2]]), ld, sagittal)
    ref = float(pt["c2_R"][0])
    assert c2 == pytest.approx(ref, rel=RTOL_LONG_WAVE)


def _stroh_c2(sc, pot, direction):
    """Continuum reference: stroh.surface_wave with A = V C + V sigma delta of the same bonds,
    rotated into the frame (propagation, inward normal, propagation x normal)."""
    d3 = np.array([direction[0], 0.0, direction[1]])
    frame = np.array([d3, [0.0, 1.0, 0.0], np.cross(d3, [0.0, 1.0, 0.0])])
    bonds = sc.bonds[0] @ frame.T
    c = elastic_constants(bonds, pot)
    a = c + np.einsum("jl,ik->ijkl", stress(bonds, pot), np.eye(3))
    res = surface_wave(a, 1.0)
    return float(res["c"]) ** 2, str(res["wave_type"])


@pytest.mark.parametrize("surface, loading, pot, s, angle, ld", [
    ("(111)", "in_plane_hydrostatic", "lj", 1.02, 0.0, None),
    ("(111)", "in_plane_hydrostatic", "harmonic", 0.97, 90.0, None),
    ("(111)", "uniaxial", "lj", 0.98, 30.0, None),
    ("(110)", "uniaxial", "harmonic", 1.0, 0.0, "[110]"),
    ("(110)", "uniaxial", "lj", 1.0, 90.0, "[110]"),
    ("(110)", "in_plane_hydrostatic", "harmonic", 0.99, 0.0, None),
    ("(110)", "in_plane_hydrostatic", "lj", 1.01, 90.0, None),
    ("(001)", "uniaxial", "morse", 1.02, 20.0, "[100]"),
])
def test_long_wave_slope_is_stroh(surface, loading, pot, s, angle, ld):
    """Reference: the general Stroh/impedance solver (surfwave.solvers.stroh.surface_wave) on
    the continuum tensor A = C + sigma of the same stressed crystal, any direction (subsonic
    surface waves only)."""
    sc = layers.surface_crystal(surface, loading, pot, [s], ld)
    t = np.radians(angle)
    direction = np.array([np.cos(t), np.sin(t)])
    ref, kind = _stroh_c2(sc, pot, direction)
    assert kind == "surface"
    c2, _ = _long_wave_c2(surface, loading, pot, s, direction, ld)
    assert c2 == pytest.approx(ref, rel=RTOL_LONG_WAVE)


def _slab_eigs(sc, pot, q_cart, n_planes):
    """Dense eigen-solve of a slab of n_planes planes, free top, clamped bottom, built plane by
    plane from D_j (no principal layers, no decimation)."""
    blk = layers.plane_blocks(sc, pot, np.asarray(q_cart, float)[None, None])
    dj = blk["D"][:, 0, 0]
    m = dj.shape[0] - 1
    h = np.zeros((3 * n_planes, 3 * n_planes), complex)
    for l in range(n_planes):
        h[3 * l:3 * l + 3, 3 * l:3 * l + 3] = dj[0]
        if l < m:
            h[3 * l:3 * l + 3, 3 * l:3 * l + 3] -= blk["missing"][l, 0, 0]
        for j in range(1, m + 1):
            if l + j < n_planes:
                h[3 * l:3 * l + 3, 3 * (l + j):3 * (l + j) + 3] = dj[j]
                h[3 * (l + j):3 * (l + j) + 3, 3 * l:3 * l + 3] = dj[j].conj().T
    w, v = eigh(h)
    return w, v.reshape(n_planes, 3, -1)


@pytest.mark.parametrize("surface, loading, pot, s, ld", [
    ("(001)", "in_plane_hydrostatic", "lj", 0.98, None),
    ("(001)", "uniaxial", "morse", 1.02, "[110]"),
    ("(111)", "in_plane_hydrostatic", "harmonic", 1.03, None),
    ("(111)", "uniaxial", "lj", 1.01, None),
    ("(110)", "uniaxial", "lj", 0.99, "[100]"),
])
def test_zone_boundary_modes_match_thick_slab(surface, loading, pot, s, ld):
    """Reference: dense eigenvalues of a 90-plane slab (free top, clamped bottom) at every
    zone-boundary point: each Green's-function surface mode is a slab eigenvalue to 1e-9
    relative, and that slab mode is localised at the top."""
    pts = layers.SYMMETRY_POINTS[surface]
    labels = [k for k in pts if k != "G"]
    q = np.array([pts[k] for k in labels])
    r = surface_phonons(pot, loading, s, surface=surface, q=q, load_direction=ld)
    sc = layers.surface_crystal(surface, loading, pot, [s], ld)
    checked = 0
    for i in range(q.shape[0]):
        w, v = _slab_eigs(sc, pot, r["q_cartesian"][0, i], 90)
        qc = r["q_cartesian"][0, i]
        qh = np.array([qc[0], 0.0, qc[1]]) / np.linalg.norm(qc)
        frame = np.array([qh, [0.0, 1.0, 0.0], np.cross(qh, [0.0, 1.0, 0.0])])
        for lam, dec, pol in zip(r["omega2"][0, i], r["decay"][0, i], r["polarisation"][0, i]):
            if not np.isfinite(lam) or dec > 0.8:
                continue
            j = np.argmin(np.abs(w - lam))
            if np.min(np.abs(np.delete(w, j) - lam)) > 1e-6:  # non-degenerate: compare polarisation
                top = np.abs(frame @ v[0, :, j]) ** 2
                np.testing.assert_allclose(pol, top / top.sum(), atol=1e-8)
            assert w[j] == pytest.approx(lam, rel=1e-9, abs=1e-12)
            amp = np.linalg.norm(v[:, :, j], axis=1)
            assert amp[45:].max() < 1e-3 * amp.max()
            if 0.2 < dec < 0.8:  # decay per plane: the slab mode's amplitude ratio deep inside
                ratio = (amp[24:30].sum() / amp[4:10].sum()) ** (1 / 20)
                assert ratio == pytest.approx(dec, rel=2e-2)
            checked += 1
    assert checked >= q.shape[0]


def test_spectral_density_matches_direct_slab_elimination():
    """Reference: G_00(z) of a 1500-layer slab by direct block elimination from its clamped
    bottom (no decimation); at Im z = 0.05 the finite slab differs from the half crystal by
    ~exp(-1500 Im k_perp), far below the tolerance."""
    sc = layers.surface_crystal("(001)", "uniaxial", "lj", [1.02], "[100]")
    qc = layers.cartesian_q(sc, np.array([[0.9, 0.4]]))
    h00, h00s, h01 = layers.principal_blocks(layers.plane_blocks(sc, "lj", qc))
    omega = np.linspace(0.05, 3.0, 37)
    z = omega**2 + 0.05j
    res = decimate(z, h00[0, 0], h00s[0, 0], h01[0, 0])
    g_dec = inv(z[:, None, None] * np.eye(3) - res["eps_s"])
    g = inv(z[:, None, None] * np.eye(3) - h00[0, 0])
    a = h01[0, 0]
    for _ in range(1500):
        g = inv(z[:, None, None] * np.eye(3) - h00[0, 0] - a @ g @ a.conj().T)
    g_top = inv(z[:, None, None] * np.eye(3) - h00s[0, 0] - a @ g @ a.conj().T)
    assert np.abs(g_dec - g_top).max() < 1e-10 * np.abs(g_top).max()
    r = surface_phonons("lj", "uniaxial", 1.02, q=[[0.9, 0.4]], omega=omega, eta=0.05, load_direction="[100]")
    ref = -2 * omega / np.pi * np.trace(g_top, axis1=-2, axis2=-1).imag
    np.testing.assert_allclose(r["spectral_density"][0, 0], ref, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("surface, q", [("(001)", [0.3, 0.1]), ("(110)", [0.2, 0.35])])
def test_sum_rule(surface, q):
    """Reference: the exact sum rule -(1/pi) int Im Tr_top G(lambda + i eta) d lambda = 3 (one
    atom's degrees of freedom) over the whole real line, by Gauss-Legendre on
    lambda = c + w tan(theta)."""
    loading, ld = ("uniaxial", "[110]") if surface == "(110)" else ("in_plane_hydrostatic", None)
    sc = layers.surface_crystal(surface, loading, "lj", [0.99], ld)
    qc = layers.cartesian_q(sc, np.array([q]))
    h00, h00s, h01 = layers.principal_blocks(layers.plane_blocks(sc, "lj", qc))
    x, wts = np.polynomial.legendre.leggauss(N_SUM_RULE)
    theta = 0.5 * np.pi * x * (1 - 1e-12)
    lam = 4.0 + 6.0 * np.tan(theta)
    jac = 6.0 / np.cos(theta) ** 2 * 0.5 * np.pi
    z = lam + 0.3j
    d = h00.shape[-1]
    res = decimate(z, h00[0, 0], h00s[0, 0], h01[0, 0])
    g = inv(z[:, None, None] * np.eye(d) - res["eps_s"])
    dens = -np.trace(g[:, :3, :3], axis1=-2, axis2=-1).imag / np.pi
    assert np.sum(wts * jac * dens) == pytest.approx(3.0, abs=1e-8)


#: Phonopy's finite-displacement amplitude (d0); its error on omega^2 is measured ~1e-7 here.
DISPLACEMENT = 3e-5


def test_bulk_band_edges_match_phonopy():
    """Reference: phonopy's dynamical matrix of the same stressed crystal (finite
    displacements, 2x2x2 supercell) at Q = q + (phi/h) n: eigenvalues at sample phases, and the
    band edges as the min/max over a fine phi grid."""
    pot = get_potential("lj")
    sc = layers.surface_crystal("(111)", "uniaxial", pot, [1.02])
    q = np.array([[0.23, 0.11], [0.5, 0.0]])
    qc = layers.cartesian_q(sc, q)
    h00, _, h01 = layers.principal_blocks(layers.plane_blocks(sc, pot, qc))
    edges = bulk_band_edges(h00[0], h01[0])
    phonon, _ = make_phonopy(sc.crystal, 0, pot, 2, DISPLACEMENT)
    rot, h = sc.rotation[0], sc.spacing[0]
    phis = np.linspace(0, 2 * np.pi, 721)
    for i in range(q.shape[0]):
        qs = np.array([qc[0, i, 0], 0.0, qc[0, i, 1]])
        w = np.array([np.linalg.eigvalsh(dynamical_matrix(phonon, rot.T @ (qs + p / h * np.array([0, 1.0, 0])),
                                                            sc.crystal.cell[0])) for p in phis])
        z = np.exp(1j * phis[::60])[:, None, None]
        mine = np.linalg.eigvalsh(h00[0, i] + h01[0, i] * z + h01[0, i].conj().T / z)
        np.testing.assert_allclose(mine, w[::60], atol=1e-7)
        np.testing.assert_allclose(edges[i, :, 0], w.min(axis=0), atol=2e-5)
        np.testing.assert_allclose(edges[i, :, 1], w.max(axis=0), atol=2e-5)
        assert np.all(edges[i, :, 0] <= w.min(axis=0) + 1e-7)
        assert np.all(edges[i, :, 1] >= w.max(axis=0) - 1e-7)


@pytest.mark.parametrize("surface", ["(111)", "(110)"])
def test_in_plane_hydrostatic_geometry(surface):
    """Reference: the bond-sum stress (surfwave.model_crystals.elastic.stress): sigma . n = 0
    and sigma isotropic in the surface plane, for the closed-form (111) stretch
    t = sqrt((3 - s^2)/2) and the Newton-solved (110) stretches."""
    for pot in ("lj", "harmonic", "morse"):
        sc = layers.surface_crystal(surface, "in_plane_hydrostatic", pot, [0.985, 1.04])
        sig = np.einsum("nia,nab,njb->nij", sc.rotation, stress(sc.crystal.bonds, pot), sc.rotation)
        assert np.abs(sig[:, 1, :]).max() < 1e-13
        np.testing.assert_allclose(sig[:, 0, 0], sig[:, 2, 2], rtol=1e-11)
        assert np.abs(sig[:, 0, 2]).max() < 1e-13
        assert np.all(np.abs(sig[:, 0, 0]) > 1e-3)


def test_gamma_corners_and_degeneracy():
    """Reference: symmetry. At Gamma the bulk band starts at omega = 0 and no mode is a true
    surface mode; the (111) K corner is three-fold, so the result must not depend on which
    of the equivalent corners (1/3, 1/3), (2/3, -1/3), (-1/3, 2/3) is asked for."""
    r = surface_phonons("lj", "in_plane_hydrostatic", 1.0, surface="(111)",
                        q=[[0, 0], [1 / 3, 1 / 3], [2 / 3, -1 / 3], [-1 / 3, 2 / 3]])
    assert np.all(np.isnan(r["omega"][0, 0]))
    assert abs(r["band_edges_omega2"][0, 0, 0, 0]) < 1e-12
    np.testing.assert_allclose(r["omega"][0, 2], r["omega"][0, 1], rtol=1e-10)
    np.testing.assert_allclose(r["omega"][0, 3], r["omega"][0, 1], rtol=1e-10)
    assert np.isfinite(r["omega"][0, 1, 0])


def test_beyond_bulk_stability_is_nan_with_reason():
    """Reference: the project's phonopy full-zone and long-wave limits
    (surfwave.point(...)["stable"]): LJ in-plane hydrostatic at d/d0 = 1.2 is long-wave
    unstable; results are NaN with a reason, and stable strains are untouched."""
    assert not surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[100]", 1.2)["stable"][0]
    r = surface_phonons("lj", "in_plane_hydrostatic", [1.0, 1.2], q="GXMG", path_density=3)
    assert list(r["bulk_stable"]) == [True, False]
    assert np.all(np.isnan(r["omega"][1])) and np.isnan(r["softest_omega2"][1])
    assert "unstable" in r["reason"][1] and r["reason"][0] == ""
    assert np.isfinite(r["softest_omega2"][0])


@pytest.mark.parametrize("kwargs", [
    {"surface": "(100)"}, {"q": [[0.1, 0.2, 0.3]]}, {"q": "GXQ"}, {"q": [[np.nan, 0.0]]},
    {"omega": [-1.0, 2.0]}, {"eta": 0.0}, {"load_direction": "[110]"}, {"path_density": -1.0},
])
def test_bad_input_is_one_clear_error(kwargs):
    """Reference: the house rule (one InputError before any computation)."""
    with pytest.raises(InputError):
        surface_phonons("lj", "in_plane_hydrostatic", 1.0, **kwargs)


def test_band_edges_find_the_deeper_of_two_wells():
    """Reference: brute force, the lowest bulk branch on 20001 phases. Morse (111) under
    in-plane tension d/d0 = 1.1905 at q = (0.09375, -0.21875) has two minima in the normal
    phase, the deeper one narrow and between grid points; a missed well once produced a
    spurious surface mode at omega^2 = -13 (now: none, and the edge is right)."""
    sc = layers.surface_crystal("(111)", "in_plane_hydrostatic", "morse", [1.1905])
    q = np.array([[0.09375, -0.21875]])
    h00, _, h01 = layers.principal_blocks(layers.plane_blocks(sc, "morse", layers.cartesian_q(sc, q)))
    edges = bulk_band_edges(h00[0], h01[0])
    w = np.linalg.eigvalsh(layers.bulk_matrix(h00[0, 0], h01[0, 0], np.linspace(0, 2 * np.pi, 20001)))
    np.testing.assert_allclose(edges[0, :, 0], w.min(axis=0), atol=1e-7)
    np.testing.assert_allclose(edges[0, :, 1], w.max(axis=0), atol=1e-7)
    r = surface_phonons("morse", "in_plane_hydrostatic", 1.1905, surface="(111)", q=q)
    assert not np.any(r["omega2"] < 0)


@pytest.mark.parametrize("pot, loading, s", [("lj", "in_plane_hydrostatic", 0.97), ("harmonic", "uniaxial", 1.03),
                                             ("morse", "in_plane_hydrostatic", 1.02)])
def test_sine_law_along_gamma_x(pot, loading, s):
    """Reference: Eq. (17)'s c_R along [110] (surfwave.point) and the sine law
    omega(q) = (2 c_R / a) sin(q a / 2), a the row period along [110]: the sagittal surface mode
    of FCC (001) along Gamma-X follows it at every q (found here, the analogue of the
    triangular lattice's Eq. 15), to rounding."""
    ld = "[110]" if loading == "uniaxial" else None
    q = np.linspace(0.02, 1.0, 12)[:, None] * np.array([0.5, 0.0])
    r = surface_phonons(pot, loading, s, q=q, load_direction=ld)
    w = np.nanmin(np.where(r["sector"][0] == 1, r["omega"][0], np.nan), axis=-1)
    a = np.linalg.norm(layers.surface_crystal("(001)", loading, pot, [s], ld).cell2d[0, 0])
    c_r = np.sqrt(surfwave.point("fcc", loading, pot, "[110]", s)["c2_R"][0])
    qn = np.linalg.norm(r["q_cartesian"][0], axis=-1)
    np.testing.assert_allclose(w, 2 * c_r / a * np.sin(qn * a / 2), rtol=1e-11)


@pytest.mark.parametrize("pot, s", [("lj", 0.97), ("morse", 1.05)])
def test_sine_law_along_gamma_m_of_111(pot, s):
    """Reference: the general Stroh solver's c_R along Gamma-M of (111) (continuum, same bonds) and
    the sine law omega = (2 c_R / L) sin(q L / 2), L = pi / |q_M|: the sagittal surface mode
    follows it at every q, to rounding."""
    q = np.linspace(0.05, 1.0, 10)[:, None] * np.array([0.5, 0.0])
    r = surface_phonons(pot, "in_plane_hydrostatic", s, surface="(111)", q=q)
    w = np.nanmin(np.where(r["sector"][0] == 1, r["omega"][0], np.nan), axis=-1)
    qc = r["q_cartesian"][0]
    qn = np.linalg.norm(qc, axis=-1)
    sc = layers.surface_crystal("(111)", "in_plane_hydrostatic", pot, [s])
    c2, kind = _stroh_c2(sc, pot, qc[-1] / qn[-1])
    assert kind in ("surface", "supersonic_decoupled")  # Gamma-M lies on a mirror: sagittal wave
    length = np.pi / qn[-1]
    np.testing.assert_allclose(w, 2 * np.sqrt(c2) / length * np.sin(qn * length / 2), rtol=1e-9)
