"""Third-order expansion against an independent implementation: pymatgen.core.elasticity.

pymatgen (package pymatgen-core) keeps elastic tensors in the same Voigt order (11, 22, 33,
23, 13, 12) with no factors of 2 for stiffnesses and uses the Lagrangian strain as the
expansion variable, so these quantities compare directly, in the natural (unstressed)
frame and in GPa:

* the sixth-rank tensor built from Voigt C3 (``ElasticTensorExpansion.from_voigt``);
* the cubic C3 filled in by symmetry from C111, C112, C123, C144, C155, C456 at Voigt
  positions (1,1,1), (1,1,2), (1,2,3), (1,4,4), (1,5,5), (4,5,6), using the space group of
  an FCC structure (``Tensor.from_values_indices(..., populate=True)``);
* the second Piola-Kirchhoff stress T = C2 : eta + 1/2 C3 : eta : eta
  (``calculate_stress(eta)``), which we get from our Cauchy stress as T = J F^-1 sigma F^-T;
* the effective constants C2 + C3 : eta (``get_effective_ecs(eta)``), which are our C*
  pulled back to the natural frame, J F^-1 F^-1 F^-1 F^-1 C*;
* pymatgen's strain from stress (a compliance series truncated at second order) against our
  exact Newton solve: they must agree to third order in the stress.

Not compared: pymatgen's Wallace tensor, which adds the natural-frame effective constants
to the stress terms without the push-forward F F F F / J, so it differs from A = C* + sigma
delta already at first order in the stress (a different approximation, not a convention).
"""
from __future__ import annotations

import numpy as np
import pytest

pytest.importorskip("pymatgen.core.elasticity")
from pymatgen.core import Lattice, Structure  # noqa: E402
from pymatgen.core.elasticity import ElasticTensorExpansion  # noqa: E402
from pymatgen.core.tensors import Tensor  # noqa: E402

from surfwave.real_crystals.toec import (  # noqa: E402
    cauchy_stress,
    cubic_toec,
    deformation_for_stress,
    stressed_constants,
    toec_tensor,
)
from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor  # noqa: E402

CU = (-1271.0, -814.0, -50.0, -3.0, -780.0, -95.0)  # Hiki & Granato (1966), GPa
C2V = cubic_voigt(168.4, 121.4, 75.4)
C3V = cubic_toec(*CU)


@pytest.mark.filterwarnings("ignore::DeprecationWarning")  # spglib, called inside pymatgen
def test_cubic_toec_matches_pymatgen_symmetry_population():
    """Our cubic C3 equals pymatgen's tensor populated from the six constants by the
    symmetry of an FCC structure (space group Fm-3m), and both Voigt -> tensor maps agree."""
    fcc = Structure(Lattice.cubic(3.615), ["Cu"] * 4,
                    [[0, 0, 0], [0.5, 0.5, 0], [0.5, 0, 0.5], [0, 0.5, 0.5]])
    idx = [(0, 0, 0), (0, 0, 1), (0, 1, 2), (0, 3, 3), (0, 4, 4), (3, 4, 5)]
    populated = Tensor.from_values_indices(list(CU), idx, populate=True, structure=fcc, voigt_rank=6)
    assert np.allclose(np.asarray(populated), toec_tensor(C3V), atol=1e-9)
    exp = ElasticTensorExpansion.from_voigt([C2V, C3V])
    assert np.array_equal(np.asarray(exp[1]), toec_tensor(C3V))
    assert np.array_equal(np.asarray(exp[0]), voigt_to_tensor(C2V))


def test_stress_and_effective_constants_match_pymatgen():
    """At a random symmetric F: T = J F^-1 sigma F^-T equals pymatgen's calculate_stress(eta),
    and J F^-1 F^-1 F^-1 F^-1 C* equals get_effective_ecs(eta), to round-off."""
    rng = np.random.default_rng(7)
    E = 0.01 * rng.normal(size=(3, 3))
    F = np.eye(3) + 0.5 * (E + E.T)
    eta = 0.5 * (F.T @ F - np.eye(3))
    exp = ElasticTensorExpansion.from_voigt([C2V, C3V])
    J, Fi = np.linalg.det(F), np.linalg.inv(F)
    T = J * Fi @ cauchy_stress(F, C2V, C3V) @ Fi.T
    assert np.allclose(T, np.asarray(exp.calculate_stress(eta)), atol=1e-12, rtol=0)
    K = J * np.einsum("ip,jq,kr,ls,pqrs->ijkl", Fi, Fi, Fi, Fi, stressed_constants(C2V, C3V, F))
    assert np.allclose(K, np.asarray(exp.get_effective_ecs(eta)), atol=1e-10, rtol=0)


def test_strain_from_stress_agrees_with_pymatgen_to_third_order():
    """pymatgen's compliance-series strain for the second Piola-Kirchhoff stress of our exact
    solution differs from our Newton eta by O(stress^3): fitted order 3 +- 0.2."""
    exp = ElasticTensorExpansion.from_voigt([C2V, C3V])
    s = np.array([0.05, 0.1, 0.2, 0.4])
    sigma = np.einsum("n,ij->nij", s, np.diag([1.0, 0.0, 0.0]) + 0.3 * np.diag([0.0, 0.0, 1.0]))
    sol = deformation_for_stress(sigma, C2V, C3V)
    err = []
    for F, eta, sig in zip(sol["F"], sol["eta"], sigma):
        Fi = np.linalg.inv(F)
        T = np.linalg.det(F) * Fi @ sig @ Fi.T
        err.append(np.abs(np.asarray(exp.get_strain_from_stress(T)) - eta).max())
    order = np.polyfit(np.log(s), np.log(err), 1)[0]
    assert 2.8 < order < 3.2, err
