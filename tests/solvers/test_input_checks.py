"""Input checks of the solvers (issue 20, item 6 and "Tracebacks and misleading messages"):
rayleigh_c2 refuses rho <= 0 and can say why a point is NaN; a Miller index that
overflows int64 is an InputError, not an OverflowError."""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.solvers import orientation, rayleigh


def isotropic(lam=1.0, mu=1.0) -> np.ndarray:
    """S of an isotropic solid (d = 2): c_R^2 = 2 - 2/sqrt 3 at lambda = mu = 1 (Rayleigh 1885)."""
    S = np.zeros((2, 2, 2, 2))
    S[0, 0, 0, 0] = S[1, 1, 1, 1] = lam + 2 * mu
    S[0, 1, 0, 1] = S[0, 1, 1, 0] = S[1, 0, 1, 0] = S[1, 0, 0, 1] = mu
    S[1, 1, 0, 0] = S[0, 0, 1, 1] = lam
    return S


@pytest.mark.parametrize("rho", [0.0, -1.0, np.nan, np.inf, [1.0, -1.0], "x"])
def test_rayleigh_c2_refuses_non_positive_rho(rho):
    """Before: rho <= 0 gave a (negative or infinite) number."""
    S = np.stack([isotropic(), isotropic()])
    with pytest.raises(InputError, match="rho must be"):
        rayleigh.rayleigh_c2(S, rho)


def test_rayleigh_c2_reasons_match_solve():
    """reasons=True gives the reasons of rayleigh.solve point by point; the default path
    returns the bare array as before."""
    S = np.stack([isotropic(), isotropic(mu=-0.1), isotropic(lam=-3.0)])
    S[2, 1, 1, 1, 1] = -1.0  # unstable normal to the surface
    c2 = rayleigh.rayleigh_c2(S)
    c2r, why = rayleigh.rayleigh_c2(S, reasons=True)
    ref = rayleigh.solve(S)
    np.testing.assert_array_equal(c2, c2r)
    np.testing.assert_array_equal(c2r, ref["c2_R"])
    assert list(why) == list(ref["reason"])
    assert why[0] == "" and c2[0] == pytest.approx(2 - 2 / 3**0.5, rel=1e-12)
    assert np.isnan(c2[1]) and why[1] == rayleigh.REASON_SHEAR
    assert np.isnan(c2[2]) and why[2] == rayleigh.REASON_PERP


@pytest.mark.parametrize("text", ["[100000000000000000000 1 0]", "(1 99999999999999999999999 0)",
                                  "[1234567 0 0]"])
def test_huge_miller_index_is_an_input_error(text):
    """Before: int64 overflow (OverflowError) for the first two."""
    parse = orientation.parse_direction if text.startswith("[") else orientation.parse_plane
    with pytest.raises(InputError, match="Miller indices must not exceed"):
        parse(text)
    assert orientation.parse_direction("[100 1 0]").tolist() == [100, 1, 0]
