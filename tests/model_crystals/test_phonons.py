"""Phonopy-assisted bulk sound speeds and full-zone stability.

Reference values come from closed forms (nearest-neighbour FCC at zero stress, Eq. A14 of
the triangular lattice), from the paper's Table I, and from the analytic bond sums of
``surfwave.point`` (Eq. A11); the tolerance 1e-5 relative is the acceptance bar.
"""

from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.data.variables import CUBES
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.phonons import (
    bulk_speeds,
    dynamical_matrix,
    make_phonopy,
    neighbour_table,
    pair_forces,
)
from surfwave.model_crystals.potentials import get_potential
from surfwave.model_crystals.stability import instability_limits

SPEEDS = ["c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH"]


def _assert_speeds(res, ref, keys=SPEEDS, rtol=1e-5):
    for k in keys:
        np.testing.assert_allclose(res[f"{k}_phonopy"], ref[k], rtol=rtol, atol=0, err_msg=k)


@pytest.mark.parametrize(
    "direction, ref",
    [
        ("[100]", {"c2_L_par": 1.0, "c2_T_par": 0.5, "c2_L_perp": 1.0, "c2_T_perp": 0.5, "c2_SH": 0.5}),
        ("[110]", {"c2_L_par": 1.25, "c2_T_par": 0.5, "c2_L_perp": 1.0, "c2_T_perp": 0.5, "c2_SH": 0.25}),
    ],
)
@pytest.mark.parametrize("potential", ["harmonic", "lj"])
def test_unstressed_fcc_closed_forms(direction, ref, potential):
    """Unstressed nearest-neighbour FCC, K = m = d0 = 1: V C11 : C12 : C44 = 2 : 1 : 1 with
    V = 1/sqrt 2, so c_L^2[100] = 1, c_T^2 = 1/2, c_L^2[110] = (C11 + C12 + 2 C44)/2 rho = 5/4,
    c_SH^2[110] (polarised [1-10]) = (C11 - C12)/2 rho = 1/4 (hand calculation)."""
    res = bulk_speeds("fcc", "in_plane_hydrostatic", potential, direction, [1.0])
    _assert_speeds(res, {k: np.array([v]) for k, v in ref.items()})
    assert res["stable_phonon"][0] and res["reason"][0] == ""


#: Table I bulk columns (paper_values.yaml key) and the phonopy speed each one is.
TABLE1_BULK = [("c2_L_par_100", "[100]", "c2_L_par"), ("c2_L_par_110", "[110]", "c2_L_par"),
               ("c2_T_par", "[100]", "c2_T_par"), ("c2_T_par", "[110]", "c2_T_par"),
               ("c2_L_perp", "[100]", "c2_L_perp"), ("c2_T_perp", "[100]", "c2_T_perp")]


def test_table1_bulk_columns(table1):
    """The paper's Table I (LJ, in-plane hydrostatic, d/d0 = 0.88 ... 1.10; transcribed once in
    src/surfwave/data/paper_values.yaml): every printed sound speed is reproduced by phonopy to
    the printed 4 decimals (half a unit of the last digit, plus 1e-5 relative for phonopy's
    finite displacements and the tie 0.48195 at d/d0 = 0.90), stable rows or not."""
    d = table1["d_over_d0"]
    res = {direction: bulk_speeds("fcc", "in_plane_hydrostatic", "lj", direction, d)
           for direction in ("[100]", "[110]")}
    for column, direction, name in TABLE1_BULK:
        printed = table1[column]
        ours = res[direction][f"{name}_phonopy"]
        assert np.all(np.abs(ours - printed) <= 0.5e-4 + 1e-5 * np.abs(printed)), (column, direction)


def _scene(name):
    from pathlib import Path

    from surfwave.pipeline import scenes

    cfg = scenes.load_config([Path(__file__).resolve().parents[2] / "config" / "config.yaml"])
    return scenes.validate_config(cfg)[name]


def test_every_stable_point_of_the_default_bulk_scene():
    """Acceptance taken literally: the default scene that asks for ``bulk``
    (``table1`` in config/config.yaml), with its own accuracy knobs, agrees with the analytic
    speeds of Eq. (A11) (``surfwave.point``) to 1e-5 relative at every long-wave-stable point,
    and every such point is also stable over the whole zone."""
    scene = _scene("table1")
    assert "bulk" in scene["quantities"]
    knobs = scene["accuracy"]["bulk"]
    for pot in scene["potentials"]:
        for direction in scene["directions"]:
            ref = surfwave.point(scene["lattice"], scene["loading"], pot, direction, scene["d_over_d0"])
            ok = ref["stable"]
            assert ok.sum() >= 10  # the scene reaches well into the stable range
            d = np.asarray(scene["d_over_d0"])[ok]
            res = bulk_speeds(scene["lattice"], scene["loading"], pot, direction, d, **knobs)
            _assert_speeds(res, {k: ref[k][ok] for k in SPEEDS})
            assert res["stable_phonon"].all() and (res["reason"] == "").all()


@pytest.mark.parametrize("d", [0.8, 0.9, 1.0, 1.1, 1.3])
def test_triangular_harmonic_eq_a14(d):
    """Triangular lattice, harmonic, Eq. (A14) with x = d/(2 d0): c^2 = V S, so
    c2_L_par = 4x^2 + 2x^4, c2_T_par = 6x^2 - 2x - 2x^4, c2_L_perp = 2 - 4x^2 + 2x^4,
    c2_T_perp = 2x^2 - 2x^4; no shear-horizontal branch in 2D (NaN)."""
    x = d / 2
    ref = {
        "c2_L_par": 4 * x**2 + 2 * x**4,
        "c2_T_par": 6 * x**2 - 2 * x - 2 * x**4,
        "c2_L_perp": 2 - 4 * x**2 + 2 * x**4,
        "c2_T_perp": 2 * x**2 - 2 * x**4,
    }
    res = bulk_speeds("triangular", "uniaxial", "harmonic", "[10]", [d])
    _assert_speeds(res, {k: np.array([v]) for k, v in ref.items()}, keys=list(ref))
    assert np.isnan(res["c2_SH_phonopy"][0])


CASES = [
    ("fcc", "in_plane_hydrostatic", "[100]"),
    ("fcc", "in_plane_hydrostatic", "[110]"),
    ("fcc", "uniaxial", "[100]"),
    ("fcc", "uniaxial", "[110]"),
    ("triangular", "uniaxial", "[10]"),
]


@pytest.mark.parametrize("lattice, loading, direction", CASES)
@pytest.mark.parametrize("potential, grid", [("harmonic", [0.87, 1.0, 1.12]), ("lj", [0.93, 0.97, 1.06])])
def test_agrees_with_analytic_a11(lattice, loading, direction, potential, grid):
    """Phonopy speeds against the analytic bond sums of Eq. (A11) (``surfwave.point``) at
    stable, stressed points of every default scene: agreement to 1e-5 relative."""
    ref = surfwave.point(lattice, loading, potential, direction, grid)
    assert ref["stable"].all()  # the grid is chosen inside the stable range
    res = bulk_speeds(lattice, loading, potential, direction, grid)
    keys = SPEEDS if lattice == "fcc" else SPEEDS[:4]
    _assert_speeds(res, ref, keys=keys)
    assert res["stable_phonon"].all()


def test_secant_equals_curvature():
    """The secant [D(eps n) - D(0)]/eps^2 through phonopy's dynamical matrix (error
    O(eps^2)) agrees with the curvature of D at Gamma to 1e-6 at eps = 1e-3."""
    kw = dict(lattice="fcc", loading="uniaxial", potential="lj", direction="[110]", d_over_d0=[0.96])
    a, b = bulk_speeds(**kw), bulk_speeds(**kw, long_wave="secant")
    for k in SPEEDS:
        np.testing.assert_allclose(a[f"{k}_phonopy"], b[f"{k}_phonopy"], rtol=1e-6)


def test_units_and_q_to_k_at_X():
    """Unstressed NN FCC at X = (2 pi / a)(1, 0, 0), a = sqrt 2: four bonds have k.b = pi, so
    omega_L^2 = 4 * 4 * (1/2) = 8 and omega_T^2 = 4 * 2 * (1/2) = 4 (doubly degenerate).
    Phonopy's frequencies with unit_conversion_factor = 1 are angular, in (K/m)^(1/2), at
    q = cell @ k / (2 pi)."""
    crystal = build("fcc", "in_plane_hydrostatic", None, "[100]", [1.0])
    phonon, _ = make_phonopy(crystal, 0, get_potential("lj"), 2, 1e-4)
    cell = crystal.cell3d()[0]
    k = np.array([2 * np.pi / np.sqrt(2), 0, 0])
    phonon.run_qpoints([cell @ k / (2 * np.pi)])
    freqs = np.sort(np.asarray(phonon.qpoints.frequencies)[0])
    np.testing.assert_allclose(freqs, [2.0, 2.0, 2 * np.sqrt(2)], rtol=1e-6)


def test_dynamical_matrix_equals_bond_sum_stressed():
    """At a generic k in a stressed crystal, phonopy's D(k) equals the bond sum
    sum_b 2 (1 - cos k.b) [phi'' b^b^ + (phi'/r)(1 - b^b^)] (docs/physics/paper.md, bond force
    constant including the prestress term)."""
    pot = get_potential("lj")
    crystal = build("fcc", "uniaxial", pot, "[110]", [1.04])
    phonon, bonds = make_phonopy(crystal, 0, pot, 2, 1e-4)
    k = np.array([0.7, -1.3, 0.4])
    r = np.linalg.norm(bonds, axis=1)
    u = bonds / r[:, None]
    kb = pot.d2phi(r)[:, None, None] * u[:, :, None] * u[:, None, :] + (pot.dphi(r) / r)[:, None, None] * (
        np.eye(3) - u[:, :, None] * u[:, None, :]
    )
    ref = np.einsum("b,bij->ij", 2 * (1 - np.cos(bonds @ k)), kb)
    np.testing.assert_allclose(dynamical_matrix(phonon, k, crystal.cell3d()[0]).real, ref, atol=1e-6)


def test_pair_forces_are_minus_energy_gradient():
    """Forces of the pair calculator equal -dE/du by central differences of the energy."""
    pot = get_potential("lj")
    crystal = build("fcc", "in_plane_hydrostatic", None, "[100]", [0.97])
    phonon, bonds = make_phonopy(crystal, 0, pot, 2, 1e-4)
    sc = phonon.supercell
    table = neighbour_table(sc.scaled_positions, sc.cell, bonds)
    rng = np.random.default_rng(1)
    u = 0.02 * rng.standard_normal((len(sc.positions), 3))

    def energy(v):
        r = bonds[None] + v[table] - v[:, None]
        return pot.phi(np.linalg.norm(r, axis=-1)).sum()

    f = pair_forces(u, bonds, table, pot)
    h = 1e-6
    for i, a in [(0, 0), (3, 1), (5, 2)]:
        up, um = u.copy(), u.copy()
        up[i, a] += h
        um[i, a] -= h
        assert abs(f[i, a] + (energy(up) - energy(um)) / (2 * h)) < 1e-7
    np.testing.assert_allclose(f.sum(axis=0), 0, atol=1e-12)


def test_known_unstable_points_flagged():
    """LJ in-plane hydrostatic: the paper tabulates d/d0 = 0.88 and 0.90, where c_T,par^2 > 0
    but the shear wave along the in-plane diagonal polarised across it has c^2 < 0
    (analytic Eq. A11, ``surfwave.point``, asserted first), and d/d0 = 1.15 in tension; all
    three are flagged, with the soft direction found along (+-1, 0, +-1)/sqrt 2 at 0.90.
    The expected flags are re-derived by a brute-force direction scan in
    test_golden_constants.py (edges 0.91987 and 1.11-1.12)."""
    grid = [0.88, 0.90, 0.95, 1.15]
    ref = surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[100]", grid)
    assert ref["stable"].tolist() == [False, False, True, False] and (ref["c2_T_par"][:2] > 0).all()
    res = bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", grid)
    assert res["stable_phonon"].tolist() == [False, False, True, False]
    assert (res["c2_T_par_phonopy"][:2] > 0).all()
    n = np.abs(res["min_c2_direction"][1])
    np.testing.assert_allclose(n, [2**-0.5, 0, 2**-0.5], atol=1e-3)
    assert res["min_omega2"][0] < 0 and res["min_omega2"][2] > 0


def test_separable_and_failures_are_nan():
    """Per-strain separability (the workflow caches points) and NaN + reason for a point
    whose geometry cannot exist (t^2 = 2 - 1.5^2 < 0), without raising mid-array."""
    args = ("fcc", "uniaxial", "lj", "[100]")
    both = bulk_speeds(*args, [0.97, 1.03])
    for i, d in enumerate([0.97, 1.03]):
        one = bulk_speeds(*args, [d])
        for k in both:
            a, b = both[k][i], one[k][0]
            assert (a == b) if k == "reason" else np.array_equal(a, b, equal_nan=True), k
    res = bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", [1.0, 1.5])
    assert np.isfinite(res["c2_L_par_phonopy"][0]) and np.isnan(res["c2_L_par_phonopy"][1])
    assert res["reason"][0] == "" and "GeometryError" in res["reason"][1]
    assert not res["stable_phonon"][1]


def test_instability_limit_triangular_closed_form():
    """Triangular harmonic lattice: by Eq. (A14) c2_T_par = 2x (3x - 1 - x^3) vanishes at
    x = 2 cos(80 deg), i.e. d/d0 = 4 cos(80 deg) = 0.694593; it is the softest long wave,
    and the full-zone limit (phonopy) must find it within the bisection tolerance."""
    lo, hi = instability_limits(
        "triangular", "uniaxial", "harmonic", "[10]", "full_zone", step=0.05, search=(0.6, 1.2)
    )
    assert abs(lo - 4 * np.cos(np.radians(80))) < 2e-4
    assert np.isnan(hi)  # stable up to the search bound


def test_variables_metadata_complete():
    """Every returned array has CF metadata for the workflow's cubes."""
    res = bulk_speeds("triangular", "uniaxial", "lj", "[10]", [1.0])
    table = {k: v for k, v in CUBES["bulk"].items() if not k.endswith("_deviation")}   # the rest: bulk.py
    assert set(res) == set(table)
    for name, meta in table.items():
        assert {"long_name", "dims"} <= set(meta) and ("units" in meta) != (name == "reason")
        assert res[name].shape[: len(meta["dims"])][0] == 1
        assert len(res[name].shape) == len(meta["dims"]), name


def test_min_omega2_wave_vector_is_cartesian_k():
    """The reported min_omega2_q is the Cartesian lab-frame k (rad/d0): the bond sum
    D(k) = sum_b 2 (1 - cos k.b) [phi'' b^b^ + (phi'/r)(1 - b^b^)] evaluated there has
    min_omega2 as its lowest eigenvalue (LJ under tension, d/d0 = 1.15, unstable)."""
    pot = get_potential("lj")
    res = bulk_speeds("fcc", "in_plane_hydrostatic", pot, "[100]", [1.15])
    assert res["min_omega2"][0] < -0.1
    bonds = build("fcc", "in_plane_hydrostatic", None, "[100]", [1.15]).bonds[0]
    r = np.linalg.norm(bonds, axis=1)
    u = bonds / r[:, None]
    kb = pot.d2phi(r)[:, None, None] * u[:, :, None] * u[:, None, :] + (pot.dphi(r) / r)[:, None, None] * (
        np.eye(3) - u[:, :, None] * u[:, None, :]
    )
    k = res["min_omega2_q"][0]
    d = np.einsum("b,bij->ij", 2 * (1 - np.cos(bonds @ k)), kb)
    assert abs(np.linalg.eigvalsh(d)[0] - res["min_omega2"][0]) < 1e-6


def test_long_wave_instability_missed_by_mesh_is_flagged():
    """Harmonic FCC under uniaxial [100] compression, d/d0 = 0.54: the analytic acoustic
    tensor (Eq. A11, ``surfwave.point``) has a negative eigenvalue (first long-wave
    instability at 0.553), soft only at long waves, so an 8^3 zone mesh alone sees no
    imaginary frequency; the full-zone flag must still be False. At 0.60 both are stable."""
    from surfwave.model_crystals.stability import stability_scan

    assert surfwave.point("fcc", "uniaxial", "harmonic", "[100]", [0.54], min_eig=True)["min_acoustic_eig"][0] < 0
    r = stability_scan("fcc", "uniaxial", "harmonic", "[100]", [0.54, 0.60])
    assert r["min_omega2"][0] > 0 and r["min_c2_phonopy"][0] < 0
    assert r["stable_long_wave"].tolist() == [False, True]
    assert r["stable_full_zone"].tolist() == [False, True]


def test_a_bug_is_raised_not_recorded_as_a_reason(monkeypatch):
    """Only physics failures (SurfwaveError: an impossible geometry; a singular matrix) become
    NaN + reason; any other exception is a bug and must surface (it used to be recorded as a
    `reason`, so a broken phonopy call looked like an unphysical point)."""
    from surfwave.model_crystals import phonons

    def broken(*args, **kwargs):
        raise TypeError("planted bug")

    monkeypatch.setattr(phonons, "_point", broken)
    with pytest.raises(TypeError, match="planted bug"):
        bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", [1.0])
