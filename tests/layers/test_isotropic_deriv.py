"""Exact derivatives of the isotropic secular functions (surfwave.layers.isotropic_deriv) and the group velocity built on them.

References: central finite differences of the secular functions themselves
(surfwave.layers.isotropic.secular_psv / secular_sh) and of the fast path's own phase speeds.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.layers.isotropic import iso_stack, secular_psv, secular_sh
from surfwave.layers.isotropic_deriv import secular_d
from surfwave.layers.stack import resolve_stack

SIO2 = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
HARD = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
HEAVY = {"E": 200.0, "nu": 0.3, "rho": 8000.0}
STACKS = {
    "bare": [],
    "one film": [{**SIO2, "thickness": 1e-6}],
    "two films": [{**SIO2, "thickness": 1e-6}, {**HEAVY, "thickness": 0.4e-6}],
    "three films": [{**HEAVY, "thickness": 0.3e-6}, {**SIO2, "thickness": 1e-6}, {**HEAVY, "thickness": 0.4e-6}],
}


@pytest.mark.parametrize("name", list(STACKS))
def test_derivatives_against_finite_differences(name):
    """F equals secular_psv / secular_sh (1e-13), F_t and F_kh their central differences (step 1e-6), 1e-6
    of the largest, on random points at and between bulk speeds of the films."""
    st = iso_stack(resolve_stack(HARD, STACKS[name]))
    rng = np.random.default_rng(3)
    tau, kh = rng.uniform(0.05, 0.95, 40), rng.uniform(0.1, 30.0, 40)
    h = 1e-6
    for prefix, fun in (("R", secular_psv), ("L", secular_sh)):
        def G(t, k):
            return fun(st, st.c_lim * np.sqrt(1.0 - t * t), k[None, :])[0]
        F, Ft, Fk = secular_d(st, prefix, tau, kh)
        assert np.abs(F - G(tau, kh)).max() <= 1e-13
        dt = (G(tau + h, kh) - G(tau - h, kh)) / (2 * h)
        dk = (G(tau, kh + h) - G(tau, kh - h)) / (2 * h)
        ok = np.abs(Ft - dt) <= 1e-6 * np.abs(dt).max()
        assert ok.sum() >= 38, (prefix, np.abs(Ft - dt).max())     # a kink of the scale g at a bulk speed
        assert np.abs(Fk - dk).max() <= 1e-6 * max(np.abs(dk).max(), 1.0)


def test_group_velocity_of_film_stacks_at_large_kh_by_finite_differences():
    """Two and three films at kh = 25 (where fourth-order differences of F failed): v_g =
    d(c kh)/dkh by central differences (step 1e-5) of the fast path's own speeds, 1e-6."""
    kh = np.array([25.0])
    d = 1e-5
    for films in (STACKS["two films"], STACKS["three films"]):
        r0, rp, rm = (surfwave.layered(HARD, films, kh=kh + s * d) for s in (0.0, 1.0, -1.0))
        assert (r0["mode"] == rp["mode"]).all() and (r0["mode"] == rm["mode"]).all()
        ok = np.isfinite(r0["c"][0])
        fd = (rp["c"][0] * (kh + d) - rm["c"][0] * (kh - d)) / (2 * d)
        assert np.allclose(r0["group_velocity"][0][ok], fd[ok], rtol=1e-6, atol=0)
