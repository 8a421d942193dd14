"""The fast long-wave stability search against the plain direction scan it replaced.

:func:`surfwave.solvers.long_wave.long_wave_stability` compares directions with a
closed-form eigenvalue, searches only one octant when the lab axes are mirror planes and
builds the acoustic tensor of all directions as one matrix product. The reference here is
the straightforward route (the same direction grid over the whole half sphere, the same
pattern refinement, every acoustic tensor by ``einsum`` and every eigenvalue by LAPACK),
written out independently below, on dense strain grids through every instability of every
lattice, loading, direction and potential.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.model_crystals import elastic
from surfwave.model_crystals.lattices import build
from surfwave.solvers import long_wave
from surfwave.solvers.tensors import rotate2, rotate4

# (lattice, loading, direction, potential) -> d/d0 span through its long-wave instabilities
# and up to its geometry edge (limits from surfwave.model_crystals.stability.instability_limits).
SPANS = {
    ("fcc", "uniaxial", "[100]", "harmonic"): (0.45, 1.60),
    ("fcc", "uniaxial", "[100]", "lj"): (0.80, 1.30),
    ("fcc", "uniaxial", "[110]", "harmonic"): (0.70, 1.72),
    ("fcc", "uniaxial", "[110]", "lj"): (0.85, 1.20),
    ("fcc", "in_plane_hydrostatic", "[100]", "harmonic"): (0.75, 1.41),
    ("fcc", "in_plane_hydrostatic", "[100]", "lj"): (0.85, 1.20),
    ("fcc", "in_plane_hydrostatic", "[110]", "harmonic"): (0.75, 1.41),
    ("fcc", "in_plane_hydrostatic", "[110]", "lj"): (0.85, 1.20),
    ("triangular", "uniaxial", "[10]", "harmonic"): (0.60, 1.99),
    ("triangular", "uniaxial", "[10]", "lj"): (0.85, 1.20),
}


def _scan_reference(C, sigma, n_directions=400, refine=12):
    """Plain scan: every direction of the half-sphere grid, LAPACK eigenvalues, then the
    shrinking 8-neighbour (2D: 2-neighbour) pattern search around the best direction."""
    dim = C.shape[-1]
    grid = long_wave._sphere_directions(dim, n_directions)
    e = np.linalg.eigvalsh(long_wave.acoustic_tensor(C, sigma, grid))[..., 0]
    best = e.argmin(1)
    n_best, e_best = grid[best], e[np.arange(len(best)), best]
    step = 0.5 * np.sqrt(4.0 * np.pi / n_directions) if dim == 3 else np.pi / n_directions
    offs = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1) if (a, b) != (0, 0)]
    for _ in range(refine):
        if dim == 3:
            helper = np.where(np.abs(n_best[:, :1]) < 0.9, [[1.0, 0, 0]], [[0, 1.0, 0]])
            t1 = np.cross(n_best, helper)
            t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
            t2 = np.cross(n_best, t1)
            cand = np.stack([n_best + step * (a * t1 + b * t2) for a, b in offs], 1)
        else:
            t1 = np.column_stack([-n_best[:, 1], n_best[:, 0]])
            cand = np.stack([n_best - step * t1, n_best + step * t1], 1)
        cand /= np.linalg.norm(cand, axis=-1, keepdims=True)
        ec = np.linalg.eigvalsh(long_wave.acoustic_tensor(C, sigma, cand))[..., 0]
        j = ec.argmin(1)
        ej = ec[np.arange(len(j)), j]
        better = ej < e_best
        n_best = np.where(better[:, None], cand[np.arange(len(j)), j], n_best)
        e_best = np.where(better, ej, e_best)
        step *= 0.5
    return e_best


@pytest.mark.parametrize("case", list(SPANS), ids=lambda c: "-".join(c))
def test_flags_and_minimum_match_the_plain_scan(case):
    """Same ``stable`` flag at every point of 150 strains through each instability (both
    flags present in every span), and a lowest eigenvalue at least as low as the plain
    scan's (the octant is searched four times as densely)."""
    lattice, loading, direction, pot = case
    lo, hi = SPANS[case]
    c = build(lattice, loading, pot, direction, np.linspace(lo, hi, 150))
    sigma = elastic.stress(c.bonds, pot)
    C = elastic.elastic_constants(c.bonds, pot)
    stable, e_min, n_min = long_wave.long_wave_stability(C, sigma)
    ref = _scan_reference(C, sigma)
    assert np.array_equal(stable, ref > 0)
    assert stable.any() and not stable.all()
    assert np.all(e_min <= ref + 1e-9)
    # the reported minimum is the exact eigenvalue at the reported direction
    q = long_wave.acoustic_tensor(C, sigma, n_min[:, None, :])[:, 0]
    np.testing.assert_allclose(e_min, np.linalg.eigvalsh(q)[:, 0], atol=1e-12)


def test_general_anisotropy_searches_the_whole_sphere():
    """Without lab mirror planes (a random rotation of an LJ crystal near its instability)
    the search must not fold directions into one octant: it matches the plain scan."""
    rng = np.random.default_rng(5)
    c = build("fcc", "in_plane_hydrostatic", "lj", "[100]", np.linspace(0.90, 0.95, 20))
    C = elastic.elastic_constants(c.bonds, "lj")
    sigma = elastic.stress(c.bonds, "lj")
    R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    C = np.einsum("ai,bj,ck,dl,sijkl->sabcd", R, R, R, R, C)
    sigma = np.einsum("ai,bj,sij->sab", R, R, sigma)
    assert not long_wave._lab_mirror_symmetric(long_wave._wave_tensor_matrix(C, sigma)).any()
    stable, e_min, _ = long_wave.long_wave_stability(C, sigma)
    ref = _scan_reference(C, sigma)
    assert np.array_equal(stable, ref > 0) and stable.any() and not stable.all()
    np.testing.assert_allclose(e_min, ref, atol=1e-12)


def test_bad_shapes_are_named():
    """C and sigma of mismatched shapes are an InputError naming both shapes."""
    from surfwave.errors import InputError

    with pytest.raises(InputError, match=r"\(2, 3, 3, 3, 3\)"):
        long_wave.long_wave_stability(np.zeros((2, 3, 3, 3, 3)), np.zeros((3, 3, 3)))


@pytest.mark.parametrize("case", list(SPANS), ids=lambda c: "-".join(c))
def test_sufficient_test_then_scan_gives_the_plain_scan_flags(case):
    """``long_wave_stable`` (strong-convexity test, scan only where it fails) against the
    plain scan above on 400 strains through each instability: identical flags; the
    sufficient test never passes a point the scan finds unstable, nor the instability
    shortcut (3D) a stable one, and the sufficient test spares the scan at 90 % of the
    stable points (else it would save little)."""
    lattice, loading, direction, pot = case
    lo, hi = SPANS[case]
    c = build(lattice, loading, pot, direction, np.linspace(lo, hi, 400))
    sigma = elastic.stress(c.bonds, pot)
    C = elastic.elastic_constants(c.bonds, pot)
    ref = _scan_reference(C, sigma) > 0
    assert np.array_equal(long_wave.long_wave_stable(C, sigma), ref)
    convex = long_wave.strongly_convex(C, sigma)
    assert not (convex & ~ref).any()
    assert convex.sum() >= 0.9 * ref.sum()
    if C.shape[-1] == 3:  # the instability shortcut never condemns a point the scan finds stable
        assert not (long_wave._surely_unstable(C, sigma) & ref).any()


def test_sufficient_test_without_lab_mirrors():
    """A randomly rotated LJ crystal through its instability (no lab mirror planes): the
    fast flags equal the plain scan's (reference: :func:`_scan_reference`)."""
    rng = np.random.default_rng(7)
    c = build("fcc", "uniaxial", "lj", "[110]", np.linspace(0.85, 1.20, 60))
    C = elastic.elastic_constants(c.bonds, "lj")
    sigma = elastic.stress(c.bonds, "lj")
    R, _ = np.linalg.qr(rng.normal(size=(3, 3)))
    C = np.einsum("ai,bj,ck,dl,sijkl->sabcd", R, R, R, R, C)
    sigma = np.einsum("ai,bj,sij->sab", R, R, sigma)
    ref = _scan_reference(C, sigma) > 0
    assert ref.any() and not ref.all()
    assert np.array_equal(long_wave.long_wave_stable(C, sigma), ref)


def test_point_min_eig_only_when_asked():
    """``surfwave.point`` gives the same ``stable`` flags with and without ``min_eig``
    (reference: the full scan of ``min_eig=True``), and ``min_acoustic_eig`` only when asked."""
    import surfwave

    s = np.linspace(0.85, 1.20, 40)
    fast = surfwave.point("fcc", "uniaxial", "lj", "[110]", s)
    full = surfwave.point("fcc", "uniaxial", "lj", "[110]", s, min_eig=True)
    assert "min_acoustic_eig" not in fast
    assert np.array_equal(fast["stable"], full["stable"]) and not full["stable"].all()
    assert np.array_equal(full["stable"], full["min_acoustic_eig"] > 0)
    np.testing.assert_array_equal(fast["c2_R"], full["c2_R"])


@pytest.mark.parametrize("case", [("fcc", "uniaxial", "[110]", "lj"), ("fcc", "in_plane_hydrostatic", "[100]", "lj"),
                                  ("triangular", "uniaxial", "[10]", "lj")], ids=lambda c: "-".join(c))
def test_mirror_blocks_against_the_full_matrix(case):
    """With lab mirror planes, A - t N splits into small blocks (``_mirror_blocks``). Their
    pivot test equals Gaussian elimination of the full (d^2, d^2) matrix at every listed
    weight t, and the weight of the golden-section search is as good as the best of 401
    weights on a grid, both judged by LAPACK's lowest eigenvalue of the full matrix."""
    lattice, loading, direction, pot = case
    lo, hi = SPANS[case]
    c = build(lattice, loading, pot, direction, np.linspace(lo, hi, 120))
    sigma = elastic.stress(c.bonds, pot)
    C = elastic.elastic_constants(c.bonds, pot)
    dim = C.shape[-1]
    eye = np.eye(dim)
    A = C + np.einsum("sjl,ik->sijkl", sigma, eye)
    A = A.reshape(len(C), dim * dim, dim * dim)
    A = 0.5 * (A + np.swapaxes(A, 1, 2))
    N = (np.einsum("il,jk->ijkl", eye, eye) - np.einsum("ij,kl->ijkl", eye, eye)).reshape(dim * dim, -1)
    scale = np.abs(A).max(axis=(1, 2))
    blocks = long_wave._mirror_blocks(A)
    for w in long_wave._NULL_WEIGHTS:
        full = long_wave._positive_definite(A - w * scale[:, None, None] * N, 1e-9 * scale)
        assert np.array_equal(long_wave._blocks_positive(blocks, w * scale[None], 1e-9 * scale)[0], full)

    def lowest(t):
        return np.linalg.eigvalsh(A - t[:, None, None] * N)[:, 0]

    brute = np.max([lowest(w * scale) for w in np.linspace(-1.0, 1.0, 401)], axis=0)
    assert np.all(lowest(long_wave._best_null_weight(blocks, scale)) >= brute - 1e-7 * scale)


def test_cholesky_certificate_gives_the_elimination_flags():
    """_pivots_above (LAPACK Cholesky of B - 2 tol I first) gives the flags of the pivot
    elimination _positive_definite (the reference) on 9 x 9 stacks that are clearly positive,
    marginal (lowest eigenvalue near tol, on both sides) or indefinite."""
    rng = np.random.default_rng(4)
    Q = np.linalg.qr(rng.normal(size=(80, 9, 9)))[0]
    w = rng.uniform(1.0, 100.0, (80, 9))
    w[:, 0] = np.concatenate([rng.uniform(1.0, 10.0, 30), 1e-7 * np.geomspace(0.01, 100.0, 45), -1e-7 * np.ones(5)])
    B = Q @ (w[..., None] * np.swapaxes(Q, -1, -2))
    B = 0.5 * (B + np.swapaxes(B, -1, -2))
    tol = 1e-9 * np.abs(B).max(axis=(1, 2))                  # ~3e-8 .. 1e-7: the marginal rows straddle it
    for rows in [slice(0, 30), slice(None), slice(30, None), slice(0, 0)] + [slice(k, k + 1) for k in range(80)]:
        pivots = long_wave._positive_definite(B[rows], tol[rows])
        np.testing.assert_array_equal(long_wave._pivots_above(B[rows], tol[rows]), pivots)
        if long_wave._all_certified(B[rows], np.zeros(len(pivots)), tol[rows]):   # t = 0: B itself
            assert pivots.all() and len(pivots)
    assert long_wave._all_certified(B[:30], np.zeros(30), tol[:30])


@pytest.mark.parametrize("case", list(SPANS), ids=lambda c: "-".join(c))
def test_whole_stack_certificate_keeps_the_sufficient_test_flags(case, monkeypatch):
    """strongly_convex with its whole-stack Cholesky certificate gives the flags it gives without
    it (the reference: the same function with the certificate switched off), on stacks that pass
    (a stable stretch) and on the full span through the instabilities (where it falls back), at
    the mirror directions and rotated off them (3D: 20 degrees about the normal, no lab mirror)."""
    lattice, loading, direction, pot = case
    lo, hi = SPANS[case]
    c = build(lattice, loading, pot, direction, np.linspace(lo, hi, 200))
    sigma = elastic.stress(c.bonds, pot)
    C = elastic.elastic_constants(c.bonds, pot)
    stacks = [(C, sigma)]
    if C.shape[-1] == 3:
        a = np.radians(20.0)
        R = np.array([[np.cos(a), 0.0, np.sin(a)], [0.0, 1.0, 0.0], [-np.sin(a), 0.0, np.cos(a)]])
        stacks.append((rotate4(C, np.broadcast_to(R, sigma.shape)), rotate2(sigma, R)))
    for Cs, ss in stacks:
        with_cert = long_wave.strongly_convex(Cs, ss)
        for rows in (np.flatnonzero(with_cert)[:60], np.arange(len(ss))):      # all pass / mixed
            got = long_wave.strongly_convex(Cs[rows], ss[rows])
            with monkeypatch.context() as mp:
                mp.setattr(long_wave, "_all_certified", lambda *args: False)
                ref = long_wave.strongly_convex(Cs[rows], ss[rows])
            np.testing.assert_array_equal(got, ref)
