"""Love waves in an isotropic film on an isotropic half-space (surfwave.metrology.love).

References: an independent finite-element solve of the SH eigenproblem on a deep slab (written
here, linear elements with Richardson extrapolation); the long- and short-wave asymptotes of the
dispersion equation derived by hand (docs/physics/metrology.md); central finite differences for
the implicit-differentiation sensitivities.
"""
from __future__ import annotations

import math

import numpy as np
import pytest
import scipy.sparse as sp
from scipy.sparse.linalg import eigsh

from surfwave.errors import InputError
from surfwave.metrology.love import LoveModel, love_cutoff, love_jacobian, love_speed

# SiO2-like film (mu 31.2 GPa, 2200 kg/m^3) on a quartz-like isotropic substrate (b2 = 5000 m/s)
P = {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0, "thickness": 1.0e-6}
B1 = math.sqrt(31.2e9 / 2200.0)
B2 = 5000.0


def fem_love_speeds(kh: float, n_modes: int, n_film: int) -> np.ndarray:
    """Lowest SH guided speeds of film (0 < z < 1) on substrate (1 < z < 1 + L), u = 0 at the bottom:
    K u = omega^2 M u with K = int mu (u'^2 + k^2 u^2), M = int rho u^2, linear elements."""
    mu1, rho1, mu2, rho2 = P["mu"], P["rho"] / 1e3, P["substrate_mu"], P["substrate_rho"] / 1e3
    k = kh
    # substrate deep enough for the modes tested (c < 0.97 b2: decay rate k q2 > 0.24 k), u = 0 at e^-40
    L = 40.0 / (k * math.sqrt(1 - 0.97**2))
    n_sub = int(n_film * L / 5)
    z = np.unique(np.concatenate([np.linspace(0, 1, n_film + 1), 1 + np.linspace(0, L, n_sub + 1)]))
    he = np.diff(z)
    mid = 0.5 * (z[1:] + z[:-1])
    mu = np.where(mid < 1, mu1, mu2)
    rho = np.where(mid < 1, rho1, rho2)
    n = z.size
    ke = [[1, -1], [-1, 1]]
    me = [[2, 1], [1, 2]]
    rows, cols, kv, mv = [], [], [], []
    for a in range(2):
        for b in range(2):
            rows.append(np.arange(n - 1) + a)
            cols.append(np.arange(n - 1) + b)
            kv.append(mu * ke[a][b] / he + mu * k * k * he * me[a][b] / 6)
            mv.append(rho * he * me[a][b] / 6)
    K = sp.csc_matrix((np.concatenate(kv), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))[:-1, :-1]
    M = sp.csc_matrix((np.concatenate(mv), (np.concatenate(rows), np.concatenate(cols))), shape=(n, n))[:-1, :-1]
    w2 = eigsh(K, k=n_modes, M=M, sigma=(k * 0.5 * B1 / 1e3) ** 2, which="LM", return_eigenvectors=False)
    return np.sort(np.sqrt(w2) / k) * 1e3  # km/s in these units -> m/s


@pytest.mark.parametrize("kh, n_modes", [(1.0, 1), (5.0, 2)])
def test_love_speed_agrees_with_finite_elements(kh, n_modes):
    """The closed form against an independent FEM eigen-solve of the SH problem on a deep slab
    (linear elements, Richardson extrapolation h -> h/2): agreement to 2e-6 (the FEM's own error)."""
    coarse = fem_love_speeds(kh, n_modes, 100)
    fine = fem_love_speeds(kh, n_modes, 200)
    fem = fine + (fine - coarse) / 3.0
    exact = np.array([love_speed([kh], P, mode=m)[0] for m in range(n_modes)])
    assert np.all(exact < B2) and np.all(exact > B1)
    np.testing.assert_allclose(fem, exact, rtol=2e-6)


def test_cutoffs_and_missing_modes():
    """Mode n is cut off at kh = n pi / sqrt(b2^2/b1^2 - 1) (where tan(kh q1) = 0 with q2 = 0): just
    above it c is within 1e-5 of b2, just below it NaN."""
    for n in (1, 2, 3):
        khc = love_cutoff(n, P["mu"], P["rho"], P["substrate_mu"], P["substrate_rho"])
        assert khc == pytest.approx(n * math.pi / math.sqrt(B2**2 / B1**2 - 1), rel=1e-12)
        above = love_speed([khc * (1 + 1e-6)], P, mode=n)[0]
        below = love_speed([khc * (1 - 1e-6)], P, mode=n)[0]
        assert 0 < 1 - above / B2 < 1e-5 and math.isnan(below)


def test_long_wave_limit():
    """kh -> 0 (mode 0): tan(kh q1) ~ kh q1 gives q2 = kh (mu/mu_s) q1^2, hence
    c = b2 [1 - (1/2) (kh (mu/mu_s) Q^2)^2 + O(kh^4)], Q^2 = b2^2/b1^2 - 1; and c(0) = b2 exactly."""
    Q2 = B2**2 / B1**2 - 1
    for kh in (1e-6, 1e-3, 3e-3):
        c = love_speed([kh], P)[0]
        first = B2 * (1 - 0.5 * (kh * P["mu"] / P["substrate_mu"] * Q2) ** 2)
        assert abs(c / first - 1) < 5 * (kh * Q2) ** 4
    assert love_speed([0.0], P)[0] == pytest.approx(B2, rel=1e-15)


def test_short_wave_limit():
    """kh -> infinity (mode 0): theta = kh q1 -> pi/2 with pi/2 - theta ~ (mu q1) / (mu_s q2inf), so
    q1 = (pi/2) / (kh + mu / (mu_s q2inf)) + O(kh^-3), q2inf = sqrt(1 - b1^2/b2^2); c = b1 sqrt(1 + q1^2)."""
    q2inf = math.sqrt(1 - B1**2 / B2**2)
    for kh in (30.0, 100.0):
        c = love_speed([kh], P)[0]
        q1 = 0.5 * math.pi / (kh + P["mu"] / (P["substrate_mu"] * q2inf))
        assert abs(c / (B1 * math.sqrt(1 + q1**2)) - 1) < 10 * kh**-4
    # higher modes tend to the film's shear speed too, from above
    c = love_speed([100.0], P, mode=3)[0]
    assert B1 < c < B1 * 1.01


def test_frequency_variable_is_consistent_with_kh():
    """At fixed frequency the solver finds kh = 2 pi f h / c itself: feeding that kh back gives the same c."""
    f = np.array([2e8, 1e9, 3e9, 4e9, 6e9])
    for mode in (0, 1):
        c_f = love_speed(f, P, mode=mode, variable="frequency")
        ok = np.isfinite(c_f)
        assert ok.sum() >= 2
        kh = 2 * np.pi * f[ok] * P["thickness"] / c_f[ok]
        np.testing.assert_allclose(love_speed(kh, P, mode=mode), c_f[ok], rtol=1e-13)


def test_no_love_wave_without_a_slow_film():
    """A film as fast as the substrate (or the substrate's own material) guides no SH wave: NaN, not a crash."""
    same = dict(P, mu=P["substrate_mu"], rho=P["substrate_rho"])
    assert np.all(np.isnan(love_speed([0.5, 2.0], same)))
    fast = dict(P, mu=200.0)
    assert np.all(np.isnan(love_speed([0.5, 2.0], fast)))
    assert math.isnan(love_cutoff(1, 200.0, 2200.0, 66.25, 2650.0))


@pytest.mark.parametrize("variable, x", [("kh", np.array([0.05, 0.7, 3.0, 9.0, 40.0])),
                                         ("frequency", np.array([5e7, 4e8, 1.5e9, 4e9, 8e9]))])
@pytest.mark.parametrize("mode", [0, 1])
def test_implicit_sensitivities_match_finite_differences(variable, x, mode):
    """dc/dp = -G_p / G_c (implicit differentiation) against central differences of love_speed with a
    relative step 1e-6 (agreement to 1e-6 of the column's largest value), every parameter, (mu) and (E, nu)."""
    for base in (P, {k: v for k, v in P.items() if k != "mu"} | {"E": 73.0, "nu": 0.17}):
        names = [k for k in base]
        J = love_jacobian(x, base, names, mode=mode, variable=variable)
        c = love_speed(x, base, mode=mode, variable=variable)
        assert np.array_equal(np.isnan(J[:, 0]), np.isnan(c))
        ok = np.isfinite(c)
        assert ok.sum() >= 2
        for j, name in enumerate(names):
            h = 1e-6 * abs(base[name])
            up, dn = dict(base), dict(base)
            up[name] += h
            dn[name] -= h
            fd = (love_speed(x, up, mode=mode, variable=variable) - love_speed(x, dn, mode=mode, variable=variable)) / (2 * h)
            scale = max(np.max(np.abs(J[ok, j])), 1e-12)
            assert np.max(np.abs(fd[ok] - J[ok, j])) <= 1e-6 * scale, name
    # kh data carry no information on the thickness
    assert np.all(love_jacobian([1.0, 2.0], P, ["thickness"])[:, 0] == 0.0)


def test_model_object_and_bad_input():
    """LoveModel wraps love_speed/love_jacobian; unknown parameters and options are refused in one line."""
    m = LoveModel(mode=1, variable="kh")
    np.testing.assert_array_equal(m(P, np.array([5.0])), love_speed([5.0], P, mode=1))
    with pytest.raises(InputError, match="mu"):
        love_speed([1.0], {"rho": 1.0, "substrate_mu": 1.0, "substrate_rho": 1.0})
    with pytest.raises(InputError, match="variable"):
        LoveModel(variable="wavelength")  # type: ignore[arg-type]
    with pytest.raises(InputError, match="unknown"):
        love_jacobian([1.0], P, ["C11"])
    with pytest.raises(InputError, match="mode"):
        love_speed([1.0], P, mode=-1)
