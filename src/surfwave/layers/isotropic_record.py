"""The :func:`surfwave.layered` record of an isotropic stack from the fast path's modes.

:func:`kh_record` (rows = kh) and :func:`frequency_record` (rows = frequencies) give the record of
the general path for the same stack (same keys, column order by speed, labels R, S1, ... and
L0, L1, ..., NaN padding, reasons; K2 and attenuation NaN, power-flow angle 0);
:func:`labelled_speeds` is :func:`surfwave.layers.solve.mode_speeds` for such a stack. The modes
come from :func:`surfwave.layers.isotropic_modes.family_roots`, checked against the exact mode
count where modes can pair up closely (:mod:`surfwave.layers.isotropic_guard`).
"""
from __future__ import annotations

import numpy as np

from surfwave.layers.isotropic import IsoStack, iso_stack
from surfwave.layers.isotropic_guard import check_families
from surfwave.layers.isotropic_modes import Rows, both_families, family_roots
from surfwave.layers.modes import label as mode_label
from surfwave.layers.partial import Family
from surfwave.layers.stack import Stack

__all__ = ["frequency_record", "kh_record", "labelled_speeds"]


def _families(st: IsoStack) -> list[Family]:
    """The two families of an isotropic stack, as the general path names them."""
    X = float(st.mu[-1])
    return [Family(idx=(0, 1), kind="sagittal", prefix="R", X_limit=X),
            Family(idx=(2,), kind="sh", prefix="L", X_limit=X)]


def kh_record(stack: Stack, kh: np.ndarray, modes: int | None = None) -> dict:
    """The :func:`surfwave.layered` record of an eligible stack at checked kh (n,)."""
    from surfwave.layers.solve import REASON_NONE, merge_families

    st = iso_stack(stack)
    rows_of = Rows(kh, freq=False)
    fams = _families(st)
    sols = check_families(stack, st, rows_of, ("R", "L"), both_families(st, rows_of, modes), modes)   # [P-SV, SH]
    C, labels, (vg,) = merge_families(fams, [s[0] for s in sols], [[s[1] for s in sols]])
    finite = np.isfinite(C)
    khm = np.broadcast_to(kh[:, None], C.shape).copy()
    freq = C * khm / (2 * np.pi * st.H) if st.H > 0 else np.full(C.shape, np.nan)
    nan = np.full(C.shape, np.nan)
    return {"c": C, "mode": labels, "group_velocity": vg, "K2": nan, "c_limit": st.c_lim,
            "attenuation": nan.copy(), "kh": khm, "frequency": freq, "reason": _reasons(finite, REASON_NONE),
            "power_flow_angle": np.where(finite, 0.0, np.nan),
            "mode_limit": np.where(finite, st.c_lim, np.nan)}   # both families: the substrate's shear speed


def frequency_record(stack: Stack, f: np.ndarray, modes: int | None = None) -> dict:
    """The :func:`surfwave.layered` record of an eligible stack with films (H > 0) at checked frequencies f (n,), Hz."""
    from surfwave.layers.solve import REASON_NONE, merge_families

    st = iso_stack(stack)
    wH = 2 * np.pi * f * st.H
    rows_of = Rows(wH, freq=True)
    fams = _families(st)
    sols = check_families(stack, st, rows_of, ("R", "L"), both_families(st, rows_of, modes), modes)   # [P-SV, SH]
    C, labels, (vg,) = merge_families(fams, [s[0] for s in sols], [[s[1] for s in sols]])
    finite = np.isfinite(C)
    nan = np.full(C.shape, np.nan)
    return {"power_flow_angle": np.where(finite, 0.0, np.nan), "c": C, "mode": labels, "group_velocity": vg,
            "K2": nan, "c_limit": st.c_lim, "attenuation": nan.copy(), "kh": wH[:, None] / C,
            "frequency": np.where(finite, f[:, None], np.nan), "reason": _reasons(finite, REASON_NONE),
            "mode_limit": np.where(finite, st.c_lim, np.nan)}


def _reasons(finite: np.ndarray, none: str) -> np.ndarray:
    """Per row (n,), object: "" where a mode was found (``finite`` (n, m)), else ``none``."""
    out = np.full(finite.shape[0], "", dtype=object)
    out[~finite.any(axis=1)] = none
    return out


def labelled_speeds(stack: Stack, kh: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Speeds (n,) of the guided mode named at each kh (n,) ("R", "S2", "L0", ...; NaN where absent or unknown)."""
    st = iso_stack(stack)
    out = np.full(kh.size, np.nan)
    for prefix, first in (("R", ("R", "S")), ("L", ("L",))):
        idx = np.array([_index(str(lab), first) for lab in labels])
        if not (idx >= 0).any():
            continue
        rows_of, n = Rows(kh, freq=False), int(idx.max()) + 1
        c, _ = check_families(stack, st, rows_of, (prefix,), [family_roots(st, prefix, rows_of, n)], n)[0]
        hit = np.flatnonzero((idx >= 0) & (idx < c.shape[1]))
        out[hit] = c[hit, idx[hit]]
    return out


def _index(label: str, first: tuple[str, ...]) -> int:
    """Column of a guided mode's label within its family (-1: another family, leaky or malformed)."""
    if label == "R" and "R" in first:
        return 0
    head, tail = label[:1], label[1:]
    if head in first and head != "R" and tail.isdigit() and label == mode_label(first[0], int(tail)):
        return int(tail)
    return -1
