"""Leaky continuation above the substrate's limiting speed (complex speed, dB per wavelength)."""
from __future__ import annotations

import numpy as np
import pytest

import surfwave


def test_zero_thickness_leaky_root_is_the_half_space_one():
    """kh = 0 on Cu (001) at 35 deg: the stack's leaky mode is the half-space pseudo-SAW of
    surfwave.material(leaky=True) (surfwave.solvers.leaky, an independent search), speed and
    attenuation to 1e-9; a film then changes it smoothly."""
    m = surfwave.material("Cu", direction=35.0, leaky=True)
    r = surfwave.layered("Cu", [{"name": "SiO2", "thickness": 1e-6}], direction=35.0, kh=[0.0, 0.01],
                         leaky=True)
    j = list(r["mode"][0]).index("M1~")
    assert r["c"][0, j] == pytest.approx(m["c_leaky"], rel=1e-9)
    assert r["attenuation"][0, j] == pytest.approx(m["leaky_attenuation"], rel=1e-7)
    assert r["mode"][1, j] == "M1~"
    assert abs(r["c"][1, j] - r["c"][0, j]) < 0.01 * r["c"][0, j]
    assert np.isnan(r["group_velocity"][0, j])


def test_stiff_film_rayleigh_mode_becomes_leaky_not_dropped():
    """Diamond on Si (001)[100]: the Rayleigh mode rises with kh; at kh = 1 it lies above the substrate's
    limiting speed and is reported as the leaky 'R~' with a positive attenuation (without leaky=True the
    row is empty and says why)."""
    kh = [0.8, 1.0]
    r = surfwave.layered("Si", [{"name": "diamond", "thickness": 1e-6}], kh=kh, leaky=True)
    assert r["mode"][0, 0] == "R" and r["c"][0, 0] < r["c_limit"]
    assert r["mode"][1, 0] == "R~"
    assert r["c"][1, 0] > r["c_limit"]
    assert 0 < r["attenuation"][1, 0] < 1.0
    plain = surfwave.layered("Si", [{"name": "diamond", "thickness": 1e-6}], kh=kh)
    assert plain["c"].shape[1] == 1 and np.isnan(plain["c"][1, 0]) and plain["reason"][1] != ""
    assert np.isnan(plain["attenuation"]).all()
