"""The fast paths of the mode search: closed-form grid eigenvalues and the per-speed interface solve."""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.recursion import top_impedance
from surfwave.layers.scan import hermitian_eigenvalues
from surfwave.layers.stack import resolve_stack


def _hermitian(rng: np.random.Generator, m: int, n: int) -> np.ndarray:
    A = rng.normal(size=(m, n, n)) + 1j * rng.normal(size=(m, n, n))
    return A + np.conj(np.swapaxes(A, -1, -2))


def test_closed_form_eigenvalues_match_lapack():
    """Reference: numpy.linalg.eigvalsh (LAPACK) on random Hermitian 1 x 1 to 4 x 4 matrices, plus
    nearly double and exactly triple eigenvalues and scaled-down ones (agreement to 1e-13 of the largest),
    and a NaN row (NaN out, the others unaffected)."""
    rng = np.random.default_rng(7)
    for n in (1, 2, 3, 4):
        Z = _hermitian(rng, 4000, n)
        Z[:50] *= 1e-9
        if n == 3:
            U = np.linalg.qr(rng.normal(size=(50, 3, 3)) + 1j * rng.normal(size=(50, 3, 3)))[0]
            d = np.array([1.0, 1.0 + 1e-9, -2.0])
            Z[50:100] = np.einsum("mij,j,mkj->mik", U, d, np.conj(U))
            Z[100] = 3.0 * np.eye(3)
        Z[101] = np.nan
        w, ref = hermitian_eigenvalues(Z), np.linalg.eigvalsh(np.where(np.isnan(Z), 0.0, Z))
        assert np.isnan(w[101]).all()
        ok = np.arange(len(Z)) != 101
        scale = np.abs(ref[ok]).max(axis=-1, keepdims=True)
        assert np.all(np.abs(w[ok] - ref[ok]) <= 1e-13 * scale), n


def test_per_speed_interface_solve_equals_per_kh_solve():
    """Reference: the recursion with the substrate's impedance broadcast over kh before the first film's
    interface solve (one solve per (c, kh), the plain route); the shared per-speed solve must agree to
    1e-13 for one and two films at kh up to 20."""
    for films in ([{"E": 70.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}],
                  [{"name": "SiO2", "thickness": 3e-7}, {"E": 200.0, "nu": 0.3, "rho": 7800.0, "thickness": 2e-7}]):
        b = scaled_blocks(resolve_stack("Si", films, direction=20.0))
        fam = families(b)[0]
        c = np.linspace(1500.0, 4800.0, 7)
        kh = np.linspace(0.0, 20.0, 9)
        M = top_impedance(b, fam, c, np.broadcast_to(kh, (c.size, kh.size)))["M"]
        Ms = top_impedance(b, fam, c, np.zeros((c.size, 1)))["M"][:, 0]
        for j, k in enumerate(kh):                     # a single kh: the plain route (no sharing)
            ref = top_impedance(b, fam, c, np.full((c.size, 1), k), M_sub=None)["M"][:, 0]
            assert np.allclose(M[:, j], ref, rtol=1e-13, atol=1e-13 * np.abs(ref).max())
        assert np.allclose(M[:, 0], Ms, rtol=1e-13, atol=1e-13 * np.abs(Ms).max())


def test_every_love_mode_at_large_kh():
    """Reference: the Love equation of an isotropic layer on an isotropic half-space (Aki & Richards,
    sec. 7.2; brentq, tests/layers/test_layers_physics.love_closed_form): at large kh the SH family has
    many steep branches, where a refinement that ends without a last evaluation must still keep every
    mode (count = branches below the substrate's shear speed; speeds to 1e-11)."""
    from test_layers_physics import FAST, SIO2, _iso, love_closed_form

    import surfwave
    kh = np.array([30.0, 50.0, 80.0])
    r = surfwave.layered(FAST, [{**SIO2, "thickness": 1e-6}], kh=kh)
    ratio = np.sqrt(_iso(FAST)[0] / FAST["rho"] / (_iso(SIO2)[0] / SIO2["rho"]) - 1)
    for i, k in enumerate(kh):
        love = r["c"][i][np.char.startswith(r["mode"][i].astype(str), "L")]
        assert len(love) == int(np.floor(k * ratio / np.pi)) + 1
        for n in (0, len(love) // 2, len(love) - 1):
            assert love[n] == pytest.approx(love_closed_form(k, n), rel=1e-11)
