"""Class-32 third-order constants built from the point group (surfwave.real_crystals.toec_classes).

References: Fumi, Phys. Rev. 86, 561 (1952) and Thurston, McSkimin and Andreatch, J. Appl. Phys.
37, 267 (1966): class 32 has 14 independent third-order constants (the ones named); the symmetry
operations of class 32 (3-fold about Z, 2-fold about X) must leave the tensor unchanged; an
isotropic third-order tensor (three constants; it is invariant under every rotation, checked
here with a random rotation, so it belongs to every class) must be rebuilt exactly from its 14
class-32 components: an independent check of every dependent component.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.real_crystals.toec import cubic_toec
from surfwave.real_crystals.toec_classes import TRIGONAL_32_TOEC, invariant_toec_basis, rotate_toec, trigonal_32_toec
from surfwave.solvers.piezo_tensors import _rot


def _named(C3):
    return {k: C3[tuple(int(c) - 1 for c in k[1:])] for k in TRIGONAL_32_TOEC}


def test_fourteen_constants_and_invariance():
    """14 independent constants (Fumi 1952); random values come back at their components and the
    tensor is invariant under the 3-fold about Z and the 2-fold about X (1e-12 relative), but not
    under a 4-fold about Z (a generic class-32 tensor is not tetragonal)."""
    assert invariant_toec_basis("32").shape == (14, 56)
    rng = np.random.default_rng(7)
    vals = dict(zip(TRIGONAL_32_TOEC, rng.normal(0, 500, 14)))
    C3 = trigonal_32_toec(**vals)
    assert all(np.isclose(_named(C3)[k], v, rtol=1e-12) for k, v in vals.items())
    scale = np.abs(C3).max()
    for g in (_rot([0, 0, 1], 120.0), _rot([1, 0, 0], 180.0)):
        assert np.abs(rotate_toec(C3, g) - C3).max() < 1e-12 * scale
    assert np.abs(rotate_toec(C3, _rot([0, 0, 1], 90.0)) - C3).max() > 1e-3 * scale
    assert np.array_equal(C3, np.transpose(C3, (1, 0, 2))) and np.array_equal(C3, np.transpose(C3, (2, 1, 0)))


def test_isotropic_tensor_is_rebuilt_from_its_class_32_components():
    """Isotropic Brugger constants (nu1, nu2, nu3 = -300, -100, -40 GPa): C111 = nu1 + 6 nu2 + 8 nu3,
    C112 = nu1 + 2 nu2, C123 = nu1, C144 = nu2, C155 = nu2 + 2 nu3, C456 = nu3 (cubic form);
    first checked isotropic (invariant under a random rotation), then rebuilt from its 14
    class-32 components to 1e-12: every dependent component of the builder is right."""
    n1, n2, n3 = -300.0, -100.0, -40.0
    iso = cubic_toec(n1 + 6 * n2 + 8 * n3, n1 + 2 * n2, n1, n2, n2 + 2 * n3, n3)
    q, _ = np.linalg.qr(np.random.default_rng(1).normal(size=(3, 3)))
    assert np.abs(rotate_toec(iso, q) - iso).max() < 1e-10
    np.testing.assert_allclose(trigonal_32_toec(**_named(iso)), iso, atol=1e-10)


def test_missing_constant_is_named():
    """A missing constant raises an InputError naming it."""
    vals = dict.fromkeys(TRIGONAL_32_TOEC[:-1], 1.0)
    with pytest.raises(InputError, match="C444"):
        trigonal_32_toec(**vals)
