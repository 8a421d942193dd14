"""Group velocity of the general (Stroh) path for modes trapped under a barrier, and no crash on singular solves.

References: the isotropic fast path (surfwave.layers.isotropic_deriv: exact derivatives of an
independent compound-matrix formulation) and central differences of the general solver's own c(kh)
(each speed from its own full solve with the exact count); for an anisotropic stack, central
differences alone.
"""
from __future__ import annotations

import numpy as np
import pytest
from general_path import layered_general

import surfwave
from surfwave.layers.linalg import safe_solve

ALN_ISO = {"E": 300.0, "nu": 0.22, "rho": 3200.0}
#: Cubic gold (Neighbours & Alers 1958, GPa), crystal axes = lab axes.
AU_CUBIC = {"voigt": [[192.3, 163.1, 163.1, 0, 0, 0], [163.1, 192.3, 163.1, 0, 0, 0], [163.1, 163.1, 192.3, 0, 0, 0],
                      [0, 0, 0, 42.0, 0, 0], [0, 0, 0, 0, 42.0, 0], [0, 0, 0, 0, 0, 42.0]], "rho": 19300.0}


_general = layered_general


def _mat(rng, E, rho):
    return {"E": float(rng.uniform(*E)), "nu": float(rng.uniform(0.05, 0.42)), "rho": float(rng.uniform(*rho))}


def _differences(sub, films, kh, r, d=1e-5):
    """Central differences d(c kh)/dkh of the general solver's speeds at kh +- d, matched by label."""
    rp, rm = _general(sub, films, kh=[kh + d]), _general(sub, films, kh=[kh - d])
    out = np.full(r["c"].shape[1], np.nan)
    for j, lab in enumerate(r["mode"][0]):
        if lab and lab in list(rp["mode"][0]) and lab in list(rm["mode"][0]):
            cp = rp["c"][0, list(rp["mode"][0]).index(lab)]
            cm = rm["c"][0, list(rm["mode"][0]).index(lab)]
            out[j] = (cp * (kh + d) - cm * (kh - d)) / (2 * d)
    return out


@pytest.mark.parametrize(("seed", "n"), [(1, 3), (7, 2)])
def test_group_velocity_of_trapped_modes_on_random_stacks(seed, n):
    """Seeded random isotropic stacks (2-3 films, kh 20 ... 60; seed 1 includes a stack whose energy
    velocity was 0.9 off before the check): every mode's group velocity from the general solver equals
    the isotropic path's (exact derivatives) and central differences of the general c(kh), 1e-6."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        sub = _mat(rng, (150.0, 600.0), (2000.0, 5000.0))
        films = [{**_mat(rng, (40.0, 600.0), (1800.0, 20000.0)), "thickness": float(rng.uniform(0.1, 1.0)) * 1e-6}
                 for _ in range(int(rng.integers(2, 4)))]
        kh = float(rng.uniform(20.0, 60.0))
        fast = surfwave.layered(sub, films, kh=[kh])
        gen = _general(sub, films, kh=[kh])
        assert (fast["mode"] == gen["mode"]).all()
        ok = np.isfinite(gen["c"][0])
        assert np.allclose(gen["group_velocity"][0, ok], fast["group_velocity"][0, ok], rtol=1e-6, atol=0)
        fd = _differences(sub, films, kh, gen)
        assert np.isfinite(fd[ok]).all()
        assert np.allclose(gen["group_velocity"][0, ok], fd[ok], rtol=1e-6, atol=0)


def test_group_velocity_of_trapped_modes_in_a_crystal_film():
    """Cubic gold under an AlN-like film on Si (001), 20 deg off [100] (all components couple), kh = 30:
    every mode's group velocity equals central differences of c(kh) (step 1e-5), 1e-6."""
    films = [{**ALN_ISO, "thickness": 0.7e-6}, {**AU_CUBIC, "thickness": 0.3e-6}]
    kh, d = 30.0, 1e-5
    r = surfwave.layered("Si", films, direction=20.0, kh=[kh - d, kh, kh + d])
    assert (r["mode"][0] == r["mode"][2]).all() and (r["mode"][0] == r["mode"][1]).all()
    ok = np.isfinite(r["c"][1])
    fd = (r["c"][2] * (kh + d) - r["c"][0] * (kh - d)) / (2 * d)
    assert ok.sum() > 5
    assert np.allclose(r["group_velocity"][1, ok], fd[ok], rtol=1e-6, atol=0)


def test_safe_solve_gives_nan_for_a_singular_matrix_in_a_batch():
    """A batch with one exactly singular matrix: numpy raises for the whole batch, safe_solve gives NaN for
    that one and numpy's answer (1e-15) for the others."""
    A = np.stack([np.eye(3) * 2.0, np.zeros((3, 3)), np.array([[1.0, 2, 0], [0, 1, 0], [0, 0, 3]])])
    B = np.ones((3, 3, 1))
    with pytest.raises(np.linalg.LinAlgError):
        np.linalg.solve(A, B)
    x = safe_solve(A, B)
    assert np.isnan(x[1]).all()
    assert np.allclose(x[[0, 2]], np.linalg.solve(A[[0, 2]], B[[0, 2]]), rtol=1e-15, atol=0)
