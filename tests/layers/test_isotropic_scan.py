"""The upward scan of the isotropic path (surfwave.layers.isotropic_scan) on a secular function with known roots.

Reference: a polynomial stand-in for the secular function whose roots are chosen (a close pair
inside one grid cell, single roots elsewhere): the brackets must hold exactly those roots, in
order, and the ``need`` cut must equal the first ``need`` brackets of the full scan.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave.layers.isotropic_scan as im
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.stack import resolve_stack

GRID = np.linspace(1.0, 10.0, 40)                   # cells 0.23 wide
#: Roots per row (the row's kh selects them): row 0 has a close pair in the cell (2.846, 3.077) below
#: two sign changes; row 1 two sign changes below a close pair; row 2 a pair only; row 3 a pair
#: between two sign changes.
ROOTS = {0.0: (2.9, 3.0, 5.1, 7.1), 1.0: (2.1, 4.1, 8.5, 8.6), 2.0: (6.15, 6.25),
         3.0: (2.1, 6.15, 6.25, 8.1)}


class _Speeds:
    def __init__(self, c: np.ndarray) -> None:
        self.c = c

    def cut(self, sl: slice) -> _Speeds:
        return _Speeds(self.c[sl])


def _F(c: np.ndarray, kh: np.ndarray) -> np.ndarray:
    kh = np.broadcast_to(kh, np.broadcast_shapes(kh.shape, c.shape))
    out = np.ones(kh.shape)
    for row, roots in ROOTS.items():
        hit = kh == row
        val = np.prod([np.broadcast_to(c, kh.shape)[hit] - r for r in roots], axis=0)
        out[hit] = val
    return out


@pytest.fixture
def fake(monkeypatch):
    """The scan's P-SV evaluations replaced by :func:`_F`; the hunt's candidates recorded."""
    seen: list[np.ndarray] = []
    hunt = im._hidden_pairs

    def spy(st, prefix, rows_of, r, cs, Fs):
        seen.append(r.copy())
        return hunt(st, prefix, rows_of, r, cs, Fs)

    monkeypatch.setattr(im, "psv_speeds", lambda st, c: _Speeds(c))
    monkeypatch.setattr(im, "psv_block", lambda st, sp, kh, kernels=None: _F(sp.c, kh.T).T)
    monkeypatch.setattr(im, "secular_psv", lambda st, c, kh, kernels=None: _F(c, kh))
    monkeypatch.setattr(im, "_hidden_pairs", spy)
    return seen


def _roots_in(lo: np.ndarray, hi: np.ndarray, row: float) -> list[float]:
    return [r for a, b in zip(lo, hi) for r in ROOTS[row] if a < r < b]


def test_scan_finds_a_hidden_pair_below_the_needed_sign_changes(fake):
    """need = 2: row 0's two lowest roots are the hidden pair (found by the hunt, split into two
    brackets), not the sign changes above it; row 1's pair lies above its two sign changes and is
    never hunted; row 2 holds just the pair; row 3 its first sign change and the lower root of the
    pair. The full scan (need = inf) brackets every root once."""
    st = iso_stack(resolve_stack({"E": 400.0, "nu": 0.25, "rho": 3500.0},
                                 [{"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}]))
    rows_of = im.Rows(np.array(list(ROOTS)), freq=False)
    rows = np.arange(len(ROOTS))
    full = im._scan(st, "R", GRID, rows_of, rows, np.inf)
    for i, row in enumerate(ROOTS):
        mine = full[0] == i
        assert _roots_in(full[1][mine], full[2][mine], row) == list(ROOTS[row])
        assert mine.sum() == len(ROOTS[row])
    fake.clear()
    two = im._scan(st, "R", GRID, rows_of, rows, 2)
    assert _roots_in(two[1][two[0] == 0], two[2][two[0] == 0], 0.0) == [2.9, 3.0]
    assert _roots_in(two[1][two[0] == 1], two[2][two[0] == 1], 1.0) == [2.1, 4.1]
    assert _roots_in(two[1][two[0] == 2], two[2][two[0] == 2], 2.0) == [6.15, 6.25]
    assert _roots_in(two[1][two[0] == 3], two[2][two[0] == 3], 3.0) == [2.1, 6.15]
    hunted = np.concatenate(fake)
    assert 0 in hunted and 2 in hunted and 1 not in hunted        # row 1's pair: above its need-th sign change
    for a, b in zip(two, full):                                   # the first two brackets of each row of the full scan
        keep = np.concatenate([np.flatnonzero(full[0] == i)[:2] for i in rows])
        np.testing.assert_array_equal(a, b[keep])
    shuffled = im._scan(st, "R", GRID, rows_of, rows[::-1].copy(), 2)    # rows in another order: the same brackets
    for a, b in zip(shuffled, two):
        np.testing.assert_array_equal(a, b)


def test_one_pass_scan_of_both_families_equals_the_separate_scans():
    """With one film, P-SV and SH are scanned in one pass sharing the film's shear-wave functions
    (_brackets_both): their brackets equal, bit for bit, those of the two separate scans
    (_brackets, the reference), with the grid kept to the top (coarsen=False), for 6 seeded random one-film stacks and a film faster than the
    substrate (the SH grid is then one point), 40 and 200 rows (one chunk; several, cut at the SH
    grid or across it) at kh and at frequency, all modes and modes = 1, 2."""
    rng = np.random.default_rng(11)

    def mat(E, rho):
        return {"E": float(rng.uniform(*E)), "nu": float(rng.uniform(0.05, 0.42)), "rho": float(rng.uniform(*rho))}
    stacks = [(mat((150.0, 600.0), (2000.0, 5000.0)), mat((40.0, 600.0), (1800.0, 20000.0))) for _ in range(6)]
    stacks.append(({"E": 150.0, "nu": 0.3, "rho": 5000.0}, {"E": 600.0, "nu": 0.2, "rho": 1800.0}))  # a fast film
    for sub, film in stacks:
        st = iso_stack(resolve_stack(sub, [{**film, "thickness": 1e-6}]))
        top = float(rng.choice([2.0, 20.0]))
        kh40, kh200 = np.sort(rng.uniform(0.0, top, 40)), np.sort(rng.uniform(0.0, top, 200))
        for rows_of in (im.Rows(kh40, freq=False), im.Rows(kh40 * st.c_lim * 0.9, freq=True),
                        im.Rows(kh200, freq=False), im.Rows(kh200 * st.c_lim * 0.9, freq=True)):
            grid = im.speed_grid(st, rows_of)
            for modes in (None, 1, 2):
                joint = im._brackets_both(st, rows_of, modes, grid, coarsen=False)
                for prefix, got in zip("RL", joint):
                    for a, b in zip(got, im._brackets(st, prefix, rows_of, modes, grid)):
                        np.testing.assert_array_equal(a, b)


def _film_case(rng: np.random.Generator) -> tuple:
    """A seeded random one-film stack (a slow film: many modes at large kh) and its IsoStack."""
    sub = {"E": float(rng.uniform(250.0, 500.0)), "nu": float(rng.uniform(0.1, 0.35)), "rho": float(rng.uniform(2500, 4000))}
    film = {"E": float(rng.uniform(40.0, 120.0)), "nu": float(rng.uniform(0.1, 0.4)), "rho": float(rng.uniform(2000, 9000)),
            "thickness": 1e-6}
    return iso_stack(resolve_stack(sub, [film]))


def _phase_steps(st, rows_of: im.Rows, grid: np.ndarray, r: int, upto: int) -> tuple[np.ndarray, np.ndarray]:
    """Row r's vertical phase Phi_r(c) = kh_r(c) sum_l h_l/H (nu_a + nu_b) advance on the cells below
    ``upto`` (from the definition, not from the grid's auxiliary curve), and whether each cell lies
    above c_lo (the rule's range)."""
    g = grid[:upto]
    nu = np.zeros(g.size)
    for v in (st.shear, st.longitudinal):
        for i in range(st.frac.size):
            nu += st.frac[i] * np.sqrt(np.maximum((g / v[i]) ** 2 - 1.0, 0.0))
    return np.diff(rows_of.pairs(np.full(g.size, r), g) * nu), g[:-1] >= 0.95 * im.slowest_speed(st)


def test_grid_left_for_the_rows_still_scanned_keeps_the_phase_step():
    """The rest of the grid rebuilt for the rows still scanned (_evaluate_both, coarsen=True) keeps
    the grid's rule for each of them: on every cell a row is evaluated on, its own vertical phase
    (_phase_steps, from the definition) advances by at most PHASE_STEP above c_lo (1 % for the
    linear interpolation of the grid's auxiliary curve; cells at the square-root onsets of the phase
    at the films' bulk speeds included). Cases: kh over two decades (most rows small: the grid is rebuilt, checked) at
    fixed kh and at fixed frequency, modes = 1, 2, for 4 seeded random slow films."""
    from surfwave.layers.isotropic_scan import _evaluate_both, _family_grid
    rng = np.random.default_rng(5)
    rebuilt = 0
    for _ in range(4):
        st = _film_case(rng)
        kh = np.sort(np.geomspace(0.3, 40.0, 150))
        for rows_of in (im.Rows(kh, freq=False), im.Rows(kh * st.c_lim * 0.6, freq=True)):
            full = im.speed_grid(st, rows_of)
            rows = np.arange(kh.size)
            for modes in (1, 2):
                _, up_r, _, _, grid, _ = _evaluate_both(st, full, _family_grid(st, "L", full), rows_of, rows, modes)
                rebuilt += grid.size < full.size
                assert np.all(np.diff(grid) > 0)
                for r in rows:
                    d, clear = _phase_steps(st, rows_of, grid, r, up_r[r])
                    assert d[clear].max(initial=0.0) <= 1.01 * im.PHASE_STEP
    assert rebuilt >= 4                       # the rule was exercised on rebuilt grids


def test_grid_left_for_the_rows_still_scanned_finds_the_same_modes():
    """Brackets with the rest of the grid rebuilt for the rows still scanned (the default) against
    those on the full grid (coarsen=False, the reference): the same number of brackets in every row
    of both families, and the roots they refine to (refine_brackets) equal to 1e-13 relative, for
    4 seeded random slow films at fixed kh and at fixed frequency, modes = 1, 2, 3."""
    import surfwave.layers.isotropic_modes as imod
    rng = np.random.default_rng(6)
    for _ in range(4):
        st = _film_case(rng)
        kh = np.sort(np.geomspace(0.3, 40.0, 120))
        for rows_of in (im.Rows(kh, freq=False), im.Rows(kh * st.c_lim * 0.6, freq=True)):
            grid = im.speed_grid(st, rows_of)
            for modes in (1, 2, 3):
                new = im._brackets_both(st, rows_of, modes, grid)
                ref = im._brackets_both(st, rows_of, modes, grid, coarsen=False)
                for prefix, a, b in zip("RL", new, ref):
                    n = kh.size
                    assert np.array_equal(np.bincount(a[0], minlength=n), np.bincount(b[0], minlength=n))
                    ca, _ = imod.refine_brackets(st, prefix, *a[1:3], rows_of, a[0], *a[3:])
                    cb, _ = imod.refine_brackets(st, prefix, *b[1:3], rows_of, b[0], *b[3:])
                    np.testing.assert_allclose(ca, cb, rtol=1e-13, atol=0.0)
