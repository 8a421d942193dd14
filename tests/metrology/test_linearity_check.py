"""The fitter's check of the linear uncertainties: the default (each refit stopped once its chi^2 rise is
known to be inside [0.6, 1.6]) against the full three-step profile refit (check_linearity="profile").

References: for a model linear in its parameters the conditional optimum of the others with one parameter
held at theta_j +- sigma_j is theta_hat +- Cov[:, j] / sigma_j and chi^2 rises there by exactly 1 (the
normal equations); the full profile refit (the check as it was before the early stop, and
scipy.optimize.least_squares over the other parameters in tests/metrology/test_fit_core.py) for models that
bend: the closed-form Love wave (its exact sensitivities) and a toy model c = a b + b x whose a is weakly
determined when b is.
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.metrology.diagnostics import PROFILE_RANGE, profile_rises
from surfwave.metrology.fit import fit
from surfwave.metrology.love import LoveModel

P = {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0, "thickness": 1.0e-6}


class Counted:
    """A model with its calls counted (and its Jacobian, if it has one, passed on)."""

    def __init__(self, model):
        self.model, self.calls = model, 0
        if hasattr(model, "jacobian"):
            self.jacobian = model.jacobian

    def __call__(self, p, x):
        self.calls += 1
        return self.model(p, x)


def toy(p, x):
    """c = a b + b x: b from the slope, a only through the intercept a b (nonlinear in a once b is uncertain)."""
    return p["a"] * p["b"] + p["b"] * x


def linearity_warning(r) -> list[str]:
    return [w for w in r["warnings"] if "linear estimate" in w]


def test_linear_model_rises_by_exactly_one():
    """A quadratic (linear in a, b, c): at the linear conditional optimum chi^2 rises by 1 to round-off, the
    early stop takes it there (one model call per side: 2 m in all) and gives the full refit's numbers."""
    x = np.linspace(-1.0, 2.0, 15)
    y = 1.0 - 0.5 * x + 0.25 * x**2 + 0.05 * np.random.default_rng(4).standard_normal(x.size)
    X = np.stack([np.ones_like(x), x, x**2], axis=1)
    beta = np.linalg.lstsq(X, y, rcond=None)[0]
    J = X / 0.05
    cov = np.linalg.inv(J.T @ J)
    calls = [0]

    def residual(u):
        calls[0] += 1
        return (X @ u - y) / 0.05

    inf = np.full(3, np.inf)
    fast = profile_rises(residual, beta, cov, J, 1.0, -inf, inf, accept=PROFILE_RANGE)
    assert calls[0] == 1 + 2 * 3
    np.testing.assert_allclose(fast, 1.0, atol=1e-9)
    full = profile_rises(residual, beta, cov, J, 1.0, -inf, inf)
    np.testing.assert_allclose(full, 1.0, atol=1e-9)


@pytest.mark.parametrize("noise, nonlinear", [(1e-3, []), (1e-2, ["mu", "rho"])])
def test_love_fast_and_profile_checks_flag_the_same_parameters(noise, nonlinear):
    """Love model (exact analytic sensitivities), (mu, rho, h) from 30 frequencies: both checks warn about the
    same parameters with the same text (at 1 % noise mu and rho, whose profile rises the full refit puts outside
    [0.6, 1.6], tests/metrology/test_fit_core.py; none at 0.1 %), the default in fewer model calls."""
    m = LoveModel(0, "frequency")
    f = np.linspace(1e8, 2e9, 30)
    c = m(P, f) * (1 + noise * np.random.default_rng(3).standard_normal(f.size))
    out = {}
    for how in (True, "profile"):
        model = Counted(m)
        r = fit(model, f, c, P, free=["mu", "rho", "thickness"], sigma=noise * m(P, f), check_linearity=how,
                curve_points=0)
        out[how] = (linearity_warning(r), model.calls, r)
    (w_fast, n_fast, r_fast), (w_full, n_full, r_full) = out[True], out["profile"]
    assert w_fast == w_full
    flagged = [] if not w_full else [k for k in ("mu", "rho", "thickness") if f"{k}: chi2 rises" in w_full[0]]
    assert flagged == nonlinear
    assert n_fast < n_full
    np.testing.assert_array_equal(r_fast["covariance"], r_full["covariance"])


@pytest.mark.parametrize("noise, nonlinear", [(0.01, []), (0.1, []), (0.3, ["a"])])
def test_toy_model_fast_and_profile_checks_agree(noise, nonlinear):
    """c = a b + b x at 20 points in [0, 1]: at sigma 0.3 (b known to ~30 %) a = intercept / b bends within one
    sigma and both checks name a, with the same rises in the text; at 0.01 and 0.1 neither warns."""
    x = np.linspace(0.0, 1.0, 20)
    c = toy({"a": 2.0, "b": 1.0}, x) + noise * np.random.default_rng(1).standard_normal(x.size)
    texts = []
    for how in ("fast", "profile"):
        r = fit(toy, x, c, {"a": 2.0, "b": 1.0}, sigma=noise, check_linearity=how, curve_points=0)
        texts.append(linearity_warning(r))
        named = [] if not texts[-1] else [k for k in ("a", "b") if f"{k}: chi2 rises" in texts[-1][0]]
        assert named == nonlinear, how
    assert texts[0] == texts[1]


def test_early_stop_is_an_upper_bound_of_the_profile():
    """Where a side stops early, its rise (chi^2 at a point with the parameter held, the others not yet
    optimal) is not below the exact profile rise (scipy.optimize.least_squares over the others, to 1e-12), and
    within 0.2 of it; the full three-step refit matches that profile to 1e-3."""
    from scipy.optimize import least_squares

    m = LoveModel(0, "frequency")
    f = np.linspace(1e8, 2e9, 30)
    noise = 3e-3
    c = m(P, f) * (1 + noise * np.random.default_rng(5).standard_normal(f.size))
    sigma = noise * m(P, f)
    names = ["mu", "rho", "thickness"]
    r = fit(m, f, c, P, free=names, sigma=sigma, check_linearity=False, curve_points=0)
    scale = np.array([P[k] for k in names])
    u = np.array([r["values"][k] for k in names]) / scale

    def residual(v):
        return (m(dict(r["values"], **{k: v[i] * scale[i] for i, k in enumerate(names)}), f) - c) / sigma

    J = m.jacobian(r["values"], f, names) * scale[None, :] / sigma[:, None]
    cov = r["covariance"] / np.outer(scale, scale)
    inf = np.full(3, np.inf)
    fast = profile_rises(residual, u, cov, J, 1.0, -inf, inf, accept=PROFILE_RANGE)
    full = profile_rises(residual, u, cov, J, 1.0, -inf, inf)
    chi0 = float(residual(u) @ residual(u))
    exact = np.empty((3, 2))
    for j in range(3):
        o = [k for k in range(3) if k != j]
        for col, sgn in enumerate((1.0, -1.0)):
            held = u[j] + sgn * np.sqrt(cov[j, j])

            def res_o(w, j=j, o=o, held=held):
                v = np.empty(3)
                v[j], v[o] = held, w
                return residual(v)

            sol = least_squares(res_o, u[o] + sgn * cov[o, j] / np.sqrt(cov[j, j]), xtol=1e-14, ftol=1e-14,
                                gtol=1e-14)
            exact[j, col] = 2 * sol.cost - chi0
    assert np.all(fast >= exact - 1e-7)
    assert np.all(fast - exact < 0.2)
    assert np.all((fast >= PROFILE_RANGE[0]) & (fast <= PROFILE_RANGE[1]))
    np.testing.assert_allclose(full, exact, atol=1e-3)


def test_bad_check_option_is_one_line():
    """An unknown check_linearity is refused before any model call."""
    model = Counted(toy)
    with pytest.raises(InputError, match="check_linearity"):
        fit(model, np.linspace(0, 1, 5), np.ones(5), {"a": 1.0, "b": 1.0}, check_linearity="quick")
    assert model.calls == 0
