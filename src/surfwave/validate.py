"""The one validator for array arguments of the library (strains, angles, theta, stresses).

Examples
--------
>>> as_1d(0.95).tolist(), as_1d([0.9, 1.0]).tolist()
([0.95], [0.9, 1.0])
>>> as_1d([[1.0]], "theta")
Traceback (most recent call last):
...
surfwave.errors.InputError: theta must be a scalar or a 1-D array, got shape (1, 1)
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError


def as_1d(values, name: str = "d_over_d0", *, finite: bool = True) -> np.ndarray:
    """``values`` (scalar or 1-D) as a float array of shape (n,).

    Parameters
    ----------
    values : float or array_like, shape (n,)
    name : str
        The argument's name, for the error message.
    finite : bool
        Refuse NaN and infinities (default). ``False`` where the function's contract is
        per point: a non-finite entry gives a NaN result with its reason, the others are
        computed.

    Raises
    ------
    InputError
        Naming ``name``: for more than one dimension, for values that are not numbers, and
        (``finite``) for NaN or infinite entries.
    """
    try:
        a = np.atleast_1d(np.asarray(values, dtype=float))
    except (TypeError, ValueError) as exc:
        raise InputError(f"{name} must be numbers, got {values!r} ({exc})") from None
    if a.ndim != 1:
        raise InputError(f"{name} must be a scalar or a 1-D array, got shape {a.shape}")
    if finite and not np.all(np.isfinite(a)):
        raise InputError(f"{name} must be finite, got {a[~np.isfinite(a)][:5]}")
    return a
