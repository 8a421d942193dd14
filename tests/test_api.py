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
from surfwave.errors import InputError
from surfwave.real_crystals.acoustoelastic import loading_stress, surface_wave_speed
from surfwave.real_crystals.materials import get_material

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


def test_non_piezoelectric_calls_keep_the_elastic_route():
    """Without piezo=, permittivity=, euler=, cut= or electrical=, a crystal of the elastic
    database (Cu, and GaAs, which is also in the piezoelectric database) keeps today's route and
    keys exactly (no K2, 3-component polarisation; Eq. 17 at the mirror direction); a name found
    only in the piezoelectric database (LiNbO3) takes the piezoelectric route. Reference: the
    elastic route's own outputs (README copper value 2012.12 m/s)."""
    for name in ("Cu", "GaAs"):
        r = surfwave.material(name, direction="[100]")
        assert "K2" not in r and np.shape(r["polarisation"]) == (3,) and r["method"] == "eq17"
    assert surfwave.material("Cu")["c_R"] == pytest.approx(2012.12, abs=0.01)
    g = surfwave.material("GaAs", direction="[110]", electrical="free")   # GaAs e14 switched on
    assert "K2" in g and np.shape(g["polarisation"]) == (4,)
    assert "K2" in surfwave.material("LiNbO3", cut="Y-Z")


def test_gaas_001_110_supersonic_piezoelectric_wave():
    """GaAs (001)[110]: the (1-10) mirror decouples the sagittal wave and the potential from the
    slower SH bulk wave, so the SAW lies above the limiting speed (elastic solver:
    supersonic_decoupled, 2859 m/s). With e14 it is found as the non-attenuating leaky root: free
    speed ~2864 m/s and K^2 ~0.06-0.07 % as commonly tabulated for GaAs (001)<110> (e.g. Datta,
    Surface Acoustic Wave Devices, 1986; our constants: McSkimin C, Auld e14), checked to 0.5 % and
    within 0.04-0.09 %; zero attenuation; and [100], where e14 does not couple, has K^2 = 0."""
    f = surfwave.material("GaAs", direction="[110]", electrical="free")
    el = surfwave.material("GaAs", direction="[110]")
    assert f["wave_type"] == el["wave_type"] == "supersonic_decoupled"
    assert f["c_free"] == pytest.approx(2864, rel=5e-3) and f["c_free"] > el["c_R"] > f["c_limit"]
    assert 0.04 < 100 * f["K2"] < 0.09 and f["leaky_attenuation"] == 0
    assert surfwave.material("GaAs", direction="[100]", electrical="free")["K2"] == pytest.approx(0, abs=1e-12)
