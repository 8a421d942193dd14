"""Modes of a stack at given frequencies: each mode at its own kh = 2 pi f H / c.

At a fixed frequency f the modes of a stack of total film thickness H have different
wavenumbers. For each family and branch j (the j-th slowest mode at fixed kh) the dispersion curve
is first computed on a kh grid (:func:`surfwave.layers.modes.family_modes`) with its group velocity,
the slope of omega(kh) H = c_j(kh) kh. That curve need not rise with kh: where v_g < 0 (a backward
wave, e.g. a soft heavy film on a much stiffer substrate) it falls, and one frequency meets the branch
two or three times. Every crossing is bracketed (:mod:`surfwave.layers.crossings`; a grid sample of
another branch, where the search at that kh missed a slower mode, is dropped first): each grid cell
across which omega H - 2 pi f H changes sign (or vanishes at a grid point), the branch being sampled
also at the turning points of each cell's cubic Hermite model where they could hide crossings, and
the cut-off cell below the curve's first grid point (start kh = omega H / c_lim there). In each
bracket the start is the inverse cubic Hermite interpolation of the cell (a monotone cell; linear
otherwise), and Newton's method on g(kh) = c_j(kh) kh - 2 pi f H with the exact slope dg/dkh = v_g
(:func:`surfwave.layers.fields.mode_fields`) polishes it, kept inside the bracket (bisection where
a step would leave it, near a turning point). Every iterate is an exact mode of the stack, so
the residual 2 pi f H - c kh measures the error.

Guaranteed: one mode per sign change of omega H - 2 pi f H between consecutive samples of a branch
(the samples are exact modes), distinct brackets giving distinct modes. Not guaranteed: two
crossings between the same two samples, i.e. a frequency so close to a branch's local extremum of
omega that both crossings lie within one cell and the cell's Hermite model does not show the
extremum reaching it (within the model's error, O(h^4) of omega for a grid step h); such crossings are
then both missed (never one of them: the parity of a branch's crossings is kept), and appear as the
frequency moves away from the extremum. A branch that turns within its cut-off cell, or beyond the
grid's last kh, is not followed there.

Labels at fixed frequency: the modes of each family at one frequency are ordered by speed and
labelled by rank (R, S1, S2, ...; L0, L1, ...; M0, M1, ...), as on the isotropic path. Where every
branch's omega rises with kh this is the branch index, the label of the same mode at fixed kh;
where a branch is not monotone, its two or three crossings take consecutive ranks, so a label at
fixed frequency may name another branch than the same label at fixed kh = 2 pi f H / c. A mode of
branch j has rank >= j: at the mode's kh the line c = omega H / kh lies above every slower branch
i < j, and at large kh below it, so branch i crosses the frequency at a larger kh, i.e. at a lower
speed; ranks 0 ... r therefore need branches 0 ... r only (:func:`mode_speeds_at_frequency`).
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.layers.crossings import brackets, stray_samples, turning_points
from surfwave.layers.fields import mode_fields
from surfwave.layers.group_check import checked_group_velocity
from surfwave.layers.modes import family_modes, label_family, lowest_speed
from surfwave.layers.partial import Blocks, Family, families, scaled_blocks
from surfwave.layers.stack import Stack
from surfwave.solvers.boundary import Boundary

__all__ = ["at_frequency", "mode_speeds_at_frequency"]

#: Points of the kh grid of the starting curves.
GRID = 160
#: Newton steps at most (per crossing).
NEWTON = 12
#: Bisection steps at most (per crossing), where a Newton step would leave the bracket.
BISECT = 40


def _frequencies(frequency) -> np.ndarray:
    f = validate.real_array(frequency, "frequency").reshape(-1)
    if not np.all(np.isfinite(f)) or np.any(f < 0):
        raise InputError(f"frequency must be finite and >= 0 (Hz), got {frequency!r}")
    if np.any(f > 1e13):
        raise InputError(f"frequency {f.max():.4g} Hz is beyond any acoustic wave (is it in Hz?)")
    return f


def at_frequency(stack: Stack, frequency, *, electrical: str | Boundary = "free", leaky: bool = False,
                 modes: int | None = None) -> dict:
    """The :func:`surfwave.layered` record at frequencies (Hz) instead of kh (same keys, rows = frequencies).

    Every crossing of each branch with the frequency is a mode (backward waves, v_g < 0, included);
    labels are ranks within the family at that frequency (see the module's docstring). K^2 of a
    piezoelectric stack compares the free and metallized speeds of the same mode label at the same
    frequency. ``modes``: at most that many modes per family, the slowest at each frequency (None: all).
    """
    from surfwave.layers.solve import k2_pair

    out = _at_frequency(stack, frequency, electrical=electrical, leaky=leaky, modes=modes)
    if stack.piezo and stack.total_thickness > 0 and out["c"].size:
        pair, free = k2_pair(electrical)
        other = _at_frequency(stack, frequency, electrical=pair)
        for i in range(out["c"].shape[0]):
            lab = {str(m): j for j, m in enumerate(other["mode"][i]) if m}
            for j, m in enumerate(out["mode"][i]):
                if m and str(m) in lab:
                    c_o = other["c"][i, lab[str(m)]]
                    cf, cm = (out["c"][i, j], c_o) if free else (c_o, out["c"][i, j])
                    out["K2"][i, j] = 2.0 * (cf - cm) / cf
    return out


def _at_frequency(stack: Stack, frequency, *, electrical: str | Boundary = "free", leaky: bool = False,
                  modes: int | None = None) -> dict:
    """:func:`at_frequency` for one electrical condition (K2 left NaN)."""
    from surfwave.layers.solve import (
        MAX_KH,
        REASON_NONE,
        assemble,
        empty_result,
        family_limits,
        merge_families,
        mode_limits,
        unstable_reason,
        use_fast_path,
    )

    f = _frequencies(frequency)
    fast = use_fast_path(stack, leaky)
    why = "" if fast else unstable_reason(stack)
    if why:
        return empty_result(f, np.nan, why)
    H = stack.total_thickness
    if H == 0:
        out = assemble(stack, np.zeros(f.size), electrical, leaky, modes)
        out["frequency"] = np.broadcast_to(f[:, None], out["c"].shape).copy()
        return out
    if leaky:
        raise InputError("leaky=True is available with kh, not with frequency")
    if fast:
        from surfwave.layers.isotropic import iso_stack
        from surfwave.layers.isotropic_record import frequency_record

        c_floor = 0.5 * float(iso_stack(stack).shear.min())             # 10 x lowest_speed, as below
        if 2 * np.pi * float(f.max()) * H / c_floor > MAX_KH * 0.999 / 1.05:
            top = 2 * np.pi * float(f.max()) * H / c_floor
            raise InputError(f"frequency {f.max():.4g} Hz gives kh up to {top:.4g}, beyond {MAX_KH:g}")
        return frequency_record(stack, f, modes)
    b = scaled_blocks(stack)
    fams = families(b)
    wH, grid = _start_grid(b, f, H)
    cs, vgs = [], []
    for fam in fams:
        C, V = _family_at_frequency(b, fam, wH, grid, electrical)
        cs.append(C)
        vgs.append(V)
    if modes is not None:
        cs, vgs = [c[:, :modes] for c in cs], [v[:, :modes] for v in vgs]
    Cm, labels, (vg, khm) = merge_families(fams, cs, [vgs, [wH[:, None] / c for c in cs]])
    reason = np.where(np.isfinite(Cm).any(axis=1), "", REASON_NONE).astype(object)
    pf = np.full(Cm.shape, np.nan)
    rows, cols = np.nonzero(np.isfinite(Cm))
    fam_of = np.array([label_family(lab) for lab in labels[rows, cols]], dtype=object)
    for fam in fams:
        mine = fam_of == fam.prefix
        if mine.any():
            pf[rows[mine], cols[mine]] = mode_fields(b, fam, Cm[rows[mine], cols[mine]], khm[rows[mine], cols[mine]],
                                                     electrical, check=False)["power_flow_angle"]
    return {"power_flow_angle": pf,
            "c": Cm, "mode": labels, "group_velocity": vg, "K2": np.full(Cm.shape, np.nan),
            "c_limit": float(np.sqrt(min(fm.X_limit for fm in fams) * b.sA / b.rho[-1])),
            "attenuation": np.full(Cm.shape, np.nan), "kh": khm,
            "frequency": np.where(np.isfinite(Cm), f[:, None], np.nan), "reason": reason,
            "mode_limit": mode_limits(labels, family_limits(b, fams))}


def _start_grid(b: Blocks, f: np.ndarray, H: float) -> tuple[np.ndarray, np.ndarray]:
    """omega H (m/s) at each frequency, shape (n,), and the kh grid of the starting curves, shape (GRID,)."""
    from surfwave.layers.solve import MAX_KH

    wH = 2 * np.pi * f * H
    c_floor = 10.0 * lowest_speed(b)
    kh_top = min(float(wH.max()) / c_floor * 1.05, MAX_KH)
    if kh_top > MAX_KH * 0.999:
        raise InputError(f"frequency {f.max():.4g} Hz gives kh up to {float(wH.max()) / c_floor:.4g}, beyond "
                         f"{MAX_KH:g}")
    return wH, np.linspace(0.0, kh_top, GRID)


def _family_at_frequency(b: Blocks, fam: Family, wH: np.ndarray, grid: np.ndarray, electrical: str | Boundary,
                         columns: Sequence[int] | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Speeds and group velocities (n, m) of one family's modes at omega H = ``wH`` (m/s), ascending per row.

    Column r is the family's r-th slowest mode at that frequency (its label: :func:`label` (prefix, r)),
    whichever branch it lies on (see the module's docstring). ``columns``: only these ranks are wanted
    (the others stay NaN); they need the branches 0 ... max(columns) alone, each solved on its own
    (the start from the curve on ``grid``, then Newton), so the numbers do not depend on which others
    are solved.
    """
    slowest = columns is not None and list(columns) == [0]             # the scans may stop above it
    cg = family_modes(b, fam, grid, electrical=electrical, lowest=slowest)  # (GRID, n_f)
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    top = cg.shape[1] if columns is None else min(max(columns, default=-1) + 1, cg.shape[1])
    found: list[tuple[np.ndarray, np.ndarray, np.ndarray]] = []       # (rows, c, v) of each branch
    zero = np.flatnonzero(wH == 0)                                   # f = 0: the bare substrate's modes
    live0 = np.array([j for j in range(top) if np.isfinite(cg[0, j])], dtype=int)
    if zero.size and live0.size:
        v0 = mode_fields(b, fam, cg[0, live0], np.zeros(live0.size), electrical)["group_velocity"]
        found.append((np.repeat(zero, live0.size), np.tile(cg[0, live0], zero.size), np.tile(v0, zero.size)))
    for j in range(top):
        ok = np.flatnonzero(np.isfinite(cg[:, j]))                    # kh = 0 too: omega H = 0, slope c
        if ok.size < 2:
            continue
        sol = _branch_crossings(b, fam, j, grid, ok, cg[ok, j], wH, c_lim, electrical, slowest)
        found.append(_polish(b, fam, j, sol, wH, electrical, slowest))
    return _ranked(found, wH.size, columns)


def _branch_crossings(b: Blocks, fam: Family, j: int, grid: np.ndarray, ok: np.ndarray, c: np.ndarray,
                      wH: np.ndarray, c_lim: float, electrical: str | Boundary, slowest: bool) -> dict:
    """Every crossing of branch j (sampled at grid[ok], speeds c) with each omega H (n,): brackets and starts.

    The branch is sampled at the grid and, in each cell, where the cubic Hermite model of omega H(kh)
    has zero slope (:func:`surfwave.layers.crossings.turning_points`; only non-monotone cells have
    such points); a target below the first sample but above c_lim x the grid point before it is the
    cut-off cell's: its bracket [omega H / c_lim, first sample] (the root's kh is above omega H / c_lim,
    the mode being slower than c_lim), its start omega H / c_lim (where the mode is absent, the cut-off's
    omega H is above the target, omega H rising from the cut-off: no crossing, and the start is
    dropped). Returns arrays (r,): ``row``, ``lo``, ``hi``, ``sign_lo`` and ``kh`` (the start), and
    ``grid``.
    """
    kh = grid[ok]
    vg = mode_fields(b, fam, c, kh, electrical, check=False)["group_velocity"]
    keep = ~stray_samples(kh, c * kh, vg)                            # another branch's mode at that kh
    kh, c, vg = kh[keep], c[keep], vg[keep]
    extra = turning_points(kh, c * kh, vg, wH)
    if extra.size:
        ce = _on_grid(b, fam, extra, grid, j, electrical, slowest)
        keep = np.isfinite(ce)
        if keep.any():
            ve = mode_fields(b, fam, ce[keep], extra[keep], electrical, check=False)["group_velocity"]
            order = np.argsort(np.concatenate([kh, extra[keep]]), kind="stable")
            kh = np.concatenate([kh, extra[keep]])[order]
            c = np.concatenate([c, ce[keep]])[order]
            vg = np.concatenate([vg, ve])[order]
    w = c * kh                                                       # omega H along the curve
    row, lo, hi, sign_lo, start = brackets(kh, w, vg, wH)
    below = np.flatnonzero((wH < w[0]) & (wH > c_lim * grid[max(ok[0] - 1, 0)]))
    kc = wH[below] / c_lim
    return {"row": np.concatenate([row, below]), "lo": np.concatenate([lo, kc]),
            "hi": np.concatenate([hi, np.full(below.size, kh[0])]),
            "sign_lo": np.concatenate([sign_lo, -np.ones(below.size)]), "kh": np.concatenate([start, kc]),
            "grid": grid}


def _polish(b: Blocks, fam: Family, j: int, sol: dict, wH: np.ndarray, electrical: str | Boundary,
            slowest: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Newton on every crossing of branch j (``sol`` of :func:`_branch_crossings`); (rows, c, v) of the modes.

    The energy velocity is checked once at the converged modes (surfwave.layers.group_check); where
    the check replaced it (a mode trapped under a barrier), Newton runs again with checked slopes.
    """
    rows = sol["row"]
    it = {"kh": sol["kh"].copy(), "lo": sol["lo"].copy(), "hi": sol["hi"].copy(), "sign_lo": sol["sign_lo"],
          "target": wH[rows], "C": np.full(rows.size, np.nan), "V": np.full(rows.size, np.nan)}
    _newton(b, fam, j, sol["grid"], np.arange(rows.size), it, electrical, slowest, False)
    C, V, kh, target = it["C"], it["V"], it["kh"], it["target"]
    live = np.flatnonzero(np.isfinite(C) & np.isfinite(kh) & (kh > 0))
    if live.size:
        vc = checked_group_velocity(b, fam, C[live], target[live] / C[live], V[live], electrical)
        redo = live[~(vc == V[live])]
        V[live] = vc
        if redo.size:
            _newton(b, fam, j, sol["grid"], redo, it, electrical, slowest, True)
    return rows, it["C"], it["V"]


def _newton(b: Blocks, fam: Family, j: int, grid: np.ndarray, idx: np.ndarray, it: dict,
            electrical: str | Boundary, slowest: bool, check: bool) -> None:
    """Newton steps on c_j(kh) kh = omega H for the crossings ``idx``, kept in their brackets.

    ``it`` holds arrays (r,), one entry per crossing, updated in place: ``kh`` (the next iterate),
    ``lo``, ``hi`` (the bracket), ``sign_lo`` (of c kh - omega H at lo), ``target`` (omega H, m/s),
    ``C``, ``V`` (speed and group velocity, m/s). Each iterate is an exact mode (branch j on the
    start curve's speed grid, :func:`_on_grid`), so the sign of c kh - omega H there narrows the
    bracket; a Newton step that would leave it (near a turning point, where v_g -> 0) is replaced
    by bisection. A kh without the mode drops the crossing (NaN). Each crossing stops when converged
    or after :data:`NEWTON` Newton steps (bisections do not count; at most :data:`BISECT` of them).
    Converged: a Newton step below 1e-11 kh (C is then the last iterate's speed carried along the
    step with dc/dkh = (v_g - c) / kh, its error second order in the step; V the iterate's) or a
    bracket shrunk to rounding (C, V of the last iterate). A crossing left with a residual
    |c kh - omega H| above 1e-9 omega H is dropped (NaN): no mode rather than a wrong one.
    """
    from surfwave.layers.solve import MAX_KH

    kh, lo, hi, sign_lo, target, C, V = (it[q] for q in ("kh", "lo", "hi", "sign_lo", "target", "C", "V"))
    at = np.full(kh.size, np.nan)                                    # kh of C
    steps = np.zeros(kh.size, dtype=int)
    todo = idx
    for _ in range(NEWTON + BISECT):
        live = np.isfinite(kh[todo]) & (kh[todo] >= 0) & (kh[todo] <= MAX_KH)
        kh[todo[~live]] = np.nan
        C[todo[~live]] = np.nan
        todo = todo[live & (steps[todo] < NEWTON)]
        if todo.size == 0:
            break
        k = kh[todo]
        c = _on_grid(b, fam, k, grid, j, electrical, slowest)
        good = np.isfinite(c)
        v = np.full(todo.size, np.nan)
        if good.any():
            v[good] = mode_fields(b, fam, c[good], k[good], electrical, check=check)["group_velocity"]
        C[todo], V[todo], at[todo] = c, v, k
        with np.errstate(all="ignore"):
            g = c * k - target[todo]
            at_lo = good & (np.sign(g) == sign_lo[todo])              # the iterate replaces its sign's end
            lo[todo] = np.where(at_lo, k, lo[todo])
            hi[todo] = np.where(at_lo, hi[todo], k)
            step = g / v
            new = k - step
            small = good & (np.abs(step) <= 1e-11 * np.maximum(new, 1e-300))
            newton = good & np.isfinite(new) & (small | ((new >= lo[todo]) & (new <= hi[todo])))
            # converged: c moved with the last step along the branch (dc/dkh = (v_g - c) / kh), so
            # that c kh = omega H to second order in the step
            C[todo[small]] = c[small] - (v[small] - c[small]) * step[small] / k[small]
        at[todo[small]] = new[small]
        kh[todo] = np.where(newton, new, np.where(good, 0.5 * (lo[todo] + hi[todo]), np.nan))
        steps[todo] += newton
        shut = ~small & (hi[todo] - lo[todo] <= 1e-13 * hi[todo])    # a bracket shrunk to rounding
        todo = todo[~(small | shut)]                                 # done: C, V of this iterate
    with np.errstate(invalid="ignore"):
        off = idx[~(np.abs(C[idx] * at[idx] - target[idx]) <= 1e-9 * target[idx])]
    C[off], V[off] = np.nan, np.nan


def _on_grid(b: Blocks, fam: Family, kh: np.ndarray, grid: np.ndarray, j: int, electrical: str | Boundary,
             slowest: bool) -> np.ndarray:
    """Branch j's speed (m,) at kh (m,), searched on the speed grid of the start curve's scan.

    The speed grid of :func:`surfwave.layers.modes.family_modes` is set by the largest kh of a call;
    the iterates are solved on the start grid's (``grid_kh``), so a mode the start curve holds is
    not lost at an iterate for want of grid points (a heavy film 70 times slower than its substrate
    lost modes on the speed grid of kh ~1.5 alone, and column j was then another branch).
    """
    allc = family_modes(b, fam, kh, electrical=electrical, lowest=slowest, grid_kh=float(grid[-1]))
    return allc[:, j] if allc.shape[1] > j else np.full(kh.size, np.nan)


def _ranked(found: list[tuple[np.ndarray, np.ndarray, np.ndarray]], n: int,
            columns: Sequence[int] | None) -> tuple[np.ndarray, np.ndarray]:
    """The modes (rows, c, v) of all branches as (n, m) arrays, each row ascending in c (NaN-padded).

    A mode found twice (two brackets converging on one root: |dc| <= 1e-10 c) is kept once; with
    ``columns``, ranks beyond max(columns) are dropped (the branches above were not solved).
    """
    if found:
        rows = np.concatenate([f[0] for f in found])
        c = np.concatenate([f[1] for f in found])
        v = np.concatenate([f[2] for f in found])
    else:
        rows, c, v = np.zeros(0, dtype=int), np.zeros(0), np.zeros(0)
    ok = np.isfinite(c)
    rows, c, v = rows[ok], c[ok], v[ok]
    order = np.lexsort((c, rows))
    rows, c, v = rows[order], c[order], v[order]
    dup = np.zeros(rows.size, dtype=bool)
    dup[1:] = (rows[1:] == rows[:-1]) & (np.abs(c[1:] - c[:-1]) <= 1e-10 * c[1:])
    rows, c, v = rows[~dup], c[~dup], v[~dup]
    counts = np.bincount(rows, minlength=n)
    m = int(counts.max(initial=0))
    if columns is not None:
        m = min(m, max(columns, default=-1) + 1)
    C, V = np.full((n, m), np.nan), np.full((n, m), np.nan)
    rank = np.arange(rows.size) - np.concatenate([[0], np.cumsum(counts)[:-1]])[rows]
    keep = rank < m
    C[rows[keep], rank[keep]], V[rows[keep], rank[keep]] = c[keep], v[keep]
    return C, V


def mode_speeds_at_frequency(stack: Stack, frequency, labels, electrical: str | Boundary = "free") -> np.ndarray:
    """Speeds of named guided modes at frequencies (Hz): their families and modes alone.

    The numbers are those of :func:`at_frequency` (and :func:`surfwave.layered` with
    ``frequency``) for the same labels: each branch is solved on its own there too, and the mode of
    rank r lies on one of the branches 0 ... r (module docstring), so the branches above the highest
    rank asked and the other families are simply not solved.

    Parameters
    ----------
    stack : Stack
    frequency : array_like, shape (n,)
        Hz.
    labels : str or sequence of str, length n
        The mode of every point (or one for all): "R", "S1", "L0", "M2", ... (guided modes).
    electrical : {"free", "metallized"} or Boundary

    Returns
    -------
    ndarray, shape (n,)
        Phase speed, m/s; NaN where the mode does not exist (or the stack is unstable).
    """
    from surfwave.layers.modes import label
    from surfwave.layers.solve import unstable_reason, use_fast_path

    f = _frequencies(frequency)
    which = np.broadcast_to(np.asarray(labels, dtype=object), f.shape)
    out = np.full(f.size, np.nan)
    fast = use_fast_path(stack)
    if not fast and unstable_reason(stack):
        return out
    H = stack.total_thickness
    if H == 0 or fast:   # the isotropic path solves every family at once (modes: only up to the highest asked)
        r = _at_frequency(stack, f, electrical=electrical, modes=_max_index(which) + 1 if fast else None)
        for i in range(f.size):
            hit = np.flatnonzero(r["mode"][i] == which[i])
            out[i] = r["c"][i, hit[0]] if hit.size else np.nan
        return out
    b = scaled_blocks(stack)
    wH, grid = _start_grid(b, f, H)
    for fam in families(b):
        cols = sorted({j for j in range(_max_index(which) + 1) if (which == label(fam.prefix, j)).any()})
        if not cols:
            continue
        C, _ = _family_at_frequency(b, fam, wH, grid, electrical, cols)
        for j in cols:
            hit = which == label(fam.prefix, j)
            if j < C.shape[1]:
                out[hit] = C[hit, j]
    return out


def _max_index(labels: np.ndarray) -> int:
    """The largest mode index in labels like "R", "S3", "L0", "M2" (R counts as 0)."""
    top = 0
    for lab in dict.fromkeys(labels.tolist()):
        text = str(lab)
        if text[1:].isdigit():
            top = max(top, int(text[1:]))
    return top
