"""Every verdict of the reproduction report can go both ways.

For each printed value (``values:``) and each qualitative claim (``claims:``) of
src/surfwave/data/paper_values.yaml, a small synthetic cube that must PASS and one that
must FAIL (or be INCONCLUSIVE), so an inverted, loosened or dropped verdict fails here.
The specs are the real ones from paper_values.yaml; the probe values are derived here,
independently of the checking code: from the paper's printed decimals (half a unit of the
last printed digit), from the closed forms (Eq. 16, Eq. 26) and from the wording of each
claim. Cubes are built in memory (no netCDF), with the names of docs/cubes.md.

Last test: every value and claim on the real physics of the paper's scenes (grids of
config/config.yaml, computed with the library's public functions): no FAIL, and the set of
PAPER-APPROX verdicts must be exactly the known one (README, "What we found").
"""
from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from surfwave.report.checks import FAIL, INCONCLUSIVE, PAPER_APPROX, PASS, value_checks
from surfwave.report.claims import claim_checks
from surfwave.report.reproduction import load_paper_values

PV = load_paper_values()
VALUES, CLAIMS = PV["values"], PV["claims"]
FCC_DIMS = ("potential", "direction", "strain")
REPO = Path(__file__).resolve().parents[2]


class Mem:
    """The report's cube access (``.get(scene, cube)``) over in-memory Datasets."""

    def __init__(self, cubes: dict):
        self.cubes = cubes

    def get(self, scene, cube):
        return self.cubes.get((scene, cube))


def _strain_coords(d):
    d = np.asarray(d, float)
    return {"strain": np.round(d - 1.0, 12), "d_over_d0": ("strain", d)}


def verdicts(checks) -> dict[str, str]:
    """label -> verdict ('' for an unlabelled check)."""
    return {c.label: c.verdict for c in checks}


def only_verdict(checks) -> str:
    (v,) = {c.verdict for c in checks}
    return v


# --------------------------------------------------------------------------- printed values
def per_potential_cube(var, values, d=(0.95, 1.0, 1.05), pots=("harmonic",), extra_dims=None):
    """Dataset with ``var`` of dims (potential, strain[, ...]); ``values`` broadcast."""
    dims = ("potential", "strain") + tuple(extra_dims or {})
    coords = {"potential": list(pots), **_strain_coords(d), **(extra_dims or {})}
    shape = tuple(len(coords[k]) if k != "strain" else len(d) for k in dims)
    return xr.Dataset({var: (dims, np.broadcast_to(values, shape).copy())}, coords=coords)


def check_value(name, cube_ds):
    spec = VALUES[name]
    return value_checks(name, spec, Mem({(spec["scene"], spec["cube"]): cube_ds}))


def eq16(d):
    """Eq. (16) of the paper: (m/K d0^2) c_R^2 = 5x^2 - x - sqrt(4x^5 + x^4 - 2x^3 + x^2), x = d_x/d0."""
    x = np.asarray(d, float) / 2.0
    return 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)


def tri_rayleigh(c2_harmonic, c2_lj, d):
    c2 = np.stack([c2_harmonic, c2_lj])[:, None, :]
    return xr.Dataset({"c2_R": (FCC_DIMS, c2)},
                      coords={"potential": ["harmonic", "lj"], "direction": ["[10]"], **_strain_coords(d)})


def test_eq16_zero_stress_pass_and_fail():
    """(3 - sqrt 3)/4 (Eq. 16 at d_x = 1/2) passes; 2e-8 off (twice the solver precision
    the check asks for) fails, for each potential separately."""
    d = np.array([0.95, 1.0, 1.05])
    good = eq16(d)
    assert good[1] == pytest.approx((3 - math.sqrt(3)) / 4, abs=1e-15)
    bad = good.copy()
    bad[1] += 2e-8
    got = verdicts(check_value("eq16_zero_stress", tri_rayleigh(good, bad, d)))
    assert got == {"harmonic": PASS, "lj": FAIL}


def test_eq16_all_strains_pass_and_fail_harmonic_only():
    """Eq. (16) holds for Hooke springs only: the harmonic curve equal to Eq. (16) passes,
    one strain point 2e-8 off fails; the LJ curve (far from Eq. 16) is not judged."""
    d = np.array([0.9, 0.95, 1.0, 1.05, 1.1])
    lj = eq16(d) * 0.9
    assert verdicts(check_value("eq16_all_strains", tri_rayleigh(eq16(d), lj, d))) == {"harmonic": PASS}
    bad = eq16(d)
    bad[-1] -= 2e-8
    assert verdicts(check_value("eq16_all_strains", tri_rayleigh(bad, lj, d))) == {"harmonic": FAIL}


S26 = 0.5 * math.log(3) - 0.5 * math.log(0.75 - math.sqrt(3) / 4) - 0.4126784  # Eq. (26) as printed


@pytest.mark.parametrize("name, var, good, bad", [
    # printed 0.711 (3 decimals): Eq. (26) itself passes, 0.7117 is outside half a unit
    ("eq26_entropy_estimate", "S_surface_estimate", S26, 0.7117),
    # Huckaby's 0.4126784 (7 decimals): +4e-8 passes, +7e-8 fails
    ("huckaby_bulk_mean_log_omega", "bulk_mean_log_omega", 0.4126784 + 4e-8, 0.4126784 + 7e-8),
    # 'numerical lattice dynamics 0.66' (2 decimals): 0.6607 passes, 0.6656 fails
    ("entropy_lattice_dynamics", "S_surface_exact", 0.6607, 0.6656),
    # 'cell cluster 0.62': the paper calls 0.71 vs 0.62 agreement (|0.09| < 0.1); 0.73 is not
    ("entropy_cell_cluster", "S_surface_exact", 0.6607, 0.73),
])
def test_entropy_values_pass_and_fail(name, var, good, bad):
    """Entropy values: references are the printed numbers and their printed decimals
    (Sec. III.C and Eq. 26 of the seed); only the zero-stress point is judged."""
    vals = np.array([[bad, good, bad]])  # the strained points must not matter
    assert only_verdict(check_value(name, per_potential_cube(var, vals))) == PASS
    vals = np.array([[good, bad, good]])
    assert only_verdict(check_value(name, per_potential_cube(var, vals))) == FAIL


@pytest.mark.parametrize("theta_c, verdict", [
    (0.119 * math.pi, PASS),  # our crossover (README): "about pi/8"
    (math.pi / 8, PASS),
    (math.pi / 9, FAIL),  # a neighbouring fraction is not "about pi/8"
    (math.pi / 7, FAIL),
])
def test_theta_c_zero_stress(theta_c, verdict):
    """'about pi/8' (Sec. III.B): closer to pi/8 than to pi/9 or pi/7."""
    vals = np.array([[math.pi / 5, theta_c, 0.0]])
    ds = per_potential_cube("theta_c", vals)
    ds["theta"] = ("theta", np.linspace(0.1, 3.0, 8))
    assert only_verdict(check_value("theta_c_zero_stress", ds)) == verdict


def displacement_cube(ratio_pi20, ratio_other):
    """u, v (potential, strain, theta, row) decaying geometrically with depth so that
    |row 9| / |row 0| is ``ratio_pi20`` at theta = pi/20 and ``ratio_other`` elsewhere."""
    theta = np.array([math.pi / 20 - 0.01, math.pi / 4, math.pi / 2])
    rows = np.arange(12)
    per_row = np.array([ratio_pi20, ratio_other, ratio_other]) ** (1 / 9)
    amp = per_row[:, None] ** rows[None, :]  # (theta, row)
    amp = np.broadcast_to(amp, (1, 3, 3, 12))
    phase = np.exp(1j * 0.3 * rows)
    dims = ("potential", "strain", "theta", "row")
    coords = {"potential": ["harmonic"], **_strain_coords([0.95, 1.0, 1.05]), "theta": theta, "row": rows}
    return xr.Dataset({"u": (dims, 0.6 * amp * phase), "v": (dims, 0.8j * amp * phase)}, coords=coords)


def test_nine_layers_at_pi_over_20():
    """'noticeable displacements nine layers into the crystal for theta = pi/20': at least
    10 % of the surface amplitude at row 9, judged at the theta nearest pi/20 only."""
    assert only_verdict(check_value("nine_layers_pi_over_20", displacement_cube(0.3, 0.01))) == PASS
    assert only_verdict(check_value("nine_layers_pi_over_20", displacement_cube(0.05, 0.9))) == FAIL


def test_every_value_and_claim_has_a_verdict_test():
    """Guard: a new printed value or claim in paper_values.yaml needs its test here."""
    tested_values = {"eq16_zero_stress", "eq16_all_strains", "eq26_entropy_estimate",
                     "huckaby_bulk_mean_log_omega", "entropy_lattice_dynamics",
                     "entropy_cell_cluster", "theta_c_zero_stress", "nine_layers_pi_over_20"}
    assert set(VALUES) == tested_values
    assert set(CLAIMS) == set(CLAIM_TESTS)


# --------------------------------------------------------------------------- FCC claims
def fcc_cubes(strain, curves, scene="fig2"):
    """elastic and rayleigh Datasets of an FCC scene from curves
    {(potential, direction): {"c2_R": ..., "c2_T_par": ..., "stable": ...}} on ``strain``."""
    strain = np.asarray(strain, float)
    pots = sorted({p for p, _ in curves})
    dirs = sorted({d for _, d in curves})
    coords = {"potential": pots, "direction": dirs, **_strain_coords(strain + 1.0)}

    def stack(key, fill):
        return np.array([[np.asarray(curves.get((p, d), {}).get(key, fill(strain)), float)
                          for d in dirs] for p in pots])

    el = xr.Dataset({"c2_T_par": (FCC_DIMS, stack("c2_T_par", lambda s: 0.5 + 0 * s)),
                     "stress": (FCC_DIMS, stack("stress", lambda s: s)),
                     "stable": (FCC_DIMS, stack("stable", lambda s: np.ones_like(s)).astype(bool))},
                    coords=coords)
    ra = xr.Dataset({"c2_R": (FCC_DIMS, stack("c2_R", lambda s: 0.3 + 0 * s))}, coords=coords)
    return {(scene, "elastic"): el, (scene, "rayleigh"): ra}


def run_claim(name, cubes):
    return claim_checks(name, CLAIMS[name], Mem(cubes))


GRID = np.round(np.arange(-0.50, 0.2001, 0.01), 10)


def line_through_zero(s0, slope=1.0):
    """A curve positive on the tensile side, zero at strain s0 (< 0), negative beyond."""
    return slope * (GRID - s0)


def claim_vanish():
    """'Rayleigh velocities vanish just before the shear instability': c_R^2 = 0 at most 10 %
    of the instability strain before c_T,par^2 = 0 passes; 25 % early fails; vanishing
    after the instability fails; a grid that does not reach c_R^2 = 0 is INCONCLUSIVE."""
    def case(s_r, s_t):
        return run_claim("vanish_before_shear_instability", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_R": line_through_zero(s_r, 0.5), "c2_T_par": line_through_zero(s_t)}}))

    assert verdicts(case(-0.38, -0.40))["lj [100]"] == PASS  # gap 5 %
    assert verdicts(case(-0.30, -0.40))["lj [100]"] == FAIL  # gap 25 %
    assert verdicts(case(-0.42, -0.40))["lj [100]"] == FAIL  # c_R outlives the instability
    assert verdicts(case(-0.60, -0.40))["lj [100]"] == INCONCLUSIVE  # grid stops at -0.50

    # the full bulk check loses stability at -0.15, before c_R vanishes: a 25 % gap is then the
    # paper's approximation (c_T,par-only stability) being off, PAPER-APPROX; c_R outliving
    # the instability stays a FAIL even so
    def unstable_case(s_r, s_t):
        return run_claim("vanish_before_shear_instability", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_R": line_through_zero(s_r, 0.5), "c2_T_par": line_through_zero(s_t),
                              "stable": GRID > -0.15}}))

    assert verdicts(unstable_case(-0.30, -0.40))["lj [100]"] == PAPER_APPROX
    assert verdicts(unstable_case(-0.38, -0.40))["lj [100]"] == PASS
    assert verdicts(unstable_case(-0.42, -0.40))["lj [100]"] == FAIL


def claim_max_strain():
    """'about 10 % (LJ) and about 40 % (harmonic)' to one significant figure (+-5 % strain):
    limits at 12 % and 38 % pass; 17 % (LJ) fails; a bulk instability (stable = False) at
    15 % in the harmonic crystal is the stability limit even though c_T,par^2 > 0 there."""
    def case(lj_t, harm_t, harm_unstable_from=None):
        stable = np.ones_like(GRID) if harm_unstable_from is None else GRID > harm_unstable_from
        return verdicts(run_claim("max_compressive_strain", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_T_par": line_through_zero(lj_t)},
            ("harmonic", "[100]"): {"c2_T_par": line_through_zero(harm_t), "stable": stable}})))

    assert case(-0.12, -0.38) == {"lj [100]": PASS, "harmonic [100]": PASS}
    assert case(-0.17, -0.38)["lj [100]"] == FAIL
    assert case(-0.12, -0.38, harm_unstable_from=-0.153)["harmonic [100]"] == FAIL
    # ... unless the paper's 40 % is where c_R^2 vanishes (its c_T,par-only reading): PAPER-APPROX
    got = verdicts(run_claim("max_compressive_strain", fcc_cubes(GRID, {
        ("harmonic", "[100]"): {"c2_T_par": line_through_zero(-0.46), "c2_R": line_through_zero(-0.38, 0.5),
                                "stable": GRID > -0.153}})))
    assert got["harmonic [100]"] == PAPER_APPROX
    got = verdicts(run_claim("max_compressive_strain", fcc_cubes(GRID, {
        ("harmonic", "[100]"): {"c2_T_par": line_through_zero(-0.46), "c2_R": line_through_zero(-0.20, 0.5),
                                "stable": GRID > -0.153}})))
    assert got["harmonic [100]"] == FAIL            # c_R^2 = 0 at 20 %: no reading gives 40 %
    assert case(-0.12, -0.60)["harmonic [100]"] == INCONCLUSIVE  # no limit within the grid


def claim_tension():
    """LJ softens under tension (c_R^2 drops by more than 5 % at the largest tensile strain);
    harmonic does not (c_R^2 never below its zero-stress value under tension)."""
    t = np.clip(GRID, 0, None)

    def case(lj_drop, harm_dip):
        harm = 0.3 + 0.1 * t
        harm[GRID == 0.05] = 0.3 - harm_dip
        return verdicts(run_claim("tension_softening", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_R": 0.3 * (1 - lj_drop * t / t.max())},
            ("harmonic", "[100]"): {"c2_R": harm}})))

    assert case(0.20, 0.0) == {"lj [100]": PASS, "harmonic [100]": PASS}
    assert case(0.03, 0.0)["lj [100]"] == FAIL
    assert case(0.20, 1e-6)["harmonic [100]"] == FAIL


def claim_faster_110():
    """'[110] a little faster than [100] when compressed': c_R[110]/c_R[100] between 1 and
    1.2 at the long-wave stable compressed points passes; [110] slower (the inverted
    verdict of issue 14) fails; 1.5 times faster is not 'a little' and fails; a large
    ratio only where the crystal is unstable does not count."""
    comp = GRID < 0
    a = 0.3 + GRID  # c_R^2 [100], positive down to -0.3

    def case(ratio_comp, stable=None):
        b = np.where(comp, a * ratio_comp**2, a * 0.9)
        extra = {} if stable is None else {"stable": stable}
        return verdicts(run_claim("faster_110_under_compression", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_R": a, **extra}, ("lj", "[110]"): {"c2_R": b, **extra}})))["lj"]

    assert case(1.05) == PASS
    assert case(0.95) == FAIL
    assert case(1.5) == FAIL
    ratio = np.where(GRID < -0.2, 1.5, 1.05)  # blows up only beyond the instability
    assert case(ratio, stable=GRID >= -0.2) == PASS


def claim_rapid_110():
    """Under tension (LJ) c_R^2 [110] falls faster than [100] (larger relative drop at the
    largest common tensile strain): 50 % vs 10 % passes, the swap fails."""
    t = np.clip(GRID, 0, None) / GRID.max()

    def case(drop100, drop110):
        return only_verdict(run_claim("rapid_decrease_110_tension", fcc_cubes(GRID, {
            ("lj", "[100]"): {"c2_R": 0.3 * (1 - drop100 * t)},
            ("lj", "[110]"): {"c2_R": 0.35 * (1 - drop110 * t)}})))

    assert case(0.10, 0.50) == PASS
    assert case(0.50, 0.10) == FAIL


def claim_upper_bound():
    """'c_T,par is a rigorous upper bound to the Rayleigh velocity': c_R^2 <= c_T,par^2
    passes; one point 1e-6 above fails."""
    ct = 0.5 + GRID

    def case(excess):
        cr = 0.9 * ct
        cr[10] = ct[10] + excess
        return verdicts(run_claim("c_T_par_upper_bound", fcc_cubes(GRID, {
            ("lj", "[110]"): {"c2_R": cr, "c2_T_par": ct}})))["lj [110]"]

    assert case(-1e-3) == PASS
    assert case(1e-6) == FAIL


def claim_eq15():
    """Eq. (15): omega = (c_R/d_x) sin(theta), d_x = (d/d0)/2: a lattice-dynamics frequency
    within 1e-7 of it passes, one point 1e-4 off fails."""
    d = np.array([0.95, 1.0, 1.05])
    theta = np.linspace(0.1, 3.0, 5)
    c2 = eq16(d)
    omega = np.sqrt(c2)[:, None] / (d[:, None] / 2) * np.sin(theta)[None, :]

    def case(rel):
        om = omega * (1 + 1e-7)
        om[1, 2] *= 1 + rel
        disp = xr.Dataset({"omega_lattice": (("potential", "strain", "theta"), om[None])},
                          coords={"potential": ["harmonic"], **_strain_coords(d), "theta": theta})
        ray = tri_rayleigh(c2, c2, d).sel(potential=["harmonic"])
        return only_verdict(run_claim("eq15_sine_dispersion", {("triangular", "dispersion"): disp,
                                                               ("triangular", "rayleigh"): ray}))

    assert case(0.0) == PASS
    assert case(1e-4) == FAIL


def claim_theta_c_trend():
    """theta_c grows as the lattice is compressed (Sec. III.B): decreasing in d/d0 over
    compression passes; increasing (the inverted trend) fails; one bump fails."""
    d = np.array([0.90, 0.95, 1.0, 1.05])
    theta = np.linspace(0.05, 3.1, 40)

    def case(tc):
        ds = per_potential_cube("theta_c", np.asarray(tc)[None], d=d)
        ds["theta"] = ("theta", theta)
        return only_verdict(run_claim("theta_c_later_under_compression", {("triangular", "dispersion"): ds}))

    assert case([0.50, 0.43, 0.37, 0.0]) == PASS
    assert case([0.30, 0.34, 0.37, 0.0]) == FAIL
    assert case([0.50, 0.30, 0.37, 0.0]) == FAIL


def claim_uniaxial_same():
    """'qualitatively the same for uniaxial and hydrostatic stress': both scenes softening
    under tension (and lower c_R^2 when compressed) passes; only one softening fails."""
    t = np.clip(GRID, 0, None) / GRID.max()

    def curve(drop):
        return {"c2_R": 0.3 * (1 - drop * t) + 0.1 * np.clip(GRID, None, 0)}

    hyd = fcc_cubes(GRID, {("lj", "[100]"): curve(0.3)}, scene="fig2")
    for drop, verdict in ((0.2, PASS), (0.01, FAIL)):
        uni = fcc_cubes(GRID, {("lj", "[100]"): curve(drop)}, scene="fig2_uniaxial")
        assert verdicts(run_claim("uniaxial_same_as_hydrostatic", {**hyd, **uni}))["lj [100]"] == verdict


CLAIM_TESTS = {
    "vanish_before_shear_instability": claim_vanish,
    "max_compressive_strain": claim_max_strain,
    "tension_softening": claim_tension,
    "faster_110_under_compression": claim_faster_110,
    "rapid_decrease_110_tension": claim_rapid_110,
    "c_T_par_upper_bound": claim_upper_bound,
    "eq15_sine_dispersion": claim_eq15,
    "theta_c_later_under_compression": claim_theta_c_trend,
    "uniaxial_same_as_hydrostatic": claim_uniaxial_same,
}


@pytest.mark.parametrize("name", sorted(CLAIM_TESTS))
def test_claim_pass_and_fail(name):
    CLAIM_TESTS[name]()


# --------------------------------------------------------------------------- the real FCC scenes
#: Known disagreements with the paper (README, "What we found"): the harmonic crystal loses
#: bulk stability at 15 % compression, long before c_R vanishes (the paper checks only
#: c_T,par and says about 40 %): the verdict PAPER-APPROX, and no FAIL.
KNOWN_PAPER_APPROX = {("vanish_before_shear_instability", "harmonic [100]"),
               ("max_compressive_strain", "harmonic [100]"),
               ("max_compressive_strain", "harmonic [110]")}


def paper_scene_cubes():
    """In-memory cubes of the paper's scenes (grids of config/config.yaml) that the report's
    value and claim checks read, computed with the library's public functions."""
    import surfwave
    from surfwave.dynamics import dispersion, entropy, triangular_surface
    from surfwave.pipeline.scenes import load_config, validate_config

    scenes = validate_config(load_config([REPO / "config" / "config.yaml"]))
    cubes = {}
    for name in ("fig2", "fig2_uniaxial"):
        sc = scenes[name]
        curves = {}
        for pot in sc["potentials"]:
            for direction in sc["directions"]:
                r = surfwave.point("fcc", sc["loading"], pot, direction, sc["d_over_d0"])
                curves[(pot, direction)] = {k: r[k] for k in ("c2_R", "c2_T_par", "stable", "stress")}
        cubes.update(fcc_cubes(np.asarray(sc["d_over_d0"]) - 1.0, curves, scene=name))
    sc = scenes["triangular"]
    d, theta, pots = np.asarray(sc["d_over_d0"]), np.asarray(sc["theta"]), sc["potentials"]
    c2 = np.stack([surfwave.point("triangular", "uniaxial", p, "[10]", d)["c2_R"] for p in pots])
    sol = [dispersion.solve(p, d, theta) for p in pots]
    disp = [dispersion.displacements(p, d, theta) for p in pots]
    n_rows = min(x["u"].shape[-1] for x in disp)
    lattice = [triangular_surface.surface_mode(p, d, theta) for p in pots]
    base = {"potential": pots, **_strain_coords(d)}
    cubes[("triangular", "rayleigh")] = xr.Dataset(
        {"c2_R": (FCC_DIMS, c2[:, None, :])}, coords={**base, "direction": ["[10]"]})
    cubes[("triangular", "dispersion")] = xr.Dataset(
        {"theta_c": (("potential", "strain"), np.stack([x["theta_c"] for x in sol])),
         "omega_lattice": (("potential", "strain", "theta"), np.stack([x["omega_lattice"] for x in lattice]))},
        coords={**base, "theta": theta})
    dims4 = ("potential", "strain", "theta", "row")
    cubes[("triangular", "displacements")] = xr.Dataset(
        {k: (dims4, np.stack([x[k][..., :n_rows] for x in disp])) for k in ("u", "v")},
        coords={**base, "theta": theta, "row": np.arange(n_rows)})
    sc = scenes["entropy"]
    d = np.asarray(sc["d_over_d0"])
    ent = [entropy.surface_entropy(p, d, tol=sc["accuracy"]["entropy"]["tol"]) for p in sc["potentials"]]
    cubes[("entropy", "entropy")] = xr.Dataset(
        {k: (("potential", "strain"), np.stack([e[k] for e in ent]))
         for k in ("S_surface_estimate", "bulk_mean_log_omega", "S_surface_exact")},
        coords={"potential": sc["potentials"], **_strain_coords(d)})
    return cubes


def test_paper_scenes_pass_except_the_known_paper_approximations():
    """Every printed value (Table I aside: test_report, test_table1) and every claim judged
    on the real physics of the paper's scenes: each gets PASS or FAIL (no INCONCLUSIVE or
    'not computed': the grids reach what every check needs), no FAIL, and the PAPER-APPROX
    verdicts are exactly the known ones -- a new one, or a known one that silently vanishes,
    fails this test."""
    cubes = Mem(paper_scene_cubes())
    got = {}
    for name, spec in VALUES.items():
        for c in value_checks(name, spec, cubes):
            got[(name, c.label)] = c.verdict
    for name, spec in CLAIMS.items():
        for c in claim_checks(name, spec, cubes):
            got[(name, c.label)] = c.verdict
    assert {n for n, _ in got} == set(VALUES) | set(CLAIMS)
    assert set(got.values()) == {PASS, PAPER_APPROX}, {k: v for k, v in got.items() if v != PASS}
    assert {k for k, v in got.items() if v == PAPER_APPROX} == KNOWN_PAPER_APPROX
