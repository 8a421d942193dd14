"""Third-order elastic constants: tensors, the deformation solve, the stressed constants.

References: the cubic point-group symmetry of C3; analytic derivatives of the pair potentials
against finite differences; and the kinematics check of the issue: for the nearest-neighbour
harmonic and Lennard-Jones FCC crystals, C2 and C3 from pair sums at d0 (analytic), then the
stressed constants C* and the Cauchy stress through the third-order expansion must approach
the *exact* pair sums at the deformed geometry (Eq. A12, ``surfwave.model_crystals.elastic``) with
errors falling as strain^2 (C*) and strain^3 (sigma), and c_R through them must approach
``surfwave.point``'s c_R at the same order. The order is fitted, not a single value checked.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import get_potential
from surfwave.real_crystals.toec import (
    cauchy_stress,
    cubic_toec,
    deformation_for_stress,
    lagrangian_strain,
    stressed_constants,
    stressed_state,
    toec_tensor,
)
from surfwave.solvers import rayleigh
from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor

CU_C2 = cubic_voigt(168.4, 121.4, 75.4)
CU_C3 = cubic_toec(-1271, -814, -50, -3, -780, -95)  # Hiki & Granato (1966)


def _rotate6(C, R):
    out = C
    for axis in range(6):
        out = np.moveaxis(np.tensordot(R, out, axes=([1], [axis])), 0, axis)
    return out


def test_cubic_toec_has_cubic_symmetry_and_full_index_symmetry():
    """C3 from six constants is symmetric in its three Voigt indices and invariant under the
    cube's 90 degree rotations and the 3-fold [111] rotation, but not a generic rotation."""
    C3v = cubic_toec(*np.arange(1.0, 7.0))
    assert np.allclose(C3v, np.transpose(C3v, (1, 0, 2))) and np.allclose(C3v, np.transpose(C3v, (2, 1, 0)))
    C3 = toec_tensor(C3v)
    for R in (np.array([[0.0, 1, 0], [-1, 0, 0], [0, 0, 1]]), np.array([[0.0, 1, 0], [0, 0, 1], [1, 0, 0]])):
        assert np.allclose(_rotate6(C3, R), C3)
    a = 0.3
    Rz = np.array([[np.cos(a), np.sin(a), 0], [-np.sin(a), np.cos(a), 0], [0, 0, 1]])
    assert not np.allclose(_rotate6(C3, Rz), C3)


@pytest.mark.parametrize("name", ["harmonic", "lj", "morse"])
def test_third_derivative_of_the_pair_potentials(name):
    """d3phi against a central difference of the analytic d2phi (error ~h^2 ~ 1e-10)."""
    pot = get_potential(name)
    r = np.linspace(0.85, 1.3, 11)
    h = 1e-5
    fd = (pot.d2phi(r + h) - pot.d2phi(r - h)) / (2 * h)
    assert np.allclose(pot.d3phi(r), fd, atol=1e-7, rtol=1e-7)


def test_pair_sum_toec_of_fcc_is_cubic_with_cauchy_relations():
    """C3 of nearest-neighbour central forces in cube axes has cubic form: rebuilding it from
    its C111, C112, C123, C144, C155, C456 gives the same tensor (this fixes where C144 and
    C155 go), and bonds along <110> give C123 = C144 = C456 = 0, C112 = C155 (Cauchy)."""
    c = build("fcc", "in_plane_hydrostatic", None, "[100]", [1.0])
    lab = np.array([[1.0, 0, 0], [0, 0, 1], [0, -1, 0]])          # lab rows in crystal axes
    bonds = c.bonds[0] @ lab                                        # back to crystal axes
    C3 = elastic.third_order_constants(bonds, "lj") / c.volume[0]
    idx = {"C111": (0, 0, 0, 0, 0, 0), "C112": (0, 0, 0, 0, 1, 1), "C123": (0, 0, 1, 1, 2, 2),
           "C144": (0, 0, 1, 2, 1, 2), "C155": (0, 0, 0, 2, 0, 2), "C456": (1, 2, 0, 2, 0, 1)}
    consts = {k: C3[i] for k, i in idx.items()}
    assert np.allclose(toec_tensor(cubic_toec(*consts.values())), C3, atol=1e-12)
    assert abs(consts["C123"]) < 1e-12 and abs(consts["C144"]) < 1e-12 and abs(consts["C456"]) < 1e-12
    assert consts["C112"] == pytest.approx(consts["C155"]) and consts["C155"] != 0


def _kinematics(potential, direction, strains):
    """Errors of sigma, C* and c_R^2 through the third-order expansion vs exact pair sums."""
    c0 = build("fcc", "in_plane_hydrostatic", None, direction, [1.0])
    V0 = c0.volume[0]
    C2 = elastic.elastic_constants(c0.bonds[0], potential) / V0
    C3 = elastic.third_order_constants(c0.bonds[0], potential) / V0
    s = 1.0 + np.asarray(strains)
    exact = surfwave.point("fcc", "in_plane_hydrostatic", potential, direction, s)
    crystal = build("fcc", "in_plane_hydrostatic", None, direction, s)
    F = np.einsum("ni,ij->nij", crystal.stretch, np.eye(3))         # lab frame, diagonal
    sig = cauchy_stress(F, C2, C3)
    Cs = stressed_constants(C2, C3, F)
    V = crystal.volume
    err_sigma = np.abs(sig - elastic.stress(crystal.bonds, potential) / V[:, None, None]).max(axis=(1, 2))
    err_C = np.abs(Cs - exact["C"] / V[:, None, None, None, None]).max(axis=(1, 2, 3, 4))
    c2 = rayleigh.solve(elastic.stress_derivatives(sig, Cs), 1.0 / V)["c2_R"]
    return err_sigma, err_C, np.abs(c2 - exact["c2_R"])


def _order(h, err):
    return np.polyfit(np.log(h), np.log(err), 1)[0]


@pytest.mark.parametrize("potential", ["harmonic", "lj"])
@pytest.mark.parametrize("direction", ["[100]", "[110]"])
def test_third_order_expansion_approaches_exact_pair_sums_at_second_order(potential, direction):
    """Kinematics check (module docstring): for d/d0 - 1 = +-0.001 ... 0.008, the fitted order
    of the error is ~2 for C* and c_R^2, ~3 for the Cauchy stress, on both sides of d0."""
    h = 0.001 * 2.0 ** np.arange(4)
    for sign in (1.0, -1.0):
        e_sig, e_C, e_R = _kinematics(potential, direction, sign * h)
        assert 2.8 < _order(h, e_sig) < 3.2, e_sig
        assert 1.8 < _order(h, e_C) < 2.2, e_C
        assert 1.8 < _order(h, e_R) < 2.2, e_R
        assert e_R[0] < 1e-3  # and small against c_R^2 ~ 0.6 (LJ: ~28 strain^2)


def test_deformation_solve_inverts_the_stress_vectorised():
    """Round trip F -> sigma(F) -> F for random symmetric stretches, leading axes (2, 3),
    with and without C3 (None: geometric nonlinearity only)."""
    rng = np.random.default_rng(3)
    E = 0.01 * rng.normal(size=(2, 3, 3, 3))
    F = np.eye(3) + 0.5 * (E + np.swapaxes(E, -1, -2))
    for C3 in (CU_C3, None):
        sol = deformation_for_stress(cauchy_stress(F, CU_C2, C3), CU_C2, C3)
        assert sol["ok"].shape == (2, 3) and sol["ok"].all()
        assert np.allclose(sol["F"], F, atol=1e-10, rtol=0)
        assert sol["iterations"].max() <= 6
        assert np.allclose(sol["eta"], lagrangian_strain(F), atol=1e-10)


def test_stressed_state_switch_and_linear_limit():
    """C3 None is the fixed-C model (C* = C2, F = I, rho0); with C3 the small-stress F is
    I + S2 : sigma (linear elasticity, compliance of copper: s11 = (C11 + C12)/((C11 - C12)(C11 + 2 C12)))."""
    sigma = np.diag([1e-3, 0.0, 0.0])
    fixed = stressed_state(CU_C2, None, sigma, 8960.0)
    assert fixed["ok"] and np.allclose(fixed["C_star"], voigt_to_tensor(CU_C2)) and fixed["rho"] == 8960.0
    st = stressed_state(CU_C2, CU_C3, sigma, 8960.0)
    s11 = (168.4 + 121.4) / ((168.4 - 121.4) * (168.4 + 2 * 121.4))
    assert st["F"][0, 0] - 1.0 == pytest.approx(s11 * 1e-3, rel=2e-3)
    assert st["rho"] == pytest.approx(8960.0 / np.linalg.det(st["F"]))


def test_extreme_stress_is_nan_with_a_reason_and_bad_input_is_refused():
    """Stress beyond the model's range gives ok False, NaN and a reason, never a crash or a
    silent number; non-symmetric or wrongly shaped stress is an InputError."""
    sigma = np.zeros((3, 3, 3))
    sigma[:, 0, 0] = [-30.0, 0.1, 20.0]
    st = stressed_state(CU_C2, CU_C3, sigma, 8960.0)
    assert list(st["ok"]) == [False, True, False]
    assert np.isnan(st["C_star"][0]).all() and np.isnan(st["rho"][2])
    assert all(("no homogeneous state" in r) or ("convex" in r) or ("Born" in r) for r in st["reason"][[0, 2]])
    with pytest.raises(InputError, match="symmetric"):
        deformation_for_stress(np.array([[0, 1.0, 0], [0, 0, 0], [0, 0, 0]]), CU_C2, CU_C3)
    with pytest.raises(InputError, match="shape"):
        stressed_state(CU_C2, CU_C3, np.zeros(3), 8960.0)
    with pytest.raises(InputError, match="rho0"):
        stressed_state(CU_C2, CU_C3, np.zeros((3, 3)), -1.0)


def test_pressure_derivative_of_the_bulk_modulus_is_the_closed_form():
    """Under hydrostatic pressure P the effective bulk modulus of the stressed state,
    B(P) = (B*_1111 + 2 B*_1122)/3 with Wallace's B* = C* - P (d_ik d_jl + d_il d_jk - d_ij d_kl),
    has dB/dP = -(C111 + 6 C112 + 2 C123)/(9 B) at P = 0 (closed form from W(eta) along
    eta = e I, derived in docs/physics/third-order-constants.md); checked for every database
    crystal with third-order constants."""
    from surfwave.real_crystals.materials import available_materials, get_material

    for name in available_materials():
        m = get_material(name)
        if m.toec is None:
            continue
        C3, h = cubic_toec(**m.toec), 1e-3
        P = np.array([-h, h])
        C = stressed_state(m.voigt, C3, -P[:, None, None] * np.eye(3), m.rho)["C_star"]
        B = (C[:, 0, 0, 0, 0] + 2 * C[:, 0, 0, 1, 1] + P) / 3
        t, c = m.toec, m.constants
        B0 = (c["C11"] + 2 * c["C12"]) / 3
        assert (B[1] - B[0]) / (2 * h) == pytest.approx(-(t["C111"] + 6 * t["C112"] + 2 * t["C123"]) / (9 * B0),
                                                        rel=1e-6), name


def test_lowest_if_needed_gives_the_flags_of_eigvalsh():
    """The Cholesky certificate in front of the Born and convexity checks: the flags equal
    eigvalsh's lowest eigenvalue > 0 (reference: LAPACK eigvalsh) for stacks that are clearly
    positive, marginal (lowest eigenvalue +-1e-13 .. 1e-6 of the scale) or indefinite, and the
    eigenvalue is reported wherever the certificate did not decide."""
    from surfwave.real_crystals.toec import lowest_if_needed

    rng = np.random.default_rng(11)
    Q = np.linalg.qr(rng.normal(size=(60, 6, 6)))[0]
    w = rng.uniform(1.0, 300.0, (60, 6))
    w[:, 0] = np.concatenate([rng.uniform(1.0, 50.0, 20), 300.0 * np.array([1e-13, -1e-13, 1e-11, -1e-11, 1e-9, 2e-9,
                                                                           -1e-9, 1e-7, -1e-7, 1e-6] * 4)])
    M = Q @ (w[..., None] * np.swapaxes(Q, -1, -2))
    M = 0.5 * (M + np.swapaxes(M, -1, -2))
    for stack in (M[:20], M, M[20:], M[:0]):
        ref = np.linalg.eigvalsh(stack)[..., 0] if len(stack) else np.zeros(0)
        positive, lowest = lowest_if_needed(stack)
        np.testing.assert_array_equal(positive, ref > 0)
        decided = np.isnan(lowest)
        assert np.all(positive[decided])                       # the certificate only ever says "positive"
        np.testing.assert_array_equal(lowest[~decided], ref[~decided])
    assert np.isnan(lowest_if_needed(M[:20])[1]).all()         # clearly positive: no eigenvalue computed


def test_jacobian_products_have_the_bits_of_the_per_matrix_forms():
    """The deformation solve's Jacobian writes its products in cheaper forms that must keep every
    bit (the cubes do not move): one (18, 3) x (3, 3) product per point for six 3 x 3 ones, and
    tr(F^-1 dF) by picking entries (references: the per-matrix products and the einsum over the
    0/1 basis tensors they replaced). A failure means the BLAS or numpy computes these entries in
    another order on this build: the forms must follow it."""
    from surfwave.real_crystals import toec as tm

    rng = np.random.default_rng(8)
    for n in (1, 7, 300):
        X, F = rng.normal(size=(n, 6, 3, 3)), rng.normal(size=(n, 3, 3))
        Ft = np.swapaxes(F, -1, -2)
        assert np.array_equal(tm._times_each(X, Ft), X @ Ft[:, None])
        FX = (F @ np.swapaxes(X, -3, -2).reshape(n, 3, 18)).reshape(n, 3, 6, 3)
        assert np.array_equal(np.swapaxes(FX, -3, -2), F[:, None] @ X)
        Finv = np.linalg.inv(F)
        Finv[0, 1, 2] = -Finv[0, 2, 1]                     # an exact zero trace entry
        trace = Finv[..., tm._VI, tm._VJ]
        trace[..., 3:] += Finv[..., tm._VJ[3:], tm._VI[3:]]
        trace += 0.0
        ref = np.einsum("...ij,...bji->...b", Finv, np.broadcast_to(tm._BASIS, (n, 6, 3, 3)))
        assert np.array_equal(trace, ref) and np.array_equal(np.signbit(trace), np.signbit(ref))
