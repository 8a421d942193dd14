"""The first scan's hidden-pair hunt evaluated with Newton's first round changes no answer.

With one film, :func:`surfwave.layers.isotropic_modes.both_families` evaluates the first step of
:func:`surfwave.layers.isotropic_scan._hidden_pairs` in the same call as Newton's first round and
keeps the brackets of the scan where :func:`surfwave.layers.isotropic_hunt.hunt_settles` says the
hunt finds nothing. Reference: the same call with the hunt run inside the scan as before (the
fold switched off by dropping the ``pending`` lists), on seeded random one-film stacks (``modes``
given: only then is the hunt folded) whose hunts both stop after one step and go on; speeds, group
velocities and counts must agree bit for bit.
"""
from __future__ import annotations

from typing import Any

import numpy as np
import pytest

import surfwave.layers.isotropic_modes as im
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.stack import resolve_stack


def _mat(rng: np.random.Generator) -> dict:
    return {"E": float(10 ** rng.uniform(0, 2.9)), "nu": float(rng.uniform(-0.4, 0.49)),
            "rho": float(10 ** rng.uniform(2.8, 4.35))}


def test_folded_hunt_changes_nothing(monkeypatch: pytest.MonkeyPatch) -> None:
    """20 seeded random one-film stacks, rows in kh and in frequency, modes 1 / 2 / 3: both_families
    with the fold equals both_families with the hunt inside the scan (bit for bit); the sample holds
    hunts the fold keeps and hunts it hands back (so both routes are exercised). (hunt_settles made to
    accept every hunt fails here: a pair the hunt finds at its first step is lost.)"""
    rng = np.random.default_rng(1)
    verdicts: list[bool] = []
    settles = im.hunt_settles

    def spy(*a: np.ndarray) -> bool:
        verdicts.append(settles(*a))
        return verdicts[-1]

    folded = im._brackets_both

    def unfolded(*a: Any, pending: Any = None, **k: Any) -> Any:
        return folded(*a, **k)                                         # the hunt inside the scan

    for _ in range(20):
        sub, film = _mat(rng), {**_mat(rng), "thickness": 1e-6}
        st = iso_stack(resolve_stack(sub, [film]))
        n = int(rng.integers(20, 120))
        modes = int(rng.integers(1, 4))
        for freq in (False, True):
            x = np.linspace(0.01, 1, n) * float(rng.uniform(1, 100))
            if freq:
                x = x * float(st.shear[0])                            # 2 pi f H, m/s
            rows_of = im.Rows(x, freq)
            with monkeypatch.context() as m:
                m.setattr(im, "hunt_settles", spy)
                got = im.both_families(st, rows_of, modes)
            with monkeypatch.context() as m:
                m.setattr(im, "_brackets_both", unfolded)
                ref = im.both_families(st, rows_of, modes)
            for (c, v), (c0, v0) in zip(got, ref):
                assert c.shape == c0.shape
                np.testing.assert_array_equal(c, c0)
                np.testing.assert_array_equal(v, v0)
    assert any(verdicts) and not all(verdicts)
