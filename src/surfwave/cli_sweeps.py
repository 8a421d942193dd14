"""The command line's values and sweeps: ``--angle``, ``--euler`` and ``--stress`` (one parser), and the
stress sweep's table.

A value is a number ("15", "-0.1") or a sweep START:STOP:STEP (STOP included). Every sweep is
checked before any array is made: numbers only, finite, within the option's bound (angles:
:data:`surfwave.validate.MAX_ANGLE` degrees; stress: :data:`MAX_GPA`), STEP > 0, STOP >= START,
and at most :data:`surfwave.pipeline.grids.MAX_POINTS` points (``0:1e9:1`` would fill the
memory, ``0:360:1e-20`` asks for 3.6e22 points). Each refusal is one line naming the option and
the text given.

Examples
--------
>>> sweep("0:90:30", "--angle").tolist()
[0.0, 30.0, 60.0, 90.0]
>>> sweep("-0.1", "--stress", kind="stress").tolist()
[-0.1]
>>> sweep("0:nan:1", "--euler")
Traceback (most recent call last):
...
surfwave.errors.InputError: --euler must be finite numbers of degrees, got nan in '0:nan:1'
"""
from __future__ import annotations

from collections.abc import Callable
from typing import Literal

import numpy as np

from surfwave.errors import InputError

#: Largest |stress| in GPa on the command line (as :data:`surfwave.api.MAX_GPA`): beyond it the
#: value is almost surely in Pa.
MAX_GPA = 1.0e5

Kind = Literal["angle", "stress"]
_UNIT = {"angle": "degrees", "stress": "GPa"}
_NOUN = {"angle": "angles", "stress": "stresses"}


def _numbers(text: str, option: str, kind: Kind) -> list[float]:
    parts = str(text).split(":")
    try:
        values = [float(v) for v in parts]
    except ValueError:
        raise InputError(f"{option} must be a number or START:STOP:STEP in {_UNIT[kind]}, got {text!r}") from None
    bad = [v for v in values if not np.isfinite(v)]
    if bad:
        raise InputError(f"{option} must be finite numbers of {_UNIT[kind]}, got {bad[0]!r} in {text!r}")
    return values


def _check_bound(values: list[float], text: str, option: str, kind: Kind) -> None:
    from surfwave.validate import MAX_ANGLE, huge_angle_error

    if kind == "angle":
        big = [v for v in values[:2] if abs(v) > MAX_ANGLE]
        if big:
            raise huge_angle_error(f"{option} {big[0]!r}", f" (got {text!r})")
    else:
        big = [v for v in values[:2] if abs(v) > MAX_GPA]
        if big:
            raise InputError(f"{option} {big[0]!r} GPa lies beyond {MAX_GPA:g} GPa: it looks like Pa (divide by "
                             f"1e9: {big[0] / 1e9:g} GPa; got {text!r})")


def sweep(text: str, option: str, kind: Kind = "angle") -> np.ndarray:
    """One value or a sweep START:STOP:STEP (STOP included) as a float array of shape (n,).

    Parameters
    ----------
    text : str
        "15" or "0:90:5" (a sweep's values are START + i STEP, i = 0, 1, ...).
    option : str
        The option's name, for the message ("--angle").
    kind : {"angle", "stress"}
        Degrees (bounded by :data:`surfwave.validate.MAX_ANGLE`) or GPa (bounded by :data:`MAX_GPA`).

    Raises
    ------
    InputError
        One line naming ``option`` and ``text``: not numbers, not finite, beyond the bound,
        not START:STOP:STEP with STEP > 0 and STOP >= START, more than
        :data:`surfwave.pipeline.grids.MAX_POINTS` points.
    """
    from surfwave.pipeline.grids import MAX_POINTS

    values = _numbers(text, option, kind)
    _check_bound(values, text, option, kind)
    if len(values) == 1:
        return np.array(values)
    if len(values) != 3 or values[2] <= 0 or values[1] < values[0]:
        raise InputError(f"{option} sweep must be START:STOP:STEP with STEP > 0 and STOP >= START, got {text!r}")
    start, stop, step = values
    with np.errstate(over="ignore"):
        n = np.floor((stop - start) / step + 1e-9) + 1
    if not n <= MAX_POINTS:  # before any array is made (also catches an overflow to inf)
        raise InputError(f"{option} sweep {text!r} has {n:.4g} {_NOUN[kind]}, more than the limit of {MAX_POINTS}; "
                         "use a larger STEP or a shorter range")
    values_n = start + step * np.arange(int(n))
    if values_n.size > 1 and np.any(np.diff(values_n) <= 0):  # STEP below the float spacing of START
        raise InputError(f"{option} sweep {text!r}: STEP {step!r} is below the precision of START {start!r} "
                         "(the values would repeat); use a larger STEP")
    return values_n


def stress_values(tokens: list[str], option: str = "--stress") -> tuple[float | np.ndarray, np.ndarray | None]:
    """``--stress`` tokens -> (the stress for one call, or None-like 0.0; the sweep's values or None).

    One number: uniaxial stress along the propagation; nine numbers: the Cauchy tensor in
    crystal axes (row by row); any other count of numbers (``-0.1 0 0.1``), or one sweep
    START:STOP:STEP: a sweep of uniaxial stresses (returned as the second item).

    Returns
    -------
    stress : float or ndarray, shape (3, 3)
        The stress of a single call (0.0 for a sweep: the caller takes each value in turn).
    values : ndarray, shape (n,), or None
        The swept stresses in GPa, sorted as given; None without a sweep.

    Examples
    --------
    >>> stress_values(["0.1"])
    (0.1, None)
    >>> stress_values(["-0.1", "0", "0.1"])[1].tolist()
    [-0.1, 0.0, 0.1]
    >>> stress_values(["-0.2:0.2:0.2"])[1].tolist()
    [-0.2, 0.0, 0.2]
    """
    from surfwave.pipeline.grids import MAX_POINTS

    if len(tokens) == 1:
        values = sweep(tokens[0], option, "stress")
        return (float(values[0]), None) if ":" not in tokens[0] else (0.0, values)
    if any(":" in t for t in tokens):
        raise InputError(f"{option} takes one value, nine (the stress tensor), a list of values or one sweep "
                         f"START:STOP:STEP, not a sweep among other values: {' '.join(tokens)}")
    if len(tokens) > MAX_POINTS:
        raise InputError(f"{option} has {len(tokens)} values, more than the limit of {MAX_POINTS}")
    values = np.concatenate([sweep(t, option, "stress") for t in tokens])
    if len(tokens) == 9:
        return values.reshape(3, 3), None
    return 0.0, values


def run_stress_sweep(call: Callable[[float], dict], stresses: np.ndarray, as_json: bool, title: str,
                     rows_of: Callable[[dict], list[dict]],
                     tables: dict[bool, Callable[[list[dict], str, list[str]], None]]) -> int:
    """Run ``call(stress)`` (a :func:`surfwave.material` with everything else fixed) for each stress
    and print one table line per stress (or a JSON list of the result rows, each with ``stress``).

    Parameters
    ----------
    call : callable
        stress (float, GPa) -> the dict of :func:`surfwave.material` for one orientation.
    stresses : ndarray, shape (n,)
        Uniaxial stresses along the propagation, GPa.
    as_json : bool
        Print JSON instead of a table.
    title : str
        The table's first line (what is fixed), without the leading "# ".
    rows_of : callable
        A result -> its JSON-ready rows (the CLI's, so that the sweep prints what one call prints).
    tables : dict
        Piezoelectric result (True) or not -> the CLI's sweep table printer ``(rows, label, first
        column texts)``: the stress sweep has the columns of an angle sweep.
    """
    import json

    rows = []
    for s in stresses:
        row = rows_of(call(float(s)))[0]
        rows.append({"stress": float(s), **row})
    if as_json:
        print(json.dumps(rows, indent=2))
        return 0
    print(f"# {title}; stress sweep (uniaxial along the propagation, GPa)")
    tables["K2" in rows[0]](rows, "stress", [f"{r['stress']:g}" for r in rows])
    return 0
