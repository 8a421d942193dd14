"""The upward scan of the isotropic path: the speed grid and the brackets of every mode on it.

The secular functions are those of :mod:`surfwave.layers.isotropic`; the brackets found here are
refined by :mod:`surfwave.layers.isotropic_modes` (Newton, group velocities, the record's tables).

Search. Per family (P-SV: labels R, S1, S2, ...; SH: L0, L1, ...) the secular function is evaluated
on one speed grid shared by all rows (kh values, or frequencies with kh = omega H / c), from the
bottom up in chunks of at most :data:`CHUNK_ELEMENTS` (row, speed) points, its kh-independent parts
once per grid (:class:`surfwave.layers.isotropic.Speeds`); with one film both families are
scanned in one pass sharing the film's shear-wave functions. A row stops once it holds ``modes``
sign changes. The function has no poles, so every sign change is a mode and the n-th one from
below is the n-th mode (c_lim below is the substrate's shear speed).

Grid: :mod:`surfwave.layers.isotropic_grid` (what it holds and what it guarantees). With one film and
``modes`` = N, rows stop at their N-th sign change, and those left are mostly the small kh (or
frequencies): once the largest of them would take at least half the phase points off the rest of the
grid (above the last speed evaluated), that rest is rebuilt for them alone by the same rule and kept
if it holds at most :data:`COARSEN` x the speeds it replaces; every row still scanned meets the rule
with its own kh, as before.
Every sign change on the grid is a mode
(the function has no poles). Two modes in one cell (modes localised in different films, weakly
coupled, can be arbitrarily close) leave no sign change: every local minimum of |F| on the grid is
hunted by parabolic steps (:func:`_hidden_pairs`), and a point of the opposite sign splits the
cell into two brackets; the pair is missed only if the dip between the two roots escapes that hunt.
(With ``modes`` = N a minimum above a row's N-th sign change is not hunted: both its roots would
rank above N, so nothing kept changes.)
As a last guard a row holding fewer modes than rows on both sides of it (modes enter only at c_lim,
so counts are monotone in kh; in frequency too, except that a branch whose omega(k) is not monotone
holds a forward / backward pair over a window of frequencies only: a row between two such windows
is searched again for nothing) is searched again on a grid :data:`RESCAN` times finer.
With ``modes`` = N that count is capped at N (a row stops at its N-th sign change), so a row that
lost a pair below it holds N brackets like its neighbours, the N-th being a mode two ranks higher
(a one-film stack at 120 frequencies returned the mode above a pair 2 m/s apart as "S2"): there a
row is also searched again when its k-th bracket (k <= N) lies wholly above the k-th brackets of
rows on both sides within :data:`JUMP_ROWS` rows (:func:`_rank_jumps`: a mode's speed is continuous
along the rows), and the finer grid's brackets replace the row's if one of them lies wholly below
the first scan's bracket of the same rank; this repeats until no row is added (a row's new
brackets change what the ranks of its neighbours show).
Invariant: with ``modes`` = N the first N modes of each family are those of ``modes`` = None, to
the refinement's tolerance, with the same guarantees (the grid by the same rule: that of
``modes`` = None, or above the speeds already scanned rebuilt by it for the rows left; the same hunt
below the N-th sign change; a rescan of ``modes`` = None that changes one of the first N modes is
one of a row that skipped a pair among them, which the ranks show instead of the count). Checked on
the stack above and a seeded random sample of one-film stacks (tests/layers/test_isotropic_needpair.py);
the rank rule is a heuristic like the count rule (a run of more than :data:`JUMP_ROWS` rows all skipping
the pair would escape it, as a run spanning the ends escapes the count rule).
This is not a proof: :mod:`surfwave.layers.isotropic_guard` checks the rows of stacks with two
films or more against the exact mode count and re-solves those that fail.
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.isotropic import (
    IsoStack,
    psv_block,
    psv_kernels,
    psv_speeds,
    secular_psv,
    secular_sh,
    sh_block,
    sh_speeds,
    wave_block,
)
from surfwave.layers.isotropic_grid import (  # noqa: F401  (the grid's names, public here as before)
    FLOOR,
    N_BASE,
    N_LOW,
    N_TOP,
    PHASE_STEP,
    Rows,
    phase_curve,
    slowest_speed,
    speed_grid,
)
from surfwave.layers.isotropic_hunt import near_miss, shrink, trial_point, vertex

__all__ = ["CHUNK", "CHUNK_ELEMENTS", "CHUNK_MIN", "FLOOR", "JUMP_ROWS", "N_BASE", "N_LOW", "N_TOP", "PAIR_STEPS",
           "PHASE_STEP", "RESCAN", "Rows", "phase_curve", "slowest_speed", "speed_grid"]

#: Speeds per chunk of the former upward scan (a public name, kept; the scan chunks by points: CHUNK_ELEMENTS).
CHUNK = 32
#: (row, speed) points per chunk of the upward scan at most (the rest of the grid is cut into the
#: fewest equal chunks within it; at least :data:`CHUNK_MIN` speeds). Every float64 temporary of a
#: chunk then stays below 64 KiB: the C allocator (glibc) may hand larger freed blocks back to the
#: system, and the next call pays them again in page faults (measured up to +0.6 ms on a 3 ms call
#: with larger blocks, in a process whose allocator trims).
CHUNK_ELEMENTS = 8000
#: Speeds per chunk at least.
CHUNK_MIN = 8
#: Parabolic / golden steps hunting two roots hidden in one grid cell.
PAIR_STEPS = 10
#: Refinement factor of the rescan of rows with too few modes.
RESCAN = 4
#: With ``modes`` = N, a row whose k-th bracket lies above those of rows on both sides within this many
#: rows is rescanned (:func:`_rank_jumps`).
JUMP_ROWS = 4
#: With one film, the rest of the grid rebuilt for the rows still scanned (module docstring) is kept
#: if it holds at most this fraction of the speeds it replaces.
COARSEN = 0.75



def _secular(st: IsoStack, prefix: str, c: np.ndarray, kh: np.ndarray) -> np.ndarray:
    """The family's secular function at speeds c (n,) and kh (r, n)."""
    if prefix == "L":
        return secular_sh(st, c, kh)
    return secular_psv(st, c, kh)


def _at(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The secular function at (row, speed) pairs r, c (m,) (evaluated in ascending c: contiguous wave branches)."""
    o = np.argsort(c, kind="stable")
    cs = c[o]
    out = np.empty(c.size)
    out[o] = _secular(st, prefix, cs, rows_of.pairs(r[o], cs)[None, :])[0]
    return out


def _hidden_pairs(st: IsoStack, prefix: str, rows_of: Rows, r: np.ndarray, cs: np.ndarray, Fs: np.ndarray
                  ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Split points of two roots hidden between grid speeds: (found (m,), x (m,), F at x (m,)).

    ``cs``, ``Fs`` (m, 3): three consecutive grid speeds around a local minimum of |F| without a sign
    change. The minimum of s F (s its sign) is hunted by parabolic steps (golden-section fallback)
    for :data:`PAIR_STEPS` steps; where s F < 0 at some point x, (c_left, x) and (x, c_right) each
    hold one root. From the second step on, a candidate whose parabola puts the minimum above 0.7 x
    the lowest value seen is dropped (a near miss).
    """
    s = np.sign(Fs[:, 1])
    (cl, cm, ch), (gl, gm, gh) = cs.T.copy(), (Fs * s[:, None]).T.copy()
    found = np.zeros(r.size, dtype=bool)
    x_out = np.full(r.size, np.nan)
    f_out = np.full(r.size, np.nan)
    idx = np.arange(r.size)
    for step in range(PAIR_STEPS):
        if idx.size == 0:
            break
        with np.errstate(all="ignore"):
            x = vertex(cl, cm, ch, gl, gm, gh)
            if step > 0:
                # after one step the parabola models the dip: a minimum it puts well above zero is a
                # near miss, not two roots
                keep = ~near_miss(cl, cm, ch, gl, gm, gh, x)
                if not keep.any():
                    break
                if not keep.all():
                    idx, cl, cm, ch, gl, gm, gh, x = (v[keep] for v in (idx, cl, cm, ch, gl, gm, gh, x))
        x = trial_point(x, cl, cm, ch)
        gx = _at(st, prefix, rows_of, r[idx], x) * s[idx]
        hit = gx < 0
        if hit.any():
            found[idx[hit]], x_out[idx[hit]], f_out[idx[hit]] = True, x[hit], gx[hit] * s[idx[hit]]
        cl, cm, ch, gl, gm, gh = shrink(cl, cm, ch, gl, gm, gh, x, gx)
        keep = ~hit & (ch - cl > 1e-9 * cm)
        if not keep.all():
            idx, cl, cm, ch, gl, gm, gh = (v[keep] for v in (idx, cl, cm, ch, gl, gm, gh))
    return found, x_out, f_out


def _scan(st: IsoStack, prefix: str, grid: np.ndarray, rows_of: Rows, rows: np.ndarray, need: float
          ) -> tuple[np.ndarray, ...]:
    """Brackets (row, lower speed, upper speed, F at both, a third grid speed next to them or NaN, F there).

    The grid is evaluated chunk by chunk (about :data:`CHUNK_ELEMENTS` (row, speed) points each,
    the kh-independent parts once for the whole grid) until each row holds ``need`` sign changes;
    a root is a sign change between grid speeds, or one of two roots hidden in a grid cell next to
    a local minimum of |F| (:func:`_hidden_pairs`). Per row the brackets are sorted and the first
    ``need`` kept; so a local minimum whose cells lie above the row's ``need``-th sign change
    (both its roots would rank above ``need``) is not hunted. Which speeds a row is evaluated at
    beyond its ``need``-th sign change (the chunking) changes nothing kept.
    """
    return _assemble(st, prefix, grid, rows_of, rows, need, *_evaluate(st, prefix, grid, rows_of, rows, need))


def _evaluate(st: IsoStack, prefix: str, grid: np.ndarray, rows_of: Rows, rows: np.ndarray, need: float
              ) -> tuple[np.ndarray, np.ndarray]:
    """The upward evaluation of :func:`_scan`: F (n, r) speed-major (valid below ``upto``) and ``upto`` (r,)."""
    n_r, n_c = rows.size, grid.size
    sh = prefix == "L"
    sp = sh_speeds(st, grid) if sh else psv_speeds(st, grid)
    F = np.empty((n_c, n_r))                                           # speed-major
    upto = np.zeros(n_r, dtype=int)                                    # speeds evaluated per row
    found = np.zeros(n_r, dtype=int)
    act = np.arange(n_r)
    start = 0
    while start < n_c and act.size:
        most = max(CHUNK_MIN, CHUNK_ELEMENTS // act.size)                 # speeds per chunk at most
        left = n_c - start
        stop = start - (-left // -(-left // most))                        # the rest in equal chunks
        sl = slice(start, stop)
        kernels = None
        if not sh and st.frac.size > 1:
            kernels = [grid[:0]] + [psv_kernels(st.lam[i], st.mu[i], sp.X[sl, i]) for i in range(1, st.frac.size)]
        kh = rows_of.grid_t(rows[act], grid[sl])
        Fn = sh_block(st, sp.cut(sl), kh) if sh else psv_block(st, sp.cut(sl), kh, kernels)
        act = _record(F, upto, found, act, start, stop, Fn, need)
        start = stop
    return F, upto


def _assemble(st: IsoStack, prefix: str, grid: np.ndarray, rows_of: Rows, rows: np.ndarray, need: float,
              F: np.ndarray, upto: np.ndarray, pending: list | None = None) -> tuple[np.ndarray, ...]:
    """:func:`_scan`'s brackets from the evaluated F (n, r) (speed-major, valid below ``upto`` (r,)).

    ``pending``: a list receiving the hunt's input (rows (m,), grid speeds and F (m, 3)) instead of
    running :func:`_hidden_pairs`: the brackets are then those of a hunt that finds nothing.
    """
    n_r, n_c = rows.size, grid.size
    pos = F > 0
    seen = np.arange(1, n_c)[:, None] < upto                           # cell j (c_j, c_j+1) evaluated
    sc = pos[1:] != pos[:-1]
    sc &= seen
    r1, j1 = np.divmod(np.flatnonzero(sc.T), n_c - 1)                  # by row, then speed (flat: cheaper than 2-D)
    j3 = np.where(j1 > 0, j1 - 1, np.minimum(j1 + 2, n_c - 1))
    out = [rows[r1], grid[j1], grid[j1 + 1], F[j1, r1], F[j1 + 1, r1], np.where(j3 == j1 + 1, np.nan, grid[j3]),
           F[j3, r1]]
    ordered = bool(np.all(rows[1:] > rows[:-1]))                       # out is sorted by (row, lower speed)
    if n_c >= 3:
        # a local minimum of |F| between cells without a sign change: two roots may hide there,
        # unless ``need`` sign changes lie below its lower cell (then both rank above ``need``)
        # (|F| compared through F's sign, the same on all three points: no temporary the size of F)
        mid = F[1:-1]
        up = (mid < F[:-2]) & (mid <= F[2:]) & pos[1:-1]                # F > 0 there: |F| = F
        down = (mid > F[:-2]) & (mid >= F[2:])
        down &= ~pos[1:-1]                                               # F <= 0 there: |F| = -F
        cand = up | down
        cand &= ~(sc[:-1] | sc[1:])
        cand &= seen[1:]
        k2, r2 = np.divmod(np.flatnonzero(cand), n_r)                  # k2: the lower cell
        if need < n_c:
            lim = np.full(n_r, n_c, dtype=np.intp)                     # the cell of each row's need-th sign change
            nth = np.arange(r1.size) - np.searchsorted(r1, r1) == need - 1
            lim[r1[nth]] = j1[nth]
            near = k2 <= lim[r2]
            k2, r2 = k2[near], r2[near]
        if r2.size and pending is not None:
            cols = k2[:, None] + np.arange(3)
            pending.append((rows[r2], grid[cols], F[cols, r2[:, None]]))
        elif r2.size:
            cols = k2[:, None] + np.arange(3)
            c3_, F3 = grid[cols], F[cols, r2[:, None]]
            ok, x, fx = _hidden_pairs(st, prefix, rows_of, rows[r2], c3_, F3)
            if ok.any():
                rk, c3_, F3, x, fx = rows[r2[ok]], c3_[ok], F3[ok], x[ok], fx[ok]
                more = [(rk, rk), (c3_[:, 0], x), (x, c3_[:, 2]), (F3[:, 0], fx), (fx, F3[:, 2]),
                        (c3_[:, 2], c3_[:, 0]), (F3[:, 2], F3[:, 0])]
                out = [np.concatenate([u, *v]) for u, v in zip(out, more)]
                ordered = False
    if not ordered:
        srt = np.lexsort((out[1], out[0]))                             # by row, then lower speed
        out = [v[srt] for v in out]
    R = out[0]
    if need >= n_c:                                                    # (no row holds more than n_c brackets)
        return tuple(out)
    take = np.arange(R.size) - np.searchsorted(R, R) < need            # rank within the row
    return tuple(v[take] for v in out)


def _family_grid(st: IsoStack, prefix: str, grid: np.ndarray) -> np.ndarray:
    """The grid a family scans: SH modes are faster than the slowest shear speed v of any layer
    (omega^2 int rho v^2 = int mu (v'^2 + k^2 v^2) >= k^2 min(mu / rho) int rho v^2), so SH starts just
    below v; P-SV scans all of it."""
    if prefix != "L":
        return grid
    v = float(st.shear.min())
    return np.concatenate([[v * (1.0 - 1e-9)], grid[grid > v]])


def _brackets(st: IsoStack, prefix: str, rows_of: Rows, modes: int | None, grid: np.ndarray | None
              ) -> tuple[np.ndarray, ...]:
    """The scan of :func:`family_roots` with its rescan of rows with too few modes: :func:`_scan`'s brackets."""
    need = np.inf if modes is None else modes
    rows = np.arange(rows_of.base.size)
    grid = speed_grid(st, rows_of) if grid is None else grid
    first = _scan(st, prefix, _family_grid(st, prefix, grid), rows_of, rows, need)
    return _rescan_dips(st, prefix, rows_of, need, first)


def _rescan_dips(st: IsoStack, prefix: str, rows_of: Rows, need: float, first: tuple[np.ndarray, ...]
                 ) -> tuple[np.ndarray, ...]:
    """Brackets ``first`` of :func:`_scan`, with the rows that look short of a mode scanned again on the
    :data:`RESCAN` times finer grid: those holding fewer modes than rows on both sides of them (in
    ascending kh or frequency) and, with ``need`` finite, those whose k-th bracket lies above the
    k-th brackets of rows on both sides (:func:`_rank_jumps`), repeated until no row is added.

    A row's rescan replaces its brackets if it holds more of them or, holding as many, one of them
    lies wholly below the bracket of the same rank (a mode the first scan skipped).
    """
    n_rows = rows_of.base.size
    r, lo, hi, flo, fhi, c3, f3 = first
    counts = np.bincount(r, minlength=n_rows)
    order = np.argsort(rows_of.base, kind="stable")
    cs = counts[order]
    dip = order[cs < np.minimum(np.maximum.accumulate(cs), np.maximum.accumulate(cs[::-1])[::-1])]
    done = np.zeros(n_rows, dtype=bool)
    fine_grid = None
    while True:
        if need < np.inf:
            jump = _rank_jumps(r, lo, hi, counts, order, int(need))
            if jump.size:
                add = np.zeros(n_rows, dtype=bool)
                add[dip] = True
                add[jump] = True
                add &= ~done
                dip = np.flatnonzero(add)
            elif done.any():
                dip = dip[~done[dip]]
        if not dip.size:
            break
        done[dip] = True
        if fine_grid is None:
            fine_grid = _family_grid(st, prefix, speed_grid(st, rows_of, RESCAN))
        more = _scan(st, prefix, fine_grid, rows_of, dip, need)
        better = np.bincount(more[0], minlength=n_rows) > counts
        if need < np.inf:
            better |= _skipped(r, lo, more[0], more[2], n_rows, int(need))
        keep, keep2 = ~better[r], better[more[0]]
        r, lo, hi, flo, fhi, c3, f3 = (np.concatenate([u[keep], v[keep2]])
                                       for u, v in zip((r, lo, hi, flo, fhi, c3, f3), more))
        if need == np.inf:                                             # (the count rule alone: one pass)
            break
        if better.any():                                               # by (row, lower speed) again
            srt = np.lexsort((lo, r))
            r, lo, hi, flo, fhi, c3, f3 = (v[srt] for v in (r, lo, hi, flo, fhi, c3, f3))
            counts = np.bincount(r, minlength=n_rows)
        dip = np.zeros(0, dtype=np.intp)
    return r, lo, hi, flo, fhi, c3, f3


def _rank_table(r: np.ndarray, v: np.ndarray, n_rows: int, width: int) -> np.ndarray:
    """Values v (m,) of brackets sorted by (row r, lower speed) as a (n_rows, width) table by rank, NaN-padded."""
    out = np.full((n_rows, width), np.nan)
    k = np.arange(r.size) - np.searchsorted(r, r)
    m = k < width
    out[r[m], k[m]] = v[m]
    return out


def _rank_jumps(r: np.ndarray, lo: np.ndarray, hi: np.ndarray, counts: np.ndarray, order: np.ndarray, need: int
                ) -> np.ndarray:
    """Rows whose k-th bracket (k < ``need``) lies wholly above the k-th brackets of a row on each side
    within :data:`JUMP_ROWS` rows.

    With ``need`` = N a row stops at its N-th sign change, so a row that lost two modes in one cell
    holds as many brackets as its neighbours (the count rule cannot see it); its k-th bracket is then
    a mode two ranks higher, above those of the rows around it (a mode's speed is continuous along
    the rows); so is every row of a run of up to :data:`JUMP_ROWS` such rows. Brackets (m,) sorted by
    (row r, lower speed lo); ``counts`` (n_rows,): brackets per row; ``order``: the rows in ascending
    kh or frequency.
    """
    n = order.size
    need = min(need, int(counts.max(initial=0)))                       # (the tables' width: no wider than used)
    if n < 3 or need == 0:
        return np.zeros(0, dtype=np.intp)
    d = min(JUMP_ROWS, n - 1)
    k = np.arange(r.size) - (np.cumsum(counts) - counts)[r]            # rank within the row (< need)
    pos = np.empty(counts.size, dtype=np.intp)                         # position along the rows
    pos[order] = np.arange(n)
    p = pos[r]
    LO = np.full((n, need), np.nan)                                    # (NaN compares False)
    LO[p, k] = lo
    HI = np.full((n + 2 * d, need), np.inf)                            # padded by d rows each side
    HI[p + d, k] = hi
    below, above = HI[d - 1:d - 1 + n].copy(), HI[d + 1:d + 1 + n].copy()   # least of the d rows below / above
    for j in range(2, d + 1):
        np.minimum(below, HI[d - j:d - j + n], out=below)
        np.minimum(above, HI[d + j:d + j + n], out=above)
    jump = LO > below
    jump &= LO > above
    return order[jump.any(axis=1)]


def _skipped(r: np.ndarray, lo: np.ndarray, r2: np.ndarray, hi2: np.ndarray, n_rows: int, need: int) -> np.ndarray:
    """Per row (n_rows,): a bracket of the rescan (rows r2, upper speeds hi2) lies wholly below the first
    scan's bracket of the same rank (rows r, lower speeds lo): the first scan skipped a mode there."""
    need = min(need, max(r.size, r2.size))                             # (the tables' width: no wider than used)
    LO, HI2 = _rank_table(r, lo, n_rows, need), _rank_table(r2, hi2, n_rows, need)
    with np.errstate(invalid="ignore"):
        out = np.any(HI2 <= LO, axis=1)
    return out


def _brackets_both(st: IsoStack, rows_of: Rows, modes: int | None, grid: np.ndarray,
                   curve: tuple[np.ndarray, np.ndarray] | None = None, coarsen: bool = True,
                   pending: tuple[list, list, list] | None = None
                   ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """:func:`_brackets` of P-SV and SH; with one film, both scans in one pass (:func:`_evaluate_both`).

    ``grid``: :func:`speed_grid` of all rows; ``curve``: its :func:`phase_curve` if at hand;
    ``coarsen``: False keeps ``grid`` to the top (the rest of it is otherwise rebuilt for the rows
    still scanned, :func:`_evaluate_both`; then the brackets are those of the separate scans,
    :func:`_brackets`, bit for bit); ``pending``: with one film, three lists: two (P-SV, SH) receive the
    first scan's hunt for hidden pairs instead of running it (:func:`_assemble`), the third a
    function returning the brackets with the hunt run (from the same evaluated grid).
    """
    if st.frac.size != 1:
        return _brackets(st, "R", rows_of, modes, grid), _brackets(st, "L", rows_of, modes, grid)
    need = np.inf if modes is None else modes
    rows = np.arange(rows_of.base.size)
    grid_l = _family_grid(st, "L", grid)
    FR, upR, FL, upL, grid, grid_l = _evaluate_both(st, grid, grid_l, rows_of, rows, need, curve, coarsen)
    if pending is not None:
        pending[2].append(lambda: _both_assembled(st, rows_of, rows, need, grid, grid_l, FR, upR, FL, upL))
    pR, pL = (None, None) if pending is None else pending[:2]
    return (_rescan_dips(st, "R", rows_of, need, _assemble(st, "R", grid, rows_of, rows, need, FR, upR, pR)),
            _rescan_dips(st, "L", rows_of, need, _assemble(st, "L", grid_l, rows_of, rows, need, FL, upL, pL)))


def _both_assembled(st: IsoStack, rows_of: Rows, rows: np.ndarray, need: float, grid: np.ndarray, grid_l: np.ndarray,
                    FR: np.ndarray, upR: np.ndarray, FL: np.ndarray, upL: np.ndarray
                    ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """The brackets of :func:`_brackets_both` (one film) from the evaluated grids of :func:`_evaluate_both`."""
    return (_rescan_dips(st, "R", rows_of, need, _assemble(st, "R", grid, rows_of, rows, need, FR, upR)),
            _rescan_dips(st, "L", rows_of, need, _assemble(st, "L", grid_l, rows_of, rows, need, FL, upL)))


def _evaluate_both(st: IsoStack, grid: np.ndarray, grid_l: np.ndarray, rows_of: Rows, rows: np.ndarray,
                   need: float, curve: tuple[np.ndarray, np.ndarray] | None = None, coarsen: bool = True
                   ) -> tuple[np.ndarray, ...]:
    """:func:`_evaluate` of P-SV on ``grid`` and of SH on ``grid_l`` (:func:`_family_grid`) for one film, in one pass.

    Both families need the film's shear-wave functions (C_b, S_b at t = kh): they are computed once
    per chunk of ``grid`` for the rows either family still scans (the SH grid is ``grid`` above the
    slowest shear speed after its own first point). Every value is the one of
    the separate scans (:func:`surfwave.layers.isotropic.psv_block`, ``sh_block``: elementwise).
    """
    n_r, n_c = rows.size, grid.size
    j0 = n_c - (grid_l.size - 1)                                       # grid[j0:] is grid_l[1:]
    sp_r, sp_l = psv_speeds(st, grid), sh_speeds(st, grid_l)
    FR, FL = np.empty((n_c, n_r)), np.empty((grid_l.size, n_r))
    up_r, up_l = np.zeros(n_r, dtype=int), np.zeros(n_r, dtype=int)
    found_r, found_l = np.zeros(n_r, dtype=int), np.zeros(n_r, dtype=int)
    # P-SV alone below j0 and the SH grid's first point on top of the chunk at j0, or chunks across
    # j0, that point on top of the chunk across it: whichever takes fewer evaluations (every row active)
    at_j0 = j0 < n_c and 1 - (-(n_c - j0) * n_r // CHUNK_ELEMENTS) <= -(-n_c * n_r // CHUNK_ELEMENTS)
    if j0 >= n_c:                                                      # (no chunk reaches the SH grid)
        FL[0] = sh_block(st, sp_l.cut(slice(0, 1)), rows_of.grid_t(rows, grid_l[:1]))[0]
        up_l[:] = 1
    l0 = j0 < n_c                                                      # the SH grid's first point still to do
    act_r, act_l = np.arange(n_r), np.arange(n_r)
    top = float(rows_of.base[rows].max(initial=0.0))                  # the grid is for rows up to this base
    start = 0
    while start < n_c and (act_r.size or act_l.size):
        if not act_r.size and start < j0:                              # SH rows alone: from their grid on
            start = j0
            continue
        if at_j0 and start < j0:
            union, end = act_r, j0
        else:
            both = np.zeros(n_r, dtype=bool)
            both[act_r] = True
            both[act_l] = True
            union, end = np.flatnonzero(both), n_c
        most = max(CHUNK_MIN, CHUNK_ELEMENTS // union.size)
        left = end - start
        stop = start - (-left // -(-left // most))                     # the rest in equal chunks
        sl = slice(start, stop)
        first = int(l0 and stop > j0)                                  # the SH grid's first point on top
        l0 = l0 and not first
        speeds, r2 = grid[sl], sp_r.r2[0, 1, sl]
        if first:
            speeds, r2 = np.concatenate([grid_l[:1], speeds]), np.concatenate([sp_l.r2[0, 1, :1], r2])
        kh = rows_of.grid_t(rows[union], speeds)
        Cb, Sb, gb = wave_block(r2, kh, True)
        assert gb is not None
        if act_l.size and stop > j0:                                   # SH first: P-SV overwrites C_b
            a = max(start, j0)
            # (the first point included: then a = j0)
            blk = np.r_[0, a - start + 1:stop - start + 1] if first and a > start else slice(a - start, None)
            cols = slice(None) if act_l.size == union.size else np.searchsorted(union, act_l)
            lo_l, hi_l = a - j0 + 1 - first, stop - j0 + 1
            kb, Cl, Sl = kh[blk], Cb[blk], Sb[blk]
            Fn = sh_block(st, sp_l.cut(slice(lo_l, hi_l)), kb[:, cols], (Cl[:, cols], Sl[:, cols]))
            act_l = _record(FL, up_l, found_l, act_l, lo_l, hi_l, Fn, need)
        if act_r.size:
            cols = slice(None) if act_r.size == union.size else np.searchsorted(union, act_r)
            Fn = psv_block(st, sp_r.cut(sl), kh[first:, cols], None,
                           (Cb[first:, cols], Sb[first:, cols], gb[first:, cols]))
            act_r = _record(FR, up_r, found_r, act_r, start, stop, Fn, need)
        start = stop
        if coarsen and start < n_c and (act_r.size < n_r or act_l.size < n_r):
            live = np.zeros(n_r, dtype=bool)
            live[act_r] = True
            live[act_l] = True
            base_left = rows_of.base[rows[live]]
            top_left = float(base_left.max(initial=0.0))
            if curve is None:
                curve = phase_curve(st)
            # phase points the rest of the grid would lose: worth building it?
            aux, nu = curve
            c_s = float(grid[start - 1])
            nu_s = float(np.interp(c_s, aux, nu))
            per = nu[-1] / aux[-1] - nu_s / c_s if rows_of.freq else nu[-1] - nu_s
            # (half the speeds left at least: fewer phase points bring base points back)
            if (top - top_left) * per >= 0.5 * (n_c - start) * PHASE_STEP:
                # the rows left have smaller kh: the rest of the grid for them alone, if it is coarser
                top = top_left
                tail = speed_grid(st, Rows(base_left, rows_of.freq), 1, curve)
                tail = tail[tail > c_s]
                if tail.size <= COARSEN * (n_c - start):
                    grid = np.concatenate([grid[:start], tail])
                    grid_l = _family_grid(st, "L", grid)
                    n_c = grid.size
                    j0 = n_c - (grid_l.size - 1)
                    sp_r, sp_l = psv_speeds(st, grid), sh_speeds(st, grid_l)
                    FR, FL = _regrid(FR, n_c, up_r), _regrid(FL, grid_l.size, up_l)
    return FR, up_r, FL, up_l, grid, grid_l


def _regrid(F: np.ndarray, n: int, upto: np.ndarray) -> np.ndarray:
    """F (m, r) on a grid whose speeds from ``upto.max()`` on are replaced: (n, r), the values below kept."""
    k = int(upto.max(initial=0))
    out = np.empty((n, F.shape[1]))
    out[:k] = F[:k]
    return out


def _record(F: np.ndarray, upto: np.ndarray, found: np.ndarray, act: np.ndarray, start: int, stop: int,
            Fn: np.ndarray, need: float) -> np.ndarray:
    """Store the block Fn (stop - start, act) of a family into F, count its new sign changes; the rows still active."""
    pos = Fn > 0
    n_sc = (pos[1:] != pos[:-1]).sum(axis=0)
    whole = act.size == F.shape[1]
    if start:
        n_sc += pos[0] != (F[start - 1] > 0 if whole else F[start - 1, act] > 0)
    if whole:
        F[start:stop] = Fn
    else:
        F[start:stop, act] = Fn
    upto[act] = stop
    found[act] += n_sc
    return act[found[act] < need]
