"""The complex root search of the leaky-wave solver (:mod:`surfwave.solvers.leaky`).

Physics and the validation of each root: docs/physics/leaky-waves.md and the docstring of
:mod:`surfwave.solvers.leaky`. This module holds the machinery: the Stroh roots and
eigenvectors at a (complex) X = rho v^2 (``_stroh_base``, ``_roots_at``), the choice and
tracking of the partial waves, the surface impedance and the boundary function of an
electrical condition, the real-speed scan shared by every condition (:func:`scan`), the secant
searches from its minima and from complex starts, their validation, and the choice of the
least-attenuated verified root per orientation (:func:`solve`). Everything works on the scaled
blocks Q, R, T (A / max|A|, e / sqrt(max|A| EPS0), eps / EPS0) and scaled X.
"""
from __future__ import annotations

import numpy as np

from surfwave.solvers.boundary import as_boundary
from surfwave.solvers.piezo_stroh import stroh_matrix

#: Points of the real-speed grid (uniform in w in (0, pi/2), X = X_L1 + (X_L2 - X_L1) sin^2 w).
SCAN = 16
MAX_ITER = 80
#: Largest secant step in w (the chosen roots are tracked between evaluations).
STEP_MAX = 0.05
#: delta below -GROW_TOL: a root growing along x1 (rejected with a reason).
GROW_TOL = 1e-9
#: Starts w = pi/2 + i y of the searches for a root above v_L2 where no search from the real-axis
#: minima converged (X = X_L1 + (X_L2 - X_L1) cosh^2 y: up to 2.4 (X_L2 - X_L1) above X_L2).
PROBE_Y = np.array([0.1, 0.3, 0.6, 1.0])
#: Starts w = u - i y (u in PROBE_U, y in PROBE_Y1, Im X < 0) of the complex searches where no search
#: converged (no real-axis minimum, or none of its searches converged): a branch whose real speed runs
#: toward v_L1 with Im w comparable to Re w has no real-axis minimum of |det| (Re X - X_L1 << |Im X|),
#: e.g. LiNbO3 rotated Y-cuts near 0 deg metallized; u = 0.1 starts near v_L1, u = 0.6 mid-window (needed
#: at free 150-154 deg). Two starts find every root that 3 x 3 starts (u 0.1, 0.45, 0.8; y 0.1, 0.2, 0.35)
#: find on the crystals scene and the rotated Y-cuts (0.5-degree steps), at less than a quarter of the cost.
PROBE_U = np.array([0.1, 0.6])
PROBE_Y1 = np.array([0.2])
#: A verified root from those complex starts is kept only with delta > PROBE_DELTA: a root with (numerically)
#: real X lies on the real axis, the real scan's business (e.g. grazing roots at the (111) mirrors of Ni and
#: at Al (110) 0.5-2 deg and W 0.5-1 deg, whose 'decaying' second-sheet wave has Im p ~ 1e-4).
PROBE_DELTA = 1e-6
#: A verified root from the searches above v_L2 that drifted into the window is kept with delta >
#: PROBE_DELTA or when every decaying partial wave has Im p > PROBE_DECAY (decays within ~160
#: wavelengths): a nearly real leaky root, not a grazing near-double one (Im p ~ 1e-6 - 1e-4).
PROBE_DECAY = 1e-3
#: Halvings of a secant step allowed in a row when the roots cannot be followed.
MAX_HALVING = 12
#: Roots with |sin w| < T_EDGE (X - X_L1 < T_EDGE^2 (X_L2 - X_L1)) are grazing bulk waves, not leaky waves.
T_EDGE = 1e-3
#: Largest first-order move of a chosen root on the check path X = Re X0 + i s Im X0 (s: 1 -> 0,
#: from a root back to real speed), as a fraction of its distance to the nearest other root.
BACK_FRAC = 0.125
#: Most eigen-decompositions on that path before the root counts as not verified.
BACK_MAX = 64
#: |Im p| below REAL_TOL max(1, |p|) counts as a real Stroh root on the real-speed grid.
REAL_TOL = 1e-7


REASON_NOROOT = "no leaky root on the slowest sheet's leaky branch (secant search did not converge)"
REASON_ABOVE = ("leaky root above the second bulk sheet's limiting speed v_L2: it would radiate into two "
                "sheets (only the slowest sheet's leaky wave is computed)")
REASON_BELOW = "root below the slowest sheet's limiting speed v_L1: a true (subsonic) surface wave, not leaky"
REASON_GROW = "root with growing amplitude along x1 (delta < 0): not a physical leaky wave"
REASON_EDGE = ("root at the slowest sheet's limiting speed (|sin w| < T_EDGE): a grazing bulk wave (e.g. the "
               "exceptional surface-skimming wave of a mirror direction), not a leaky surface wave")
REASON_NOMIN = ("no leaky root found: |det| has no interior minimum between v_L1 and v_L2 where the slowest "
                "sheet has a single real pair of Stroh roots, and no search from the complex starts near v_L1 "
                "converged (the root, if any, was not found)")
REASON_LOW = ("no leaky root found between v_L1 and v_L2; the search found a root of the continued "
              "partial-wave set with Re(rho v^2) at or below rho v_L1^2 (below the slowest sheet's limiting "
              "speed: real speed below v_L1, or a real root below v_L1), not a leaky wave of the window")
REASON_MULTI = ("leaky root where the slowest sheet has more than one real pair of Stroh roots (cuspidal "
                "slowness or a second radiating sheet): not computed")
REASON_SHEET = ("root on another partial-wave choice: a partial wave meant to decay into the crystal has "
                "Im p <= 0 (grows or does not decay with depth), so it is not the slowest sheet's leaky wave")
REASON_INCOMING = ("root of another partial-wave choice: followed back to real speed (Re X), the chosen waves are "
                   "not the outgoing bulk wave (real p, energy flux into the crystal) plus d - 1 decaying waves "
                   "(e.g. the incoming bulk wave was taken instead of a decaying one)")
REASON_TRACK = "partial-wave tracking failed (two chosen roots merged)"

def _stroh_base(Q, R, T, d) -> np.ndarray:
    """Real Stroh matrix at X = 0, shape (m, 2d, 2d), from the scaled blocks Q, R, T (m, d, d).

    N(X) = N(0) + X [[0, 0], [M, 0]], M = diag(1, 1, 1[, 0]) (:func:`_roots_at`); built once
    per orientation (:func:`surfwave.solvers.piezo_stroh.stroh_matrix`: the inverse of T and the
    products do not depend on X).
    """
    return stroh_matrix(Q, R, T, np.zeros(Q.shape[0]), nm=3)


def _roots_at(N0, X, d) -> tuple[np.ndarray, np.ndarray]:
    """Stroh roots p (m, 2d) and eigenvectors xi = (a, b) (m, 2d, 2d), complex, at X (m,).

    ``N0`` (m, 2d, 2d) from :func:`_stroh_base`. A real X (float dtype) builds the real N (its
    eigen-decomposition is ~3x cheaper).
    """
    N = N0.astype(X.dtype)
    k = np.arange(3)
    N[:, d + k, k] += X[:, None]
    p, xi = np.linalg.eig(N)
    return p.astype(complex), xi.astype(complex)


def _boundary(xi, idx, d, electrical) -> tuple[np.ndarray, np.ndarray]:
    """Boundary function f (m,) and the effective impedance matrix (m, d', d') of the chosen waves.

    M = B A^-1 of the partial waves ``idx`` (m, d); free: M - i e4 e4^T (vacuum), metallized:
    its mechanical 3 x 3 block (phi = 0); elastic: M. :func:`_condition` of :func:`_impedance`.
    """
    return _condition(_impedance(xi, idx, d), d, electrical)


def _impedance(xi, idx, d) -> np.ndarray:
    """Surface impedance M = B A^-1 (m, d, d) of the partial waves ``idx`` (m, d) of the
    eigenvectors xi = (a, b) (m, 2d, 2d); NaN where A is singular. The same for every electrical
    condition (only :func:`_condition` differs)."""
    sel = np.take_along_axis(xi, idx[:, None, :], axis=2)
    a, b = sel[:, :d], sel[:, d:]
    with np.errstate(invalid="ignore", over="ignore"):
        da = np.abs(np.linalg.det(a))
    good = np.isfinite(da) & (da > 1e-14 * np.prod(np.linalg.norm(a, axis=1), axis=1))
    M = np.full(b.shape, np.nan + 0j)
    if good.any():
        M[good] = np.swapaxes(np.linalg.solve(np.swapaxes(a[good], 1, 2), np.swapaxes(b[good], 1, 2)), 1, 2)
    return M


def _condition(M, d, electrical) -> tuple[np.ndarray, np.ndarray]:
    """Boundary function det (m,) and the matrix of one electrical condition from M (m, d, d).

    Free: M - i e4 e4^T (a copy; vacuum, scaled EPS0 = 1); metallized: the mechanical 3 x 3 block
    (phi = 0); elastic (d = 3): M itself.
    """
    if d == 4:
        M = as_boundary(electrical).secular_matrix(M)
    with np.errstate(invalid="ignore"):
        return np.linalg.det(M), M


def _choose_real(p, xi, d) -> np.ndarray:
    """Chosen partial waves (m, d) at real X between v_L1 and v_L2.

    The d - 1 roots with Im p > 0 farthest from the real axis plus, of the two (nearly) real
    roots of the slowest sheet, the one whose x2 energy flux Re(a^H b) is positive.
    """
    order = np.argsort(np.abs(p.imag), axis=1)
    real2 = order[:, :2]
    flux = np.einsum("mjk,mjk->mk", xi[:, :d].conj(), xi[:, d:]).real
    f2 = np.take_along_axis(flux, real2, axis=1)
    out_ = np.where(f2[:, 0] > f2[:, 1], real2[:, 0], real2[:, 1])
    rest = order[:, 2:]
    up = np.take_along_axis(p, rest, axis=1).imag > 0
    rank = np.argsort(~up, axis=1, kind="stable")[:, :d - 1]
    return np.concatenate([out_[:, None], np.take_along_axis(rest, rank, axis=1)], axis=1)


def _track(p_prev, p) -> tuple[np.ndarray, np.ndarray]:
    """Indices (m, d) of the roots p (m, 2d) nearest to the previous chosen ones (m, d); ok flag.

    Not ok where the match is ambiguous: a chosen root's nearest new root is not at least
    twice as close as the second nearest (the step was too large to follow it).
    """
    dist = np.abs(p[:, None, :] - p_prev[:, :, None])
    order = np.argsort(dist, axis=2)
    idx = order[:, :, 0]
    d1 = np.take_along_axis(dist, order[:, :, :1], axis=2)[..., 0]
    d2 = np.take_along_axis(dist, order[:, :, 1:2], axis=2)[..., 0]
    s = np.sort(idx, axis=1)
    ok = np.all(s[:, 1:] != s[:, :-1], axis=1) & np.all(2 * d1 <= d2, axis=1)
    return idx, ok


def _dp_dx(xi, idx, d) -> np.ndarray:
    """dp/dX = a^T M a / (2 a^T b) of the chosen roots (n, d), M = diag(1, 1, 1[, 0]).

    First-order perturbation of N xi = p xi with the left eigenvector (b, a) (N^T J = J N,
    J = [[0, I], [I, 0]]) and dN/dX = [[0, 0], [M, 0]].
    """
    sel = np.take_along_axis(xi, idx[:, None, :], axis=2)
    a, b = sel[:, :d], sel[:, d:]
    am = a[:, :3]
    return np.einsum("nkj,nkj->nj", am, am) / (2 * np.einsum("nkj,nkj->nj", a, b))


def _secant(N0, x0, span, t, t1, f1, p1, g1, d, electrical, tol):
    """Secant iteration in complex w from (t1, f1) and t, tracking the chosen roots p1 (n, d).

    The chosen roots are followed from the last accepted point, predicted to first order with
    their dp/dX (g1 at the start); a trial point where they cannot be matched unambiguously is
    pulled halfway back (at most ``MAX_HALVING`` times in a row).
    Returns t (n,) complex of the last accepted evaluation, its chosen roots p (n, d) and
    eigen-data (roots (n, 2d), vectors (n, 2d, 2d), indices (n, d)), converged and
    tracking-ok flags, and the number of evaluations.
    """
    n = N0.shape[0]
    t_prev, f_prev, p_prev, g = t1.copy(), f1.copy(), p1.copy(), g1.copy()
    conv = np.zeros(n, dtype=bool)
    trk = np.ones(n, dtype=bool)
    its = np.zeros(n, dtype=int)
    halv = np.zeros(n, dtype=int)
    p_all = np.zeros((n, 2 * d), dtype=complex)
    xi_all = np.zeros((n, 2 * d, 2 * d), dtype=complex)
    idx = np.zeros((n, d), dtype=int)
    act = np.arange(n)
    for _ in range(MAX_ITER):
        X = x0[act] + span[act] * np.sin(t[act]) ** 2
        p, xi = _roots_at(N0[act], X, d)
        dw = (span[act] * np.sin(2 * t_prev[act]) * (t[act] - t_prev[act]))[:, None]
        sel, okt = _track(p_prev[act] + g[act] * dw, p)
        its[act] += 1
        # ambiguous: back off halfway towards the last accepted point
        bad = act[~okt]
        halv[bad] += 1
        t[bad] = 0.5 * (t[bad] + t_prev[bad])
        trk[bad[halv[bad] > MAX_HALVING]] = False
        acc = act[okt]
        halv[acc] = 0
        f, _ = _boundary(xi[okt], sel[okt], d, electrical)
        p_prev[acc] = np.take_along_axis(p[okt], sel[okt], axis=1)
        idx[acc], p_all[acc], xi_all[acc] = sel[okt], p[okt], xi[okt]
        g[acc] = _dp_dx(xi[okt], sel[okt], d)
        den = f - f_prev[acc]
        safe = np.isfinite(den) & (den != 0)
        step = np.where(safe, f * (t[acc] - t_prev[acc]) / np.where(safe, den, 1), np.nan)
        big = np.abs(step) > STEP_MAX
        step = np.where(big, step * STEP_MAX / np.abs(np.where(big, step, 1)), step)
        t_prev[acc], f_prev[acc] = t[acc], f
        t[acc] = t[acc] - step
        dX = span[acc] * np.abs(step) * (np.abs(np.sin(2 * t_prev[acc])) + np.abs(step))
        small = dX <= tol * np.abs(x0[acc] + span[acc] * np.sin(t_prev[acc]) ** 2)
        conv[acc[small]] = True
        stop = np.zeros(n, dtype=bool)
        stop[acc[small | ~np.isfinite(step)]] = True
        stop[~trk] = True
        act = act[~stop[act]]
        if act.size == 0:
            break
    return t_prev, p_prev, (p_all, xi_all, idx), conv, trk, its


def _back_to_real(N0, X0, p0, pall0, g0, d) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Follow the chosen roots from the complex roots X0 back to real speed Re X0.

    Path X = Re X0 + i s Im X0, s: 1 -> 0. Each step's length is set by the roots themselves:
    the first-order move |dp/dX| |dX| of every chosen root is at most :data:`BACK_FRAC` times its
    distance to the nearest other root. Near a square-root branch point X_b of p(X) (where two
    roots can swap), p = p_b +- c sqrt(X - X_b) gives |X - X_b| = sep / (4 |dp/dX|), so such a step
    stays within |X - X_b| / 2 of its start: no branch point is stepped over. Each new point is
    matched to the first-order prediction p + dp/dX dX (:func:`_track`, unambiguous match); an
    ambiguous match halves the step (at most :data:`MAX_HALVING` times in a row), more than
    :data:`BACK_MAX` steps count as not verified.

    Parameters
    ----------
    N0 : ndarray, shape (n, 2d, 2d)
        Real Stroh matrices at X = 0 (:func:`_stroh_base`).
    X0 : ndarray, shape (n,), complex
        Roots (scaled rho v^2).
    p0 : ndarray, shape (n, d), complex
        Chosen roots at X0, the radiating one first.
    pall0 : ndarray, shape (n, 2d), complex
        All Stroh roots at X0.
    g0 : ndarray, shape (n, d), complex
        dp/dX of the chosen roots at X0.
    d : int
        3 (elastic) or 4 (piezoelectric).

    Returns
    -------
    ok : ndarray, shape (n,), bool
        True where the path was followed and, at real X, the first root is real with energy flux
        Re(a^H b) > 0 into the crystal (the outgoing bulk wave) and the other d - 1 have
        Im p > REAL_TOL max(1, |p|) (decaying, not the incoming bulk wave).
    nreal : ndarray, shape (n,), int
        Number of real Stroh roots (|Im p| <= REAL_TOL max(1, |p|)) at Re X0.
    steps : ndarray, shape (n,), int
        Eigen-decompositions on the path (the real end point included).
    """
    n = X0.shape[0]
    ok = np.zeros(n, dtype=bool)
    nreal = np.zeros(n, dtype=int)
    steps = np.zeros(n, dtype=int)
    if n == 0:
        return ok, nreal, steps
    s = np.ones(n)
    p_prev, g, pall = p0.copy(), g0.copy(), pall0.copy()
    halv = np.zeros(n, dtype=int)
    fail = np.zeros(n, dtype=bool)
    act = np.arange(n)
    eta = np.abs(X0.imag)
    while act.size:
        # separation of every chosen root from the nearest other root at the current point
        dist = np.abs(pall[act][:, None, :] - p_prev[act][:, :, None])
        sep = np.sort(dist, axis=2)[:, :, 1]
        move = np.max(np.abs(g[act]) * eta[act, None] / sep, axis=1)   # |dp/dX| |Im X0| / sep per unit s
        with np.errstate(divide="ignore"):
            ds = np.where(move > 0, BACK_FRAC / move, np.inf) * 0.5 ** halv[act]
        s_new = np.where(ds >= s[act], 0.0, s[act] - ds)
        p_new = np.zeros((act.size, 2 * d), dtype=complex)
        xi_new = np.zeros((act.size, 2 * d, 2 * d), dtype=complex)
        real = s_new == 0
        for part, Xp in ((real, X0[act].real), (~real, X0[act].real + 1j * s_new * X0[act].imag)):
            if part.any():
                j = act[part]
                p_new[part], xi_new[part] = _roots_at(N0[j], Xp[part], d)
        steps[act] += 1
        dX = 1j * (s_new - s[act]) * X0[act].imag
        sel, okt = _track(p_prev[act] + g[act] * dX[:, None], p_new)
        bad = act[~okt]
        halv[bad] += 1
        fail[bad[halv[bad] > MAX_HALVING]] = True
        acc = act[okt]
        halv[acc] = 0
        s[acc] = s_new[okt]
        p_prev[acc] = np.take_along_axis(p_new[okt], sel[okt], axis=1)
        pall[acc] = p_new[okt]
        g[acc] = _dp_dx(xi_new[okt], sel[okt], d)
        end = okt & real
        if end.any():
            e_ = act[end]
            xi_e, sel_e, pa = xi_new[end], sel[end], p_new[end]
            nreal[e_] = (np.abs(pa.imag) <= REAL_TOL * np.maximum(1, np.abs(pa))).sum(axis=1)
            flux = np.einsum("mjk,mjk->mk", xi_e[:, :d].conj(), xi_e[:, d:]).real
            f0 = np.take_along_axis(flux, sel_e[:, :1], axis=1)[:, 0]
            pe = p_prev[e_]
            tl = REAL_TOL * np.maximum(1, np.abs(pe))
            ok[e_] = (np.abs(pe[:, 0].imag) <= tl[:, 0]) & (f0 > 0) & np.all(pe[:, 1:].imag > tl[:, 1:], axis=1)
        fail[act[steps[act] >= BACK_MAX]] = True
        done = np.zeros(n, dtype=bool)
        done[act[end]] = True
        done |= fail
        act = act[~done[act]]
    # not followed to the end: the real-speed root count still decides REASON_MULTI
    f = np.nonzero(fail)[0]
    if f.size:
        pr, _ = _roots_at(N0[f], X0[f].real, d)
        nreal[f] = (np.abs(pr.imag) <= REAL_TOL * np.maximum(1, np.abs(pr))).sum(axis=1)
    return ok, nreal, steps


def _candidates(N0, XL, rows, t, t1, f1, p1, g1, d, electrical, tol) -> dict:
    """Secant searches (:func:`_secant`) and the validation of their roots, one per candidate.

    Parameters
    ----------
    N0 : ndarray, shape (m, 2d, 2d)
        Real Stroh matrices at X = 0 (:func:`_stroh_base`).
    XL : ndarray, shape (m, 2)
        Scaled limiting X of the slowest and second sheet.
    rows : ndarray, shape (n,), int
        Orientation of each candidate.
    t, t1 : ndarray, shape (n,), complex
        First trial point and the last accepted point (w) of each search.
    f1, p1, g1 : ndarray, shapes (n,), (n, d), (n, d), complex
        Boundary function, chosen roots and their dp/dX at ``t1``.
    d : int
    electrical : str
    tol : float

    Returns
    -------
    dict
        ``why`` (n,) reasons ("" for a verified leaky root); ``X`` (n,) complex roots; ``delta``
        (n,); ``p`` (n, d) chosen roots; ``xi`` (n, 2d, 2d) and ``idx`` (n, d) eigen-data at the
        root; ``its`` (n,) evaluations; ``converged`` (n,) bool (search converged and tracked).
    """
    x0, span = XL[:, 0], XL[:, 1] - XL[:, 0]
    tc, pch, (pall, xiall, ich), conv, trk, its = _secant(
        N0[rows], x0[rows], span[rows], t, t1, f1, p1, g1, d, electrical, tol)
    Xc = x0[rows] + span[rows] * np.sin(tc) ** 2
    delta_c = -(np.sqrt(Xc)).imag / np.sqrt(Xc).real
    why = np.full(rows.size, "", dtype=object)
    why[~conv] = REASON_NOROOT
    why[~trk] = REASON_TRACK
    why[(why == "") & (np.abs(np.sin(tc)) < T_EDGE)] = REASON_EDGE
    # the reported real speed c_leaky = 1 / Re(1 / v) (>= Re v) must lie below v_L2
    with np.errstate(invalid="ignore", divide="ignore"):
        x_real = 1.0 / (1.0 / np.sqrt(Xc)).real ** 2
    why[(why == "") & ((Xc.real > XL[rows, 1]) | (x_real >= XL[rows, 1]))] = REASON_ABOVE
    why[(why == "") & (delta_c < -GROW_TOL)] = REASON_GROW
    # every non-radiating partial wave must decay into the crystal (Im p > 0) at the root: a
    # root of a set that includes a growing wave (e.g. both members of a complex-conjugate
    # pair at a real X) satisfies det = 0 but is not a surface wave
    why[(why == "") & np.any(~(pch[:, 1:].imag > 0), axis=1)] = REASON_SHEET
    # the slowest sheet must have a single real pair at Re X (no cusp, no second sheet), and,
    # followed back to real speed, the chosen waves must be the outgoing bulk wave and d - 1
    # decaying ones (a decaying and the incoming wave can swap around a branch point of p(X));
    # one path per root gives both (its end point is the real-speed decomposition)
    chk = np.nonzero(why == "")[0]
    if chk.size:
        r_ = rows[chk]
        okb, nr, _ = _back_to_real(N0[r_], Xc[chk], pch[chk], pall[chk], _dp_dx(xiall[chk], ich[chk], d), d)
        low = Xc[chk].real <= XL[r_, 0]       # no real pair at Re X: below the window, not a cusp
        why[chk[(nr != 2) & low]] = REASON_LOW
        why[chk[(nr != 2) & ~low]] = REASON_MULTI
        why[chk[(nr == 2) & ~okb]] = REASON_INCOMING
    return {"why": why, "X": Xc, "delta": delta_c, "p": pch, "xi": xiall, "idx": ich, "its": its,
            "converged": conv & trk}


def scan(Q, R, T, XL, d) -> dict:
    """The real-speed scan shared by every electrical condition: Stroh matrices, grid roots, choice.

    Parameters
    ----------
    Q, R, T : ndarray, shape (m, d, d)
        Scaled blocks.
    XL : ndarray, shape (m, 2)
        Scaled limiting X of the slowest and second sheet.
    d : int

    Returns
    -------
    dict
        ``N0`` (m, 2d, 2d) real Stroh matrices at X = 0; ``tg`` (SCAN,) grid in w; ``pg`` (m SCAN, 2d)
        and ``xig`` (m SCAN, 2d, 2d) roots and eigenvectors at the grid speeds; ``idx`` (m SCAN, d)
        the outgoing choice; ``pc`` (m SCAN, d) its roots; ``nreal`` (m, SCAN) real roots per grid
        point; ``Mg`` (m SCAN, d, d) the surface impedance of the choice (:func:`_impedance`).
    """
    m = Q.shape[0]
    N0 = _stroh_base(Q, R, T, d)
    x0, span = XL[:, 0], XL[:, 1] - XL[:, 0]
    tg = 0.5 * np.pi * (np.arange(SCAN) + 0.5) / SCAN
    Xg = (x0[:, None] + span[:, None] * np.sin(tg) ** 2).reshape(-1)
    pg, xig = _roots_at(np.repeat(N0, SCAN, axis=0), Xg, d)
    idx = _choose_real(pg, xig, d)
    pc = np.take_along_axis(pg, idx, axis=1)
    nreal = (np.abs(pg.imag) <= REAL_TOL * np.maximum(1, np.abs(pg))).sum(axis=1).reshape(m, SCAN)
    return {"N0": N0, "tg": tg, "pg": pg, "xig": xig, "idx": idx, "pc": pc, "nreal": nreal,
            "Mg": _impedance(xig, idx, d)}


def solve(sc, XL, d, electrical, tol):
    """Secant in w from every local minimum of |det| of the scan ``sc`` (:func:`scan`) for one
    electrical condition; the least-attenuated root wins.

    Parameters
    ----------
    sc : dict
        The real-speed scan of the m points (:func:`scan`).
    XL : ndarray, shape (m, 2)
        Scaled limiting X of the slowest and second sheet.
    d : int
        3 (elastic) or 4 (piezoelectric).
    electrical : Boundary
        The electrical condition.
    tol : float
        Relative accuracy of X.

    Returns
    -------
    tuple of ndarray
        X (m,) complex scaled roots, chosen p (m, d) (radiating first), polarisation (m, d),
        evaluations (m,) int, reasons (m,) object str.
    """
    m = sc["N0"].shape[0]
    fg, _ = _condition(sc["Mg"], d, electrical)
    af = np.where(sc["nreal"] == 2, np.abs(fg).reshape(m, SCAN), np.inf)
    rows, kg, t = _real_axis_starts(af, fg, sc["tg"])
    cand = _candidates_from(sc, XL, rows, t, kg, fg, d, electrical, tol)
    conv_row = np.zeros(m, dtype=bool)
    conv_row[rows[cand["converged"]]] = True
    has_row = np.zeros(m, dtype=bool)
    has_row[rows] = True
    fin = np.isfinite(af)
    extra_its = np.zeros(m)
    stuck = np.nonzero(has_row & ~conv_row & fin.any(axis=1))[0]     # minima, but no search converged
    low_rows = np.nonzero(~conv_row & fin.any(axis=1))[0]             # no search converged (or no minimum)
    for probe, prows in ((_probe_above, stuck), (_probe_below, low_rows)):
        if prows.size:
            prow, keep, extra = probe(sc, XL, prows, fin, fg, d, electrical, tol)
            extra_its += np.bincount(prow, weights=extra["its"], minlength=m)
            cand = {key: np.concatenate([cand[key], extra[key][keep]]) for key in cand}
            rows = np.concatenate([rows, prow[keep]])
    best = _best_candidates(rows, cand, m)
    reason = np.full(m, REASON_NOMIN, dtype=object)
    X = np.full(m, np.nan + 0j)
    p_out = np.full((m, d), np.nan + 0j)
    u = np.full((m, d), np.nan + 0j)
    nit = np.full(m, SCAN)
    has = best >= 0
    b = best[has]
    why, pch = cand["why"], cand["p"]
    reason[has] = why[b]
    X[has] = cand["X"][b]
    nit[has] += (np.bincount(rows, weights=cand["its"], minlength=m) + extra_its)[has].astype(int)
    rest = np.take_along_axis(pch[b, 1:], np.argsort(pch[b, 1:].imag, axis=1), axis=1)
    p_out[has] = np.concatenate([pch[b, :1], rest], axis=1)
    u[has] = _root_polarisation(cand["xi"][b], cand["idx"][b], d, electrical)
    return X, p_out, u, nit, reason


def _real_axis_starts(af, fg, tg) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Start points of the secant searches: one per local minimum of |det| over the real scan.

    Parameters
    ----------
    af : ndarray, shape (m, SCAN)
        |det| of the outgoing choice at the grid speeds, inf where the slowest sheet does not
        have exactly one real pair of Stroh roots.
    fg : ndarray, shape (m SCAN,), complex
        The boundary function at the grid speeds.
    tg : ndarray, shape (SCAN,)
        The grid in w (radians).

    Returns
    -------
    rows : ndarray, shape (n,), int
        Point of each search.
    kg : ndarray, shape (n,), int
        Flat grid index (row * SCAN + column) of the last accepted point of each search.
    t : ndarray, shape (n,), complex
        First trial point in w: the root of the parabola through the three grid values around
        the minimum, or a small step off the real axis where that fails.
    """
    m = af.shape[0]
    # local minima of |det| (grid points where the slowest sheet has one real pair)
    loc = np.zeros((m, SCAN), dtype=bool)
    loc[:, 1:-1] = (af[:, 1:-1] < af[:, :-2]) & (af[:, 1:-1] < af[:, 2:]) & np.isfinite(af[:, 1:-1])
    # the top grid point too (the root may lie between it and v_L2): fit around its neighbour
    loc[:, -1] = (af[:, -1] < af[:, -2]) & np.isfinite(af[:, -1]) & np.isfinite(af[:, -3])
    rows, cols = np.nonzero(loc)
    cols = np.minimum(cols, SCAN - 2)
    k = rows * SCAN + cols
    t1 = tg[cols].astype(complex)
    # start: root of the parabola through the three grid values around the minimum
    h = tg[1] - tg[0]
    fm, f0, fp = fg[k - 1], fg[k], fg[k + 1]
    c1, c2 = (fp - fm) / (2 * h), (fp - 2 * f0 + fm) / (2 * h * h)
    disc = np.sqrt(c1 * c1 - 4 * c2 * f0)
    den = np.where(np.abs(c1 + disc) >= np.abs(c1 - disc), c1 + disc, c1 - disc)
    with np.errstate(invalid="ignore", divide="ignore"):
        dt = -2 * f0 / den
    fallback = ~np.isfinite(dt) | (np.abs(dt) > 3 * h)
    t = t1 + np.where(fallback, 1e-3 * (t1 - 1j * tg[0]), dt)
    return rows, k, t


def _candidates_from(sc, XL, rows, t, kg, fg, d, electrical, tol) -> dict:
    """:func:`_candidates` of searches starting at ``t`` and continued from the grid points ``kg``.

    Parameters
    ----------
    sc : dict
        The scan (:func:`scan`).
    XL : ndarray, shape (m, 2)
    rows, kg : ndarray, shape (n,), int
        Point and flat grid index (row * SCAN + column) of each search.
    t : ndarray, shape (n,), complex
        First trial points in w.
    fg : ndarray, shape (m SCAN,), complex
        The boundary function at the grid speeds.
    d : int
    electrical : Boundary
    tol : float

    Returns
    -------
    dict
        As :func:`_candidates`.
    """
    return _candidates(sc["N0"], XL, rows, t, sc["tg"][kg % SCAN].astype(complex), fg[kg], sc["pc"][kg],
                       _dp_dx(sc["xig"][kg], sc["idx"][kg], d), d, electrical, tol)


def _probe_above(sc, XL, stuck, fin, fg, d, electrical, tol) -> tuple[np.ndarray, np.ndarray, dict]:
    """Searches from w = pi/2 + i y for points whose real-axis searches all failed.

    The branch may have left the window through v_L2, out of reach from the real-axis minima;
    searches from w = pi/2 + i y (real X above X_L2, X = X_L1 + (X_L2 - X_L1) cosh^2 y,
    y in :data:`PROBE_Y`), continued from the highest grid point with a single real pair, find
    such roots. Kept: roots above v_L2 (REASON_ABOVE after the same validation) and verified
    roots of the window that are not grazing: delta > PROBE_DELTA, or every decaying wave with
    Im p > PROBE_DECAY (rotated Y LiNbO3 free near 41Y-X: a nearly real root above the top grid
    point, delta down to 0 at -49.42 deg, Im p >= 0.038, whose real-axis search wandered off;
    not Pb (111) 30 deg's real root with Im p = 3e-6). Other probes that drift back into the
    window are the real-axis search's business.

    Parameters
    ----------
    sc : dict
        The scan (:func:`scan`).
    XL : ndarray, shape (m, 2)
    stuck : ndarray, shape (k,), int
        The points to probe.
    fin : ndarray of bool, shape (m, SCAN)
        Grid points where the slowest sheet has one real pair.
    fg : ndarray, shape (m SCAN,), complex
    d : int
    electrical : Boundary
    tol : float

    Returns
    -------
    prow : ndarray, shape (k PROBE_Y.size,), int
        Point of each probe.
    keep : ndarray of bool, same shape
        Probes whose candidate is kept.
    extra : dict
        :func:`_candidates` of every probe.
    """
    top = SCAN - 1 - np.argmax(fin[stuck, ::-1], axis=1)
    prow = np.repeat(stuck, PROBE_Y.size)
    kp = prow * SCAN + np.repeat(top, PROBE_Y.size)
    tp = 0.5 * np.pi + 1j * np.tile(PROBE_Y, stuck.size)
    extra = _candidates_from(sc, XL, prow, tp, kp, fg, d, electrical, tol)
    good = extra["converged"] & (extra["why"] == "") & (
        (extra["delta"] > PROBE_DELTA) | np.all(extra["p"][:, 1:].imag > PROBE_DECAY, axis=1))
    keep = (extra["why"] == REASON_ABOVE) | good
    return prow, keep, extra


def _probe_below(sc, XL, low_rows, fin, fg, d, electrical, tol) -> tuple[np.ndarray, np.ndarray, dict]:
    """Searches from w = u - i y for points where no real-axis search converged (or there was no minimum).

    The branch may run toward v_L1 with Im w comparable to Re w (Re X - X_L1 << |Im X|), where
    |det| over real speeds is monotone. Searches from w = u - i y (PROBE_U x PROBE_Y1,
    Im X < 0), continued from the lowest grid point with a single real pair, find it; kept are
    verified roots with delta > PROBE_DELTA and roots that left the window through v_L1
    (REASON_LOW), after the same validation.

    Parameters
    ----------
    As :func:`_probe_above` (``low_rows``: the points to probe).

    Returns
    -------
    prow : ndarray, shape (k PROBE_U.size PROBE_Y1.size,), int
    keep : ndarray of bool, same shape
    extra : dict
        As :func:`_probe_above`.
    """
    bot = np.argmax(fin[low_rows], axis=1)
    starts = (PROBE_U[:, None] - 1j * PROBE_Y1[None, :]).reshape(-1)
    prow = np.repeat(low_rows, starts.size)
    kp = prow * SCAN + np.repeat(bot, starts.size)
    tp = np.tile(starts, low_rows.size)
    extra = _candidates_from(sc, XL, prow, tp, kp, fg, d, electrical, tol)
    keep = extra["converged"] & (((extra["why"] == "") & (extra["delta"] > PROBE_DELTA))
                                 | (extra["why"] == REASON_LOW))
    return prow, keep, extra


def _best_candidates(rows, cand, m) -> np.ndarray:
    """Per point: the least-attenuated good candidate, else the first converged search (its
    reason names what was found), else the first one.

    Parameters
    ----------
    rows : ndarray, shape (n,), int
        Point of each candidate.
    cand : dict
        The candidates (:func:`_candidates`, concatenated).
    m : int
        Number of points.

    Returns
    -------
    ndarray, shape (m,), int
        Index of the chosen candidate, -1 where a point has none.
    """
    score = np.where(cand["why"] == "", cand["delta"], np.inf)
    key = np.where(cand["converged"], 0, 1)
    best = np.full(m, -1)
    bscore = np.full(m, np.inf)
    bkey = np.full(m, 2)
    for c in range(rows.size):
        r = rows[c]
        if best[r] < 0 or score[c] < bscore[r] or (score[c] == bscore[r] == np.inf and key[c] < bkey[r]):
            best[r], bscore[r], bkey[r] = c, score[c], key[c]
    return best


def _root_polarisation(xi, idx, d, electrical) -> np.ndarray:
    """Surface polarisation at the roots: the null vector of the boundary condition.

    Parameters
    ----------
    xi : ndarray, shape (k, 2d, 2d), complex
        Stroh eigenvectors at the roots.
    idx : ndarray, shape (k, d), int
        The chosen partial waves.
    d : int
    electrical : Boundary

    Returns
    -------
    ndarray, shape (k, d), complex
        (u1, u2, u3[, phi]) with unit mechanical norm, phase such that the largest
        displacement component is real and positive; NaN where the condition is not finite.
    """
    _, M = _boundary(xi, idx, d, electrical)
    fin = np.all(np.isfinite(M), axis=(1, 2))
    w: np.ndarray = np.full(M.shape[:2], np.nan + 0j)
    if fin.any():
        w[fin] = np.linalg.svd(M[fin])[2][:, -1].conj()
    if w.shape[1] < d:   # a condition that fixes the potential (metallized): phi = 0 at the surface
        w = np.concatenate([w, np.zeros((w.shape[0], d - w.shape[1]))], axis=1)
    nm = np.linalg.norm(w[:, :3], axis=1)
    w = w / np.where(nm > 0, nm, 1)[:, None]
    big = np.take_along_axis(w, np.argmax(np.abs(w[:, :3]), axis=1)[:, None], axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        return w * (np.abs(big) / big)
