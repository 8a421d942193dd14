"""Stress, elastic constants, stress derivatives and stability.

References: Eq. (A14) closed forms of the triangular lattice (docs/physics/paper.md); an independent
finite-difference route through the lattice energy W(H) = (1/V) sum phi(|(1 + H) r|), whose
first derivative is sigma and whose second derivative A_ijkl = C_ijkl + sigma_jl delta_ik
gives the acoustic tensor that Eq. (A11) must reproduce (this checks the prestress terms).
"""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import surfwave
from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import get_potential
from surfwave.solvers import long_wave


@pytest.mark.parametrize("pot", ["harmonic"])
def test_triangular_closed_forms_A14(pot):
    """Eq. (A14): V sigma_xx = 4x^2 - 2x, V C_xxxx = 2x + 2x^4, V C_yyyy = 2 - 4x^2 + 2x^4,
    V C_xyxy = 2x^2 - 2x^4 with x = d_x/d0 (harmonic springs, inclined bonds at rest)."""
    d = np.linspace(0.6, 1.9, 50)
    x = d / 2
    c = build("triangular", "uniaxial", None, "[10]", d)
    sig = elastic.stress(c.bonds, pot)
    C = elastic.elastic_constants(c.bonds, pot)
    np.testing.assert_allclose(sig[:, 0, 0], 4 * x**2 - 2 * x, atol=1e-14)
    np.testing.assert_allclose(sig[:, 1, 1], 0.0, atol=1e-14)  # free surface needs no relaxation
    np.testing.assert_allclose(C[:, 0, 0, 0, 0], 2 * x + 2 * x**4, atol=1e-14)
    np.testing.assert_allclose(C[:, 1, 1, 1, 1], 2 - 4 * x**2 + 2 * x**4, atol=1e-14)
    np.testing.assert_allclose(C[:, 0, 1, 0, 1], 2 * x**2 - 2 * x**4, atol=1e-14)


def energy_density(bonds, pot, volume, H):
    """W(H) = (1/V) sum_bonds phi(|(1 + H) r|), H shape (..., d, d) (per atom; times V returned)."""
    p = get_potential(pot)
    r = np.einsum("...ij,bj->...bi", np.eye(bonds.shape[-1]) + H, bonds)
    return p.phi(np.linalg.norm(r, axis=-1)).sum(-1)


def fd_tensors(bonds, pot, h=1e-4):
    """V sigma and V A (A_ijkl = d^2 W / dH_ij dH_kl) by central finite differences."""
    d = bonds.shape[-1]
    E = np.eye(d * d).reshape(d * d, d, d)
    sig = np.array([(energy_density(bonds, pot, 1, h * e) - energy_density(bonds, pot, 1, -h * e)) / (2 * h)
                    for e in E]).reshape(d, d)
    A = np.empty((d * d, d * d))
    for m, em in enumerate(E):
        for n, en in enumerate(E):
            A[m, n] = (energy_density(bonds, pot, 1, h * (em + en)) - energy_density(bonds, pot, 1, h * (em - en))
                       - energy_density(bonds, pot, 1, h * (en - em)) + energy_density(bonds, pot, 1, -h * (em + en))) / (4 * h * h)
    return sig, A.reshape(d, d, d, d)


CASES = [("fcc", "in_plane_hydrostatic", "[100]"), ("fcc", "in_plane_hydrostatic", "[110]"),
         ("fcc", "uniaxial", "[100]"), ("fcc", "uniaxial", "[110]"), ("triangular", "uniaxial", "[10]")]


@settings(max_examples=30, deadline=None)
@given(case=st.sampled_from(CASES), pot=st.sampled_from(["harmonic", "lj", "morse"]), s=st.floats(0.9, 1.1))
def test_A11_matches_energy_hessian(case, pot, s):
    """S from Eq. (A11) reproduces the acoustic tensor Q_ik(n) = A_ijkl n_j n_l of the
    finite-difference energy Hessian for random directions, and the stress itself."""
    c = build(case[0], case[1], pot, case[2], s)
    bonds = c.bonds[0]
    sig_fd, A = fd_tensors(bonds, pot)
    sig = elastic.stress(bonds, pot)
    S = elastic.stress_derivatives(sig, elastic.elastic_constants(bonds, pot))
    np.testing.assert_allclose(sig, sig_fd, rtol=1e-5, atol=1e-6)
    rng = np.random.default_rng(0)
    n = rng.normal(size=(10, bonds.shape[-1]))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    Q_fd = np.einsum("ijkl,nj,nl->nik", A, n, n)
    Q_S = np.einsum("jikl,nj,nl->nik", S, n, n)  # rho c^2 = S_{n e e n}
    np.testing.assert_allclose(Q_S, Q_fd, rtol=1e-5, atol=1e-6)  # FD truncation ~ h^2 phi""""


@pytest.mark.parametrize("case", CASES)
@pytest.mark.parametrize("pot", ["harmonic", "lj"])
def test_free_surface_in_equilibrium(case, pot):
    """docs/physics/paper.md: every loading keeps sigma_yy = 0 (and sigma_zz = 0 for uniaxial), no shear stress."""
    c = build(case[0], case[1], pot, case[2], np.linspace(0.9, 1.1, 9))
    sig = elastic.stress(c.bonds, pot)
    assert np.abs(sig[:, 1, 1]).max() < 1e-12
    off = sig - np.einsum("sii->si", sig)[..., None] * np.eye(c.dim)
    assert np.abs(off).max() < 1e-12
    if case[1] == "uniaxial" and c.dim == 3:
        assert np.abs(sig[:, 2, 2]).max() < 1e-12


def test_unstressed_fcc_voigt_ratios():
    """Nearest-neighbour FCC at zero stress: V C11 : V C12 : V C44 = 1 : 1/2 : 1/2 (C11:C12:C44 = 2:1:1)."""
    r = surfwave.point("fcc", "in_plane_hydrostatic", "harmonic", "[100]", 1.0)
    C = r["C"][0]
    assert C[0, 0, 0, 0] == pytest.approx(1.0)
    assert C[0, 0, 1, 1] == pytest.approx(0.5)
    assert C[0, 1, 0, 1] == pytest.approx(0.5)
    assert r["stable"][0]


def test_stability_sees_instability_off_axis():
    """The paper checks only c_T,par; at d/d0 = 0.88 (LJ, in-plane hydrostatic) c_T,par^2 > 0 yet
    another bulk wave is unstable. Independent check: a dense brute-force direction scan."""
    r = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[100]", 0.88, min_eig=True)
    assert r["c2_T_par"][0] > 0 and not r["stable"][0]
    rng = np.random.default_rng(3)
    n = rng.normal(size=(20000, 3))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    c = build("fcc", "in_plane_hydrostatic", None, "[100]", 0.88)
    sig = elastic.stress(c.bonds, "lj")
    Q = long_wave.acoustic_tensor(elastic.elastic_constants(c.bonds, "lj"), sig, n)
    brute = np.linalg.eigvalsh(Q)[..., 0].min()
    assert brute < 0
    assert r["min_acoustic_eig"][0] <= brute + 1e-9  # the refined search finds at least as low


@pytest.mark.parametrize("pot", ["harmonic", "lj"])
def test_stable_at_zero_stress_everywhere(pot):
    """An unstressed nearest-neighbour crystal is stable in every direction (all cases)."""
    for case in CASES:
        assert surfwave.point(case[0], case[1], pot, case[2], 1.0)["stable"][0]


def test_sound_speeds_definitions():
    """Eq. (A7) index conventions: c_T,par^2 = S_xyyx = C_xyyx + sigma_xx (string tension term)."""
    r = surfwave.point("fcc", "uniaxial", "lj", "[110]", 1.05)
    S, C = r["S"][0], r["C"][0]
    assert r["c2_T_par"][0] == pytest.approx(C[0, 1, 1, 0] + r["stress"][0])
    assert r["c2_L_par"][0] == pytest.approx(C[0, 0, 0, 0] + r["stress"][0])
    assert r["c2_SH"][0] == pytest.approx(S[0, 2, 2, 0])


@settings(max_examples=25, deadline=None)
@given(case=st.sampled_from(CASES), pot=st.sampled_from(["harmonic", "lj"]), s=st.floats(0.9, 1.1))
def test_A11_matches_finite_differences_of_the_stress(case, pot, s):
    """Route through the stress itself: deform the prestressed crystal by F = 1 + H, take the
    Cauchy stress of the deformed bonds (same bond sum, no new physics), convert it to the
    nominal stress V0 P = (V' sigma') F^-T, and differentiate numerically: dP_ij/dH_kl = A_ijkl.
    The acoustic tensor from S (Eq. A11) must match A_ijkl n_j n_l."""
    c = build(case[0], case[1], pot, case[2], s)
    bonds = c.bonds[0]
    dim = bonds.shape[-1]
    h = 1e-6

    def nominal(H):
        F = np.eye(dim) + H
        return elastic.stress(bonds @ F.T, pot) @ np.linalg.inv(F).T

    A = np.empty((dim, dim, dim, dim))
    for k in range(dim):
        for m in range(dim):
            E = np.zeros((dim, dim))
            E[k, m] = h
            A[:, :, k, m] = (nominal(E) - nominal(-E)) / (2 * h)
    S = elastic.stress_derivatives(elastic.stress(bonds, pot), elastic.elastic_constants(bonds, pot))
    n = np.random.default_rng(1).normal(size=(10, dim))
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    np.testing.assert_allclose(np.einsum("jikl,nj,nl->nik", S, n, n),
                               np.einsum("ijkl,nj,nl->nik", A, n, n), rtol=1e-6, atol=1e-8)


def test_stress_derivatives_against_the_delta_sums_with_broadcasting():
    """Eq. (A11) written with explicit Kronecker deltas by einsum (the reference) against
    the in-place form, on random tensors whose leading axes broadcast ((4, 1) with (1, 3)),
    in 2D and 3D."""
    rng = np.random.default_rng(11)
    for dim in (2, 3):
        C = rng.normal(size=(4, 1) + (dim,) * 4)
        sigma = rng.normal(size=(1, 3, dim, dim))
        d = np.eye(dim)
        ref = (np.einsum("...ad,bc->...abcd", sigma, d) + np.einsum("...bd,ac->...abcd", sigma, d)
               - np.einsum("...ab,cd->...abcd", sigma, d) + C)
        np.testing.assert_allclose(elastic.stress_derivatives(sigma, C), ref, rtol=0, atol=1e-14)
