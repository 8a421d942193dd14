"""Voigt conversions and rotations (references: the definitions and rotation invariants)."""
import numpy as np

from surfwave.solvers.tensors import (
    cross,
    cubic_voigt,
    hexagonal_voigt,
    rotate2,
    rotate4,
    tensor_to_voigt,
    voigt_to_tensor,
)


def test_voigt_round_trip_and_symmetries():
    """Random symmetric 6x6 -> tensor has minor and major symmetries and converts back."""
    rng = np.random.default_rng(0)
    M = rng.normal(size=(4, 6, 6))
    C6 = M + np.swapaxes(M, -1, -2)
    C = voigt_to_tensor(C6)
    assert np.allclose(C, np.swapaxes(C, -4, -3))           # C_ijkl = C_jikl
    assert np.allclose(C, np.swapaxes(C, -2, -1))           # C_ijkl = C_ijlk
    assert np.allclose(C, np.moveaxis(C, (-4, -3), (-2, -1)))  # C_ijkl = C_klij
    assert np.allclose(tensor_to_voigt(C), C6)


def test_cubic_is_invariant_under_cube_rotations_and_hexagonal_about_c():
    """A cubic tensor is unchanged by a 90 deg turn about a cube axis; a hexagonal one by any
    turn about its c axis (transverse isotropy, C66 = (C11 - C12)/2)."""
    C = voigt_to_tensor(cubic_voigt(168.4, 121.4, 75.4))
    R90 = np.array([[0.0, 1, 0], [-1, 0, 0], [0, 0, 1]])
    assert np.allclose(rotate4(C, R90), C)
    H = voigt_to_tensor(hexagonal_voigt(59.7, 26.2, 21.7, 61.7, 16.4))
    a = 0.37
    Rz = np.array([[np.cos(a), np.sin(a), 0], [-np.sin(a), np.cos(a), 0], [0, 0, 1]])
    assert np.allclose(rotate4(H, Rz), H)
    assert not np.allclose(rotate4(C, Rz), C)


def test_rotate2_matches_matrix_product():
    rng = np.random.default_rng(1)
    s = rng.normal(size=(3, 3))
    Q, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    assert np.allclose(rotate2(s, Q), Q @ s @ Q.T)


def test_stacked_rotate4_has_the_bits_of_the_einsum_chain():
    """rotate4 of (m, 3, 3, 3, 3) stacks (stacked_rotate4, products and sums of whole arrays) gives
    every entry with the bits of the four-einsum chain it replaced (reference: that chain, written
    out here), zeros included with their +0 sign: the cubes keep their numbers bit for bit. A
    failure means numpy's einsum adds its terms in another order: the fast path must follow it."""
    rng = np.random.default_rng(5)
    for m in (8, 57, 400):
        R = np.linalg.qr(rng.normal(size=(m, 3, 3)))[0]
        C = rng.normal(size=(m, 3, 3, 3, 3)) * 100.0
        C[:2] = 0.0                                   # exact zeros (signs)
        C[2, 0] = -0.0
        R[3] = np.eye(3)
        ref = np.einsum("...ai,...ijkl->...ajkl", R, C)
        for spec in ("...bj,...ajkl->...abkl", "...ck,...abkl->...abcl", "...dl,...abcl->...abcd"):
            ref = np.einsum(spec, R, ref)
        out = rotate4(C, R)
        assert np.array_equal(out, ref)
        assert np.array_equal(np.signbit(out), np.signbit(ref))


def test_cross_has_the_bits_of_np_cross():
    """tensors.cross (used on the hot path for the lab axes) equals np.cross (the reference) bit
    for bit, broadcasting a stack against one vector and one vector against a stack."""
    rng = np.random.default_rng(6)
    a, b = rng.normal(size=(50, 3)), rng.normal(size=(50, 3))
    for x, y in ((a, b), (a, b[0]), (a[0], b), (a[0], b[0]), (a.reshape(5, 10, 3), b[:10])):
        assert np.array_equal(cross(x, y), np.cross(x, y))
