"""The count check of the isotropic fast path at fixed frequency where a branch runs backward (v_g < 0).

The stack: a soft, heavy film (shear speed 553 m/s) 1 um thick on a very stiff substrate (c_lim
14468 m/s). Its S3 branch's omega(kh) is not monotone, so near omega H = 4043.5 m/s one frequency
meets it three times: S3 (forward), S4 (backward, v_g ~ -92 m/s) and S5 (forward).

References: the unchecked one-film answer (one film on a half-space is not counted, so the grid's
answer is returned as found); the same stack written as two identical films of 0.5 um (the same
physics, and a stack of two films is checked by default); the fixed-kh answer at each mode's own
kh = omega H / c (the count is exact at fixed kh); central differences of c(kh) at fixed kh for
the backward mode's group velocity; the general Stroh path at fixed kh for the backward mode's speed.
"""
from __future__ import annotations

import numpy as np
import pytest
from general_path import layered_general

import surfwave
import surfwave.layers.isotropic_guard as guard
from surfwave.layers.counting import mode_count, sublayers
from surfwave.layers.isotropic import iso_stack
from surfwave.layers.isotropic_modes import FLOOR, family_roots
from surfwave.layers.isotropic_scan import Rows
from surfwave.layers.partial import families, scaled_blocks
from surfwave.layers.stack import resolve_stack

SUB = {"E": 681.6019454227651, "nu": 0.1233962647007325, "rho": 1449.2962671448738}
FILM = {"E": 4.139906256531708, "nu": 0.188408244626737, "rho": 5692.229565476481}
ONE = [{**FILM, "thickness": 1e-6}]
TWO = [{**FILM, "thickness": 0.5e-6}, {**FILM, "thickness": 0.5e-6}]
#: omega H / (2 pi H) of the row where the backward mode was lost (omega H = 4042.95 m/s).
F0 = 643455672.660757
#: The row itself and 10 frequencies around it, all within the window (-1 %, +0.55 %) that holds the backward mode.
FREQ = F0 * np.r_[1.0, np.linspace(0.99, 1.0055, 10)]


def _one_unchecked(**kw):
    keep = guard.ALWAYS
    try:
        guard.ALWAYS = False
        return surfwave.layered(SUB, ONE, **kw)
    finally:
        guard.ALWAYS = keep


def _same(a, b):
    """Same modes row by row: labels, speeds to 1e-10, group velocities to 1e-6 (the two stacks round differently)."""
    assert a["mode"].shape == b["mode"].shape and (a["mode"] == b["mode"]).all()
    ok = np.isfinite(a["c"])
    assert (np.isfinite(b["c"]) == ok).all()
    assert np.allclose(a["c"][ok], b["c"][ok], rtol=1e-10, atol=0)
    assert np.allclose(a["group_velocity"][ok], b["group_velocity"][ok], rtol=1e-6, atol=1e-6)


def test_backward_mode_kept_by_the_checked_two_film_stack():
    """Two films of 0.5 um (checked) at 11 frequencies around the lost row: every row equals the
    unchecked one-film answer (9 modes, speeds to 1e-10, labels), and each row holds exactly one
    sagittal mode with v_g < 0 between two forward ones."""
    one, two = _one_unchecked(frequency=FREQ), surfwave.layered(SUB, TWO, frequency=FREQ)
    _same(two, one)
    assert (np.isfinite(two["c"]).sum(axis=1) == 9).all()
    back = two["group_velocity"] < 0
    assert (back.sum(axis=1) == 1).all()
    for i in range(FREQ.size):
        j = int(np.flatnonzero(back[i])[0])
        assert two["mode"][i, j].startswith("S") and two["group_velocity"][i, j - 1] > 0 < two["group_velocity"][i, j + 1]


def test_backward_mode_kept_with_always():
    """The one-film stack with ``isotropic_guard.ALWAYS = True`` (every stack checked): the same
    answer as unchecked, at the same 11 frequencies."""
    keep = guard.ALWAYS
    try:
        guard.ALWAYS = True
        chk = surfwave.layered(SUB, ONE, frequency=FREQ)
    finally:
        guard.ALWAYS = keep
    _same(chk, _one_unchecked(frequency=FREQ))


def test_backward_mode_is_a_fixed_kh_mode_with_negative_group_velocity():
    """The backward mode of the lost row at its own kh = omega H / c: a mode of the checked fixed-kh
    answer (1e-10) and of the general Stroh path (1e-9), and its group velocity c + kh dc/dkh by central
    differences of c(kh) (step 1e-5 in kh) negative and equal to the fixed-frequency one to 1e-5 of c."""
    two = surfwave.layered(SUB, TWO, frequency=FREQ[:1])
    j = int(np.flatnonzero(two["group_velocity"][0] < 0)[0])
    c, kh, vg = two["c"][0, j], two["kh"][0, j], two["group_velocity"][0, j]
    h = 1e-5
    r = surfwave.layered(SUB, TWO, kh=[kh - h, kh, kh + h])
    near = [int(np.nanargmin(np.abs(r["c"][q] - c))) for q in range(3)]
    assert r["c"][1, near[1]] == pytest.approx(c, rel=1e-10)
    fd = c + kh * (r["c"][2, near[2]] - r["c"][0, near[0]]) / (2 * h)
    assert fd < 0 and fd == pytest.approx(vg, abs=1e-5 * c)
    gen = layered_general(SUB, TWO, kh=[kh])
    assert np.nanmin(np.abs(gen["c"][0] / c - 1.0)) <= 1e-9


def test_fixed_kh_rows_unchanged():
    """At fixed kh (the kh of every mode of the lost row) the checked two-film answer equals the
    unchecked one-film answer: the count there is exact and the guard changes nothing."""
    kh = np.sort(surfwave.layered(SUB, ONE, frequency=FREQ[:1])["kh"][0])
    kh = kh[np.isfinite(kh)]
    _same(surfwave.layered(SUB, TWO, kh=kh), _one_unchecked(kh=kh))


@pytest.mark.parametrize("modes", [4, 5, 6])
def test_modes_keyword_with_a_backward_mode(modes):
    """``modes`` = 4, 5, 6 (the sagittal family's 5th mode is the backward one): the checked two-film
    answer equals the unchecked one-film answer with the same ``modes``."""
    f = FREQ[:4]
    _same(surfwave.layered(SUB, TWO, frequency=f, modes=modes), _one_unchecked(frequency=f, modes=modes))


@pytest.mark.parametrize("drop", [0, 3, 5])
def test_repair_keeps_the_grid_modes(drop):
    """A row the grid got wrong, simulated: the sagittal table of the lost row with one mode removed
    (R, S3 (forward), S5 (forward)). The check repairs it back to the full table (the six sagittal
    modes, speeds to 1e-10), the backward S4 included: the repair keeps every mode the grid found."""
    stack = resolve_stack(SUB, TWO)
    st = iso_stack(stack)
    rows_of = Rows(2 * np.pi * FREQ[:1] * st.H, freq=True)
    c, vg = family_roots(st, "R", rows_of, None)
    assert np.isfinite(c).sum() == 6 and (vg[0] < 0).sum() == 1
    keep = np.arange(c.shape[1]) != drop
    got_c, got_vg = guard.check_families(stack, st, rows_of, ("R",), [(c[:, keep], vg[:, keep])], None)[0]
    assert got_c.shape == c.shape
    assert np.allclose(got_c, c, rtol=1e-10, atol=0)
    assert (np.sign(got_vg) == np.sign(vg)).all()


def test_rows_with_a_backward_mode_pass_the_check(monkeypatch):
    """The comparison itself: at the 11 frequencies (``modes`` None and 5) every row of the two-film
    stack agrees with the count as (forward) - (backward) below the check speed, so no row is
    repaired (the repair is never called)."""
    calls = []

    def spy(*a, **k):
        calls.append(a[5])
        return _modes_by_count(*a, **k)

    _modes_by_count = guard._modes_by_count
    monkeypatch.setattr(guard, "_modes_by_count", spy)
    surfwave.layered(SUB, TWO, frequency=FREQ)
    surfwave.layered(SUB, TWO, frequency=FREQ, modes=5)
    assert calls == []


def test_repair_never_drops_a_grid_mode(monkeypatch):
    """A repair whose count bisection finds no mode at all (as when every crossing it could isolate
    comes in forward / backward pairs) on a row missing its S5: the row keeps the five modes the grid
    found, the backward S4 included (speeds and group velocities unchanged)."""
    stack = resolve_stack(SUB, TWO)
    st = iso_stack(stack)
    rows_of = Rows(2 * np.pi * FREQ[:1] * st.H, freq=True)
    c, vg = family_roots(st, "R", rows_of, None)
    none = (np.zeros(0, dtype=int), np.zeros(0), np.zeros(0))
    monkeypatch.setattr(guard, "_modes_by_count", lambda *a, **k: none)
    got_c, got_vg = guard.check_families(stack, st, rows_of, ("R",), [(c[:, :5], vg[:, :5])], None)[0]
    assert (got_c == c[:, :5]).all() and (got_vg == vg[:, :5]).all() and (got_vg < 0).sum() == 1


def test_three_film_stack_with_a_backward_mode(monkeypatch):
    """A random three-film stack (stiff light / soft / stiff films on a soft substrate; seed 27 of a
    study of 600 random 2-3 film stacks, 3 of which had a backward mode) at 2.598 GHz: 7 modes, S2
    backward (v_g -73.1 m/s). Each (c, kh) is a mode of the checked fixed-kh answer at its kh (1e-10);
    per family (forward) - (backward) below c_lim (1 - 1e-9) equals the Wittrick-Williams count
    along the row (0 at the floor); S2's group velocity equals central differences of c(kh) at fixed
    kh (1e-5 of c); the row passes the check (no repair)."""
    sub = {"E": 105.5443592758609, "nu": -0.12070529772203586, "rho": 972.4236289539878}
    films = [{"E": 501.78122751320933, "nu": 0.3028039088065537, "rho": 653.9275613566301, "thickness": 3.591465737491801e-07},
             {"E": 7.0799421804575635, "nu": 0.43963998335074583, "rho": 2662.731865679023, "thickness": 3.4545287725445544e-07},
             {"E": 312.69788643368094, "nu": 0.4072924307190725, "rho": 1852.291619987027, "thickness": 4.841584833911856e-07}]
    f = 2597645134.1642213
    calls = []
    _modes_by_count = guard._modes_by_count

    def spy(*a, **k):
        calls.append(a[5])
        return _modes_by_count(*a, **k)

    monkeypatch.setattr(guard, "_modes_by_count", spy)
    r = surfwave.layered(sub, films, frequency=[f])
    assert calls == []
    ok = np.isfinite(r["c"][0])
    c, kh, vg, lab = r["c"][0][ok], r["kh"][0][ok], r["group_velocity"][0][ok], r["mode"][0][ok]
    assert c.size == 7 and list(lab[vg < 0]) == ["S2"]
    at = surfwave.layered(sub, films, kh=kh)
    for i in range(c.size):
        assert np.nanmin(np.abs(at["c"][i] / c[i] - 1.0)) <= 1e-10
    stack = resolve_stack(sub, films)
    st, b = iso_stack(stack), scaled_blocks(stack)
    wH = 2 * np.pi * f * stack.total_thickness
    ends = np.array([FLOOR * float(st.shear.min()), st.c_lim * (1.0 - guard.TOP)])
    nsub = sublayers(b, wH / ends[0], float(ends[1]))
    assert nsub is not None
    for fam in families(b):
        n = mode_count(b, fam, ends, (wH / ends)[:, None], "free", nsub)[:, 0]
        mine = np.array([m[0] in (("R", "S") if fam.prefix == "R" else ("L",)) for m in lab]) & (c < ends[1])
        assert n[0] == 0 and n[1] == (mine & (vg > 0)).sum() - (mine & (vg < 0)).sum()
    j, h = int(np.flatnonzero(vg < 0)[0]), 1e-5
    fd = surfwave.layered(sub, films, kh=[kh[j] - h, kh[j] + h])
    c2 = [fd["c"][q, int(np.nanargmin(np.abs(fd["c"][q] - c[j])))] for q in range(2)]
    assert c[j] + kh[j] * (c2[1] - c2[0]) / (2 * h) == pytest.approx(vg[j], abs=1e-5 * c[j])
