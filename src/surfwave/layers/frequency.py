"""Modes of a stack at given frequencies: each mode at its own kh = 2 pi f H / c.

At a fixed frequency f the modes of a stack of total film thickness H have different
wavenumbers. For each family and mode index j the dispersion curve is first computed on a kh grid
(:func:`surfwave.layers.modes.family_modes`), omega(kh) H = c_j(kh) kh is interpolated to give a
start, and Newton's method on g(kh) = c_j(kh) kh - 2 pi f H with the exact slope
dg/dkh = v_g (the group velocity, :func:`surfwave.layers.fields.mode_fields`) polishes it;
every iterate is an exact mode of the stack, so the residual 2 pi f H - c kh measures the error.
"""
from __future__ import annotations

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.layers.fields import mode_fields
from surfwave.layers.modes import family_modes, lowest_speed
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import Stack

__all__ = ["at_frequency"]

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


def at_frequency(stack: Stack, frequency, *, electrical: str = "free", leaky: bool = False) -> dict:
    """The :func:`surfwave.layered` record at frequencies (Hz) instead of kh (same keys, rows = frequencies)."""
    from surfwave.layers.solve import MAX_KH, REASON_NONE, _empty, _merge, assemble, unstable_reason

    f = _frequencies(frequency)
    why = unstable_reason(stack)
    if why:
        return _empty(f, np.nan, why)
    H = stack.total_thickness
    if H == 0:
        out = assemble(stack, np.zeros(f.size), electrical, leaky)
        out["frequency"] = np.broadcast_to(f[:, None], out["c"].shape).copy()
        return out
    if leaky:
        raise InputError("leaky=True is available with kh, not with frequency")
    b = scaled_blocks(stack)
    fams = families(b)
    wH = 2 * np.pi * f * H
    c_floor = 10.0 * lowest_speed(b)
    kh_top = min(float(wH.max()) / c_floor * 1.05, MAX_KH)
    if kh_top > MAX_KH * 0.999:
        raise InputError(f"frequency {f.max():.4g} Hz gives kh up to {float(wH.max()) / c_floor:.4g}, beyond "
                         f"{MAX_KH:g}")
    grid = np.linspace(0.0, kh_top, GRID)
    cs, vgs = [], []
    for fam in fams:
        cg = family_modes(b, fam, grid, electrical=electrical)           # (GRID, n_f)
        C = np.full((f.size, cg.shape[1]), np.nan)
        V = np.full(C.shape, np.nan)
        for j in range(cg.shape[1]):
            w = cg[:, j] * grid                                          # omega H along the curve
            ok = np.isfinite(w)
            if ok.sum() < 2:
                continue
            inside = (wH >= w[ok].min()) & (wH <= w[ok].max())
            kh = np.where(inside, np.interp(wH, w[ok], grid[ok]), np.nan)
            rows = np.flatnonzero(inside)
            for _ in range(NEWTON):
                live = np.isfinite(kh[rows]) & (kh[rows] >= 0) & (kh[rows] <= MAX_KH)
                kh[rows[~live]] = np.nan
                C[rows[~live], j] = np.nan
                rows = rows[live]
                if rows.size == 0:
                    break
                allc = family_modes(b, fam, kh[rows], electrical=electrical)
                c = allc[:, j] if allc.shape[1] > j else np.full(rows.size, np.nan)
                good = np.isfinite(c)
                v = np.full(rows.size, np.nan)
                if good.any():
                    v[good] = mode_fields(b, fam, c[good], kh[rows][good], electrical)["group_velocity"]
                C[rows, j], V[rows, j] = c, v
                step = (c * kh[rows] - wH[rows]) / v
                kh[rows] = np.where(good, kh[rows] - step, np.nan)
                if np.all(np.abs(step[good]) <= 1e-13 * np.maximum(kh[rows][good], 1e-300)):
                    break
        cs.append(C)
        vgs.append(V)
    Cm, labels, (vg, khm) = _merge(fams, cs, [vgs, [wH[:, None] / c for c in cs]])
    reason = np.where(np.isfinite(Cm).any(axis=1), "", REASON_NONE).astype(object)
    return {"c": Cm, "mode": labels, "group_velocity": vg, "K2": np.full(Cm.shape, np.nan),
            "c_limit": float(np.sqrt(min(fm.X_limit for fm in fams) * b.sA / b.rho[-1])),
            "attenuation": np.full(Cm.shape, np.nan), "kh": khm,
            "frequency": np.where(np.isfinite(Cm), f[:, None], np.nan), "reason": reason}
