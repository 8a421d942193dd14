"""Modes trapped in a slow layer buried under a stiff one (their zero of det Z hides next to a pole).

References: the isotropic fast path (surfwave.layers.isotropic: compound matrices, pole-free, an
independent formulation) for the general solver forced on isotropic stacks; the Chebyshev
collocation route of tests/layers/layers_collocation.py for an anisotropic stack off a mirror.
"""
from __future__ import annotations

import numpy as np
import pytest
from general_path import layered_general
from layers_collocation import collocation_speeds

import surfwave
from surfwave.layers.counting import mode_count, sublayers
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import resolve_stack

SIO2 = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
SI_ISO = {"E": 170.0, "nu": 0.28, "rho": 2330.0}
ALN_ISO = {"E": 300.0, "nu": 0.22, "rho": 3200.0}
GOLD = {"E": 79.0, "nu": 0.42, "rho": 19300.0}
BURIED = (SI_ISO, [{**SIO2, "thickness": 0.4e-6}, {**ALN_ISO, "thickness": 0.3e-6}, {**GOLD, "thickness": 0.3e-6}])
#: Cubic gold (Neighbours & Alers 1958, GPa), crystal axes = lab axes.
AU_CUBIC = {"voigt": [[192.3, 163.1, 163.1, 0, 0, 0], [163.1, 192.3, 163.1, 0, 0, 0], [163.1, 163.1, 192.3, 0, 0, 0],
                      [0, 0, 0, 42.0, 0, 0], [0, 0, 0, 0, 42.0, 0], [0, 0, 0, 0, 0, 42.0]], "rho": 19300.0}


_general = layered_general


def _same_record(fast, gen, rtol):
    assert fast["mode"].shape == gen["mode"].shape
    assert (fast["mode"] == gen["mode"]).all()
    assert (np.isnan(fast["c"]) == np.isnan(gen["c"])).all()
    ok = np.isfinite(gen["c"])
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=rtol, atol=0)


def test_buried_gold_general_path_equals_the_isotropic_path():
    """SiO2 / AlN-like / gold on Si-like: every sagittal and SH mode of the general solver (forced) at
    kh = 10 and on a kh sweep 0.5 ... 20 equals the isotropic fast path (compound matrices, no poles)
    to 1e-9, labels included; R at kh = 10 is the trapped fundamental mode (1930.19 m/s)."""
    sub, films = BURIED
    for kh in ([10.0], np.linspace(0.5, 20.0, 25)):
        fast = surfwave.layered(sub, films, kh=kh)
        gen = _general(sub, films, kh=kh)
        _same_record(fast, gen, 1e-9)
    r = _general(sub, films, kh=[10.0])
    assert list(r["mode"][0][:2]) == ["L0", "R"] and r["c"][0, 1] == pytest.approx(1930.19, abs=0.01)


def test_buried_gold_at_fixed_frequency():
    """The same stack at fixed frequencies (each mode at its own kh, L0 trapped too): the general solver
    equals the isotropic fast path to 1e-9, labels included."""
    sub, films = BURIED
    f = np.array([3e8, 1.5e9, 3e9])
    _same_record(surfwave.layered(sub, films, frequency=f), _general(sub, films, frequency=f), 1e-9)


@pytest.mark.parametrize(("direction", "stress", "n_trapped"), [(20.0, (None, None), 3), (35.0, (0.5, -0.3), 4)])
def test_trapped_modes_of_a_crystal_film_off_a_mirror_against_collocation(direction, stress, n_trapped):
    """Cubic gold under a stiff film on Si (001), off [100] (all components couple), unstressed and with
    film stresses (0.5 GPa on the stiff film, -0.3 GPa on the gold, equibiaxial): every mode below
    0.95 c_limit at kh = 4 and 10 equals the Chebyshev collocation route (films and a clamped 40/k-deep
    substrate slice, tests/layers/layers_collocation.py, with the stressed tensors A), one to one, to
    1e-8; at kh = 10 several are trapped in the gold and the scan of det Z alone finds fewer."""
    films = [{**ALN_ISO, "thickness": 0.7e-6}, {**AU_CUBIC, "thickness": 0.3e-6}]
    for f, s in zip(films, stress):
        if s is not None:
            f["stress"] = s
    st = resolve_stack("Si", films, direction=direction)
    for kh in (4.0, 10.0):
        r = surfwave.layered("Si", films, direction=direction, kh=[kh])
        ref = collocation_speeds([f.A for f in st.films], [f.rho for f in st.films],
                                 [kh * f.thickness / 1e-6 for f in st.films], st.substrate.A, st.substrate.rho)
        ref = ref[ref < 0.95 * r["c_limit"]]
        got = r["c"][0][np.isfinite(r["c"][0])]
        got = got[got < 0.95 * r["c_limit"]]
        assert all(str(m).startswith("M") for m in r["mode"][0] if m)
        assert got.size == ref.size and np.allclose(got, ref, rtol=1e-8, atol=0)
    assert ref[0] < 1900.0
    # the trapped ones: absent from the scan of det Z without the count
    b = scaled_blocks(st)
    fam = families(b)[0]
    scan_only = _scan_without_count(b, fam, 10.0)
    assert ref.size - np.sum(scan_only < 0.95 * r["c_limit"]) == n_trapped


def _scan_without_count(b, fam, kh):
    """The modes of the det Z scan alone (surfwave.layers.modes with the count switched off)."""
    import surfwave.layers.modes as modes

    keep = modes.needed
    try:
        modes.needed = lambda *a: False
        c = modes.family_modes(b, fam, np.array([kh]))[0]
    finally:
        modes.needed = keep
    return c[np.isfinite(c)]


def test_count_equals_the_number_of_modes_of_the_fast_path():
    """The Wittrick-Williams count at c (surfwave.layers.counting.mode_count) is the number of modes
    below c of the isotropic fast path, per family, at speeds halfway between its modes (kh = 10)."""
    sub, films = BURIED
    b = scaled_blocks(resolve_stack(sub, films))
    fast = surfwave.layered(sub, films, kh=[10.0])
    for fam in families(b):
        c_lim = float(np.sqrt(fam.X_limit * b.sA / b.rho[-1]))
        prefix = ("R", "S") if fam.kind == "sagittal" else ("L",)
        c = np.sort([x for x, m in zip(fast["c"][0], fast["mode"][0]) if m and m[0] in prefix])
        probe = np.r_[0.5 * c[0], 0.5 * (c[1:] + c[:-1]), 0.5 * (c[-1] + c_lim)]
        n = mode_count(b, fam, probe, np.array([[10.0]]), "free", sublayers(b, 10.0, c_lim))[:, 0]
        assert (n - n[0] == np.arange(probe.size)).all()


def test_zero_frequency_gives_the_bare_substrate_on_both_paths():
    """f = 0: the general solver (forced) gives R at the substrate's Rayleigh speed with kh = 0, as the
    isotropic path does (the stack at zero frequency is the bare substrate), 1e-12."""
    sub, films = BURIED
    fast = surfwave.layered(sub, films, frequency=[0.0, 1e9])
    gen = _general(sub, films, frequency=[0.0, 1e9])
    assert list(gen["mode"][0][:1]) == ["R"] and gen["kh"][0, 0] == 0.0
    _same_record(fast, gen, 1e-9)
    assert gen["c"][0, 0] == pytest.approx(fast["c"][0, 0], rel=1e-12)


#: Si (001) cubic constants (GPa; McSkimin 1953) with a permittivity, for piezoelectric stacks.
SI_CUBIC = {"voigt": [[165.7, 63.9, 63.9, 0, 0, 0], [63.9, 165.7, 63.9, 0, 0, 0], [63.9, 63.9, 165.7, 0, 0, 0],
                      [0, 0, 0, 79.6, 0, 0], [0, 0, 0, 0, 79.6, 0], [0, 0, 0, 0, 0, 79.6]], "rho": 2330.0,
            "permittivity": 11.7}


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_trapped_modes_of_a_weakly_piezoelectric_stack(electrical):
    """The piezoelectric code path (u and phi, 8 x 8 Stroh, free or metallized top): the gold film carries
    piezoelectric constants of 1e-5 C/m^2 (every component couples to phi, a shift of ~1e-13 in c), so
    every mode below 0.95 c_limit at kh = 10 equals the elastic Chebyshev collocation route to 1e-8,
    the trapped ones (missed by the det Z scan alone) included."""
    e = np.zeros((3, 6))
    e[0, 4] = e[1, 3] = 1e-5
    e[2, 0] = e[2, 1] = -1e-5
    e[2, 2] = 2e-5
    films = [{**ALN_ISO, "permittivity": 9.0, "thickness": 0.7e-6},
             {**AU_CUBIC, "piezo": e.tolist(), "permittivity": 6.0, "thickness": 0.3e-6}]
    st = resolve_stack(SI_CUBIC, films, direction=20.0)
    b = scaled_blocks(st)
    (fam,) = families(b)
    assert fam.idx == (0, 1, 2, 3)
    r = surfwave.layered(SI_CUBIC, films, direction=20.0, kh=[10.0], electrical=electrical)
    ref = collocation_speeds([f.A for f in st.films], [f.rho for f in st.films], [10.0 * f.thickness / 1e-6
                                                                                   for f in st.films],
                             st.substrate.A, st.substrate.rho)
    ref = ref[ref < 0.95 * r["c_limit"]]
    got = r["c"][0][np.isfinite(r["c"][0])]
    got = got[got < 0.95 * r["c_limit"]]
    assert got.size == ref.size == 8 and np.allclose(got, ref, rtol=1e-8, atol=0)
    assert np.sum(_scan_without_count(b, fam, 10.0) < 0.95 * r["c_limit"]) < ref.size


def test_group_velocity_of_trapped_modes_against_finite_differences():
    """Buried gold, general solver (forced): the energy velocity of the trapped modes L0, R, S1, L1 at
    kh = 10 and 20 equals d(c kh)/dkh by central differences (step 1e-5) of the solver's own speeds, 1e-6."""
    sub, films = BURIED
    d = 1e-5
    for k in (10.0, 20.0):
        r = _general(sub, films, kh=[k - d, k, k + d])
        for lab in ("L0", "R", "S1", "L1"):
            j = [list(r["mode"][i]).index(lab) for i in range(3)]
            fd = (r["c"][2, j[2]] * (k + d) - r["c"][0, j[0]] * (k - d)) / (2 * d)
            assert r["group_velocity"][1, j[1]] == pytest.approx(fd, rel=1e-6), (k, lab)


def test_slow_flexural_mode_under_a_heavy_top_film():
    """A heavy top film on a soft one (three films): at kh = 3 the general solver's R lies below 0.95 x
    every layer's Rayleigh speed (2211.7 m/s); it equals the root (brentq) of the isotropic P-SV secular
    function (compound matrices, surfwave.layers.isotropic.secular_psv) to 1e-10."""
    from scipy.optimize import brentq

    from surfwave.layers.isotropic import iso_stack, secular_psv

    sub = {"E": 281.82, "nu": 0.1972, "rho": 5138.9}
    films = [{"E": 268.34, "nu": 0.2204, "rho": 13215.7, "thickness": 5.486e-7},
             {"E": 66.63, "nu": 0.3666, "rho": 2930.1, "thickness": 8.448e-7},
             {"E": 415.74, "nu": 0.3957, "rho": 13959.2, "thickness": 2.446e-7}]
    r = _general(sub, films, kh=[3.0])
    c_r = r["c"][0, list(r["mode"][0]).index("R")]
    st = iso_stack(resolve_stack(sub, films))
    ref = brentq(lambda x: secular_psv(st, np.array([x]), np.array([[3.0]]))[0, 0], 2150.0, 2260.0, xtol=1e-12)
    assert c_r == pytest.approx(ref, rel=1e-10)
    assert c_r < 0.95 * 2600.0                   # the slowest Rayleigh speed, the top film's, is about 2650 m/s
