"""surfwave.material with materials by name and third-order constants (toec=).

References: the README's copper value (2012.12 m/s, (001)[100]); the fixed-C results of the
same function (toec=None), which the third-order model must reproduce at zero stress; the
acoustoelastic module (surfwave.real_crystals.acoustoelastic), a separate code path to the same
stressed state, at mirror and off-mirror directions; the database's Hiki & Granato constants
(toec=True must equal passing them by hand).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.real_crystals.acoustoelastic import loading_stress, surface_wave_speed
from surfwave.real_crystals.materials import get_material
from surfwave.errors import InputError

CU = get_material("Cu")


def test_material_by_name_equals_the_constants_and_toec_vanishes_at_zero_stress():
    """'Cu' by name = the constants by hand (2012.12 m/s); with TOEC at zero stress the speeds
    and density are unchanged for several angles and another surface."""
    by_hand = surfwave.material(168.4, 121.4, 75.4, 8960, "[100]")
    assert surfwave.material("copper")["c_R"] == by_hand["c_R"] == pytest.approx(2012.12, abs=0.01)
    for kwargs in ({"direction": [0.0, 22.5, 45.0]}, {"direction": "[1-10]", "surface": "(111)"}):
        a = surfwave.material("Cu", toec=True, **kwargs)
        b = surfwave.material("Cu", **kwargs)
        assert np.allclose(a["c_R"], b["c_R"], rtol=1e-12) and np.allclose(a["rho"], 8960.0)
        assert np.all(a["toec"]) and not np.any(b["toec"])


@pytest.mark.parametrize("direction, surface", [("[100]", "(001)"), (22.5, "(001)"), ("[1-10]", "(111)")])
def test_toec_speed_matches_the_acoustoelastic_path(direction, surface):
    """Under uniaxial stress along the propagation, material(..., toec=True) equals
    surface_wave_speed on the same stressed state (mirror, off-mirror and (111) directions);
    toec=(C111, ..., C456) by hand equals toec=True."""
    s = np.array([-0.3, 0.2])
    sig = loading_stress("along", s, surface, direction)
    ref = surface_wave_speed(CU.voigt, CU.toec_voigt, CU.rho, sig, surface, direction)["c_R"]
    for k, sk in enumerate(s):
        r = surfwave.material("Cu", direction=direction, surface=surface, stress=sk, toec=True)
        assert r["c_R"] == pytest.approx(ref[k], rel=1e-9)
        assert r["rho"] == pytest.approx(CU.rho / np.linalg.det(surface_wave_speed(
            CU.voigt, CU.toec_voigt, CU.rho, sig[k], surface, direction)["F"]), rel=1e-12)
    t = CU.toec
    by_hand = surfwave.material(168.4, 121.4, 75.4, 8960, direction, 0.2, surface,
                                toec=(t["C111"], t["C112"], t["C123"], t["C144"], t["C155"], t["C456"]))
    assert by_hand["c_R"] == pytest.approx(ref[1], rel=1e-9)


def test_toec_errors_and_extremes():
    """Missing TOEC names the material and the constants; toec=True needs a name; a name with
    constants is ambiguous; a stress past the model's range is NaN with a reason."""
    with pytest.raises(InputError, match=r"Mg.*C111, C112, C123, C144, C155, C456"):
        surfwave.material("Mg", direction="[100]", surface="(001)", toec=True)
    with pytest.raises(InputError, match="by name"):
        surfwave.material(168.4, 121.4, 75.4, 8960, "[100]", toec=True)
    with pytest.raises(InputError, match="do not also give"):
        surfwave.material("Cu", 121.4)
    with pytest.raises(InputError, match="toec must be"):
        surfwave.material("Cu", toec=(1.0, 2.0))
    with pytest.raises(InputError, match="unknown material"):
        surfwave.material("Cuu")
    r = surfwave.material("Cu", direction="[100]", stress=-30.0, toec=True)
    assert np.isnan(r["c_R"]) and r["wave_type"] == "none" and "third-order model" in r["reason"]
    assert not r["stable"]
