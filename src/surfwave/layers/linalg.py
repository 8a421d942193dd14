"""Batched linear solves that never raise: an exactly singular matrix in a batch gives NaN rows.

``numpy.linalg.solve`` raises ``LinAlgError`` for a whole batch when one of its matrices is exactly
singular (a mode or a pole of a sub-stack can fall exactly on a speed where a layer's matrix must be
inverted). These helpers solve the batch, and where that fails solve each matrix on its own, the
singular ones giving NaN (the callers then report NaN with a reason, or take another route).
"""
from __future__ import annotations

import numpy as np

__all__ = ["safe_solve", "safe_solve_right"]


def safe_solve(A: np.ndarray, B: np.ndarray) -> np.ndarray:
    """A^-1 B for stacks of square matrices A (..., n, n) and B (..., n, r); NaN where A is singular."""
    try:
        return np.linalg.solve(A, B)
    except np.linalg.LinAlgError:
        pass
    shape = np.broadcast_shapes(A.shape[:-2], B.shape[:-2])
    Ab = np.broadcast_to(A, shape + A.shape[-2:]).reshape((-1,) + A.shape[-2:])
    Bb = np.broadcast_to(B, shape + B.shape[-2:]).reshape((-1,) + B.shape[-2:])
    out = np.full(Bb.shape, np.nan, dtype=np.result_type(Ab.dtype, Bb.dtype))
    for i in range(Ab.shape[0]):
        try:
            out[i] = np.linalg.solve(Ab[i], Bb[i])
        except np.linalg.LinAlgError:
            pass
    return out.reshape(shape + B.shape[-2:])


def safe_solve_right(Y: np.ndarray, X: np.ndarray) -> np.ndarray:
    """Y X^-1 for stacks of square matrices; NaN where X is singular."""
    return np.swapaxes(safe_solve(np.swapaxes(X, -1, -2), np.swapaxes(Y, -1, -2)), -1, -2)
