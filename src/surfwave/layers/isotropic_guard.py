"""The isotropic fast path checked against the exact Wittrick-Williams count: all its modes, or the count's.

Why. The fast path (:mod:`surfwave.layers.isotropic_modes`) finds the zeros of a pole-free secular
function on a speed grid. Every sign change is a mode, but two modes in one grid cell leave none;
its hunt for such pairs (parabolic steps at local minima of |F|) is a heuristic, and where a film
lies under a faster one, modes trapped in the buried film pair up with modes of the films above
within far less than a cell (SiO2 / AlN / gold on Si at kh = 20 lost two of 26 modes).

Check. Per family and per row, the number of modes found below c_top = c_lim (1 - :data:`TOP`)
must equal the count's rise from the grid's floor to c_top (:func:`surfwave.layers.counting.mode_count`
on the general Stroh blocks of the same stack: exact, pole-free), and the count at the floor must
be 0 (no mode below it). With ``modes`` = N, a row holding N modes is checked at just above its
N-th mode instead (no slower mode missed). Modes above c_top (within t = sqrt(2 TOP) of the
cut-off, where a mode enters alone) are not checked, nor rows at kh = 0 (the bare substrate) or
rows whose films would need more than :data:`surfwave.layers.counting.MAX_SUB` sublayers for the
count (buried gold: kh ~ 1000); their answer is the grid's.

Fixed frequency. Rows at fixed frequency (kh = omega H / c) are counted at each speed's own kh:
the count at (c, omega H / c) is the number of branches with omega_n(k) < omega at k = omega / c.
Walking up in c along that line (k falling), a branch whose frequency rises with k is crossed once,
forward (group velocity v_g > 0), and adds one; but a branch's omega(k) need not be monotone (a
soft heavy film on a very stiff substrate: the S3 branch falls between kh 0.47 and 0.99, so one
frequency meets it three times, the middle crossing backward with v_g ~ -92 m/s), and a backward
crossing takes one away. So the count below c is (forward) - (backward) of the modes slower than c,
not their number, and that difference (from the fast path's exact group velocities; a NaN one
counts as forward) is what the check compares, with or without ``modes``. What this guarantees at
fixed frequency: no forward mode and no backward mode missed ALONE (or any set of misses with
unequal forward and backward numbers). A missed forward / backward PAIR leaves the count unchanged:
it is not detectable by the count. At fixed kh every branch is crossed once (the count never falls
with c) and the check is exact.

Repair. In a row that fails, the modes are located by bisection on the count until every interval
holds a rise (or, at fixed frequency, a fall) of exactly one with a sign change of the secular
function at its ends, and those brackets go to the fast path's own Newton refinement
(:func:`surfwave.layers.isotropic_modes.refine_brackets`: the same speeds to ~1e-14 and the same
exact group velocities). Bisection stops at intervals of relative width 1e-14 (a degenerate pair:
the midpoint, twice). At fixed kh the count has every mode below the check speed, and its modes
replace the row's there. At fixed frequency it cannot isolate a forward / backward pair that shares
an interval, so the repair never drops a mode the grid found (each is a sign change of the secular
function in its own bracket: a true root): the row keeps all of them and gains those of the count
that are not among them (within :data:`SAME`, relative). The repaired row is not checked again.

Which stacks are checked (:func:`guarded`): every stack with two films or more. Close pairs need
two places a mode can live in: a film buried under a faster one (SiO2 / AlN / gold on Si) but
also, less often, films whose speeds rise downward (a slow top film over a film barely slower
than the substrate: 2 of 186 random such stacks lost two sagittal modes at kh ~ 79 on the grid
alone), so no cheaper criterion (such as :func:`surfwave.layers.counting.needed`) is safe. One
film on a half-space is counted when the substrate's shear speed exceeds :data:`CONTRAST` x the
film's: there a film holds many modes close together below c_lim (about kh q_max / pi per wave
type, q_max = sqrt(c_lim^2 / v^2 - 1)), and the grid alone lost modes on three such stacks
(film shear 200 m/s on 11871 m/s at kh 0.7 called alone: a pair S21 / S22 in the cell next to
S20's sign change, where no hunt starts; 452 on 3326 m/s with ``modes`` = 3: a pair the hunt
took for a near miss; a heavy film's Love modes packed within 0.2 m/s above its shear speed,
before the grid resolved that onset). A film of lower contrast is not counted: the count would
double the cost there (200 kh rows: 7 ms on top of 8 ms, before the fast path took 2 ms), and on
600 random one-film stacks (kh 0.1 ... 100) and 2300 calls of 575 more (kh and frequency rows,
``modes`` None and 2), all contrasts, the grid found every mode the count has. That is evidence,
not a proof. :data:`ALWAYS` checks every
stack. The cost on a guarded stack: about 15 % (buried gold, 200 kh rows 0.5 ... 20: 0.30 s
against 0.26 s unchecked).
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.counting import applicable, mode_count, sublayers
from surfwave.layers.isotropic import IsoStack
from surfwave.layers.isotropic_deriv import secular_d
from surfwave.layers.isotropic_modes import FLOOR, Rows, refine_brackets, roots_table, secular_at
from surfwave.layers.partial import Blocks, Family, families, scaled_blocks
from surfwave.layers.stack import Stack

__all__ = ["ALWAYS", "CONTRAST", "SAME", "TOP", "check_families", "guarded", "row_counts"]

#: The count's top speed is c_lim (1 - TOP).
TOP = 1e-9
#: One film is counted when the substrate's shear speed exceeds this many times the film's (:func:`guarded`).
CONTRAST = 3.0
#: Check every stack (tests; default: only those of :func:`guarded`).
ALWAYS = False
#: Bisection steps on the count at most.
MAX_SPLIT = 80
#: Relative width at which two modes are taken as one degenerate pair.
DEGENERATE = 1e-14
#: Relative distance within which a mode of the count's repair is taken as one the grid found (fixed frequency).
SAME = 1e-10
#: Marks a count that could not be taken (too many sublayers, or a failed evaluation).
UNCOUNTED = -10**6


def guarded(stack: Stack, st: IsoStack | None = None) -> bool:
    """True when :func:`check_families` counts this stack's modes (module docstring).

    Two films or more; one film whose shear speed is below 1 / :data:`CONTRAST` of the substrate's
    (given ``st``, the stack's :class:`surfwave.layers.isotropic.IsoStack`); or :data:`ALWAYS`.
    """
    films = sum(f.thickness > 0 for f in stack.films)
    if ALWAYS or films >= 2:
        return True
    return films == 1 and st is not None and st.c_lim > CONTRAST * float(st.shear[:-1].min())


def row_counts(b: Blocks, fam: Family, rows_of: Rows, rows: np.ndarray, c: np.ndarray) -> np.ndarray:
    """The Wittrick-Williams count at (row, speed) pairs (m,), each at its row's kh; :data:`UNCOUNTED` where not taken.

    Parameters
    ----------
    rows : ndarray of int, shape (m,)
        Rows of ``rows_of`` (kh > 0).
    c : ndarray, shape (m,)
        Speeds, m/s.
    """
    out = np.full(rows.size, UNCOUNTED)
    if rows.size == 0:
        return out
    kh = rows_of.pairs(rows, c)
    nsub = sublayers(b, float(kh.max()), float(c.max()))
    if nsub is not None:
        return _count(b, fam, c, kh, nsub)
    # some point needs too many sublayers: count the others in bins of kh (powers of two)
    key = np.ceil(np.log2(np.maximum(kh, 1e-300)))
    for k in np.unique(key):
        m = key == k
        nsub = sublayers(b, float(kh[m].max()), float(c[m].max()))
        if nsub is not None:
            out[m] = _count(b, fam, c[m], kh[m], nsub)
    return out


def _count(b: Blocks, fam: Family, c: np.ndarray, kh: np.ndarray, nsub: np.ndarray) -> np.ndarray:
    """:func:`row_counts` at pairs (c, kh) (m,) with these sublayers."""
    if np.all(c == c[0]):                           # one speed: the layers' eigen-solutions shared by all rows
        n = mode_count(b, fam, c[:1], kh[None, :], "free", nsub)[0]
    else:
        n = mode_count(b, fam, c, kh[:, None], "free", nsub)[:, 0]
    return np.where(n > -1000, n, UNCOUNTED)


def check_families(stack: Stack, st: IsoStack, rows_of: Rows, prefixes: tuple[str, ...],
                   sols: list[tuple[np.ndarray, np.ndarray]], modes: int | None) -> list[tuple[np.ndarray, np.ndarray]]:
    """The fast path's (speeds, group velocities) per family, each row checked against the count and repaired.

    Parameters
    ----------
    stack : Stack
        The resolved stack (its general Stroh blocks give the count).
    st : IsoStack
        The same stack for the fast path.
    rows_of : Rows
        The rows (kh or frequencies).
    prefixes : tuple of {"R", "L"}
        The family of each entry of ``sols``.
    sols : list of (ndarray, ndarray), each (n_rows, width)
        Speeds and group velocities (m/s), ascending per row, NaN-padded.
    modes : int or None
        At most this many modes per row and family (as asked of the fast path).

    Returns
    -------
    list of (ndarray, ndarray)
        ``sols`` where every row agrees with the count; in rows that did not, the count's modes
        (refined by the fast path's Newton iteration): below the check speed instead of the row's at
        fixed kh, added to the row's at fixed frequency. Unchanged for a stack :func:`guarded` leaves alone.
    """
    if not guarded(stack, st):
        return sols
    b = scaled_blocks(stack)
    if not applicable(b):
        return sols
    fams = {f.prefix: f for f in families(b)}
    return [_check(b, fams[p], st, p, rows_of, c, vg, modes) for p, (c, vg) in zip(prefixes, sols)]


def _check(b: Blocks, fam: Family, st: IsoStack, prefix: str, rows_of: Rows, c: np.ndarray, vg: np.ndarray,
           modes: int | None) -> tuple[np.ndarray, np.ndarray]:
    """:func:`check_families` for one family: the table (n_rows, width) of speeds and group velocities."""
    n_rows = c.shape[0]
    rows = np.flatnonzero(rows_of.base > 0)         # kh = 0 (or f = 0): the bare substrate, one Rayleigh root
    if rows.size == 0:
        return c, vg
    c_top = st.c_lim * (1.0 - TOP)
    c_floor = FLOOR * float(st.shear.min())
    chk = np.full(n_rows, c_top)
    if modes is not None and c.shape[1] >= modes:
        full = np.isfinite(c[:, modes - 1])
        chk[full] = np.minimum(c[full, modes - 1] * (1.0 + 1e-10), c_top)
    with np.errstate(invalid="ignore"):
        below = c < chk[:, None]
        if rows_of.freq:                            # the count is (forward) - (backward) there
            below = np.where(vg < 0, -1, 1) * below
    expected = below.sum(axis=1)
    n0 = row_counts(b, fam, rows_of, rows, np.full(rows.size, c_floor))
    n1 = row_counts(b, fam, rows_of, rows, chk[rows])
    counted = (n0 != UNCOUNTED) & (n1 != UNCOUNTED)
    bad = counted & ((n0 != 0) | (n1 - n0 != expected[rows]))
    if not bad.any():
        return c, vg
    fix = rows[bad]
    # a mode below the floor (not seen in unstressed stacks): search from far below it, where the count is 0
    lo = np.where(n0[bad] == 0, c_floor, 1e-3 * c_floor)
    r, cr, vr = _modes_by_count(b, fam, st, prefix, rows_of, fix, lo, chk[fix], np.zeros(fix.size, dtype=int), n1[bad])
    if rows_of.freq:
        # the count cannot see a forward / backward pair: every mode of the grid stays, the count's are added
        R, C, V = _merge(c, vg, r, cr, vr)
    else:
        keep = ~np.isin(np.arange(n_rows), fix)
        ik, jm = np.nonzero(np.isfinite(c) & keep[:, None])
        R = np.concatenate([ik, r])
        C = np.concatenate([c[ik, jm], cr])
        V = np.concatenate([vg[ik, jm], vr])
        # modes above the check speed of a fixed row (found by the fast path, not counted) stay
        for row in fix:
            above = np.isfinite(c[row]) & (c[row] >= chk[row])
            R, C, V = np.r_[R, np.full(int(above.sum()), row)], np.r_[C, c[row, above]], np.r_[V, vg[row, above]]
    if modes is not None:
        srt = np.lexsort((C, R))
        R, C, V = R[srt], C[srt], V[srt]
        rank = np.arange(R.size) - np.searchsorted(R, R)
        R, C, V = R[rank < modes], C[rank < modes], V[rank < modes]
    return roots_table(n_rows, R, C, V)


def _merge(c: np.ndarray, vg: np.ndarray, r: np.ndarray, cr: np.ndarray, vr: np.ndarray
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every mode of the grid's table (n_rows, width) and those of the count (m,) it lacks.

    Returns rows, speeds (m/s) and group velocities (m/s), each (p,), unsorted.

    A mode of the count is the grid's when an unmatched mode of the grid in its row lies within
    :data:`SAME` (relative) of it (both come from the same Newton refinement, to ~1e-14).
    """
    ik, jm = np.nonzero(np.isfinite(c))
    R, C, V = [ik], [c[ik, jm]], [vg[ik, jm]]
    for row in np.unique(r):
        grid = c[row][np.isfinite(c[row])]
        free = np.ones(grid.size, dtype=bool)
        new = np.zeros(0, dtype=int)
        for q in np.flatnonzero(r == row):
            d = np.where(free, np.abs(grid - cr[q]), np.inf)
            j = int(np.argmin(d)) if d.size else -1
            if j >= 0 and d[j] <= SAME * abs(cr[q]):
                free[j] = False
            else:
                new = np.r_[new, q]
        R, C, V = R + [r[new]], C + [cr[new]], V + [vr[new]]
    return np.concatenate(R), np.concatenate(C), np.concatenate(V)


def _modes_by_count(b: Blocks, fam: Family, st: IsoStack, prefix: str, rows_of: Rows, rows: np.ndarray,
                    lo: np.ndarray, hi: np.ndarray, n_lo: np.ndarray, n_hi: np.ndarray
                    ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The modes in (lo, hi) of each row (r,) (counts ``n_lo``, ``n_hi`` there): rows, speeds, group velocities (m,).

    Bisection on the count until each interval's count rises or falls by one and the secular
    function changes sign across it; then the fast path's Newton refinement of those brackets. At
    fixed kh that is every mode; at fixed frequency an interval whose count does not change (a
    forward / backward pair) is left.
    """
    br: list[tuple[np.ndarray, ...]] = []
    deg: list[tuple[np.ndarray, np.ndarray]] = []
    r = rows.copy()
    lo, hi, nl, nh = lo.astype(float), hi.astype(float), n_lo.copy(), n_hi.copy()
    for _ in range(MAX_SPLIT):
        live = (nh != nl) & (nl != UNCOUNTED) & (nh != UNCOUNTED)
        r, lo, hi, nl, nh = r[live], lo[live], hi[live], nl[live], nh[live]
        if r.size == 0:
            break
        one = np.flatnonzero(np.abs(nh - nl) == 1)   # a fall: a backward mode (fixed frequency)
        if one.size:
            f_lo = secular_at(st, prefix, rows_of, r[one], lo[one])
            f_hi = secular_at(st, prefix, rows_of, r[one], hi[one])
            sc = f_lo * f_hi < 0
            br.append((r[one[sc]], lo[one[sc]], hi[one[sc]], f_lo[sc], f_hi[sc]))
            out = np.zeros(r.size, dtype=bool)
            out[one[sc]] = True
        else:
            out = np.zeros(r.size, dtype=bool)
        tiny = ~out & (hi - lo <= DEGENERATE * hi)
        if tiny.any():
            k = np.abs(nh - nl)[tiny]
            deg.append((np.repeat(r[tiny], k), np.repeat(0.5 * (lo + hi)[tiny], k)))
        go = ~out & ~tiny
        r, lo, hi, nl, nh = r[go], lo[go], hi[go], nl[go], nh[go]
        if r.size == 0:
            break
        mid = 0.5 * (lo + hi)
        nm = row_counts(b, fam, rows_of, r, mid)
        r, lo, hi = np.r_[r, r], np.r_[lo, mid], np.r_[mid, hi]
        nl, nh = np.r_[nl, nm], np.r_[nm, nh]
    rr, cc, vv = [np.zeros(0, dtype=int)], [np.zeros(0)], [np.zeros(0)]
    if br:
        R, LO, HI, FLO, FHI = (np.concatenate([x[k] for x in br]) for k in range(5))
        if R.size:
            nan = np.full(R.size, np.nan)
            c, v = refine_brackets(st, prefix, LO, HI, rows_of, R, FLO, FHI, nan, nan)
            rr.append(R)
            cc.append(c)
            vv.append(v)
    for R, c in deg:
        t = np.sqrt(1.0 - (c / st.c_lim) ** 2)
        kh = rows_of.pairs(R, c)
        ratio = secular_d(st, prefix, t, kh, ratio=True)[3]
        rr.append(R)
        cc.append(c)
        vv.append(c + kh * ratio * st.c_lim ** 2 * t / c)
    return np.concatenate(rr), np.concatenate(cc), np.concatenate(vv)
