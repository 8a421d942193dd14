"""Modes of a stack at given frequencies: each mode at its own kh = 2 pi f H / c.

At a fixed frequency f the modes of a stack of total film thickness H have different
wavenumbers. For each family and mode index j the dispersion curve is first computed on a kh grid
(:func:`surfwave.layers.modes.family_modes`) with its group velocity; omega(kh) H = c_j(kh) kh
(monotone, slope v_g) is inverted by cubic Hermite interpolation to give a start (kh = omega H /
c_lim below the curve's first grid point, near the mode's cut-off), and Newton's method on
g(kh) = c_j(kh) kh - 2 pi f H with the exact slope dg/dkh = v_g (the group velocity,
:func:`surfwave.layers.fields.mode_fields`) polishes it;
every iterate is an exact mode of the stack, so the residual 2 pi f H - c kh measures the error.
"""
from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.layers.fields import mode_fields
from surfwave.layers.group_check import checked_group_velocity
from surfwave.layers.modes import family_modes, label_family, lowest_speed
from surfwave.layers.partial import Blocks, Family, families, scaled_blocks
from surfwave.layers.stack import Stack
from surfwave.solvers.boundary import Boundary

__all__ = ["at_frequency", "mode_speeds_at_frequency"]

#: Points of the kh grid of the starting curves.
GRID = 160
#: Newton steps at most.
NEWTON = 8


def _frequencies(frequency) -> np.ndarray:
    f = validate.real_array(frequency, "frequency").reshape(-1)
    if not np.all(np.isfinite(f)) or np.any(f < 0):
        raise InputError(f"frequency must be finite and >= 0 (Hz), got {frequency!r}")
    if np.any(f > 1e13):
        raise InputError(f"frequency {f.max():.4g} Hz is beyond any acoustic wave (is it in Hz?)")
    return f


def _hermite_inverse(w: np.ndarray, kh: np.ndarray, slope: np.ndarray, target: np.ndarray) -> np.ndarray:
    """kh at omega H = target on the curve (w ascending, kh) with dw/dkh = slope: cubic Hermite in w; NaN outside."""
    out = np.full(target.size, np.nan)
    i = np.searchsorted(w, target, side="right") - 1
    inside = (i >= 0) & (i < w.size - 1)
    exact = target == w[-1]
    i = i[inside]
    h = w[i + 1] - w[i]
    s = (target[inside] - w[i]) / h
    d0, d1 = h / slope[i], h / slope[i + 1]
    h00, h10, h01, h11 = 2 * s**3 - 3 * s**2 + 1, s**3 - 2 * s**2 + s, -2 * s**3 + 3 * s**2, s**3 - s**2
    out[inside] = h00 * kh[i] + h10 * d0 + h01 * kh[i + 1] + h11 * d1
    out[exact] = kh[-1]
    return out


def at_frequency(stack: Stack, frequency, *, electrical: str | Boundary = "free", leaky: bool = False,
                 modes: int | None = None) -> dict:
    """The :func:`surfwave.layered` record at frequencies (Hz) instead of kh (same keys, rows = frequencies).

    K^2 of a piezoelectric stack compares the free and metallized speeds of the same mode label at
    the same frequency. ``modes``: at most that many modes per family (None: all).
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
    """Speeds and group velocities (n, n_f) of one family's modes at omega H = ``wH`` (m/s).

    ``columns``: only these mode indices of the family (the others stay NaN); each mode is solved
    on its own (the start from the curve on ``grid``, then Newton), so the numbers do not depend
    on which others are solved.
    """
    slowest = columns is not None and list(columns) == [0]             # the scans may stop above it
    cg = family_modes(b, fam, grid, electrical=electrical, lowest=slowest)  # (GRID, n_f)
    C = np.full((wH.size, cg.shape[1]), np.nan)
    V = np.full(C.shape, np.nan)
    c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
    wanted = list(range(cg.shape[1])) if columns is None else [j for j in columns if j < cg.shape[1]]
    zero = np.flatnonzero(wH == 0)                                   # f = 0: the bare substrate's modes
    live0 = np.array([j for j in wanted if np.isfinite(cg[0, j])], dtype=int)
    if zero.size and live0.size:
        C[np.ix_(zero, live0)] = cg[0, live0]
        V[np.ix_(zero, live0)] = mode_fields(b, fam, cg[0, live0], np.zeros(live0.size), electrical)["group_velocity"]
    for j in wanted:
        ok = np.flatnonzero(np.isfinite(cg[:, j]) & (grid > 0))
        if ok.size < 2:
            continue
        vg_grid = mode_fields(b, fam, cg[ok, j], grid[ok], electrical, check=False)["group_velocity"]
        w = cg[ok, j] * grid[ok]                                     # omega H along the curve
        kh = _hermite_inverse(w, grid[ok], vg_grid, wH)
        # between the last grid point without the mode and the first with it: the cut-off is
        # there (c = c_lim at cut-off), so start at kh = omega H / c_lim
        below = (wH < w[0]) & (wH > c_lim * grid[max(ok[0] - 1, 0)])
        kh[below] = wH[below] / c_lim
        rows = np.flatnonzero(np.isfinite(kh))
        _newton(b, fam, j, kh, rows, wH, C, V, electrical, slowest, check=False)
        # the energy velocity checked once at the converged modes (surfwave.layers.group_check);
        # where the check replaced it (a mode trapped under a barrier), Newton again with checked slopes
        rows = np.flatnonzero(np.isfinite(C[:, j]) & np.isfinite(kh) & (kh > 0))
        if rows.size:
            vc = checked_group_velocity(b, fam, C[rows, j], wH[rows] / C[rows, j], V[rows, j], electrical)
            redo = rows[~(vc == V[rows, j])]
            V[rows, j] = vc
            if redo.size:
                _newton(b, fam, j, kh, redo, wH, C, V, electrical, slowest, check=True)
    return C, V


def _newton(b: Blocks, fam: Family, j: int, kh: np.ndarray, rows: np.ndarray, wH: np.ndarray, C: np.ndarray,
            V: np.ndarray, electrical: str | Boundary, slowest: bool, check: bool) -> None:
    """Newton steps on c_j(kh) kh = omega H for mode j at ``rows``, updating kh (n,), C and V (n, n_f) in place."""
    from surfwave.layers.solve import MAX_KH

    for _ in range(NEWTON):
        live = np.isfinite(kh[rows]) & (kh[rows] >= 0) & (kh[rows] <= MAX_KH)
        kh[rows[~live]] = np.nan
        C[rows[~live], j] = np.nan
        rows = rows[live]
        if rows.size == 0:
            break
        allc = family_modes(b, fam, kh[rows], electrical=electrical, lowest=slowest)
        c = allc[:, j] if allc.shape[1] > j else np.full(rows.size, np.nan)
        good = np.isfinite(c)
        v = np.full(rows.size, np.nan)
        if good.any():
            v[good] = mode_fields(b, fam, c[good], kh[rows][good], electrical,
                                 check=check)["group_velocity"]
        C[rows, j], V[rows, j] = c, v
        step = (c * kh[rows] - wH[rows]) / v
        kh[rows] = np.where(good, kh[rows] - step, np.nan)
        if np.all(np.abs(step[good]) <= 1e-11 * np.maximum(kh[rows][good], 1e-300)):
            break


def mode_speeds_at_frequency(stack: Stack, frequency, labels, electrical: str | Boundary = "free") -> np.ndarray:
    """Speeds of named guided modes at frequencies (Hz): their families and modes alone.

    The numbers are those of :func:`at_frequency` (and :func:`surfwave.layered` with
    ``frequency``) for the same labels: each mode is solved on its own there too, so the modes
    a fit does not measure (other families, other mode indices) are simply not solved.

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
