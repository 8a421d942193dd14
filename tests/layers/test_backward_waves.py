"""Backward waves (v_g < 0) at fixed frequency on the general path: every crossing of a branch with the frequency.

A soft heavy film (shear speed ~550 m/s) on a much stiffer substrate has a Sezawa branch whose omega(kh) first
rises, then falls (v_g < 0), then rises again: between its local minimum and maximum of omega H one frequency meets
it three times. References, per test: the isotropic fast path (compound matrices, its own root search at fixed
frequency, left unchecked on one film), and fixed-kh solves of the general path (no frequency machinery: the
same (c, kh = omega H / c) must be a mode at kh; a dense kh scan of every branch, with sign changes of
omega H - target counted, gives the number of crossings; central differences of c(kh) kh give the group velocity).
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
import surfwave.layers.isotropic_guard as guard
from surfwave.layers import solve
from surfwave.layers.frequency import mode_speeds_at_frequency
from surfwave.layers.stack import resolve_stack

H = 1.0e-6
#: A random one-film stack (seed 2077 of the study of unchecked against checked isotropic answers): its S3 branch
#: has omega H between 3983.2 (kh 2.05, a minimum) and 4066.9 m/s (kh 0.64, a maximum) three times.
ISO_SUB = {"E": 681.6019454227651, "nu": 0.1233962647007325, "rho": 1449.2962671448738}
ISO_FILM = {"E": 4.139906256531708, "nu": 0.188408244626737, "rho": 5692.229565476481, "thickness": H}
#: The study's row 54 (omega H = 4042.95 m/s: S3 1358.98, S4 4099.17 backward, S5 8601.08 m/s) and omega H below,
#: inside and above the backward window, one of them 0.4 m/s below the branch's maximum.
ISO_WH = np.array([643455672.660757 * 2 * np.pi * H, 3970.0, 4000.0, 4060.0, 4066.5, 4080.0])
#: The same film on diamond (001)[100] (cubic, general path): its S3 branch's omega H has a maximum of 4088.79 m/s
#: at kh ~0.59; 4088.78 is 0.01 m/s below it, where its two crossings are 0.009 apart in kh (a tenth of the start grid's step).
DIAMOND_WH = np.array([4040.0, 4070.0, 4088.78])


def _branch_crossings(r, kh, wH):
    """Crossings of each fixed-kh branch with each omega H (n,), counted per family on a dense kh scan ``r``.

    Sign changes of c kh - omega H between consecutive kh holding the branch; a branch entering (at c = its
    family's limit) between two kh of the scan, kh_a without it and kh_b with it, enters with omega H between
    limit x kh_a and c kh_b: a target there is ambiguous for the scan and is refused, one below that band
    is not met by the branch's start, one above it is met there only if the branch rises from below it.
    Returns {family prefix: (n,) counts}.
    """
    counts: dict[str, np.ndarray] = {}
    for lab in sorted(set(r["mode"].ravel().tolist()) - {""}):
        fam = "R" if lab[0] in "RS" else lab[0]
        has = np.array([lab in list(m) for m in r["mode"]])
        i = np.flatnonzero(has)
        c = np.array([r["c"][q][list(r["mode"][q]).index(lab)] for q in i])
        lim = r["mode_limit"][i[0]][list(r["mode"][i[0]]).index(lab)]
        d = np.sign(c[None, :] * kh[i][None, :] - wH[:, None])
        n = (d[:, 1:] * d[:, :-1] < 0).sum(axis=1)
        if i[0] > 0:
            lo, hi = lim * kh[i[0] - 1], c[0] * kh[i[0]]
            assert not np.any((wH >= lo) & (wH <= hi)), f"a target within the scan's step of {lab}'s cut-off"
        counts[fam] = counts.get(fam, 0) + n
    return counts


def test_isotropic_stack_general_path_equals_isotropic_path(monkeypatch):
    """Soft heavy film on a stiff isotropic half-space, six frequencies in and around the backward window: the
    general path (solve.FAST_ISOTROPIC = False) finds every mode of the isotropic path (unchecked), with the same
    labels (ranks within the family), speeds to 1e-8 and group velocities to 1e-6 (the backward ones included);
    at the study's row, S3, S4 (v_g -92.6 m/s) and S5 lie on one branch."""
    monkeypatch.setattr(guard, "ALWAYS", False, raising=False)
    f = ISO_WH / (2 * np.pi * H)
    iso = surfwave.layered(ISO_SUB, [ISO_FILM], frequency=f)
    monkeypatch.setattr(solve, "FAST_ISOTROPIC", False)
    gen = surfwave.layered(ISO_SUB, [ISO_FILM], frequency=f)
    n = np.isfinite(iso["c"]).sum(axis=1)
    np.testing.assert_array_equal(np.isfinite(gen["c"]).sum(axis=1), n)
    m = int(n.max())
    np.testing.assert_array_equal(gen["mode"][:, :m], iso["mode"][:, :m])
    np.testing.assert_allclose(gen["c"][:, :m], iso["c"][:, :m], rtol=1e-8)
    np.testing.assert_allclose(gen["group_velocity"][:, :m], iso["group_velocity"][:, :m], rtol=1e-6)
    row = list(gen["mode"][0])
    c, vg = gen["c"][0], gen["group_velocity"][0]
    assert abs(c[row.index("S4")] - 4099.17) < 0.01 and abs(c[row.index("S5")] - 8601.08) < 0.01
    assert abs(vg[row.index("S4")] + 92.64) < 0.01
    backward = np.nansum(gen["group_velocity"] < 0, axis=1)
    np.testing.assert_array_equal(backward, [1, 0, 1, 1, 1, 0])  # inside the window: one each; below, above: none
    # the same three speeds at kh = omega H / c are modes of the general path at fixed kh (one branch, S3)
    kh = ISO_WH[0] / c[[row.index("S3"), row.index("S4"), row.index("S5")]]
    at_kh = surfwave.layered(ISO_SUB, [ISO_FILM], kh=kh)
    for i, lab in enumerate(("S3", "S4", "S5")):
        assert at_kh["mode"][i][np.nanargmin(np.abs(at_kh["c"][i] - c[row.index(lab)]))] == "S3"


#: A film 70 times slower than its substrate and 12 times denser (shear 156 against ~15000 m/s): its modes crowd
#: near the floor (a call at one small kh gets a speed grid that holds them: test_single_kh_grid.py).
SLOW_SUB = {"E": 645.8731811250179, "nu": 0.0944253498173546, "rho": 1319.73508333182}
SLOW_FILM = {"E": 1.0507174046061092, "nu": 0.328625655480177, "rho": 16321.33118120104, "thickness": H}


def test_very_slow_heavy_film_general_path_equals_isotropic_path(monkeypatch):
    """A very slow heavy film: at omega H = 241 m/s the general path finds the isotropic path's L0, R and S1 (labels,
    speeds 1e-8), R at kh 0.076 inside the first cell of the start grid, where c falls from 13339 to 2326 m/s;
    at 872 m/s its S2 (named: mode_speeds_at_frequency) is the isotropic path's 586.15 m/s
    (found on the start curve; Newton's iterates must be solved on the same speed grid, or branch 2 is another mode
    at kh 1.49: 1157.07 m/s was reported)."""
    monkeypatch.setattr(guard, "ALWAYS", False, raising=False)
    f = np.array([241.24026391296005, 872.1872968660834]) / (2 * np.pi * H)
    iso = surfwave.layered(SLOW_SUB, [SLOW_FILM], frequency=f)
    monkeypatch.setattr(solve, "FAST_ISOTROPIC", False)
    gen = surfwave.layered(SLOW_SUB, [SLOW_FILM], frequency=f[:1])
    assert list(gen["mode"][0]) == list(iso["mode"][0][:3]) == ["L0", "R", "S1"]
    np.testing.assert_allclose(gen["c"][0], iso["c"][0, :3], rtol=1e-8)
    s2 = list(iso["mode"][1]).index("S2")
    assert abs(iso["c"][1, s2] - 586.15) < 0.01
    np.testing.assert_allclose(mode_speeds_at_frequency(resolve_stack(SLOW_SUB, [SLOW_FILM]), f[1:], "S2"),
                               iso["c"][1, s2], rtol=1e-8)


@pytest.fixture(scope="module")
def diamond():
    """The soft heavy film on diamond (001)[100] at DIAMOND_WH, general path (a cubic substrate)."""
    film = {"E": 4.14, "nu": 0.188, "rho": 5692.0, "thickness": H}
    stack = resolve_stack("C-diamond", [film])
    assert not solve.use_fast_path(stack)
    return film, stack, surfwave.layered("C-diamond", [film], frequency=DIAMOND_WH / (2 * np.pi * H))


def test_anisotropic_every_crossing_is_a_mode_at_fixed_kh(diamond):
    """Every mode found at frequency is, at its kh = omega H / c, a mode of the fixed-kh search (1e-8), and the
    number of modes of each family equals the number of crossings of its fixed-kh branches with the frequency
    (a dense kh scan to kh 8.3, 0.02 apart and 0.0005 near the maximum); each row holds one backward mode."""
    film, _, r = diamond
    rows, cols = np.nonzero(np.isfinite(r["c"]))
    c = r["c"][rows, cols]
    at_kh = surfwave.layered("C-diamond", [film], kh=DIAMOND_WH[rows] / c)
    err = np.nanmin(np.abs(at_kh["c"] - c[:, None]), axis=1) / c
    assert np.all(err <= 1e-8), err.max()
    kh = np.unique(np.concatenate([np.linspace(0.005, 0.5, 100), np.linspace(0.5, 8.3, 391),
                                   np.linspace(0.55, 0.65, 201)]))
    scan = surfwave.layered("C-diamond", [film], kh=kh)
    assert np.nanmin(scan["c"][-1]) * kh[-1] > DIAMOND_WH.max()      # beyond the scan no mode is slow enough
    counts = _branch_crossings(scan, kh, DIAMOND_WH)
    for fam, want in counts.items():
        got = [sum(1 for lab in r["mode"][i] if lab and ("R" if lab[0] in "RS" else lab[0]) == fam)
               for i in range(DIAMOND_WH.size)]
        np.testing.assert_array_equal(got, want, err_msg=fam)
    assert np.all(np.nansum(r["group_velocity"] < 0, axis=1) == 1)


def test_anisotropic_backward_group_velocity_and_named_modes(diamond):
    """The backward mode's group velocity (energy velocity) equals central differences of omega H = c(kh) kh along
    its fixed-kh branch (relative step 1e-5), 1e-6, and is negative; the modes named by rank (S3, S4, S5) at
    frequency (mode_speeds_at_frequency, branches 0 ... 5 only) equal layered(frequency=)'s bit for bit."""
    film, stack, r = diamond
    for i in range(DIAMOND_WH.size):
        j = int(np.flatnonzero(r["group_velocity"][i] < 0)[0])
        c, vg = r["c"][i, j], r["group_velocity"][i, j]
        k = DIAMOND_WH[i] / c
        d = 1e-5 * k
        near = surfwave.layered("C-diamond", [film], kh=[k - d, k, k + d])
        lab = near["mode"][1][np.nanargmin(np.abs(near["c"][1] - c))]
        cm, cp = (near["c"][q][list(near["mode"][q]).index(lab)] for q in (0, 2))
        fd = (cp * (k + d) - cm * (k - d)) / (2 * d)
        assert vg < 0
        np.testing.assert_allclose(vg, fd, rtol=1e-6)
    f = np.tile(DIAMOND_WH / (2 * np.pi * H), 3)
    labels = np.repeat(["S3", "S4", "S5"], DIAMOND_WH.size)
    want = np.array([r["c"][i % DIAMOND_WH.size][list(r["mode"][i % DIAMOND_WH.size]).index(lab)]
                     for i, lab in enumerate(labels)])
    np.testing.assert_array_equal(mode_speeds_at_frequency(stack, f, labels), want)
