"""Surface waves of real crystals under in-plane stress and their acoustoelastic coefficients.

References: the README's copper value c_R = 2012.12 m/s (unstressed, (001)[100], through the
existing Eq. (17) route of ``surfwave.material``); the fixed-C model against
``surfwave.material(..., stress=)`` (the same physics, A = C + sigma delta, reached through a
separate code path); Eq. (A11), in which sigma_zz cannot enter the sagittal components
(so the fixed-C coefficient across the propagation is exactly zero); linearity of the
derivative at zero stress (biaxial = along + across); the h^2 convergence of a central
difference; and the issue's statement for copper (001)[100]: the third-order constants raise
the along-coefficient about 2.5-fold and give a larger one of opposite sign across.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals.acoustoelastic import (
    acoustoelastic_coefficients,
    check_in_plane,
    loading_stress,
    surface_wave_speed,
)
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.toec import cubic_toec

CU = get_material("Cu")
CU_C3 = cubic_toec(**CU.toec)


def test_unstressed_copper_and_fixed_c_model_match_the_existing_route():
    """At zero stress both models give 2012.12 m/s; under uniaxial stress along [100] the
    fixed-C model equals surfwave.material(..., stress=) (Eq. A11 route)."""
    sig = loading_stress("along", [0.0, -0.5, 0.3], "(001)", "[100]")
    fixed = surface_wave_speed(CU.voigt, None, CU.rho, sig, "(001)", "[100]")
    toec = surface_wave_speed(CU.voigt, CU_C3, CU.rho, sig[:1], "(001)", "[100]")
    assert fixed["c_R"][0] == pytest.approx(2012.12, abs=0.01)
    assert toec["c_R"][0] == pytest.approx(fixed["c_R"][0], rel=1e-12)
    c = CU.constants
    for k, s in enumerate([0.0, -0.5, 0.3]):
        ref = surfwave.material(c["C11"], c["C12"], c["C44"], CU.rho, "[100]", stress=s)["c_R"]
        assert fixed["c_R"][k] == pytest.approx(ref, rel=1e-10)


@pytest.mark.parametrize("direction", ["[100]", "[110]"])
def test_acoustoelastic_coefficients_linearity_and_fixed_c_across(direction):
    """biaxial = along + across for both models (linearity at zero stress); the fixed-C model
    has no coefficient across (sigma_zz does not enter the sagittal S of Eq. A11); halving the
    step changes nothing beyond 1e-6 relative (O(h^2) with h = 1e-4 GPa)."""
    r = acoustoelastic_coefficients(CU.voigt, CU_C3, CU.rho, "(001)", direction)
    for model in ("toec", "fixed_C"):
        k = r[model]
        assert k["biaxial"] == pytest.approx(k["along"] + k["across"], rel=1e-6, abs=1e-10)
    assert abs(r["fixed_C"]["across"]) < 1e-10
    half = acoustoelastic_coefficients(CU.voigt, CU_C3, CU.rho, "(001)", direction, step=5e-5)
    assert half["toec"]["along"] == pytest.approx(r["toec"]["along"], rel=1e-6)


def test_copper_toec_effect_as_stated_in_the_issue():
    """Cu (001)[100]: (1/v) dv/dsigma along the propagation is ~2.5 times the fixed-C value
    with the third-order constants; across it, TOEC give a coefficient of opposite sign and
    larger magnitude than the along one, where fixed C gives none."""
    r = acoustoelastic_coefficients(CU.voigt, CU_C3, CU.rho, "(001)", "[100]")
    ratio = r["toec"]["along"] / r["fixed_C"]["along"]
    assert 2.2 < ratio < 2.8
    assert r["toec"]["across"] * r["toec"]["along"] < 0
    assert abs(r["toec"]["across"]) > abs(r["toec"]["along"])
    no_toec = acoustoelastic_coefficients(CU.voigt, None, CU.rho, "(001)", "[100]")
    assert np.isnan(no_toec["toec"]["along"]) and no_toec["fixed_C"] == r["fixed_C"]


def test_extremes_and_bad_input():
    """Out-of-plane stress is refused (check_in_plane naming the component; surface_wave_speed in
    the case check's words, as surfwave.material, naming the traction); a stress past the model's
    range is NaN with a reason; a direction outside the surface is an InputError."""
    with pytest.raises(InputError, match="sigma_yy"):
        check_in_plane(np.diag([0.0, 0.0, 1.0]), "(001)", "[100]")
    loaded = np.array([[0, 0, 0.1], [0, 0, 0], [0.1, 0, 0]])
    with pytest.raises(InputError) as api:
        surfwave.material("Cu", stress=loaded, toec=True)
    with pytest.raises(InputError) as ae:
        surface_wave_speed(CU.voigt, CU_C3, CU.rho, loaded)
    assert str(ae.value) == str(api.value)
    assert str(ae.value).startswith("prestress must lie in the surface plane (001): its traction sigma . n = [0.1, 0.0, 0.0]")
    with pytest.raises(InputError, match="in GPa"):
        surface_wave_speed(CU.voigt, CU_C3, CU.rho, np.diag([2000.0, 0.0, 0.0]))
    r = surface_wave_speed(CU.voigt, CU_C3, CU.rho, loading_stress("along", [-40.0, 0.2]))
    assert np.isnan(r["c_R"][0]) and r["reason"][0] and r["wave_type"][0] == "none"
    assert np.isfinite(r["c_R"][1]) and r["reason"][1] == ""
    with pytest.raises(InputError, match="does not lie in the surface"):
        loading_stress("along", 1.0, "(001)", "[101]")
    with pytest.raises(InputError, match="loading"):
        loading_stress("shear", 1.0)
