"""The exact fast path for isotropic, unstressed stacks (surfwave.layers.isotropic, isotropic_modes).

References: the general Stroh/impedance solver of surfwave.layers (forced with
``solve.FAST_ISOTROPIC = False``), the closed-form Love equation, the Rayleigh equation of a
half-space, and a direct product of 4 x 4 matrix exponentials (scipy.linalg.expm) of the P-SV ODE.
"""
from __future__ import annotations

import numpy as np
import pytest
import scipy.linalg as sl
from scipy.optimize import brentq

import surfwave
import surfwave.layers.solve as solve
from surfwave.errors import InputError
from surfwave.layers.isotropic import (
    _c2,
    eligible,
    is_isotropic,
    iso_stack,
    psv_kernels,
    secular_psv,
    top_row,
    wave_functions,
)
from surfwave.layers.stack import isotropic_voigt, resolve_stack

SIO2 = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
HARD = {"E": 400.0, "nu": 0.25, "rho": 3500.0}
SI_ISO = {"E": 170.0, "nu": 0.28, "rho": 2330.0}
DIAMOND = {"E": 1050.0, "nu": 0.1, "rho": 3500.0}
ALN_ISO = {"E": 300.0, "nu": 0.22, "rho": 3200.0}
GOLD = {"E": 79.0, "nu": 0.42, "rho": 19300.0}

STACKS = {
    "slow film on fast substrate": (HARD, [{**SIO2, "thickness": 1e-6}]),
    "fast film on slow substrate (R leaves)": (SIO2, [{**DIAMOND, "thickness": 1e-6}]),
    "three films": (SI_ISO, [{**GOLD, "thickness": 0.2e-6}, {**SIO2, "thickness": 0.5e-6},
                             {**ALN_ISO, "thickness": 0.3e-6}]),
    "zero-thickness film": (SI_ISO, [{**SIO2, "thickness": 1e-6}, {**ALN_ISO, "thickness": 0.0}]),
    "film nearly the substrate": (SI_ISO, [{"E": 169.0, "nu": 0.28, "rho": 2331.0, "thickness": 1e-6}]),
}
KH = np.array([0.0, 1e-6, 0.05, 0.5, 1.5, 4.0, 12.0, 40.0, 100.0])
FREQ = np.array([0.0, 1e5, 1e8, 6e8, 2e9, 5e9])


def _both(sub, films, **kw):
    try:
        solve.FAST_ISOTROPIC = True
        fast = surfwave.layered(sub, films, **kw)
        solve.FAST_ISOTROPIC = False
        general = surfwave.layered(sub, films, **kw)
    finally:
        solve.FAST_ISOTROPIC = True
    return fast, general


def _speeds(m: dict) -> tuple[float, float, float]:
    """Longitudinal and shear speeds (m/s) and mu (Pa) of an {E, nu, rho} solid."""
    C = isotropic_voigt(m["E"], m["nu"]) * 1e9
    return float(np.sqrt(C[0, 0] / m["rho"])), float(np.sqrt(C[3, 3] / m["rho"])), float(C[3, 3])


def _rayleigh(m: dict) -> float:
    """The Rayleigh speed of an isotropic half-space: root of (2 - x)^2 = 4 sqrt(1 - x) sqrt(1 - x b^2/a^2)."""
    a, b, _ = _speeds(m)
    x = brentq(lambda x: (2 - x) ** 2 - 4 * np.sqrt((1 - x) * (1 - x * b * b / (a * a))), 0.5, 1.0, xtol=1e-16)
    return b * np.sqrt(x)


def test_compound_propagator_equals_the_second_compound_of_expm():
    """K0 + C_a C_b K1 + ... equals C2(expm(-A t)) (scipy.linalg.expm, definition of the compound), below,
    at and above both bulk speeds (X = mu and X = lam + 2 mu: no 0/0); the closed-form top row equals
    the NT row of the kernels."""
    lam, mu = 0.3, 0.5
    M = lam + 2 * mu
    for X in (0.2, 0.6, mu, 0.9, M, 1.5):
        A = np.array([[0, 1, 0, 1 / mu], [-lam / M, 0, 1 / M, 0], [0, -X, 0, -1],
                      [4 * mu * (lam + mu) / M - X, 0, lam / M, 0]])
        K = psv_kernels(lam, mu, np.array([X]))[0]
        for t in (0.0, 0.3, 3.0):
            Ca, Sa, ga = wave_functions(np.array(1 - X / M), np.array(t))
            Cb, Sb, gb = wave_functions(np.array(1 - X / mu), np.array(t))
            got = (ga * gb * K[0] + Ca * Cb * K[1] + Ca * Sb * K[2] + Sa * Cb * K[3] + Sa * Sb * K[4]) / (ga * gb)
            ref = _c2(sl.expm(-A * t))
            assert np.abs(got - ref).max() <= 1e-13 * np.abs(ref).max()
        m = np.array([0.3, -0.2, 0.5, 0.1, 0.7, -0.4])
        k0, k2, k3, k4 = top_row(mu, M, np.array([X]), m)
        assert np.allclose([k0[0], k2[0], k3[0], k4[0]], K[[0, 2, 3, 4], 5] @ m, rtol=1e-13, atol=1e-13)
        assert np.isclose(K[1, 5] @ m, m[5] - k0[0], rtol=1e-13, atol=1e-13)


@pytest.mark.parametrize("name", list(STACKS))
def test_fast_path_equals_the_general_solver(name):
    """Fixed kh and fixed frequency: the same record as the general Stroh solver (forced): labels,
    NaN padding, reasons, c_limit, kh/frequency columns; speeds 1e-10, group velocity 1e-7."""
    sub, films = STACKS[name]
    for kw in ({"kh": KH}, {"frequency": FREQ[1:]}):
        fast, gen = _both(sub, films, **kw)
        assert set(fast) == set(gen)
        assert fast["mode"].shape == gen["mode"].shape, (name, kw)
        assert (fast["mode"] == gen["mode"]).all()
        for key in ("c", "group_velocity", "kh", "frequency", "K2", "attenuation", "power_flow_angle"):
            assert (np.isnan(fast[key]) == np.isnan(gen[key])).all(), key
        ok = np.isfinite(gen["c"])
        assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-10, atol=0)
        assert np.allclose(fast["group_velocity"][ok], gen["group_velocity"][ok], rtol=1e-7, atol=0)
        assert np.allclose(fast["kh"][ok], gen["kh"][ok], rtol=1e-10, atol=0)
        assert np.allclose(fast["power_flow_angle"][ok], 0.0, atol=1e-9)
        assert (fast["reason"] == gen["reason"]).all()
        assert fast["c_limit"] == pytest.approx(gen["c_limit"], rel=1e-12)


def test_rayleigh_leaves_above_the_substrate_shear_speed():
    """Diamond on silica: R rises with kh and leaves the guided list at c_lim, as in the general solver
    (rows without a mode carry its reason)."""
    sub, films = STACKS["fast film on slow substrate (R leaves)"]
    fast = surfwave.layered(sub, films, kh=[0.05, 3.0])
    assert list(fast["mode"][0]) == ["R"]
    assert fast["c"].shape[1] == 1 and np.isnan(fast["c"][1, 0])
    assert "no guided mode" in fast["reason"][1]


def test_love_modes_closed_form():
    """Love modes of an isotropic layer on an isotropic half-space: tan(kh nu1) = mu2 r2 / (mu1 nu1),
    nu1 = sqrt(c^2/b1^2 - 1), r2 = sqrt(1 - c^2/b2^2), solved branch by branch with brentq; 1e-11."""
    _, b1, mu1 = _speeds(SIO2)
    _, b2, mu2 = _speeds(HARD)
    kh = np.array([0.5, 3.0, 20.0, 100.0])
    r = surfwave.layered(HARD, [{**SIO2, "thickness": 1e-6}], kh=kh)
    for i, k in enumerate(kh):
        def g(c):
            nu1, r2 = np.sqrt(c * c / b1 ** 2 - 1), np.sqrt(1 - c * c / b2 ** 2)
            return mu1 * nu1 * np.sin(k * nu1) - mu2 * r2 * np.cos(k * nu1)
        # branch n: k nu1 in ((n - 1/2) pi, n pi + pi/2) ... bracket between consecutive zeros of cos
        edges = [b1 * np.sqrt(1 + (q / k) ** 2) for q in np.arange(0, 200) * np.pi + np.pi / 2]
        lo = b1 * (1 + 1e-15)
        roots = []
        for hi in [e for e in edges if e < b2] + [b2 * (1 - 1e-15)]:
            if g(lo) * g(hi) < 0:
                roots.append(brentq(g, lo, hi, xtol=1e-14, rtol=1e-15))
            lo = hi
        labels = [f"L{n}" for n in range(len(roots))]
        got = [r["c"][i, list(r["mode"][i]).index(lab)] for lab in labels]
        assert len(roots) >= 1 and np.allclose(got, roots, rtol=1e-11, atol=0)
        assert f"L{len(roots)}" not in list(r["mode"][i])


def test_rayleigh_limits():
    """kh = 0: the substrate's Rayleigh speed (Rayleigh equation, brentq) to 1e-12, kh = 1e-6 within
    1e-6 of it (first order in kh); kh = 100: R is the film's own Rayleigh speed to 1e-10."""
    r = surfwave.layered(HARD, [{**SIO2, "thickness": 1e-6}], kh=[0.0, 1e-6, 100.0])
    c_sub, c_film = _rayleigh(HARD), _rayleigh(SIO2)
    assert r["c"][0, 0] == pytest.approx(c_sub, rel=1e-12)
    assert r["c"][1, 0] == pytest.approx(c_sub, rel=1e-6)
    assert r["c"][2, list(r["mode"][2]).index("R")] == pytest.approx(c_film, rel=1e-10)


def _expm_secular(st, c: float, kh: float) -> float:
    """det of the traction rows of the substrate's decaying pair carried up by scipy.linalg.expm per film."""
    X = st.rho * c * c / st.s
    lam, mu = st.lam, st.mu
    ra, rb = np.sqrt(1 - X[-1] / (lam[-1] + 2 * mu[-1])), np.sqrt(1 - X[-1] / mu[-1])
    q = X[-1] - 2 * mu[-1]
    Y = np.array([[1, rb], [ra, 1], [q, -2 * mu[-1] * rb], [-2 * mu[-1] * ra, q]])
    for layer in range(st.frac.size - 1, -1, -1):
        M, x, m_ = lam[layer] + 2 * mu[layer], X[layer], mu[layer]
        A = np.array([[0, 1, 0, 1 / m_], [-lam[layer] / M, 0, 1 / M, 0], [0, -x, 0, -1],
                      [4 * m_ * (lam[layer] + m_) / M - x, 0, lam[layer] / M, 0]])
        Y = sl.expm(-A * kh * st.frac[layer]) @ Y
        Y /= np.abs(Y).max()
    return float(np.linalg.det(Y[2:]))


def test_trapped_modes_of_a_buried_heavy_layer_against_expm():
    """A slow, heavy gold layer buried under a stiff film: every sagittal mode at kh = 10 equals the
    roots (brentq) of the direct matrix-exponential route, sign changes on a 6000-point scan, 1e-9.
    (Two of them lie 57 m/s apart, inside one cell of the search grid: found as a hidden pair.)"""
    sub, films = SI_ISO, [{**SIO2, "thickness": 0.4e-6}, {**ALN_ISO, "thickness": 0.3e-6},
                          {**GOLD, "thickness": 0.3e-6}]
    st = iso_stack(resolve_stack(sub, films))
    c = np.linspace(0.9 * 1200.0, st.c_lim * (1 - 1e-9), 6000)
    F = np.array([_expm_secular(st, x, 10.0) for x in c])
    idx = np.flatnonzero(np.sign(F[1:]) != np.sign(F[:-1]))
    ref = [brentq(lambda x: _expm_secular(st, x, 10.0), c[i], c[i + 1], xtol=1e-12) for i in idx]
    r = surfwave.layered(sub, films, kh=[10.0])
    got = [x for x, m in zip(r["c"][0], r["mode"][0]) if m and m[0] in "RS"]
    assert len(ref) == 7 and np.allclose(got, ref, rtol=1e-9, atol=0)
    # the fast secular function has the sign changes of the direct route
    Ff = secular_psv(st, c, np.full((1, c.size), 10.0))[0]
    assert (np.flatnonzero(np.sign(Ff[1:]) != np.sign(Ff[:-1])) == idx).all()


def test_group_velocity_by_finite_differences():
    """v_g = d(c kh)/dkh by central differences (step 1e-5) of the fast path's own speeds, 1e-7."""
    kh = np.array([0.7, 6.0, 30.0])
    d = 1e-5
    films = [{**SIO2, "thickness": 1e-6}]
    r0 = surfwave.layered(HARD, films, kh=kh)
    rp, rm = surfwave.layered(HARD, films, kh=kh + d), surfwave.layered(HARD, films, kh=kh - d)
    for i in range(kh.size):
        for j, lab in enumerate(r0["mode"][i]):
            if not lab or lab not in list(rp["mode"][i]) or lab not in list(rm["mode"][i]):
                continue
            cp = rp["c"][i, list(rp["mode"][i]).index(lab)]
            cm = rm["c"][i, list(rm["mode"][i]).index(lab)]
            fd = (cp * (kh[i] + d) - cm * (kh[i] - d)) / (2 * d)
            assert r0["group_velocity"][i, j] == pytest.approx(fd, rel=1e-7), (kh[i], lab)


def test_modes_keyword_gives_the_first_columns_of_each_family():
    """modes=2: per family exactly the first two modes of the full call, bit for bit (kh and frequency)."""
    sub, films = STACKS["slow film on fast substrate"]
    for kw in ({"kh": np.array([0.0, 0.3, 5.0, 40.0])}, {"frequency": np.array([1e8, 1e9, 5e9])}):
        full = surfwave.layered(sub, films, **kw)
        two = surfwave.layered(sub, films, modes=2, **kw)
        for i in range(full["c"].shape[0]):
            want = {m: (full["c"][i, j], full["group_velocity"][i, j]) for j, m in enumerate(full["mode"][i])
                    if m in ("R", "S1", "L0", "L1")}
            got = {m: (two["c"][i, j], two["group_velocity"][i, j]) for j, m in enumerate(two["mode"][i]) if m}
            assert got == want


def test_modes_keyword_on_the_general_path_and_bad_values():
    """The general path truncates each family to ``modes`` columns; bad values are one InputError line."""
    films = [{**SIO2, "thickness": 1e-6}]
    r = surfwave.layered("Si", films, kh=[8.0], modes=1)
    assert sorted(m for m in r["mode"][0] if m) == ["L0", "R"]
    for bad in (0, -1, 2.5, True, "2"):
        with pytest.raises(InputError, match="modes must be a positive integer"):
            surfwave.layered(HARD, films, kh=[1.0], modes=bad)


def test_mode_speeds_and_eligibility():
    """mode_speeds (the fitter's forward model) equals layered on the fast path; only isotropic,
    unstressed, elastic stacks qualify (C11 = C12 + 2 C44 to 1e-12)."""
    films = [{**SIO2, "thickness": 1e-6}]
    stack = resolve_stack(HARD, films)
    assert eligible(stack)
    assert not eligible(resolve_stack(HARD, [{**SIO2, "thickness": 1e-6, "stress": 0.1}]))
    assert not eligible(resolve_stack("Si", films))
    C = isotropic_voigt(70.0, 0.2)
    assert is_isotropic(C)
    C[3, 3] *= 1 + 1e-9
    assert not is_isotropic(C)
    kh = np.array([0.5, 5.0, 5.0, 5.0, 20.0])
    labels = ["R", "S1", "L0", "S0", "L3"]
    full = surfwave.layered(HARD, films, kh=kh)
    want = [full["c"][i, list(full["mode"][i]).index(m)] if m in list(full["mode"][i]) else np.nan
            for i, m in enumerate(labels)]
    got = solve.mode_speeds(stack, kh, labels)
    assert np.array_equal(got, np.array(want), equal_nan=True)
    assert np.isnan(got[3])                                   # "S0" names no mode


def test_twenty_layers_and_zero_frequency():
    """Twenty 50 nm films of one material equal one 1 um film (the same stack: 1e-12 in speed, 1e-8 in
    group velocity, same labels); at f = 0 the stack is the bare substrate: R at its Rayleigh speed
    (Rayleigh equation, brentq), kh = 0."""
    kh = [0.5, 5.0, 30.0]
    one = surfwave.layered(HARD, [{**SIO2, "thickness": 1e-6}], kh=kh)
    many = surfwave.layered(HARD, [{**SIO2, "thickness": 5e-8}] * 20, kh=kh)
    assert (one["mode"] == many["mode"]).all()
    assert np.allclose(many["c"], one["c"], rtol=1e-12, atol=0, equal_nan=True)
    assert np.allclose(many["group_velocity"], one["group_velocity"], rtol=1e-8, atol=0, equal_nan=True)
    r = surfwave.layered(HARD, [{**SIO2, "thickness": 1e-6}], frequency=[0.0])
    assert list(r["mode"][0]) == ["R"] and r["kh"][0, 0] == 0.0
    assert r["c"][0, 0] == pytest.approx(_rayleigh(HARD), rel=1e-12)
