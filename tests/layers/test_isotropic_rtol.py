"""The accuracy keyword ``rtol`` of surfwave.layered (the refinement of surfwave.layers.isotropic_modes).

Reference: the default-accuracy answer of the same call (speeds to about 1e-13, the isotropic path's
own checks against the general solver and closed forms are in test_isotropic_fast.py). A looser
``rtol`` may stop the refinement earlier; the answer must stay within ``rtol`` of that reference,
with the same modes and labels.
"""
from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest
from general_path import layered_general

import surfwave
from surfwave.errors import InputError

SIO2 = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
HARD = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
GOLD = {"E": 79.0, "nu": 0.42, "rho": 19300.0}
ALN_ISO = {"E": 300.0, "nu": 0.22, "rho": 3200.0}
SI_ISO = {"E": 170.0, "nu": 0.28, "rho": 2330.0}

CASES: dict[str, tuple[dict, list[dict], dict[str, Any]]] = {
    # the disba comparison's stack at its 200 periods (modes of both families, fixed frequency)
    "film on half-space, frequencies": (HARD, [{**SIO2, "thickness": 1e-6}],
                                        {"frequency": 1e9 / np.linspace(0.05, 2.0, 200)}),
    # two films (many modes, near-crossings of modes living in different films), fixed kh
    "two films, kh": (SI_ISO, [{**GOLD, "thickness": 0.3e-6}, {**ALN_ISO, "thickness": 0.7e-6}],
                      {"kh": np.linspace(0.2, 30.0, 60)}),
}


@pytest.mark.parametrize("rtol", [1e-6, 1e-9])
@pytest.mark.parametrize("name", list(CASES))
def test_answer_within_rtol_of_the_default(name, rtol):
    """Speeds and group velocities within ``rtol`` (relative) of the default-accuracy answer; the same
    modes and labels (reference: the same call without ``rtol``)."""
    sub, films, kw = CASES[name]
    ref = surfwave.layered(sub, films, **kw)
    got = surfwave.layered(sub, films, rtol=rtol, **kw)
    assert got["mode"].shape == ref["mode"].shape and (got["mode"] == ref["mode"]).all()
    ok = np.isfinite(ref["c"])
    assert ok.sum() > 300 and (np.isfinite(got["c"]) == ok).all()
    for key in ("c", "group_velocity"):
        rel = np.abs(got[key][ok] / ref[key][ok] - 1.0)
        assert rel.max() <= rtol, (key, rel.max())


def test_default_is_rtol_none():
    """``rtol=None`` is the default call, bit for bit (reference: the call without the keyword)."""
    sub, films, kw = CASES["film on half-space, frequencies"]
    a = surfwave.layered(sub, films, **kw)
    b = surfwave.layered(sub, films, rtol=None, **kw)
    for key in ("c", "group_velocity"):
        np.testing.assert_array_equal(a[key], b[key])


def test_general_path_accepts_rtol_and_keeps_its_accuracy():
    """The general (Stroh) path solves at its own fixed accuracy whatever ``rtol`` asks (documented):
    the same numbers with and without it (reference: the general path's default call)."""
    films = [{**SIO2, "thickness": 1e-6}]
    a = layered_general(HARD, films, kh=[0.5, 3.0])
    b = layered_general(HARD, films, kh=[0.5, 3.0], rtol=1e-4)
    for key in ("c", "group_velocity"):
        np.testing.assert_array_equal(a[key], b[key])


@pytest.mark.parametrize("bad", [0, 0.0, -1e-6, 0.1, 1.0, float("nan"), float("inf"), 1e-14, "1e-6", True,
                                 [1e-6], np.array([1e-6]), 1j])
def test_bad_rtol_is_one_input_error_line(bad):
    """Non-numbers, non-finite values and values outside [1e-13, 0.1): one InputError line, before any
    computation."""
    with pytest.raises(InputError, match=r"rtol must be a number in \[1e-13, 0.1\)") as err:
        surfwave.layered(HARD, [{**SIO2, "thickness": 1e-6}], kh=[1.0], rtol=bad)
    assert "\n" not in str(err.value)


def test_cli_rtol(capsys):
    """``surfwave layered --rtol``: the record of surfwave.layered(..., rtol=...) (reference: the API call);
    a bad value is one error line (exit 2)."""
    from surfwave.cli import main

    argv = ["layered", "--substrate", "fused-SiO2", "--film", "Au-poly:100nm", "--kh", "0.5", "2", "--json"]
    assert main([*argv, "--rtol", "1e-6"]) == 0
    got = json.loads(capsys.readouterr().out)
    ref = surfwave.layered("fused-SiO2", [{"name": "Au-poly", "thickness": 1e-7}], kh=[0.5, 2.0], rtol=1e-6)
    np.testing.assert_array_equal(np.array(got["c"], dtype=float), ref["c"])
    assert main([*argv, "--rtol", "0"]) == 2
    err = capsys.readouterr().err.strip()
    assert "rtol must be a number" in err and "\n" not in err
