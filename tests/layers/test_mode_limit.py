"""The limiting speed of each mode's family (``mode_limit`` of surfwave.layered and of the layered cube).

References: the SH bulk wave along [100] of Si (001), sqrt(C44 / rho) with the database's C44 and rho (the
shear-horizontal family's limit); surfwave.material's c_limit of bare Si (001)[100] (the sagittal family's,
a different solver path: the half-space Stroh solver); the shear speed sqrt(mu / rho) of an isotropic
substrate (both families' limit). Every guided mode lies below its own family's limit, which is what the
record and the figures now say (a Love mode may lie above ``c_limit``, the lower of the two).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.layers.cube import dispersion_cube
from surfwave.real_crystals.materials import get_material

SIO2 = {"name": "SiO2", "thickness": 1e-6}


@pytest.mark.parametrize("how", [{"kh": np.linspace(0.5, 4.0, 8)}, {"frequency": [5e8, 1.2e9]},
                                 {"kh": [1.0, 3.0], "leaky": True}])
def test_sagittal_and_sh_limits_of_si_001_100(how):
    """SiO2 on Si (001)[100]: R/S modes carry material()'s c_limit, L modes sqrt(C44/rho) (1e-9); guided
    entries lie below their own limit, and some L mode lies above c_limit (the case the key exists for)."""
    si = get_material("Si")
    sh = np.sqrt(si.voigt[3, 3] * 1e9 / si.rho)
    sag = float(surfwave.material("Si", direction="[100]")["c_limit"])
    r = surfwave.layered("Si", [SIO2], **how)
    lab = r["mode"].astype(str)
    first = np.char.str_len(lab) > 0
    is_sh = np.char.startswith(lab, "L") & first
    is_sag = (np.char.startswith(lab, "R") | np.char.startswith(lab, "S")) & first
    assert is_sh.any() and is_sag.any()
    np.testing.assert_allclose(r["mode_limit"][is_sh], sh, rtol=1e-9)
    np.testing.assert_allclose(r["mode_limit"][is_sag], sag, rtol=1e-9)
    assert np.isnan(r["mode_limit"][~first]).all()
    guided = first & ~np.char.endswith(lab, "~")
    assert (r["c"][guided] < r["mode_limit"][guided]).all()
    if "kh" in how and not how.get("leaky"):
        assert (r["c"][is_sh] > r["c_limit"]).any()


@pytest.mark.parametrize("how", [{"kh": [0.5, 2.0, 8.0]}, {"frequency": [2e8, 1e9]}, {"kh": [1.0], "modes": 1}])
def test_isotropic_substrate_both_families_share_the_shear_speed(how):
    """Isotropic substrate (E 400 GPa, nu 0.25, rho 3500): every mode's limit is its shear speed sqrt(mu/rho)."""
    E, nu, rho = 400e9, 0.25, 3500.0
    r = surfwave.layered({"E": 400.0, "nu": nu, "rho": rho}, [{"E": 73.0, "nu": 0.17, "rho": 2200.0,
                                                             "thickness": 1e-6}], **how)
    live = r["mode"].astype(str) != ""
    np.testing.assert_allclose(r["mode_limit"][live], np.sqrt(E / (2 * (1 + nu)) / rho), rtol=1e-12)


def test_cube_carries_one_limit_per_mode():
    """dispersion_cube's mode_limit (film_stress, electrical, mode) equals the record's per label."""
    kh = np.array([1.0, 3.0])
    ds = dispersion_cube("Si", [SIO2], kh)
    r = surfwave.layered("Si", [dict(SIO2, stress=0.0)], kh=kh)
    for mode in ds["mode"].values:
        hit = r["mode"] == mode
        assert float(ds["mode_limit"].sel(mode=mode).squeeze()) == pytest.approx(float(r["mode_limit"][hit][0]),
                                                                                 rel=1e-14)


def test_figure_draws_one_limit_per_family():
    """plots.layered.limit_lines: Si (001)[100] gives the sagittal (material()'s c_limit) and the SH
    (sqrt(C44/rho)) lines, ascending; an isotropic substrate one "substrate limit" line at c_limit."""
    from surfwave.plots.layered import limit_lines

    si = get_material("Si")
    ds = dispersion_cube("Si", [SIO2], np.array([1.0, 3.0])).isel(film_stress=0, electrical=0)
    (v1, lab1), (v2, lab2) = limit_lines(ds)
    assert (lab1, lab2) == ("limit, sagittal modes", "limit, SH modes")
    assert v1 == pytest.approx(float(surfwave.material("Si", direction="[100]")["c_limit"]), rel=1e-9)
    assert v2 == pytest.approx(np.sqrt(si.voigt[3, 3] * 1e9 / si.rho), rel=1e-9)
    iso = dispersion_cube({"E": 400.0, "nu": 0.25, "rho": 3500.0},
                          [{"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}], np.array([1.0]))
    iso = iso.isel(film_stress=0, electrical=0)
    assert limit_lines(iso) == [(float(iso["c_limit"]), "substrate limit")]
