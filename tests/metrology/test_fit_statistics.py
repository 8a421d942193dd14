"""Synthetic truth: 200 seeded fits of Love-wave dispersion at 0.1 % noise (surfwave.metrology.fit).

Reference: for a model that is linear over the noise scale, the estimate is Gaussian with the
Jacobian covariance, so the truth lies within 2 sigma in 95.4 % of fits (with sigma from the
reduced chi^2, Student's t with 27 degrees of freedom: 94.4 %); the test asks for 90 % (3 binomial
standard deviations below) and for the spread of the 200 estimates to match the mean predicted
1-sigma within 20 % (a covariance off by a factor 2 either way fails one of the two).
"""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.metrology.fit import fit
from surfwave.metrology.love import LoveModel

TRUTH = {"mu": 31.2, "rho": 2200.0, "substrate_mu": 66.25, "substrate_rho": 2650.0, "thickness": 1.0e-6}
N_FITS = 200
NOISE = 1e-3


@pytest.mark.parametrize("variable, x, free, with_sigma", [
    ("kh", np.linspace(0.2, 6.0, 30), ["mu", "rho", "substrate_mu"], False),
    ("frequency", np.linspace(1e8, 2e9, 30), ["mu", "rho", "thickness"], True),
])
def test_truth_within_two_sigma(variable, x, free, with_sigma):
    model = LoveModel(0, variable)
    c_true = model(TRUTH, x)
    start = dict(TRUTH, **{k: 1.1 * TRUTH[k] for k in free})  # 10 % off
    truth = np.array([TRUTH[k] for k in free])
    values, sds = [], []
    for seed in range(N_FITS):
        rng = np.random.default_rng(seed)
        c = c_true * (1 + NOISE * rng.standard_normal(x.size))
        r = fit(model, x, c, start, free=free, sigma=NOISE * c_true if with_sigma else None, curve_points=0,
                check_linearity=False)
        assert r["success"]
        assert r["uncertainty_basis"] == ("sigma" if with_sigma else "reduced_chi2")
        values.append([r["values"][k] for k in free])
        sds.append([r["uncertainties"][k] for k in free])
    values, sds = np.array(values), np.array(sds)
    inside = np.mean(np.abs(values - truth) < 2 * sds, axis=0)
    assert np.all(inside >= 0.90), dict(zip(free, inside))
    spread = np.std(values, axis=0) / np.mean(sds, axis=0)
    assert np.all((spread > 0.8) & (spread < 1.2)), dict(zip(free, spread))
