"""A pair potential registered by a user works everywhere by name (library route).

The potential: Mie n-m, phi = [m r^-n - n r^-m] / (n m (n - m)), here 9-6 ("mie9_6", not
shipped with surfwave), which has phi'(1) = 0 and phi''(1) = 1 like every reduced-unit
potential (docs/physics/paper.md); Mie 12-6 is the paper's Lennard-Jones. References, none of them the
code path under test:
- triangular lattice: the bond sums of Eq. (A12) written out by hand (in-row bond 2x,
  inclined bonds at rest: c_L,par^2 = 4x^2 phi''(2x) + 2x^4, c_T,par^2 = 2x phi'(2x) +
  2x^2 y^2, c_L,perp^2 = 2y^4, c_T,perp^2 = 2x^2 y^2, x = d_x/d0, y^2 = 1 - x^2) and
  Eq. (20) on them; Eq. (15) against the numerical lattice-dynamics surface mode;
- FCC at zero stress: rho c_R^2 / C44 = (3 - sqrt 3)/2 along [100], (7 - sqrt 17)/4 along
  [110] (docs/physics/paper.md; every potential gives C11:C12:C44 = 2:1:1 there);
- FCC under stress: phonopy finite displacements against the analytic speeds, and the
  Mie 12-6 instance against the built-in "lj";
- surface entropy at zero stress: equal to the harmonic lattice's (same force constants).

The workflow cannot use a potential registered at run time: its jobs are fresh Python
processes that know only the potentials surfwave.model_crystals.potentials registers on import
(a scene naming any other potential fails validation before any job; test_scenes).
"""
from __future__ import annotations

import math

import numpy as np
import pytest

import surfwave
from surfwave.model_crystals import potentials
from surfwave.model_crystals.potentials import PairPotential, available_potentials, get_potential, register


def mie(n: float, m: float, name: str) -> PairPotential:
    """Mie n-m potential in reduced units (phi'(1) = 0, phi''(1) = 1), typed from its formula."""
    scale = 1.0 / (n - m)
    return PairPotential(
        name=name,
        phi=lambda r: scale * (m * np.asarray(r, float) ** -n - n * np.asarray(r, float) ** -m) / (n * m),
        dphi=lambda r: scale * (np.asarray(r, float) ** (-m - 1) - np.asarray(r, float) ** (-n - 1)),
        d2phi=lambda r: scale * ((n + 1) * np.asarray(r, float) ** (-n - 2) - (m + 1) * np.asarray(r, float) ** (-m - 2)),
        description=f"Mie {n:g}-{m:g} (user-registered in a test)",
        params={"n": n, "m": m},
    )


@pytest.fixture
def mie96():
    """Register "mie9_6" for one test, then remove it (the registry is module state; removal
    uses its internal dict, as there is no public unregister)."""
    pot = register(mie(9.0, 6.0, "mie9_6"))
    yield pot
    potentials._REGISTRY.pop("mie9_6", None)


def triangular_by_hand(pot: PairPotential, d):
    """Long-wave speeds squared of the triangular lattice from the hand-written bond sums,
    and c_R^2 of Eq. (20) on them."""
    x = 0.5 * np.asarray(d, float)
    y2 = 1.0 - x * x
    s = {"c2_L_par": 4 * x * x * pot.d2phi(2 * x) + 2 * x**4,
         "c2_T_par": 2 * x * pot.dphi(2 * x) + 2 * x * x * y2,
         "c2_L_perp": 2 * y2**2, "c2_T_perp": 2 * x * x * y2}
    a, b = s["c2_L_par"], s["c2_T_par"]
    s["c2_R"] = 0.5 * (a + b) - 0.5 * np.sqrt((a - b) ** 2 + 4 * s["c2_T_perp"] ** 3 / s["c2_L_perp"])
    return s


def test_registered_by_name_and_listed(mie96):
    assert "mie9_6" in available_potentials()
    assert get_potential("mie9_6") is mie96
    assert float(mie96.dphi(1.0)) == pytest.approx(0.0, abs=1e-15)
    assert float(mie96.d2phi(1.0)) == pytest.approx(1.0, rel=1e-15)


def test_triangular_point_matches_hand_bond_sums_and_eq20(mie96):
    d = np.array([0.93, 1.0, 1.07])
    r = surfwave.point("triangular", "uniaxial", "mie9_6", "[10]", d)
    ref = triangular_by_hand(mie96, d)
    for k in ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_R"):
        np.testing.assert_allclose(r[k], ref[k], rtol=1e-12, err_msg=k)
    assert r["stable"].all() and (r["wave_type"] == "surface").all()


def test_fcc_point_zero_stress_closed_forms_and_lj_instance(mie96):
    """At d/d0 = 1 any potential gives the nearest-neighbour FCC ratios; under stress the
    user's Mie 12-6 reproduces the built-in LJ (same function, different code)."""
    c44 = 0.5  # V C44 of nearest-neighbour FCC at zero stress, K d0^2 (test_elastic)
    ref = {"[100]": (3 - math.sqrt(3)) / 2 * c44, "[110]": (7 - math.sqrt(17)) / 4 * c44}
    for direction, c2 in ref.items():
        r = surfwave.point("fcc", "in_plane_hydrostatic", "mie9_6", direction, [0.97, 1.0, 1.03])
        assert r["c2_R"][1] == pytest.approx(c2, rel=1e-12)
        assert np.isfinite(r["c2_R"]).all() and r["stable"].all()
    register(mie(12.0, 6.0, "mie12_6_user"))
    try:
        for loading in ("in_plane_hydrostatic", "uniaxial"):
            a = surfwave.point("fcc", loading, "mie12_6_user", "[110]", [0.95, 1.04])
            b = surfwave.point("fcc", loading, "lj", "[110]", [0.95, 1.04])
            for k in ("stress", "c2_T_par", "c2_R"):
                np.testing.assert_allclose(a[k], b[k], rtol=1e-12, err_msg=(loading, k))
    finally:
        potentials._REGISTRY.pop("mie12_6_user", None)


def test_phonopy_speeds_agree_with_analytic(mie96):
    """The phonopy stage (finite displacements of the user's pair forces) against the
    analytic bond sums, under uniaxial stress: within the 1e-5 acceptance."""
    from surfwave.model_crystals.phonons import bulk_speeds

    d = [0.96]
    ph = bulk_speeds("fcc", "uniaxial", "mie9_6", "[100]", d)
    an = surfwave.point("fcc", "uniaxial", "mie9_6", "[100]", d)
    for k in ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH"):
        np.testing.assert_allclose(ph[f"{k}_phonopy"], an[k], rtol=1e-5, err_msg=k)
    assert ph["stable_phonon"].all()


def test_dispersion_and_surface_mode_and_entropy(mie96):
    """Eq. (15) with c_R^2 by hand (Eq. 20) against the analytic solution and the numerical
    semi-infinite lattice-dynamics surface mode; the zero-stress surface entropy equals the
    harmonic lattice's."""
    from surfwave.dynamics import dispersion, entropy, triangular_surface

    d, theta = np.array([0.95, 1.05]), np.array([0.2, 1.0, 2.5])
    eq15 = np.sqrt(triangular_by_hand(mie96, d)["c2_R"])[:, None] / (0.5 * d[:, None]) * np.sin(theta)
    np.testing.assert_allclose(dispersion.solve("mie9_6", d, theta)["omega"], eq15, rtol=1e-10)
    lattice = triangular_surface.surface_mode("mie9_6", d, theta)
    np.testing.assert_allclose(lattice["omega_lattice"], eq15, rtol=1e-7)
    s = entropy.surface_entropy("mie9_6", [1.0])["S_surface_exact"]
    h = entropy.surface_entropy("harmonic", [1.0])["S_surface_exact"]
    np.testing.assert_allclose(s, h, rtol=0, atol=1e-9)
