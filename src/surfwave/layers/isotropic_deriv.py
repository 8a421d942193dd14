"""The isotropic secular functions with their exact derivatives (forward mode), for Newton steps and group velocity.

At points (t_j, kh_j), t = sqrt(1 - c^2 / c_lim^2) (c_lim the substrate's shear speed), the recursions
of :mod:`surfwave.layers.isotropic` are carried with two tangents: d/dt at fixed kh and d/dkh at
fixed c. Each call returns the value of :func:`secular_psv` / :func:`secular_sh` and its two
derivatives. P-SV: the tangents hold every positive factor (the overflow scale g of each
evanescent wave, the renormalisation of the vector) constant, and the factors' own
log-derivatives are added (d log g = -t dr / dt, d log |m| = m . m' / |m|^2), so the derivatives
are those of the function itself (Newton on the scaled function, which is bounded,
converges where Newton on the unscaled one, dominated by exp(r t), would crawl). SH: the function
tau / |(v, tau)| is invariant under positive factors, so they are held constant and drop out.

Derivatives of the layer functions (unscaled C(s) = cosh(sqrt(s) t), S(s) = sinh(sqrt(s) t) / sqrt(s),
s = r^2, t the layer thickness in units of 1/k): dC/ds = t S / 2, dS/ds = (t C - S) / (2 s) (by its
series t^3 sum_k>=1 (s t^2)^(k-1) k / (2k + 1)! where |s t^2| < 1/2: no cancellation at a bulk
speed), dC/dt = s S, dS/dt = C. The c-dependence of the substrate's minors, the closed-form top row
and the kernels of buried films (polynomial or rational in X, r_a, r_b, no branch switch) is taken
by a complex step of :data:`STEP` in t: exact to rounding. The tangent along t also travels as that
complex step through the substrate's unit vector, the top film's row and the SH recursion (each
film's C + i STEP dC/dt, S + i STEP dS/dt from :func:`_layer_d`: one complex product instead of
the product rule written out); the tangent along kh, and both tangents of buried films, are real.

:func:`secular_d_pair` evaluates P-SV at some points and SH at others in one pass (the layer
functions of both wave types once for all of them, :func:`_layers`); both families always take
their layer functions from :func:`_layers`, so a point's numbers do not depend on which other
points are evaluated with it.
"""
from __future__ import annotations

import math

import numpy as np

from surfwave.layers.isotropic import IsoStack, psv_kernels, substrate_psv, top_row

__all__ = ["STEP", "secular_d", "secular_d_pair"]

#: Per film: :func:`_layer_d` of the P and S waves ((2, m) each).
Layer = tuple[np.ndarray, ...]
#: X = rho c^2 / s of every layer with its complex step along t (m, L + 1), and every film's :data:`Layer`.
Layers = tuple[np.ndarray, list[Layer]]

#: Complex step in t (no subtraction: any tiny value gives the derivative to rounding).
STEP = 1e-20
#: Series coefficients k / (2k + 1)! of (t C - S) / (2 s t^3), k = 1 ... 8, highest first (Horner);
#: for |s t^2| < 1/2 the next term is below 1e-16 of the sum.
_SERIES = np.array([k / math.factorial(2 * k + 1) for k in range(8, 0, -1)])


def _dS_ds(r2: np.ndarray, t: np.ndarray, C: np.ndarray, S: np.ndarray, g: np.ndarray) -> np.ndarray:
    """g dS/ds of one wave type (scaled C, S, g of :func:`wave_functions`), elementwise (m,).

    The series (where |s t^2| < 1/2) is evaluated on all points and selected (no indexing).
    """
    x = r2 * t * t
    out = (t * C - S) / (2.0 * r2)
    small = np.abs(x) < 0.5
    if small.any():
        acc = _SERIES[0] * x
        acc += _SERIES[1]
        for a in _SERIES[2:]:                      # (in place: the same numbers, no temporaries)
            acc *= x
            acc += a
        out = np.where(small, g * t ** 3 * acc, out)
    return out


def _layer_d(r2: np.ndarray, dr2: np.ndarray, t: np.ndarray, frac: float) -> tuple[np.ndarray, ...]:
    """Scaled C, S and their tangents of one wave type at points (m,) (or several: r2 (k, m), t (m,)).

    Returns C + i STEP g dC and S + i STEP g dS (complex: the tangent along t at fixed kh as a
    complex step), g, g dC and g dS along kh at fixed c, and the log-derivatives of g itself along
    t and along kh. C, S, g are those of :func:`wave_functions`
    (the same formulas, both branches evaluated on all points and selected: no indexing).
    Floating-point warnings are the caller's (:func:`secular_d` turns them off).
    """
    ev = r2 > 0
    r = np.sqrt(np.abs(r2))
    rt = r * t
    e = np.expm1(-rt)
    u = np.tan(0.5 * rt)
    uu = u * u
    d = 1.0 / (1.0 + uu)
    g = np.where(ev, 1.0 + e, 1.0)
    C = np.where(ev, 0.5 * (1.0 + g * g), (1.0 - uu) * d)
    S = np.where(ev, e * (-2.0 - e), 4.0 * u * d) / (2.0 * r)          # (the same numbers as 2 u d / r)
    if not r.all():
        S = np.where(r > 0, S, t)
    h = 0.5 * t * dr2
    lg_t = np.where(ev, -h / r, 0.0)
    Cc = C + (1j * STEP) * (h * S)
    Sc = S + (1j * STEP) * (_dS_ds(r2, t, C, S, g) * dr2)
    return Cc, Sc, g, r2 * S * frac, C * frac, lg_t, np.where(ev, -r * frac, 0.0)


def _unit(m: np.ndarray, *tangents: np.ndarray) -> tuple[np.ndarray, ...]:
    """m / |m| along the last axis and the derivatives of that unit vector from those of m."""
    n = np.sqrt(np.einsum("ij,ij->i", m, m))[:, None]
    u = m / n
    return (u, *(d / n - u * np.einsum("ij,ij->i", u, d)[:, None] / n for d in tangents))


def _rsqrt(z: np.ndarray) -> np.ndarray:
    """1 / sqrt(z) of a complex step z = a + i b (a > 0, |b| tiny): a^(-1/2) (1 - i b / (2 a)) (exact to rounding:
    the terms dropped are of order (b / a)^2; numpy's complex sqrt and division cost several times more)."""
    a = z.real
    r = 1.0 / np.sqrt(a)
    return r - (0.5j * r) * (z.imag / a)


def _psv(st: IsoStack, tau: np.ndarray, kh: np.ndarray, lay: Layers | None = None) -> tuple[np.ndarray, ...]:
    """(F, F_t, F_kh, R) of the P-SV secular function at points (m,) (``lay``: :func:`_layers` there).

    The vector m and the top film's row carry their derivative along t as a complex step
    (m + i STEP dm/dt), the derivative along kh separately; the films below the top one carry both
    tangents as real arrays (:func:`_unit`).
    """
    Xc, lds = _layers(st, tau, kh) if lay is None else lay
    tc = tau + 1j * STEP
    Msub = st.lam[-1] + 2.0 * st.mu[-1]
    mc = substrate_psv(st.mu[-1], Xc[:, -1], np.sqrt(1.0 - Xc[:, -1] / Msub), tc)
    mc = mc * _rsqrt((mc * mc).sum(axis=1))[:, None]                   # m / |m| with its step (as _unit)
    L = st.frac.size
    if L == 0:
        return mc[:, 5].real.copy(), mc[:, 5].imag / STEP, np.zeros(tau.size), np.zeros(tau.size)
    mk = None
    if L > 1:                                                          # the films below the top one
        m, mt = mc.real, mc.imag / STEP
        mk = np.zeros_like(m)
        for layer in range(L - 1, 0, -1):
            lam, mu = st.lam[layer], st.mu[layer]
            Cc, Sc, (ga, gb), (kCa, kCb), (kSa, kSb), lt, lk = lds[layer]
            (Ca, Cb), (Sa, Sb) = Cc.real, Sc.real
            (dCa, dCb), (dSa, dSb) = Cc.imag / STEP, Sc.imag / STEP
            Dt, Dk = lt[0] + lt[1], lk[0] + lk[1]                          # d log(g_a g_b)
            w = (ga * gb, Ca * Cb, Ca * Sb, Sa * Cb, Sa * Sb)
            wt = (dCa * Cb + Ca * dCb, dCa * Sb + Ca * dSb, dSa * Cb + Sa * dCb, dSa * Sb + Sa * dSb)
            wk = (kCa * Cb + Ca * kCb, kCa * Sb + Ca * kSb, kSa * Cb + Sa * kCb, kSa * Sb + Sa * kSb)
            Kc = psv_kernels(lam, mu, Xc[:, layer])                        # (m, 5, 6, 6)
            K, Kt = Kc.real, Kc.imag / STEP
            Km = np.einsum("npij,nj->npi", K, m)
            Ktm = np.einsum("npij,nj->npi", Kt, m)
            Kmt = np.einsum("npij,nj->npi", K, mt)
            Kmk = np.einsum("npij,nj->npi", K, mk)
            W = np.stack(w, axis=1)[:, :, None]                            # (m, 5, 1)
            m_new = (W * Km).sum(axis=1)
            mt = (W * (Ktm + Kmt)).sum(axis=1) + sum(wt[p - 1][:, None] * Km[:, p] for p in range(1, 5))
            mk = (W * Kmk).sum(axis=1) + sum(wk[p - 1][:, None] * Km[:, p] for p in range(1, 5))
            m, mt, mk = _unit(m_new, mt + m_new * Dt[:, None], mk + m_new * Dk[:, None])
        mc = m + 1j * STEP * mt
    # the top film: the NT row only, closed form; F = g_a g_b k0 + C_a P + S_a Q,
    # P = C_b (m_NT - k0) + S_b k2, Q = C_b k3 + S_b k4 (complex: with the step along t)
    lam, mu = st.lam[0], st.mu[0]
    M = lam + 2.0 * mu
    (Cca, Ccb), (Sca, Scb), (ga, gb), (kCa, kCb), (kSa, kSb), (lta, ltb), (lka, lkb) = lds[0]
    k0, k2, k3, k4 = top_row(mu, M, Xc[:, 0], mc)
    q = mc[:, 5] - k0
    P, Q = Ccb * q + Scb * k2, Ccb * k3 + Scb * k4
    G = ga * gb
    Fc = G * k0 + Cca * P + Sca * Q
    F, Ft = Fc.real, Fc.imag / STEP
    Ca, Sa, Cb, Sb = Cca.real, Sca.real, Ccb.real, Scb.real
    Pr, Qr = P.real, Q.real
    Pk, Qk = kCb * q.real + kSb * k2.real, kCb * k3.real + kSb * k4.real
    if mk is not None:                                                 # the vector below depends on kh
        k0k, k2k, k3k, k4k = top_row(mu, M, Xc[:, 0].real, mk)
        Pk = Pk + Cb * (mk[:, 5] - k0k) + Sb * k2k
        Qk = Qk + Cb * k3k + Sb * k4k
        Fk = G * k0k + kCa * Pr + Ca * Pk + kSa * Qr + Sa * Qk
    else:
        Fk = kCa * Pr + Ca * Pk + kSa * Qr + Sa * Qk
    return F, Ft + F * (lta + ltb), Fk + F * (lka + lkb), Fk / Ft   # the last: g held constant (module docstring)


def _sh(st: IsoStack, tau: np.ndarray, kh: np.ndarray, lay: Layers | None = None) -> tuple[np.ndarray, ...]:
    """(F, F_t, F_kh, R) of the SH secular function tau / |(v, tau)| at the top, points (m,).

    F is invariant under positive factors of (v, tau), so every factor (g, the renormalisation
    after each film) is held constant in the tangents and F's derivatives are exact (no N).
    (v, tau) carry their derivative along t as a complex step, along kh separately.
    ``lay``: :func:`_layers` there (the S wave's functions are used).
    """
    Xc, lds = _layers(st, tau, kh) if lay is None else lay
    s = -st.mu[-1] * (tau + 1j * STEP)                                 # substrate: (1, -mu r_b), r_b = t
    L = st.frac.size
    if L == 0:
        v, vk, sk = np.ones(tau.shape), np.zeros(tau.shape), np.zeros(tau.shape)
    for layer in range(L - 1, -1, -1):
        mu = st.mu[layer]
        ld = lds[layer]
        Cc, Sc, kC, kS = ld[0][-1], ld[1][-1], ld[3][-1], ld[4][-1]
        mr = Xc[:, layer] - mu                                         # -mu r_b^2, with its step
        sr = s.real
        if layer == L - 1:                                             # from the substrate: v = 1, no kh part
            vk, sk = kC - kS * sr / mu, mr.real * kS + kC * sr
            v, s = Cc - Sc * s / mu, mr * Sc + Cc * s
        else:
            Cb, Sb, vr = Cc.real, Sc.real, v.real
            vk, sk = (kC * vr + Cb * vk - (kS * sr + Sb * sk) / mu,
                      mr.real * (kS * vr + Sb * vk) + kC * sr + Cb * sk)
            v, s = Cc * v - Sc * s / mu, mr * Sc * v + Cc * s
        if layer:                                                      # renormalise (held constant)
            n = 1.0 / np.hypot(v.real, s.real)
            v, s, vk, sk = v * n, s * n, vk * n, sk * n
    rs = _rsqrt(v * v + s * s)
    Fc = s * rs
    vr, sr, nr = v.real, s.real, rs.real
    Fk = vr * nr * nr * nr * (sk * vr - sr * vk)
    # R: the ratio of tau's own derivatives (the renormalisations held constant, positive factors that
    # drop out at tau = 0): at a root equal to F_kh / F_t, and smooth where F is not. At a mode
    # trapped under a barrier v and tau are both tiny at the top and F = tau / |(v, tau)| swings
    # through 0 within rounding of c, so the root found has |F| ~ 0.1 and F's own ratio is that
    # of the background (buried stack at kh = 60: v_g 2550.75 against 2549.83 m/s by differences)
    return Fc.real, Fc.imag / STEP, Fk, sk / (s.imag / STEP)


def secular_d(st: IsoStack, prefix: str, tau: np.ndarray, kh: np.ndarray, ratio: bool = False
              ) -> tuple[np.ndarray, ...]:
    """The family's secular function and its exact derivatives at points (m,).

    Parameters
    ----------
    st : IsoStack
    prefix : {"R", "L"}
        P-SV or SH.
    tau : ndarray, shape (m,)
        t = sqrt(1 - c^2 / c_lim^2) in (0, 1).
    kh : ndarray, shape (m,)
        Wavenumber x total film thickness.
    ratio : bool
        Also return a smooth F_kh / F_t (below).

    Returns
    -------
    F, F_t, F_kh : ndarray, shape (m,)
        F (as :func:`secular_psv` / :func:`secular_sh`), dF/dt at fixed kh and dF/dkh at fixed c.
    R : ndarray, shape (m,), with ``ratio``
        F_kh / F_t of the function without the top film's overflow scale g (SH: of F itself, which has
        none): equal to F_kh / F_t at a root, and smooth across a film's bulk speed, where g (so F_t
        away from a root) has a kink; the group velocity carried from a near-root iterate uses it.
    """
    tau = np.asarray(tau, dtype=float)
    kh = np.asarray(kh, dtype=float)
    with np.errstate(all="ignore"):
        out = _sh(st, tau, kh) if prefix == "L" else _psv(st, tau, kh)
    return out if ratio else out[:3]


def _layers(st: IsoStack, tau: np.ndarray, kh: np.ndarray) -> Layers:
    """X with its step (m, L + 1) and per film (from the top) :func:`_layer_d` of both wave types (P, S)
    at points (m,) ((2, m) each). Both families use these, so a point's values do not depend on
    which other points (or family) are evaluated with it."""
    c_lim2 = st.c_lim ** 2
    tc = tau + 1j * STEP
    Xc = st.rho * (c_lim2 * (1.0 - tc * tc))[:, None] / st.s           # (m, L + 1), complex step along t
    X, dX = Xc.real, Xc.imag / STEP
    out: list[Layer] = []
    for layer in range(st.frac.size):
        inv = np.array([[1.0 / (st.lam[layer] + 2.0 * st.mu[layer])], [1.0 / st.mu[layer]]])
        r2, dr2 = 1.0 - X[:, layer] * inv, -dX[:, layer] * inv
        out.append(_layer_d(r2, dr2, kh * st.frac[layer], st.frac[layer]))
    return Xc, out


def _take(lay: Layers, sl: slice) -> Layers:
    """:func:`_layers` at the points ``sl``."""
    return lay[0][sl], [tuple([v[:, sl] for v in ld]) for ld in lay[1]]


def secular_d_pair(st: IsoStack, tau: np.ndarray, kh: np.ndarray, k: int) -> tuple[np.ndarray, ...]:
    """:func:`secular_d` with ``ratio`` of P-SV at the first ``k`` points (m,) and of SH at the rest, in one pass.

    The layer functions of both wave types are computed once for all points (the SH function uses
    the S wave's); the result is that of the two calls of :func:`secular_d` to rounding.

    Returns
    -------
    F, F_t, F_kh, R : ndarray, shape (m,)
    """
    tau = np.asarray(tau, dtype=float)
    kh = np.asarray(kh, dtype=float)
    if k == 0 or k == tau.size:
        return secular_d(st, "R" if k else "L", tau, kh, ratio=True)
    with np.errstate(all="ignore"):
        lay = _layers(st, tau, kh)
        p = _psv(st, tau[:k], kh[:k], _take(lay, slice(None, k)))
        h = _sh(st, tau[k:], kh[k:], _take(lay, slice(k, None)))
    return tuple(np.concatenate((a, b)) for a, b in zip(p, h))
