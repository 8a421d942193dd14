"""Analytic surface-wave dispersion of the prestressed triangular lattice (Eqs. 3a-16).

Row equations and geometry: :mod:`surfwave.dynamics.triangular` (row I at y = I d_y, row amplitudes
U_I multiply exp(i theta (I + 2J)) at atom (I, J); theta = k d_x). Bond force constants:
in-row bond (2 d_x, 0) gives Phi_row = diag(p, t) with p = phi''(2 d_x), t = phi'(2 d_x)/(2 d_x);
the inclined bonds (+-d_x, d_y) sit at d0, so with phi'(d0) = 0 they are pure springs
k r^r^ with k = phi''(d0): a = k d_x^2, b = k d_x d_y, c = k d_y^2 (a c = b^2).

A bulk wave U_I = exp(-q I) (U, iV) obeys (Eq. 3a corrected, Delta = (omega^2 - omega_0^2)/(4 a|c))

    Delta_L = cos(theta)(1 - cosh q) - R^-1 sin(theta) sinh q,
    Delta_T = cos(theta)(1 - cosh q) + R sin(theta) sinh q,      R = (a/c)^(1/2) U/V,

so that cosh q solves a quadratic (Eq. 6a) for ANY in-row potential (only p and t enter,
through omega_L, omega_T of Eq. 4a). The free-surface condition (Eqs. 7a-9a) does not involve
the in-row bond, so the paper's factorisation (Eqs. 12-14) carries over with
Omega_L^2 = (omega^2/4 - p sin^2 theta)/(k d_x^2) and Omega_T^2 = (omega^2/4 - t sin^2 theta)/(k d_y^2):
Eq. (14) is solved by omega^2 = 4 k y sin^2 theta with y the smaller root of

    2 y^2 - (2P + 2T + 1) y + (2 P T + T d_x^2 + P d_y^2) = 0,   P = p/k, T = t/k,

i.e. Eq. (15) omega = (c_R/d_x) sin(theta) with c_R^2 = 4 k y d_x^2 for every pair potential
with phi'(d0) = 0 (harmonic: Eq. 16). The numerical solve in :mod:`surfwave.dynamics.triangular_surface`
checks this independently. Units: m = K = d0 = 1; frequencies in (K/m)^(1/2).
"""
from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from surfwave.dynamics.surface_green import inv2, null_vector2
from surfwave.dynamics.triangular import bond_force_constants, row_matrices
from surfwave.errors import InputError
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.validate import as_1d

REASON_THETA = "theta outside (0, pi)"
REASON_SURFACE = "surface unstable: c_R^2 <= 0 (the free surface buckles before or with the bulk)"
REASON_BULK = "bulk unstable: a long-wave sound speed squared is <= 0"
REASON_PRESTRESS = "analytic solution needs stress-free inclined bonds, phi'(d0) = 0"
REASON_BOUNDARY = "root of Eq. 14 fails the unsquared free-surface condition"


#: pi - float(np.pi): adding it makes pi - theta exact to rounding for theta near pi.
_PI_LO = 1.2246467991473532e-16


def _fold(th):
    """(far, theta') with far = theta > pi/2 and theta' = min(theta, pi - theta), the latter
    computed with the low part of pi so that sin(theta') = sin(theta) to rounding near pi."""
    far = th > 0.5 * np.pi
    return far, np.where(far, (np.pi - th) + _PI_LO, th)


def lattice_constants(potential: str | PairPotential, d_over_d0: ArrayLike) -> dict[str, np.ndarray]:
    """Geometry and force constants entering the analytic solution, each shape (n,).

    Returns dx, dy (d0), a, b, c (inclined bond, K), p, t (in-row bond, K), k = a + c,
    incl_stress = phi'(|inclined bond|) (K d0), c2_R (Eq. 15/16 generalised, K d0^2/m),
    c2_L_par, c2_T_par (long-wave, from the q = 0 limits of Eq. 4a, K d0^2/m) and
    ``valid_strain`` (bool) with ``strain_reason`` (str).

    Raises
    ------
    GeometryError
        If d_over_d0 is outside (0, 2) (the inclined bonds cannot stay at d0).
    """
    pot = get_potential(potential)
    s = as_1d(d_over_d0, "d_over_d0")
    phi = bond_force_constants(pot, s)  # (n, 3, 2, 2): row, up, um
    dx = 0.5 * s
    dy = np.sqrt(1.0 - dx**2)
    a, b, c = phi[:, 1, 0, 0], phi[:, 1, 0, 1], phi[:, 1, 1, 1]
    p, t = phi[:, 0, 0, 0], phi[:, 0, 1, 1]
    k = a + c
    incl_stress = np.asarray(pot.dphi(np.ones_like(s)), dtype=float)
    with np.errstate(all="ignore"):
        P, T = p / k, t / k
        lin = 2 * P + 2 * T + 1
        const = 2 * P * T + T * dx**2 + P * dy**2
        root = np.sqrt(np.maximum(lin**2 - 8 * const, 0.0))  # >= 0 always (module docstring)
        y = np.where(lin > 0, 2 * const / (lin + root), (lin - root) / 4)
    c2_R = 4 * k * y * dx**2
    c2_L_par = (4 * p + 2 * a) * dx**2
    c2_T_par = (4 * t + 2 * c) * dx**2
    reason = np.full(s.shape, "", dtype=object)
    reason[~(c2_R > 0)] = REASON_SURFACE
    reason[~((c2_T_par > 0) & (c2_L_par > 0) & (k > 0))] = REASON_BULK
    reason[np.abs(incl_stress) > 1e-12 * np.maximum(np.abs(k), 1.0)] = REASON_PRESTRESS
    return dict(dx=dx, dy=dy, a=a, b=b, c=c, p=p, t=t, k=k, incl_stress=incl_stress,
                c2_R=c2_R, c2_L_par=c2_L_par, c2_T_par=c2_T_par,
                valid_strain=reason == "", strain_reason=reason)


def _y_quadratic(lc: dict, W, th):
    """Coefficients (A, B, C) of A Y^2 + B Y + C = 0, Y = cosh q - 1, at 0 < th <= pi/2.

    Written with h = 1 - cos th and s = sin^2 th so that all terms are computed without
    cancellation as th -> 0 (B ~ th^2, C ~ th^4). Shapes broadcast (n, m).
    """
    a, b, c, p, t = (lc[key][:, None] for key in "abcpt")
    h = 2 * np.sin(0.5 * th) ** 2
    s = np.sin(th) ** 2
    C = np.cos(th)
    al, be = 4 * p - W, 4 * t - W  # alpha = 4a + s al, beta = 4c + s be
    A = 16 * (a * c * C**2 + b**2 * s)
    B = 32 * a * c * h - 32 * (a * c - b**2) * s - 4 * C * s * (al * c + be * a)
    Cc = 16 * a * c * h**2 + 4 * s * h * (a * be + c * al) + s**2 * al * be
    return A, B, Cc


def _discriminant(lc: dict, W, th):
    A, B, Cc = _y_quadratic(lc, W, th)
    return B**2 - 4 * A * Cc


def crossover_theta(lc: dict, n_grid: int = 512, n_bisect: int = 60) -> np.ndarray:
    """theta_c per strain: the smallest theta in (0, pi/2] where q1, q2 turn complex, shape (n,).

    Grid scan of the sign of the Eq. 6a discriminant (at omega of Eq. 15) followed by a
    vectorised bisection to ~1e-16. 0 where q is complex at all wavelengths (tension), NaN
    where the strain is invalid or q stays real up to pi/2.

    Parameters
    ----------
    lc : dict
        From :func:`lattice_constants` (arrays of shape (n,)).
    n_grid, n_bisect : int
        Points of the sign scan on (0, pi/2] and bisection steps.

    Returns
    -------
    ndarray, shape (n,)
        theta_c in rad; by symmetry q is complex on theta_c < theta < pi - theta_c.
    """
    W = (lc["c2_R"] / lc["dx"] ** 2)[:, None]
    grid = np.linspace(0.5 * np.pi / n_grid, 0.5 * np.pi, n_grid)[None, :]
    with np.errstate(all="ignore"):
        neg = _discriminant(lc, W, grid) < 0  # (n, n_grid)
        # long-wave sign (the discriminant ~ theta^4 D0 is computed without cancellation)
        always = _discriminant(lc, W, np.full((1, 1), 1e-6))[:, 0] < 0  # complex at all theta
    has = neg.any(axis=1) & lc["valid_strain"]
    first = np.argmax(neg, axis=1)
    hi = grid[0, first]
    lo = np.where(first > 0, grid[0, np.maximum(first - 1, 0)], 1e-6)
    W1 = W[:, 0]
    for _ in range(n_bisect):
        mid = 0.5 * (lo + hi)
        with np.errstate(all="ignore"):
            m_neg = _discriminant(lc, W1[:, None], mid[:, None])[:, 0] < 0
        hi = np.where(m_neg, mid, hi)
        lo = np.where(m_neg, lo, mid)
    return np.where(has, np.where(always, 0.0, 0.5 * (lo + hi)), np.nan)


def _decay_constants(lc: dict, W, th):
    """[(q1, z1, c1), (q2, z2, c2)]: decay constants (Re q > 0) at any th in (0, pi), with
    z = sinh(q'/2), c = cosh(q'/2), q' = q (th <= pi/2) or q - i pi; shapes (n, m), complex.

    Uses the symmetry of Eq. 6a under theta -> pi - theta, cosh q -> -cosh q, so that
    theta > pi/2 is as accurate as theta < pi/2 (there q = q' + i pi).
    """
    far, thp = _fold(th)
    A, B, Cc = _y_quadratic(lc, W, thp)
    D = B**2 - 4 * A * Cc
    sq = np.sqrt(np.abs(D))
    Q = -0.5 * (B + np.where(B >= 0, sq, -sq))  # Citardauq for real roots
    safeQ = np.where(Q == 0, 1.0, Q)
    y_a, y_b = Q / A, np.where(Q == 0, Q / A, Cc / safeQ)
    y_real_lo, y_real_hi = np.minimum(y_a, y_b), np.maximum(y_a, y_b)
    y_cplx = (-B + 1j * sq) / (2 * A)
    y1 = np.where(D >= 0, y_real_lo + 0j, np.conj(y_cplx))
    y2 = np.where(D >= 0, y_real_hi + 0j, y_cplx)
    out = []
    for y in (y1, y2):
        z = np.sqrt(0.5 * y)  # sinh(q'/2)
        q = 2 * np.arcsinh(z)
        flip = q.real < 0
        q, z = np.where(flip, -q, q), np.where(flip, -z, z)
        ch = np.sqrt(1 + 0.5 * y)  # cosh(q'/2)
        out.append((np.where(far, q + 1j * np.pi, q), z, ch))
    return out


def _ratios(lc: dict, W, th, qzc):
    """R = (a/c)^(1/2) U/V of the wave exp(-q I) at omega^2 = W sin^2 th (Eq. 3a), shape (n, m).

    ``qzc`` = (q, sinh(q'/2), cosh(q'/2)) from :func:`_decay_constants`.
    """
    a, b, c, p, t = (lc[key][:, None] for key in "abcpt")
    _, z, ch = qzc
    s = np.sin(th) ** 2
    far, thp = _fold(th)  # there q = q' + i pi: use theta' = pi - theta to avoid cancellation
    one_m_cx = 2 * np.sin(0.5 * thp) ** 2 - np.cos(thp) * 2 * z**2  # 1 - cos(th) cosh(q)
    sh = np.where(far, -2.0, 2.0) * z * ch  # sinh q
    w2 = W * s
    den_x = 4 * p * s - w2 + 4 * a * one_m_cx  # alpha - 4 a C X
    num_y = -(4 * t * s - w2 + 4 * c * one_m_cx)  # -(beta - 4 c C X)
    off = 4 * b * np.sin(th) * sh
    use_x = np.abs(den_x) >= np.abs(off)
    with np.errstate(all="ignore"):
        u_over_v = np.where(use_x, off / np.where(use_x, den_x, 1.0), num_y / np.where(use_x, 1.0, off))
    return np.sqrt(a / c) * u_over_v


def _boundary_rows(th, w1, w2, R1, R2):
    """Rows (x, y) of the free-surface condition on (V1, V2), Eqs. (7a)-(8a), shape (2, 2, n, m).

    ``w1``, ``w2`` = (q, sinh(q'/2), cosh(q'/2)) from :func:`_decay_constants`. Columns are
    scaled by |R_j e^q_j| + |e^q_j| + 1 so that the two rows compare fairly.
    e^q cos(theta) - 1 = expm1(q') cos(theta') - 2 sin^2(theta'/2) with
    expm1(q') = 2 sinh(q'/2) (cosh(q'/2) + sinh(q'/2)) (q' = q, theta' = theta, or q - i pi,
    pi - theta beyond pi/2) is formed without cancellation, so the residual stays at rounding
    level as theta -> 0 or pi (where q' -> 0).
    """
    _, thp = _fold(th)
    S, h, Cp = np.sin(th), 2 * np.sin(0.5 * thp) ** 2, np.cos(thp)
    cols = []
    for (q, z, ch), R in ((w1, R1), (w2, R2)):
        e = np.exp(q)
        ecm1 = 2 * z * (ch + z) * Cp - h  # e^q cos(theta) - 1
        scale = np.abs(R * e) + np.abs(e) + 1
        cols.append(((R * ecm1 + e * S) / scale, (R * e * S - ecm1) / scale, scale))
    return cols


def _amplitude_ratio(th, w1, w2, R1, R2):
    """Eq. (8a): V1/V2 from the better conditioned row of the free-surface condition.

    Returns the ratio and the residual |det| / max|row|^2 of the (scaled) 2x2 boundary
    matrix, which vanishes for a genuine surface wave (the unsquared condition, Eq. 9a).
    """
    (x1, y1, s1), (x2, y2, s2) = _boundary_rows(th, w1, w2, R1, R2)
    nx = np.abs(x1) ** 2 + np.abs(x2) ** 2
    ny = np.abs(y1) ** 2 + np.abs(y2) ** 2
    use_x = nx >= ny
    num = np.where(use_x, x2, y2)
    den = np.where(use_x, x1, y1)
    ratio = -(num * s2) / (den * s1)
    resid = np.abs(x1 * y2 - x2 * y1) / np.maximum(nx, ny)
    return ratio, resid


def solve(potential: str | PairPotential, d_over_d0: ArrayLike, theta: ArrayLike) -> dict[str, np.ndarray]:
    """Analytic surface-wave solution of the triangular lattice on a (strain, theta) grid.

    Parameters
    ----------
    potential : str or PairPotential
        Any registered pair potential; the solution assumes phi'(d0) = 0 (else NaN + reason).
    d_over_d0 : array_like, shape (n,)
        2 d_x / d0, in (0, 2) (else GeometryError).
    theta : array_like, shape (m,)
        k d_x in radians; valid in (0, pi), other values give NaN with a reason.

    Returns
    -------
    dict
        ``omega``, ``omega_L``, ``omega_T`` (n, m) float, (K/m)^(1/2);
        ``q1``, ``q2``, ``R1``, ``R2``, ``amplitude_ratio`` (n, m) complex, dimensionless;
        ``theta_c`` (n,) rad; ``c2_R`` (n,) K d0^2/m; ``reason`` (n, m) str ("" if valid);
        ``boundary_residual`` (n, m): relative residual of the unsquared surface condition.
        Metadata in ``surfwave.data.variables.CUBES["dispersion"]``.

    Examples
    --------
    >>> import numpy as np
    >>> r = solve("harmonic", [1.0], [np.pi / 2])
    >>> round(float(r["omega"][0, 0]), 6), round(float(r["c2_R"][0]), 6)
    (1.126033, 0.316987)
    """
    lc = lattice_constants(potential, d_over_d0)
    th_in = as_1d(theta, "theta")
    n, m = lc["dx"].size, th_in.size
    reason = np.empty((n, m), dtype=object)
    reason[:] = lc["strain_reason"][:, None]
    bad_th = ~((th_in > 0) & (th_in < np.pi))
    reason[:, bad_th] = np.where(lc["valid_strain"][:, None], REASON_THETA, reason[:, bad_th])
    th = np.where(bad_th, 0.5 * np.pi, th_in)[None, :]  # (1, m), broadcasts against (n, 1)
    ok = lc["valid_strain"][:, None] & ~bad_th[None, :]
    # Invalid strains get harmless stand-in constants so no warning is raised; masked below.
    lcs = dict(lc)
    for key, val in (("a", 0.25), ("b", 0.75**0.5 / 2), ("c", 0.75), ("p", 1.0), ("t", 0.0)):
        lcs[key] = np.where(lc["valid_strain"], lc[key], val)
    c2 = np.where(lc["valid_strain"], lc["c2_R"], (3 - 3**0.5) / 4)
    dx = np.where(lc["valid_strain"], lc["dx"], 0.5)
    W = (c2 / dx**2)[:, None]
    w1, w2_ = _decay_constants(lcs, W, th)
    q1, q2 = w1[0], w2_[0]
    R1, R2 = _ratios(lcs, W, th, w1), _ratios(lcs, W, th, w2_)
    with np.errstate(all="ignore"):
        ratio, resid = _amplitude_ratio(th, w1, w2_, R1, R2)
    fail = ok & (~(resid < 1e-6) | ~((q1.real > 0) & (q2.real > 0)))
    reason[fail] = REASON_BOUNDARY
    ok &= ~fail
    h = 2 * np.sin(0.5 * th) ** 2
    s = np.sin(th) ** 2
    wl2 = 4 * lcs["p"][:, None] * s + 4 * lcs["a"][:, None] * h
    wt2 = 4 * lcs["t"][:, None] * s + 4 * lcs["c"][:, None] * h
    nan = np.nan
    omega = np.where(ok, np.sqrt(W) * np.sin(th), nan)
    out = {
        "omega": omega,
        "q1": np.where(ok, q1, nan), "q2": np.where(ok, q2, nan),
        "R1": np.where(ok, R1, nan), "R2": np.where(ok, R2, nan),
        "amplitude_ratio": np.where(ok, ratio, nan),
        "theta_c": crossover_theta(lcs) * np.where(lc["valid_strain"], 1.0, nan),
        "omega_L": np.where(ok, np.sqrt(np.abs(wl2)), nan),
        "omega_T": np.where(ok, np.sqrt(np.abs(wt2)), nan),
        "c2_R": np.where(lc["valid_strain"], lc["c2_R"], nan),
        "reason": reason,
        "boundary_residual": np.where(ok, resid, nan),
    }
    return out


def decay_solvent(A0: np.ndarray, A1: np.ndarray, omega2: np.ndarray, q1: np.ndarray, q2: np.ndarray) -> np.ndarray:
    """Row-to-row propagator Lambda (U_{I+1} = Lambda U_I) of the decaying solutions.

    From Cayley-Hamilton, Lambda^2 = sigma Lambda - pi with sigma = e^-q1 + e^-q2 and
    pi = e^-(q1+q2); with A1 Lambda^2 + (A0 - omega^2) Lambda + A1^H = 0 this gives
    Lambda = (sigma A1 + A0 - omega^2)^-1 (pi A1 - A1^H), smooth through q1 = q2.

    Parameters
    ----------
    A0, A1 : ndarray, shape (n, m, 2, 2), complex (K/m)
    omega2 : ndarray, shape (n, m), K/m
    q1, q2 : ndarray, shape (n, m), complex

    Returns
    -------
    ndarray, shape (n, m, 2, 2), complex
    """
    sig = (np.exp(-q1) + np.exp(-q2))[..., None, None]
    pro = np.exp(-(q1 + q2))[..., None, None]
    lhs = sig * A1 + A0 - omega2[..., None, None] * np.eye(2)
    # singular lhs (measure-zero points) gives NaN, not an error (inv2 suppresses the warning)
    return inv2(lhs) @ (pro * A1 - np.conj(np.swapaxes(A1, -1, -2)))


def default_rows(q1: np.ndarray, q2: np.ndarray, floor: float = 1e-3, minimum: int = 10, maximum: int = 400) -> int:
    """Rows needed for the slowest wave to decay to ``floor``: ln(1/floor)/min Re q, clipped."""
    qmin = np.nanmin(np.minimum(np.real(q1), np.real(q2)), initial=np.inf)
    if not np.isfinite(qmin) or qmin <= 0:
        return minimum
    return int(np.clip(np.ceil(np.log(1.0 / floor) / qmin) + 1, minimum, maximum))


def displacements(potential: str | PairPotential, d_over_d0: ArrayLike, theta: ArrayLike,
                  n_rows: int | None = None) -> dict:
    """Surface-wave displacement amplitudes of rows 0..n_rows-1 (Fig. 3).

    The surface row U_0 is the null vector of omega^2 - A0_surface - A1 Lambda and
    U_I = Lambda^I U_0, with Lambda from :func:`decay_solvent` (exact q1, q2 of Eq. 6a and
    omega of Eq. 15); this equals the paper's (q1, q2, R1, R2, Eq. 8a) superposition and stays
    regular at theta_c where q1 = q2.

    Parameters
    ----------
    potential, d_over_d0, theta
        As :func:`solve`; shapes (n,), (m,).
    n_rows : int, optional
        Rows returned. Default: until the slowest decay falls to 1e-3, at least 10, at most 400.

    Returns
    -------
    dict
        ``u``, ``v``: (n, m, rows) complex; u_IJ = u_I exp(i theta (I + 2J)) at atom (I, J).
        Normalised so that max_I (|u_I|^2 + |v_I|^2)^(1/2) = 1, phase such that v_0 is
        positive imaginary (the paper's (U, iV) form: u real, v imaginary while q is real);
        if |v_0| < 1e-12 then u_0 is real positive. NaN where :func:`solve` is NaN.
        ``row``: (rows,) int. ``reason``: (n, m) as in :func:`solve`.

    Notes
    -----
    Lambda inverts a matrix that becomes singular like theta as theta -> 0 or pi, so the
    row equations hold to ~1e-11 down to theta = 1e-6 (from either end) but only to
    ~eps / theta below (measured: 1e-5 at theta = 1e-12). omega, q and R from :func:`solve`
    stay exact to rounding there.
    """
    sol = solve(potential, d_over_d0, theta)
    ok = sol["reason"] == ""
    if n_rows is None:
        n_rows = default_rows(sol["q1"], sol["q2"])
    if int(n_rows) < 1:
        raise InputError(f"n_rows must be >= 1, got {n_rows}")
    n_rows = int(n_rows)
    th_in = as_1d(theta, "theta")
    th = np.where((th_in > 0) & (th_in < np.pi), th_in, 0.5 * np.pi)
    A0, A0s, A1 = row_matrices(potential, d_over_d0, th)
    w2 = np.where(ok, sol["omega"], 1.0) ** 2
    q1 = np.where(ok, sol["q1"], 1.0)
    q2 = np.where(ok, sol["q2"], 2.0)
    with np.errstate(all="ignore"):
        lam = np.where(ok[..., None, None], decay_solvent(A0, A1, w2, q1, q2), 0.0)
        S = w2[..., None, None] * np.eye(2) - A0s - A1 @ lam
    U = null_vector2(S)
    rows = [U]
    for _ in range(n_rows - 1):
        rows.append((lam @ rows[-1][..., None])[..., 0])
    disp = np.stack(rows, axis=-2)  # (n, m, rows, 2)
    v0 = disp[..., 0, 1]
    phase = np.where(np.abs(v0) > 1e-12 * np.abs(disp[..., 0, :]).max(-1),
                     1j * np.abs(v0) / np.where(v0 == 0, 1, v0),
                     np.abs(disp[..., 0, 0]) / np.where(disp[..., 0, 0] == 0, 1, disp[..., 0, 0]))
    norm = np.linalg.norm(disp, axis=-1).max(axis=-1)
    with np.errstate(all="ignore"):
        disp = disp * (phase / norm)[..., None, None]
    disp = np.where(ok[..., None, None], disp, np.nan)
    return {"u": disp[..., 0], "v": disp[..., 1], "row": np.arange(n_rows), "reason": sol["reason"]}

