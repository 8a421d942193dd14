"""Leaky (pseudo) surface waves with attenuation, elastic and piezoelectric, vectorised.

Physics (docs/physics/leaky-waves.md). Above the limiting speed v_L1 of the SLOWEST bulk sheet
(the lowest trace speed along x1 of the bulk waves, where one pair of Stroh roots p turns
real), a surface wave can only exist as a leaky wave: one partial wave is a bulk wave of that
sheet carrying energy into the crystal (+x2). It is chosen at real speed by the sign of its
x2 energy flux Re(a^H b) (> 0 into the crystal), and followed by continuity (nearest-root
tracking along the root search) to complex X = rho v^2. With real omega and a wave decaying
along +x1, k = k_r (1 + i delta), delta > 0, so v = omega / k has Im v < 0 and Im X < 0; the
outgoing bulk root then has Im p < 0 (dp/dX = 1 / (2 rho v V_g2) > 0): it grows with depth,
the signature of a leaky wave. The other d - 1 partial waves decay (Im p > 0).

The boundary function is det of the surface impedance of the chosen partial waves,
M = B A^-1 (b = M u at the surface, independent of the eigenvector normalisation):
elastic det M; piezoelectric, electrically free det(M - i eps0~ e4 e4^T) (vacuum potential
exp(ik x1 + k x2) gives D2 = -EPS0 dphi/dx2 = -EPS0 k phi, hence b4 = D2 / (ik) = +i EPS0 a4);
metallized det(M_mech) (phi = 0). Its root in the complex variable w,
X = X_L1 + (X_L2 - X_L1) sin^2 w (sqrt(X - X_L1) and sqrt(X_L2 - X) are analytic in w), is
found by the secant method from every minimum of |det| over a grid of real speeds between
v_L1 and v_L2; the least-attenuated root is kept. Where none of these searches converges, searches
from w = pi/2 + i y (real X above X_L2) look for the branch that left the window through v_L2
(kept as a NaN with REASON_ABOVE) or for a nearly real root just below v_L2 that the real-axis
search missed (kept when verified and not grazing: delta > PROBE_DELTA or Im p > PROBE_DECAY).
Without a verified root the reason of the first converged search is reported, else the first
search's.

Only the leaky wave that radiates into the slowest bulk sheet is reported: a root whose
real speed lies above the second sheet's limiting speed v_L2 (radiating into two sheets)
is NaN with a reason, as is a root with growing amplitude along x1 (delta < 0).

Every root is validated before it is reported (docs/physics/leaky-waves.md, "Every root is
validated"): c_leaky below v_L2, the d - 1 non-radiating partial waves decaying (Im p > 0) at the
root, and, followed back to real speed Re X, the chosen set is the outgoing bulk wave (real p,
flux > 0) plus d - 1 decaying waves, not the incoming one. Otherwise NaN with a reason.
"""
from __future__ import annotations

import numpy as np

from surfwave.errors import InputError
from surfwave.solvers.boundary import Boundary, as_boundary
from surfwave.solvers.leaky_search import (  # noqa: F401  (public names of this module, kept)
    BACK_FRAC,
    BACK_MAX,
    GROW_TOL,
    MAX_HALVING,
    MAX_ITER,
    PROBE_DECAY,
    PROBE_DELTA,
    PROBE_U,
    PROBE_Y,
    PROBE_Y1,
    REAL_TOL,
    REASON_ABOVE,
    REASON_BELOW,
    REASON_EDGE,
    REASON_GROW,
    REASON_INCOMING,
    REASON_LOW,
    REASON_MULTI,
    REASON_NOMIN,
    REASON_NOROOT,
    REASON_SHEET,
    REASON_TRACK,
    SCAN,
    STEP_MAX,
    T_EDGE,
    scan,
    solve,
)
from surfwave.solvers.piezo_stroh import generalised_blocks
from surfwave.solvers.piezo_tensors import EPS0
from surfwave.vocab import ELECTRICAL  # noqa: F401  (kept: a public name of this module)

#: dB per wavelength per unit delta: 20 log10(exp(2 pi delta)) = 40 pi log10(e) delta.
DB_PER_DELTA = 40 * np.pi * np.log10(np.e)
#: Points of the angle grid for the limiting speeds of the bulk sheets.
LIMIT_GRID = 64
#: Golden-section steps refining each sheet's minimum (bracket shrinks by 0.618^GOLDEN).
GOLDEN = 22

REASON_UNSTABLE = "no leaky wave: T = A_i2k2 (mechanical block) not positive definite or v_L1^2 <= 0"


def _sheet_x(Q, R, T, p, d) -> np.ndarray:
    """rho v_trace^2 of the bulk sheets for real slopes p (m, k): ascending eigenvalues (m, k, 3)."""
    G = Q[:, None] + p[..., None, None] * (R + np.swapaxes(R, -1, -2))[:, None] + \
        (p * p)[..., None, None] * T[:, None]
    S = G[..., :3, :3]
    if d == 4:  # quasi-static electric field: stiffened Christoffel matrix (Schur complement)
        S = S - G[..., :3, 3:] * G[..., 3:, :3] / G[..., 3:, 3:]
    return np.linalg.eigvalsh(S)


def _limits(Q, R, T, d) -> np.ndarray:
    """Limiting X = rho v_L^2 of the slowest and second sheet, min over real p, shape (m, 2).

    Grid in the bulk-wave angle phi (p = tan phi), then golden-section refinement of each
    branch's best grid minimum (a bracket of two grid steps), both sheets in one evaluation per
    step: each step reuses one interior point, so it costs one new point per sheet.
    """
    m = Q.shape[0]
    h = np.pi / LIMIT_GRID
    phi = -0.5 * np.pi + h * (np.arange(LIMIT_GRID) + 0.5)
    lam = _sheet_x(Q, R, T, np.broadcast_to(np.tan(phi), (m, LIMIT_GRID)), d)   # (m, k, 3)
    g = 0.5 * (np.sqrt(5) - 1)
    sh = np.arange(2)

    def branch(x):   # sheet s at x[:, s], shape (m, 2)
        return _sheet_x(Q, R, T, np.tan(x), d)[:, sh, sh]

    j = np.argmin(lam[:, :, :2], axis=1)                                        # (m, 2)
    lo, hi = phi[j] - h, phi[j] + h
    x1, x2 = hi - g * (hi - lo), lo + g * (hi - lo)
    f1, f2 = branch(x1), branch(x2)
    for it in range(GOLDEN):
        left = f1 < f2      # the minimum lies in [lo, x2]: x2 <- x1 and a new x1, else mirrored
        hi = np.where(left, x2, hi)
        lo = np.where(left, lo, x1)
        if it == GOLDEN - 1:
            break
        new = np.where(left, hi - g * (hi - lo), lo + g * (hi - lo))
        fn = branch(new)
        x1, x2 = np.where(left, new, x2), np.where(left, x1, new)
        f1, f2 = np.where(left, fn, f2), np.where(left, f1, fn)
    c = 0.5 * (lo + hi)
    return np.minimum(branch(c), lam[:, :, :2].min(1))


def _check(A, rho, e, eps):
    A = np.asarray(A, dtype=float)
    if A.ndim != 5 or A.shape[1:] != (3, 3, 3, 3):
        raise InputError(f"A must have shape (m, 3, 3, 3, 3), got {A.shape}")
    m = A.shape[0]
    rho = np.broadcast_to(np.asarray(rho, dtype=float), (m,))
    if np.any(~np.isfinite(rho) | (rho <= 0)):
        raise InputError(f"rho must be positive and finite (kg/m^3), got {rho[~(rho > 0)][:3]}")
    if not np.all(np.isfinite(A)):
        raise InputError("A contains non-finite values")
    if (e is None) != (eps is None):
        raise InputError(f"give both e and eps or neither (e is {type(e).__name__}, eps is {type(eps).__name__})")
    if e is not None:
        e = np.broadcast_to(np.asarray(e, dtype=float), (m, 3, 3, 3))
        eps = np.broadcast_to(np.asarray(eps, dtype=float), (m, 3, 3))
        if not (np.all(np.isfinite(e)) and np.all(np.isfinite(eps))):
            raise InputError("e or eps contains non-finite values")
        big = np.abs(eps).max()
        if big > 1e-6 or big < 1e-14:
            raise InputError(f"eps must be absolute permittivity in F/m (eps_r * EPS0), got max |eps| = {big:g}")
    return A, rho, e, eps


def leaky_wave(A, rho, e=None, eps=None, *, electrical="free", tol=1e-10) -> dict:
    """Leaky surface wave radiating into the slowest bulk sheet: complex speed and attenuation.

    Only the leaky wave whose radiated partial wave belongs to the SLOWEST bulk sheet (real
    speed between the limiting speeds v_L1 and v_L2 of the two slowest sheets) is reported;
    leaky waves radiating into two or more sheets are NaN with a reason.

    Parameters
    ----------
    A : array_like, shape (m, 3, 3, 3, 3), Pa
        Wave-propagation tensor A_ijkl = C_ijkl + sigma0_jl delta_ik, lab frame (x1 propagation,
        x2 inward normal).
    rho : float or array_like, shape (m,), kg/m^3
    e : None or array_like, shape (m, 3, 3, 3), C/m^2
        Piezoelectric stress constants e_kij, lab frame; None: non-piezoelectric (6 x 6 problem).
    eps : None or array_like, shape (m, 3, 3), F/m
        Absolute clamped permittivity, lab frame (with ``e``).
    electrical : {"free", "metallized"}, a :class:`surfwave.solvers.boundary.Boundary`, or a sequence of them
        Electrically free surface (vacuum above) or shorted (phi = 0), or any boundary object
        (its ``secular_matrix``; the result is keyed by its ``name``). Ignored without ``e``.
        A sequence (e.g. ``("free", "metallized")``, each once) solves every condition in one call:
        the limits, the real-speed scan's eigen-decompositions, the outgoing choice and the surface
        impedance M = B A^-1 on the grid are shared (only the boundary function's electrical part
        differs); the secant searches and the validation are per condition. The answers are
        bit-identical to one call per condition.
    tol : float
        Relative accuracy of the complex X = rho v^2.

    Returns
    -------
    dict of ndarray, leading shape (m,); with a sequence ``electrical``: dict condition -> that dict
        ``c_leaky`` omega / k_r (m/s) with k = k_r (1 + i delta); ``leaky_attenuation``
        40 pi log10(e) delta, dB per wavelength (>= 0); ``c_leaky_complex`` v = omega / k
        (complex, m/s, Im v <= 0); ``delta`` (1, signed, also where the root was rejected, e.g.
        delta < 0 beyond a cut angle where the attenuation passes through zero); ``reason`` (object str, "" when found);
        ``radiating_sheet`` (int: 0 = slowest bulk sheet, -1 where none); ``decay`` (m, d)
        complex Stroh roots p of the partial waves, the radiating one (Im p <= 0) first, the
        decaying ones after in ascending Im p (d = 3 elastic, 4 piezoelectric); ``polarisation``
        (m, d) complex surface (u1, u2, u3[, phi]) with unit mechanical norm (phi in V per m of
        displacement); ``c_limits`` (m, 2) v_L1, v_L2 (m/s); ``iterations`` (m,) int.

    Raises
    ------
    InputError
        Wrong shapes, non-finite values, rho <= 0, eps not absolute, unknown ``electrical``.
    """
    several = not isinstance(electrical, (str, Boundary))
    bounds = tuple(as_boundary(el) for el in (electrical if several else (electrical,)))
    conds = tuple(b.name for b in bounds)         # the result's keys; the objects do the physics
    if not conds or len(set(conds)) != len(conds):
        raise InputError(f"electrical: each condition once, at least one, got {electrical!r}")
    A, rho, e, eps = _check(A, rho, e, eps)
    m = A.shape[0]
    s = np.abs(A).max(axis=(1, 2, 3, 4))
    if e is None:
        d = 3
        An = A / s[:, None, None, None, None]
        Q, R, T = An[:, :, 0, :, 0], An[:, :, 0, :, 1], An[:, :, 1, :, 1]
    else:
        d = 4
        Q, R, T = generalised_blocks(A / s[:, None, None, None, None], e / np.sqrt(s * EPS0)[:, None, None, None],
                                      eps / EPS0)
    XL = np.full((m, 2), np.nan)
    ok = np.linalg.eigvalsh(T[:, :3, :3])[:, 0] > 0
    if ok.any():
        XL[ok] = _limits(Q[ok], R[ok], T[ok], d)
    ok &= XL[:, 0] > 0
    ii = np.nonzero(ok)[0]
    sc = scan(Q[ii], R[ii], T[ii], XL[ii], d) if ii.size else None
    out: dict = {}
    for el, bound in zip(conds, bounds):
        if d == 3 and out:          # elastic: the condition is ignored, the same answer (copied)
            first = out[conds[0]]
            out[el] = {k: v.copy() for k, v in first.items()}
            continue
        reason = np.full(m, "", dtype=object)
        reason[~ok] = REASON_UNSTABLE
        X = np.full(m, np.nan + 0j)
        pch = np.full((m, d), np.nan + 0j)
        pol = np.full((m, d), np.nan + 0j)
        its = np.zeros(m, dtype=int)
        if ii.size:
            X[ii], pch[ii], pol[ii], its[ii], reason[ii] = solve(sc, XL[ii], d, bound, tol)
        out[el] = _result(X, pch, pol, its, reason, XL, s, rho, d)
    return out if several else out[conds[0]]


def _result(X, pch, pol, its, reason, XL, s, rho, d) -> dict:
    """The dict :func:`leaky_wave` returns for one condition from the scaled solution.

    X (m,) complex scaled rho v^2; pch, pol (m, d) complex; its (m,) int; reason (m,) object;
    XL (m, 2) scaled limits; s (m,) Pa stiffness scale; rho (m,) kg/m^3; d 3 or 4.
    """
    if d == 4:
        pol[:, 3] *= np.sqrt(s / EPS0)              # back from the scaled potential to volts
    # physical speeds: v = omega / k, k = k_r (1 + i delta)  =>  1 / v = (1 + i delta) / c_leaky
    v = np.sqrt(X * (s / rho))                      # principal branch: Re v > 0
    with np.errstate(invalid="ignore", divide="ignore"):
        inv = 1.0 / v
        delta = inv.imag / inv.real
        c_l = 1.0 / inv.real
    found = reason == ""
    pch[~found] = np.nan
    pol[~found] = np.nan
    return {
        "c_leaky": np.where(found, c_l, np.nan),
        "leaky_attenuation": np.where(found, DB_PER_DELTA * np.maximum(delta, 0.0), np.nan),
        "c_leaky_complex": np.where(found, v, np.nan),
        "delta": delta,
        "reason": reason,
        "radiating_sheet": np.where(found, 0, -1),
        "decay": pch,
        "polarisation": pol,
        "c_limits": np.sqrt(XL * (s / rho)[:, None]),
        "iterations": its,
    }
