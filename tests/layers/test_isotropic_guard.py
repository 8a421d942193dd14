"""The isotropic fast path against the exact mode count (surfwave.layers.isotropic_guard).

References: the Wittrick-Williams count of surfwave.layers.counting (exact, pole-free, on the
general Stroh blocks); the general Stroh/impedance solver of surfwave.layers (forced with
``solve.FAST_ISOTROPIC = False``; it checks itself against the same count); central finite
differences of c(kh) for group velocities.
"""
from __future__ import annotations

import numpy as np
import pytest
from general_path import layered_general

import surfwave
import surfwave.layers.isotropic_guard as guard
from surfwave.layers.counting import mode_count, sublayers
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.isotropic_modes import FLOOR
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import resolve_stack

SIO2 = {"E": 73.0, "nu": 0.17, "rho": 2200.0}
SI_ISO = {"E": 170.0, "nu": 0.28, "rho": 2330.0}
ALN_ISO = {"E": 300.0, "nu": 0.22, "rho": 3200.0}
GOLD = {"E": 79.0, "nu": 0.42, "rho": 19300.0}
BURIED = (SI_ISO, [{**SIO2, "thickness": 0.4e-6}, {**ALN_ISO, "thickness": 0.3e-6}, {**GOLD, "thickness": 0.3e-6}])


_general = layered_general


def _unguarded(sub, films, **kw):
    keep = guard.guarded
    try:
        guard.guarded = lambda stack, st=None: False
        return surfwave.layered(sub, films, **kw)
    finally:
        guard.guarded = keep


def _counts(sub, films, kh):
    """Wittrick-Williams count per family {prefix: (n,)} of the modes between the grid floor and c_lim (1 - TOP),
    and the count at the floor itself."""
    stack = resolve_stack(sub, films)
    st, b = iso_stack(stack), scaled_blocks(stack)
    c = np.array([FLOOR * float(st.shear.min()), st.c_lim * (1.0 - guard.TOP)])
    out, floor = {}, {}
    for fam in families(b):
        n = mode_count(b, fam, c, kh[None, :], "free", sublayers(b, float(kh.max()), float(c[1])))
        out[fam.prefix], floor[fam.prefix] = n[1] - n[0], n[0]
    return out, floor, st.c_lim * (1.0 - guard.TOP)


def _per_family(r, prefix, c_top):
    first = ("R", "S") if prefix == "R" else ("L",)
    fam = np.array([[bool(m) and m[0] in first for m in row] for row in r["mode"]])
    return (fam & (r["c"] < c_top)).sum(axis=1)


def _random_stack(rng):
    def mat(E, rho):
        return {"E": float(rng.uniform(*E)), "nu": float(rng.uniform(0.05, 0.42)), "rho": float(rng.uniform(*rho))}
    sub = mat((150.0, 600.0), (2000.0, 5000.0))
    films = [{**mat((40.0, 600.0), (1800.0, 20000.0)), "thickness": float(rng.uniform(0.1, 1.0)) * 1e-6}
             for _ in range(int(rng.integers(1, 4)))]
    return sub, films


def test_random_stacks_count_and_general_path():
    """20 seeded random isotropic stacks (1-3 films, light to heavy, slow to fast; kh 0.1 ... 60): per
    row and family the fast path's number of modes below c_lim (1 - 1e-9) equals the Wittrick-Williams
    count (and the count at the grid floor is 0), and every mode equals the general solver's to 1e-9,
    labels included."""
    rng = np.random.default_rng(20261127)
    kh = np.array([0.1, 0.9, 4.0, 13.0, 31.0, 60.0])
    for _ in range(20):
        sub, films = _random_stack(rng)
        fast = surfwave.layered(sub, films, kh=kh)
        counts, floor, c_top = _counts(sub, films, kh)
        for prefix, n in counts.items():
            assert (floor[prefix] == 0).all()
            assert (_per_family(fast, prefix, c_top) == n).all(), (sub, films, prefix)
        gen = _general(sub, films, kh=kh)
        assert fast["mode"].shape == gen["mode"].shape and (fast["mode"] == gen["mode"]).all()
        ok = np.isfinite(gen["c"])
        assert (np.isfinite(fast["c"]) == ok).all()
        assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-9, atol=0)


def test_buried_gold_at_large_kh_every_mode():
    """Buried gold (SiO2 / AlN-like / gold on Si-like) at kh = 57.2, 87.8, 89.8, where the grid alone
    misses close pairs: every mode (70, 106, 111 of them) equals the general solver's to 1e-9, labels
    included, and the count per family; without the guard the fast path finds fewer."""
    sub, films = BURIED
    kh = np.array([57.2, 87.8, 89.8])
    fast, gen = surfwave.layered(sub, films, kh=kh), _general(sub, films, kh=kh)
    assert fast["mode"].shape == gen["mode"].shape and (fast["mode"] == gen["mode"]).all()
    ok = np.isfinite(gen["c"])
    assert (np.isfinite(fast["c"]) == ok).all()
    assert np.allclose(fast["c"][ok], gen["c"][ok], rtol=1e-9, atol=0)
    counts, _, c_top = _counts(sub, films, kh)
    for prefix, n in counts.items():
        assert (_per_family(fast, prefix, c_top) == n).all()
    raw = _unguarded(sub, films, kh=kh)
    assert np.isfinite(raw["c"]).sum() < np.isfinite(fast["c"]).sum()


def test_repaired_rows_and_modes_keyword():
    """kh = 20 of buried gold, where the grid alone misses two sagittal modes: the guarded fast path
    has every mode of the general solver; with ``modes`` = 12 (the 12 slowest of each family) each
    mode equals the general solver's (1e-9, same label)."""
    sub, films = BURIED
    raw = _unguarded(sub, films, kh=[20.0])
    fast, gen = surfwave.layered(sub, films, kh=[20.0]), _general(sub, films, kh=[20.0])
    assert np.isfinite(raw["c"]).sum() < np.isfinite(gen["c"]).sum() == np.isfinite(fast["c"]).sum()
    m = surfwave.layered(sub, films, kh=[20.0], modes=12)
    for lab, c in zip(m["mode"][0], m["c"][0]):
        j = list(gen["mode"][0]).index(lab)
        assert c == pytest.approx(gen["c"][0, j], rel=1e-9)
    assert sum(str(x).startswith(("R", "S")) for x in m["mode"][0]) == 12


def test_repaired_row_at_fixed_frequency():
    """Buried gold at 35.6 GHz (kh ~ 70), where the grid alone misses two modes: per family the number
    of modes equals the Wittrick-Williams count taken along the row (kh = omega H / c at each speed),
    and each mode the guard adds, and every 8th, (c, kh) is a mode of the fixed-kh answer at its kh
    (1e-9, same label; that answer is checked against the general solver above)."""
    sub, films = BURIED
    f = np.linspace(3e10, 9e10, 300)[28:29]
    fast, raw = surfwave.layered(sub, films, frequency=f), _unguarded(sub, films, frequency=f)
    assert np.isfinite(raw["c"]).sum() < np.isfinite(fast["c"]).sum()
    stack = resolve_stack(sub, films)
    st, b = iso_stack(stack), scaled_blocks(stack)
    wH = 2 * np.pi * f[0] * stack.total_thickness
    c = np.array([FLOOR * float(st.shear.min()), st.c_lim * (1.0 - guard.TOP)])
    for fam in families(b):
        n = mode_count(b, fam, c, (wH / c)[:, None], "free", sublayers(b, wH / c[1], float(c[1])))[:, 0]
        assert n[0] == 0 and _per_family(fast, fam.prefix, c[1])[0] == n[1]
    ok = np.isfinite(fast["c"][0])
    near = np.abs(fast["c"][0][:, None] / raw["c"][0][None, :] - 1.0) <= 1e-9
    added = ~np.any(near, axis=1)                                      # the modes the guard adds
    assert added.sum() == np.isfinite(fast["c"]).sum() - np.isfinite(raw["c"]).sum()
    ok &= added | (np.arange(ok.size) % 8 == 0)
    kh = fast["kh"][0][ok]
    at_kh = surfwave.layered(sub, films, kh=kh)
    for i, (lab, ci) in enumerate(zip(fast["mode"][0][ok], fast["c"][0][ok])):
        j = list(at_kh["mode"][i]).index(lab)
        assert at_kh["c"][i, j] == pytest.approx(ci, rel=1e-9)


@pytest.mark.parametrize("kh", [10.0, 20.0])
def test_group_velocity_of_trapped_and_repaired_modes(kh):
    """Buried gold at kh = 10 (L0 and R trapped in the gold) and kh = 20 (two modes the guard adds):
    every mode's group velocity c + kh dc/dkh equals central finite differences of c(kh) (step 1e-6 in
    kh) to 1e-6 relative."""
    sub, films = BURIED
    h = 1e-6
    r = surfwave.layered(sub, films, kh=[kh - h, kh, kh + h])
    assert (r["mode"][0] == r["mode"][1]).all() and (r["mode"][2] == r["mode"][1]).all()
    ok = np.isfinite(r["c"][1])
    fd = r["c"][1] + kh * (r["c"][2] - r["c"][0]) / (2 * h)
    assert np.allclose(r["group_velocity"][1][ok], fd[ok], rtol=1e-6, atol=0)


def test_group_velocity_of_a_deeply_trapped_love_mode():
    """A Love mode trapped in the slow bottom film of three, under a barrier of a faster, heavy film
    (kh = 60, L0 at 2590.4 m/s): F = tau / |(v, tau)| swings through 0 within rounding of c there, so
    the group velocity must come from the ratio of tau's own derivatives: equal to central
    differences of c(kh) (steps 1e-4 and 1e-3 in kh, which agree to 1e-9) to 1e-7 (it was 2550.75
    against 2549.83 m/s)."""
    sub = {"E": 559.09, "nu": 0.3387, "rho": 3759.5}
    films = [{"E": 538.46, "nu": 0.2405, "rho": 18129.5, "thickness": 0.9321e-6},
             {"E": 345.16, "nu": 0.2762, "rho": 5291.4, "thickness": 0.3108e-6},
             {"E": 145.86, "nu": 0.4103, "rho": 7833.0, "thickness": 0.8185e-6}]
    kh = 60.0
    for h in (1e-4, 1e-3):
        r = surfwave.layered(sub, films, kh=[kh - h, kh, kh + h])
        j = [list(r["mode"][q]).index("L0") for q in range(3)]
        fd = r["c"][1, j[1]] + kh * (r["c"][2, j[2]] - r["c"][0, j[0]]) / (2 * h)
        assert r["group_velocity"][1, j[1]] == pytest.approx(fd, rel=1e-7)


def _shear_layer(vs: float, rho: float, nu: float) -> dict:
    """An isotropic layer of shear speed vs (m/s), density rho (kg/m^3) and Poisson ratio nu (E in GPa)."""
    return {"E": 2.0 * (1.0 + nu) * rho * vs ** 2 / 1e9, "nu": nu, "rho": rho}


FAST_SUB = _shear_layer(11871.0, 19059.0, 0.427)
FAST_FILM = dict(_shear_layer(200.0, 10725.0, 0.065), thickness=1e-6)


def test_one_high_contrast_film_is_counted():
    """A film of shear speed 200 m/s on a substrate of 11871 m/s at kh = 0.7 called alone: the grid by itself
    lost the pair S21 / S22 (11217.48, 11305.99 m/s) in the cell next to S20's sign change, where no hunt
    starts. One film of contrast above CONTRAST is counted, so the default call has every mode. Reference: the
    general (Stroh) path on the same stack (solve.FAST_ISOTROPIC = False): the same labels, speeds to 1e-8."""
    from surfwave.layers import solve
    from surfwave.layers.isotropic import iso_stack
    from surfwave.layers.stack import resolve_stack

    fast = surfwave.layered(FAST_SUB, [FAST_FILM], kh=[0.7])
    keep = solve.FAST_ISOTROPIC
    solve.FAST_ISOTROPIC = False
    try:
        general = surfwave.layered(FAST_SUB, [FAST_FILM], kh=[0.7])
    finally:
        solve.FAST_ISOTROPIC = keep
    assert list(fast["mode"][0]) == list(general["mode"][0])
    np.testing.assert_allclose(fast["c"], general["c"], rtol=1e-8)
    assert {"S21", "S22"} <= set(fast["mode"][0])
    # the rule itself: this stack is counted, the low-contrast stack of the disba comparison is not
    stack = resolve_stack(FAST_SUB, [FAST_FILM])
    assert guard.guarded(stack, iso_stack(stack))
    low = resolve_stack({"E": 400.0, "nu": 0.25, "rho": 3500.0}, [{"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}])
    assert not guard.guarded(low, iso_stack(low))
