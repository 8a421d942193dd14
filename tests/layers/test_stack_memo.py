"""The remembered resolution of materials and layer tensors in :func:`surfwave.layers.stack.resolve_stack`.

Reference: the same resolution with the memo emptied before every call (the uncached route), and
the InputError lines of a fresh resolution.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.layers import stack as stack_mod
from surfwave.layers.stack import resolve_stack

FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}
HALF = {"E": 400.0, "nu": 0.25, "rho": 3500.0}


def _fresh(*args, **kw):
    stack_mod._MATERIALS.clear()
    stack_mod._TENSORS.clear()
    return resolve_stack(*args, **kw)


def _same(a, b) -> bool:
    layers_a, layers_b = [*a.films, a.substrate], [*b.films, b.substrate]
    return len(layers_a) == len(layers_b) and all(
        x.name == y.name and x.rho == y.rho and x.thickness == y.thickness and np.array_equal(x.A, y.A)
        and np.array_equal(x.sigma, y.sigma) for x, y in zip(layers_a, layers_b))


def test_remembered_stack_equals_a_fresh_one_and_follows_changed_values():
    """A second (remembered) resolution equals a fresh one bit for bit; after the caller changes a
    value in the same mapping (E, rho, an integer for a float, a stress) the answer follows the
    new values (the memo is keyed on values, not on the mapping object)."""
    film = dict(FILM)
    ref = _fresh(HALF, [film])
    assert _same(resolve_stack(HALF, [film]), ref)
    film["E"] = 80.0
    assert _same(resolve_stack(HALF, [film]), _fresh(HALF, [film]))
    assert not _same(resolve_stack(HALF, [film]), ref)
    film["rho"] = 2300                                  # an int: a different key, the same kind of answer
    assert resolve_stack(HALF, [film]).films[0].rho == 2300.0
    film["stress"] = -0.5
    assert _same(resolve_stack(HALF, [film]), _fresh(HALF, [film]))


def test_remembered_arrays_are_not_shared_with_the_caller():
    """Writing into one resolved stack's tensors does not change the next resolution."""
    a = resolve_stack(HALF, [FILM])
    keep = a.films[0].A.copy()
    a.films[0].A[...] = 0.0
    assert np.array_equal(resolve_stack(HALF, [FILM]).films[0].A, keep)


def test_refusals_after_a_remembered_success_are_the_same_line():
    """A mapping resolved once, then given an unknown key or a bad value, is refused with the line
    of a fresh resolution (refusals are never remembered)."""
    resolve_stack(HALF, [FILM])
    for bad in ({**FILM, "colour": "red"}, {**FILM, "nu": 0.5}, {**FILM, "thickness": 1.0}):
        with pytest.raises(InputError) as cached:
            resolve_stack(HALF, [bad])
        with pytest.raises(InputError) as fresh:
            _fresh(HALF, [bad])
        assert str(cached.value) == str(fresh.value)


def test_memo_is_bounded():
    """Many different films keep at most MEMO_SIZE entries in each memo."""
    for k in range(stack_mod.MEMO_SIZE + 10):
        resolve_stack(HALF, [{**FILM, "E": 50.0 + k}])
    assert len(stack_mod._MATERIALS) <= stack_mod.MEMO_SIZE
    assert len(stack_mod._TENSORS) <= stack_mod.MEMO_SIZE


def test_named_films_are_remembered_by_name():
    """A film given by ``material`` (or ``name``) is remembered under that name: another name after
    it resolves to its own constants, an unknown one is refused as on a fresh resolution."""
    a = resolve_stack(HALF, [{"material": "fused-SiO2", "thickness": 1e-6}])
    b = resolve_stack(HALF, [{"material": "Al", "thickness": 1e-6}])
    assert _same(a, _fresh(HALF, [{"material": "fused-SiO2", "thickness": 1e-6}]))
    assert _same(b, _fresh(HALF, [{"material": "Al", "thickness": 1e-6}]))
    assert not _same(a, b)
    resolve_stack(HALF, [{"name": "fused-SiO2", "thickness": 1e-6}])
    with pytest.raises(InputError, match="unknown material 'SiO3'"):
        resolve_stack(HALF, [{"material": "SiO3", "thickness": 1e-6}])
