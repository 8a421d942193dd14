"""``modes`` = N on the isotropic path gives the first N modes of each family of ``modes`` = None.

Reference: the same call with ``modes=None`` (every mode: the scan runs every row to the top of
the grid, and its rescan of rows holding fewer modes than their neighbours sees the full counts),
and for the one-film stack with a close pair the exact Wittrick-Williams count
(:mod:`surfwave.layers.isotropic_guard` forced on), which places the pair independently of the grid.
With ``modes`` = N each row stops at its N-th sign change, so a row that lost two modes in one
grid cell holds as many brackets as its neighbours: before the rank rule of
:func:`surfwave.layers.isotropic_scan._rescan_dips` it returned the mode above the pair as "S2".
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
import surfwave.layers.isotropic_guard as guard
from surfwave.records import LayeredResult


def _family(rec: LayeredResult, i: int, sh: bool) -> tuple[np.ndarray, list[str]]:
    """Speeds (ascending) and labels of one family (SH: labels L...) in row i of a record."""
    lab = [str(x) for x in rec["mode"][i]]
    c = np.asarray(rec["c"][i], dtype=float)
    keep = [k for k, s in enumerate(lab) if np.isfinite(c[k]) and s.startswith("L") == sh]
    return c[keep], [lab[k] for k in keep]


def _assert_first(rec_n: LayeredResult, rec_all: LayeredResult, n: int, rows: range | np.ndarray) -> None:
    """Per row and family: the modes of rec_n are the first n of rec_all (speeds 1e-12, labels)."""
    for i in rows:
        for sh in (False, True):
            c_n, lab_n = _family(rec_n, i, sh)
            c_a, lab_a = _family(rec_all, i, sh)
            assert lab_n == lab_a[:n], (i, n, lab_n, lab_a[:n])
            np.testing.assert_allclose(c_n, c_a[:n], rtol=1e-12, atol=0, err_msg=f"row {i}, modes={n}")


def _film_stack(rng: np.random.Generator) -> tuple[dict, dict, float]:
    """A random isotropic substrate and 1 um film (E GPa, nu, rho kg/m^3) and the film's shear speed, m/s."""
    def mat() -> dict:
        return {"E": float(10 ** rng.uniform(0, 2.9)), "nu": float(rng.uniform(-0.4, 0.49)),
                "rho": float(10 ** rng.uniform(2.8, 4.35))}
    sub, film = mat(), {**mat(), "thickness": 1e-6}
    vs = float(np.sqrt(surfwave.layers.stack.isotropic_voigt(film["E"], film["nu"])[3, 3] * 1e9 / film["rho"]))
    return sub, film, vs


@pytest.fixture
def unchecked() -> object:
    """One film: the default (count check off); restored afterwards."""
    old = guard.ALWAYS
    guard.ALWAYS = False
    yield None
    guard.ALWAYS = old


def test_close_pair_row_kept_with_modes(unchecked: object) -> None:
    """A slow heavy film on a light substrate at 120 frequencies: in row 93 S2 / S3 (861.92 / 864.08 m/s)
    share one grid cell. modes = 1 ... 4 must give the first modes of modes = None (rows 88 ... 98),
    and S2, S3 must be those of the exact count (the checked path, modes=None)."""
    rng = np.random.default_rng(376)
    sub, film, vs = _film_stack(rng)
    rng.integers(2)
    f = np.linspace(0.01, 1, 120) * rng.uniform(1, 100) * vs / (2 * np.pi * 1e-6)
    full = surfwave.layered(sub, [film], frequency=f)
    guard.ALWAYS = True
    counted = surfwave.layered(sub, [film], frequency=f)
    guard.ALWAYS = False
    c_cnt, lab_cnt = _family(counted, 93, False)
    assert lab_cnt[2:4] == ["S2", "S3"] and 0 < c_cnt[3] - c_cnt[2] < 3.0       # the close pair
    c_all, _ = _family(full, 93, False)
    np.testing.assert_allclose(c_all[:4], c_cnt[:4], rtol=1e-12)
    for n in (1, 2, 3, 4):
        _assert_first(surfwave.layered(sub, [film], frequency=f, modes=n), full, n, range(88, 99))


@pytest.mark.parametrize("seed", [0, 1, 2])
def test_random_one_film_modes_prefix(unchecked: object, seed: int) -> None:
    """Seeded random one-film stacks (10 per seed), rows in kh and in frequency, modes = 1 ... 4:
    every row's modes are the first N of modes = None per family (speeds 1e-12, labels)."""
    rng = np.random.default_rng(1000 + seed)
    for _ in range(10):
        sub, film, vs = _film_stack(rng)
        kmax = float(rng.uniform(1, 100))
        if rng.integers(2):
            kw: dict = {"frequency": np.linspace(0.01, 1, 60) * kmax * vs / (2 * np.pi * 1e-6)}
        else:
            kw = {"kh": np.linspace(0.01, 1, 60) * kmax}
        full = surfwave.layered(sub, [film], **kw)
        for n in (1, 2, 3, 4):
            _assert_first(surfwave.layered(sub, [film], modes=n, **kw), full, n, range(60))


def test_rank_jumps_sees_runs() -> None:
    """Brackets made up by hand (one rank, 10 rows): a run of three rows whose bracket lies a mode
    spacing above the rows around it is returned whole; a steadily falling mode (normal dispersion)
    and a single row one cell off are not. Reference: the rule as stated in ``_rank_jumps``."""
    from surfwave.layers.isotropic_scan import _rank_jumps

    rows = np.arange(10)
    order = rows.copy()
    lo = 100.0 - 2.0 * rows
    lo[3:6] += 50.0                                               # rows 3, 4, 5 skipped a pair
    assert _rank_jumps(rows, lo, lo + 1.0, np.ones(10, int), order, 1).tolist() == [3, 4, 5]
    lo = 100.0 - 5.0 * rows                                       # falls by 5 cells a row: no jump
    assert _rank_jumps(rows, lo, lo + 1.0, np.ones(10, int), order, 1).size == 0
    lo = np.full(10, 100.0)
    lo[4] = 101.0                                                 # the next cell: touching, not above
    assert _rank_jumps(rows, lo, lo + 1.0, np.ones(10, int), order, 1).size == 0


def test_huge_mode_limit_is_all_modes(unchecked: object) -> None:
    """modes far above the number of modes (10**9) gives every mode: the same record as modes=None
    (and no table as wide as ``modes``). Reference: modes=None."""
    rng = np.random.default_rng(376)
    sub, film, vs = _film_stack(rng)
    kh = np.linspace(0.1, 30.0, 40)
    full = surfwave.layered(sub, [film], kh=kh)
    _assert_first(surfwave.layered(sub, [film], kh=kh, modes=10**9), full, 10**9, range(40))
