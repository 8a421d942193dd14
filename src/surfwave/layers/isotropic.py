"""Secular functions of isotropic, unstressed, non-piezoelectric stacks: pole-free and overflow-free.

An isotropic stack splits exactly into a sagittal (P-SV: u1, u3 with our x2 as depth) and a
shear-horizontal (SH) family. Each is a linear ODE in depth, z in units of 1/k (z = k x_depth),
for a real state vector y: with u_x = U e^{i theta}, u_z = i W e^{i theta}, sigma_zz = i k N e^{i theta},
sigma_xz = k T e^{i theta} (theta = k x - omega t; z down, into the substrate) and X = rho c^2,

    U' = W + T / mu,          W' = (N - lam U) / M,          (M = lam + 2 mu)
    N' = -X W - T,            T' = (4 mu (lam + mu) / M - X) U + lam N / M,

and for SH (u_y = v e^{i theta}, sigma_yz = k tau e^{i theta}): v' = tau / mu, tau' = (mu - X) v.
A' = A y has the eigenvalues +-r_a, +-r_b with r_a^2 = 1 - X / M, r_b^2 = 1 - X / mu.

Layer propagator. Going up through a layer of thickness t (units 1/k), y_top = exp(-A t) y_bottom,
and exp(-A t) = C(A^2) - A S(A^2) with the entire functions C(s) = cosh(sqrt(s) t) and
S(s) = sinh(sqrt(s) t) / sqrt(s) (cos(q t) and sin(q t) / q for s = -q^2 < 0, i.e. above the
bulk speed; C = 1, S = t at s = 0, so c at a bulk speed is no special case). With the spectral
projectors Ma = (A^2 - r_b^2) / (r_a^2 - r_b^2) and Mb = 1 - Ma (no square roots: polynomial in
c^2 over X (lam + mu) / (mu M), which vanishes only at c = 0),
exp(-A t) = Pa + Pb, Pa = (C_a - S_a A) Ma, Pb = (C_b - S_b A) Mb.

SH: the 2 x 2 propagator [[C_b, -S_b / mu], [-mu r_b^2 S_b, C_b]] acts on (v, tau); the substrate's
decaying solution is (1, -mu r_b); the secular function is tau at the free top.

P-SV (compound matrices, Dunkin 1965): the two decaying solutions of the substrate span a plane;
its 2 x 2 minors m (order UW, UN, UT, WN, WT, NT) are carried upward by the second compound C2 of
each layer's propagator, and the free top (N = T = 0 for both solutions' combination) is m_NT = 0.
Writing C2(Pa + Pb) = C2(Pa) + C2(Pb) + D(Pa, Pb) (D the mixed term, bilinear), and using that
Pa has determinant C_a^2 - r_a^2 S_a^2 = 1 on its plane (so C2(Pa) = C2(Ma) exactly, likewise b),

    C2(exp(-A t)) = K0 + C_a C_b K1 - C_a S_b K2 - S_a C_b K3 + S_a S_b K4,
    K0 = C2(Ma) + C2(Mb),  K1 = D(Ma, Mb),  K2 = D(Ma, A Mb),  K3 = D(A Ma, Mb),  K4 = D(A Ma, A Mb).

The K depend on c only (shared by every kh), and the identity cosh^2 - sinh^2 = 1 has been used
analytically: no term grows like exp(2 r t), which is what a numerical product of transfer
matrices (or their compounds) would cancel in rounding.

Overflow. For an evanescent wave (r^2 > 0) C and S grow like exp(r t); every layer's compound is
multiplied by the positive factor exp(-(r_a + r_b) t) (only over the evanescent ones), which turns
C, S into (1 + e^{-2rt}) / 2 and -expm1(-2 r t) / (2 r) and K0 into K0 e^{-(r_a + r_b) t}, all
bounded; the vector is renormalised after each layer. Positive factors change neither the zeros
nor the sign of the secular function, which is returned as m_NT (the vector entering the top film
normalised; SH: tau / |(v, tau)|), bounded, analytic in c below the substrate's shear speed and
without poles (the substrate's r_a, r_b are analytic there and every layer's factor is entire):
its zeros are exactly the modes.

Scaled units: stiffnesses by the stack's largest, so X = rho c^2 / s.

Evaluation. What depends on c only (X, r^2 of every wave, the substrate's unit vector, with one
film the top row's coefficients) is computed once per set of speeds (:class:`Speeds`); blocks of
(speed, row) points are evaluated speed-major (:func:`psv_block`, :func:`sh_block`), so the
evanescent speeds of a wave (ascending speeds: the first ones) are contiguous rows, each branch
runs on whole rows, and every element is computed by the same operations whatever block it is in
(a scan's chunk or a hunt's pairs give the same value for the same (c, kh)).
"""
from __future__ import annotations

import functools
import weakref
from dataclasses import dataclass

import numpy as np

from surfwave.layers.stack import Stack
from surfwave.solvers.tensors import tensor_to_voigt

__all__ = ["IsoStack", "Speeds", "eligible", "is_isotropic", "iso_stack", "psv_at", "psv_block", "psv_speeds",
           "secular_psv", "secular_sh", "sh_at", "sh_block", "sh_speeds", "substrate_psv", "top_row", "wave_block",
           "wave_functions"]

#: Relative tolerance of the isotropy test of a stiffness.
ISO_TOL = 1e-12
#: Minor order of the 6-vector (pairs of U, W, N, T).
PAIRS = ((0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3))
_I = np.array([p[0] for p in PAIRS])
_J = np.array([p[1] for p in PAIRS])


def is_isotropic(C6, tol: float = ISO_TOL) -> bool:
    """True when a Voigt stiffness (6, 6) is isotropic to a relative ``tol`` of its largest entry.

    C11 = C22 = C33, C12 = C13 = C23, C44 = C55 = C66 = (C11 - C12) / 2, every other entry 0.
    """
    C = np.asarray(C6, dtype=float)
    s = float(np.abs(C).max())
    if s == 0 or not np.all(np.isfinite(C)):
        return False
    c11, c12 = C[0, 0], C[0, 1]
    ref = np.zeros((6, 6))
    ref[:3, :3] = c12
    ref[[0, 1, 2], [0, 1, 2]] = c11
    ref[[3, 4, 5], [3, 4, 5]] = 0.5 * (c11 - c12)
    return bool(np.abs(C - ref).max() <= tol * s)


def eligible(stack: Stack) -> bool:
    """True when the fast isotropic path applies: every layer isotropic, unstressed, no piezoelectricity."""
    return _resolved(stack) is not None


#: :func:`_resolved` of each live stack (a stack is immutable: frozen, its tensors not written after resolution).
_RESOLVED: weakref.WeakKeyDictionary[Stack, IsoStack | None] = weakref.WeakKeyDictionary()


def _resolved(stack: Stack) -> IsoStack | None:
    """The :class:`IsoStack` of an eligible stack, None for any other; remembered per stack object."""
    try:
        return _RESOLVED[stack]
    except KeyError:
        pass
    layers = [*stack.films, stack.substrate]
    out = None
    if not stack.piezo and not any(np.any(lay.sigma) for lay in layers):
        vs = [v for v in (_voigt(lay.A) for lay in layers) if v is not None]
        if len(vs) == len(layers):
            out = _lame(stack, np.stack(vs))
    _RESOLVED[stack] = out
    return out


#: :func:`_voigt` of recent layer tensors, by value (:data:`VOIGT_MEMO` entries at most).
_VOIGT: dict[bytes, np.ndarray | None] = {}
VOIGT_MEMO = 64


def _voigt(A: np.ndarray) -> np.ndarray | None:
    """The Voigt matrix (6, 6) of a wave-propagation tensor A (3, 3, 3, 3) if isotropic, else None.

    Isotropic: :func:`is_isotropic`. Remembered by the values of A (read-only results).
    """
    key = np.ascontiguousarray(A, dtype=float).tobytes()
    if key in _VOIGT:
        return _VOIGT[key]
    V = tensor_to_voigt(A)
    out = V if is_isotropic(V) else None
    if out is not None:
        out.setflags(write=False)
    if len(_VOIGT) >= VOIGT_MEMO:
        _VOIGT.pop(next(iter(_VOIGT)), None)
    _VOIGT[key] = out
    return out


@dataclass(frozen=True, eq=False)
class IsoStack:
    """Lame constants of an isotropic stack, scaled.

    Attributes
    ----------
    lam, mu, rho : ndarray, shape (L + 1,)
        Lame constants / ``s`` and densities (kg/m^3); films from the top, the substrate last.
    frac : ndarray, shape (L,)
        Film thickness / total film thickness (0 when the total is 0).
    s : float
        Stiffness scale, Pa.
    H : float
        Total film thickness, m.
    """

    lam: np.ndarray
    mu: np.ndarray
    rho: np.ndarray
    frac: np.ndarray
    s: float
    H: float

    @functools.cached_property
    def c_lim(self) -> float:
        """The substrate's shear speed (the guided limit of both families), m/s."""
        return float(np.sqrt(self.mu[-1] * self.s / self.rho[-1]))

    @functools.cached_property
    def shear(self) -> np.ndarray:
        """Shear speeds of every layer, m/s, shape (L + 1,) (read-only)."""
        v = np.sqrt(self.mu * self.s / self.rho)
        v.setflags(write=False)
        return v

    @functools.cached_property
    def longitudinal(self) -> np.ndarray:
        """Longitudinal speeds of every layer, m/s, shape (L + 1,) (read-only)."""
        v = np.sqrt((self.lam + 2 * self.mu) * self.s / self.rho)
        v.setflags(write=False)
        return v


def iso_stack(stack: Stack) -> IsoStack:
    """The Lame constants of an :func:`eligible` stack (lab-frame tensors are isotropic: any frame)."""
    st = _resolved(stack)
    if st is None:
        return _lame(stack, np.stack([tensor_to_voigt(lay.A) for lay in [*stack.films, stack.substrate]]))
    return st


def _lame(stack: Stack, V: np.ndarray) -> IsoStack:
    """:class:`IsoStack` from the Voigt stiffnesses V (L + 1, 6, 6), Pa, of the films and the substrate."""
    layers = [*stack.films, stack.substrate]
    s = float(np.abs(V).max())
    H = stack.total_thickness
    frac = np.array([f.thickness / H if H > 0 else 0.0 for f in stack.films])
    return IsoStack(lam=V[:, 0, 1] / s, mu=V[:, 3, 3] / s, rho=np.array([lay.rho for lay in layers]),
                    frac=frac, s=s, H=H)


def wave_functions(r2: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Scaled C, S of one wave type and the scale factor g, elementwise.

    Parameters
    ----------
    r2 : ndarray, shape (n,) or ()
        r^2 = 1 - c^2 / v^2 (v the bulk speed), one per speed (the last axis of ``t``).
    t : ndarray, shape (..., n) or ()
        Thickness in units of 1/k (>= 0).

    Returns
    -------
    C, S, g : ndarray, shape of ``t`` broadcast with ``r2``
        g = exp(-r t) for r^2 > 0 (else 1); C = g cosh(r t), S = g sinh(r t) / r for r^2 > 0
        (from e = expm1(-r t): C = (1 + (1 + e)^2) / 2, S = -e (2 + e) / (2 r), no cancellation),
        cos(q t) and sin(q t) / q with q^2 = -r^2 otherwise (S = t at r = 0; both from
        u = tan(q t / 2): cos = (1 - u^2) / (1 + u^2), sin = 2 u / (1 + u^2), exact to rounding
        and one transcendental call). Each speed's branch is computed on its own columns only.
    """
    r2 = np.asarray(r2, dtype=float)
    t = np.asarray(t, dtype=float)
    shape = np.broadcast_shapes(r2.shape, t.shape)
    r2v = np.broadcast_to(r2, shape[-1:] if shape else ()).reshape(-1)
    tb = np.broadcast_to(t, shape).reshape((-1, r2v.size))
    C, S, g = _wave(r2v, np.ascontiguousarray(tb.T), True)             # speed-major blocks
    assert g is not None
    return C.T.reshape(shape), S.T.reshape(shape), g.T.reshape(shape)


def _wave(r2: np.ndarray, t: np.ndarray, want_g: bool) -> tuple[np.ndarray, np.ndarray, np.ndarray | None]:
    """:func:`wave_functions` of r2 (n,) at t (n, r) (speed-major float arrays); g only if ``want_g``.

    Each element is computed by the same operations whatever the block (the scan's chunks, the
    hunt's pairs). Ascending speeds put the evanescent ones (r^2 > 0) first: the branch of the
    majority runs on the whole block (finite where it does not apply) and the other overwrites its
    rows (contiguous in memory); speeds in another order are indexed.
    """
    n = r2.size
    r = np.sqrt(np.abs(r2))
    pos = r2 > 0
    k = int(np.count_nonzero(pos))
    C, S = np.empty(t.shape), np.empty(t.shape)
    g = np.empty(t.shape) if want_g else None
    if not pos[:k].all():                               # not ascending: index the two branches
        ev, pr = np.flatnonzero(pos), np.flatnonzero(~pos)
        Ce, Se = np.empty((k,) + t.shape[1:]), np.empty((k,) + t.shape[1:])
        ge = np.empty((k,) + t.shape[1:]) if g is not None else None
        _evanescent(r[ev], t[ev], Ce, Se, ge)
        Cp, Sp = np.empty((n - k,) + t.shape[1:]), np.empty((n - k,) + t.shape[1:])
        _propagating(r[pr], t[pr], Cp, Sp)
        C[ev], S[ev], C[pr], S[pr] = Ce, Se, Cp, Sp
        if g is not None:
            g[ev], g[pr] = ge, 1.0
        return C, S, g
    if 2 * k <= n or not (r > 0).all():                 # mostly propagating (or a speed at r = 0)
        _propagating(r, t, C, S)
        if g is not None:
            g[...] = 1.0
        if k:
            _evanescent(r[:k], t[:k], C[:k], S[:k], None if g is None else g[:k])
    else:                                               # mostly evanescent (r > 0 everywhere)
        _evanescent(r, t, C, S, g)
        if k < n:
            if g is not None:
                g[k:] = 1.0
            _propagating(r[k:], t[k:], C[k:], S[k:])
    return C, S, g


#: :func:`_wave` for callers that share one wave type's block between families.
wave_block = _wave


def _evanescent(re: np.ndarray, te: np.ndarray, C: np.ndarray, S: np.ndarray, g: np.ndarray | None) -> None:
    """Scaled C, S (and g) into C, S, g (m, r) from r = re (m,) > 0 and t = te (m, r) (:func:`wave_functions`)."""
    if re.size == 0:
        return
    e = te * (-re)[:, None]
    np.expm1(e, out=e)
    np.add(e, 1.0, out=C)
    if g is not None:
        g[...] = C
    np.multiply(C, C, out=C)
    C += 1.0
    C *= 0.5
    np.add(e, 2.0, out=S)
    S *= e
    S *= (-0.5 / re)[:, None]


def _propagating(rp: np.ndarray, tp: np.ndarray, C: np.ndarray, S: np.ndarray) -> None:
    """C = cos(q t), S = sin(q t) / q (S = t at q = 0) into C, S (m, r) from q = rp (m,), t = tp (m, r)."""
    if rp.size == 0:
        return
    u = tp * (0.5 * rp)[:, None]
    np.tan(u, out=u)                                    # half-angle tangent: cos and sin from one call
    np.multiply(u, u, out=C)                            # u^2, then 1 - u^2
    d = C + 1.0
    np.divide(1.0, d, out=d)
    np.subtract(1.0, C, out=C)
    C *= d
    u *= d
    if (rp > 0).all():
        np.multiply(u, (2.0 / rp)[:, None], out=S)
    else:                                               # the same rule per element, S = t at r = 0
        zero = rp == 0
        np.multiply(u, (2.0 / np.where(zero, 1.0, rp))[:, None], out=S)
        S[zero] = tp[zero]


def _c2(M: np.ndarray) -> np.ndarray:
    """Second compound of 4 x 4 matrices (..., 4, 4) -> (..., 6, 6), minor order :data:`PAIRS`."""
    i, j, k, l = _I[:, None], _J[:, None], _I[None, :], _J[None, :]
    return M[..., i, k] * M[..., j, l] - M[..., i, l] * M[..., j, k]


def _mixed(X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """The mixed term D(X, Y) of C2(X + Y) = C2(X) + C2(Y) + D(X, Y), shape (..., 6, 6)."""
    i, j, k, l = _I[:, None], _J[:, None], _I[None, :], _J[None, :]
    return (X[..., i, k] * Y[..., j, l] + Y[..., i, k] * X[..., j, l]
            - X[..., i, l] * Y[..., j, k] - Y[..., i, l] * X[..., j, k])


def psv_kernels(lam: float, mu: float, X: np.ndarray) -> np.ndarray:
    """K0 ... K4 of one isotropic layer at scaled X = rho c^2 / s (n,), signs folded in: shape (n, 5, 6, 6).

    The layer's compound propagator upward over t is g_a g_b K0 + C_a C_b K1 + C_a S_b K2 + S_a C_b K3
    + S_a S_b K4 with the scaled C, S, g of :func:`wave_functions` (the module docstring).
    """
    M = lam + 2.0 * mu
    n = X.size
    A = np.zeros((n, 4, 4), dtype=np.result_type(X, float))             # complex X: complex-step derivatives
    A[:, 0, 1] = 1.0
    A[:, 0, 3] = 1.0 / mu
    A[:, 1, 0] = -lam / M
    A[:, 1, 2] = 1.0 / M
    A[:, 2, 1] = -X
    A[:, 2, 3] = -1.0
    A[:, 3, 0] = 4.0 * mu * (lam + mu) / M - X
    A[:, 3, 2] = lam / M
    B = A @ A
    rb2 = 1.0 - X / mu
    gap = X * (lam + mu) / (mu * M)                                     # r_a^2 - r_b^2
    eye = np.eye(4)
    Ma = (B - rb2[:, None, None] * eye) / gap[:, None, None]
    Mb = eye - Ma
    AMa, AMb = A @ Ma, A @ Mb
    return np.stack([_c2(Ma) + _c2(Mb), _mixed(Ma, Mb), -_mixed(Ma, AMb), -_mixed(AMa, Mb), _mixed(AMa, AMb)], axis=1)


def substrate_psv(mu: float, X: np.ndarray, ra: np.ndarray, rb: np.ndarray) -> np.ndarray:
    """Minors (n, 6) of the substrate's decaying solutions [1, r_a, X-2mu, -2mu r_a], [r_b, 1, -2mu r_b, X-2mu]."""
    q = X - 2.0 * mu
    rr = ra * rb
    return np.stack([1.0 - rr, -X * rb, q + 2.0 * mu * rr, -q - 2.0 * mu * rr, X * ra, q * q - 4.0 * mu * mu * rr],
                    axis=-1)


def top_row(mu: float, M: float, X: np.ndarray, m: np.ndarray) -> tuple[np.ndarray, ...]:
    """The NT row of K0, K2, K3, K4 of the top film applied to m (..., 6) (K1's is m_NT - K0's), closed form.

    With q = X - 2 mu, r_a^2 = 1 - X/M, r_b^2 = 1 - X/mu and d = m_UT - m_WN (the forms of
    :func:`psv_kernels` reduced by hand):
    K0 m = (-8 mu^2 q^2 m_UW - 2 mu q (q - 2 mu) d + 4 mu q m_NT) / X^2,
    K2 m = -(q^2 m_UN + 4 mu^2 r_b^2 m_WT) / X,   K3 m = (4 mu^2 r_a^2 m_UN + q^2 m_WT) / X,
    K4 m = (-(q^4 + 16 mu^4 P) m_UW + (q^3 - 8 mu^3 P) d - (q^2 + 4 mu^2 P) m_NT) / X^2, P = r_a^2 r_b^2.
    """
    q = X - 2.0 * mu
    ra2, rb2 = 1.0 - X / M, 1.0 - X / mu
    P = ra2 * rb2
    iX = 1.0 / X
    m0, m1, m4, m5 = m[..., 0], m[..., 1], m[..., 4], m[..., 5]
    d = m[..., 2] - m[..., 3]
    q2 = q * q
    k0 = (-8.0 * mu * mu * q2 * m0 - 2.0 * mu * q * (q - 2.0 * mu) * d + 4.0 * mu * q * m5) * iX * iX
    k2 = -(q2 * m1 + 4.0 * mu * mu * rb2 * m4) * iX
    k3 = (4.0 * mu * mu * ra2 * m1 + q2 * m4) * iX
    k4 = (-(q2 * q2 + 16.0 * mu ** 4 * P) * m0 + (q2 * q - 8.0 * mu ** 3 * P) * d
          - (q2 + 4.0 * mu * mu * P) * m5) * iX * iX
    return k0, k2, k3, k4


@dataclass(frozen=True, eq=False)
class Speeds:
    """The kh-independent parts of a family's secular function at speeds c (n,) (cut by :meth:`cut`).

    Attributes
    ----------
    X : ndarray, shape (n, L + 1)
        rho c^2 / s of every layer.
    r2 : ndarray, shape (L, 2, n)
        r_a^2 and r_b^2 of each film (P-SV; SH: r_b^2 twice).
    head : ndarray, shape (k, n)
        P-SV: the substrate's unit minor vector m (6 rows) and, with one film, the top row's
        m_NT - K0 m, K2 m, K3 m, K4 m, K0 m (5 more); SH: the substrate's unit (v, tau) and
        -mu r_b^2 of each film.
    """

    X: np.ndarray
    r2: np.ndarray
    head: np.ndarray

    def cut(self, sl: slice) -> Speeds:
        """These parts at the speeds ``sl`` of the last axis."""
        return Speeds(self.X[sl], self.r2[..., sl], self.head[:, sl])


def psv_speeds(st: IsoStack, c: np.ndarray) -> Speeds:
    """:class:`Speeds` of the P-SV family at speeds c (n,) below the substrate's shear speed, m/s."""
    X = st.rho * (c[:, None] ** 2) / st.s                                 # (n, L + 1)
    ra = np.sqrt(np.maximum(1.0 - X[:, -1] / (st.lam[-1] + 2 * st.mu[-1]), 0.0))
    rb = np.sqrt(np.maximum(1.0 - X[:, -1] / st.mu[-1], 0.0))
    m = substrate_psv(st.mu[-1], X[:, -1], ra, rb)
    m = m / np.sqrt((m * m).sum(axis=-1, keepdims=True))                 # (n, 6), kh-independent
    L = st.frac.size
    r2 = np.empty((L, 2, c.size))
    for layer in range(L):
        r2[layer, 0] = 1.0 - X[:, layer] / (st.lam[layer] + 2 * st.mu[layer])
        r2[layer, 1] = 1.0 - X[:, layer] / st.mu[layer]
    rows = [m.T]
    if L == 1:
        k0, k2, k3, k4 = top_row(st.mu[0], st.lam[0] + 2 * st.mu[0], X[:, 0], m)
        rows.append(np.stack([m[..., 5] - k0, k2, k3, k4, k0]))
    return Speeds(X, r2, np.concatenate(rows))


def sh_speeds(st: IsoStack, c: np.ndarray) -> Speeds:
    """:class:`Speeds` of the SH family at speeds c (n,) below the substrate's shear speed, m/s."""
    X = st.rho * (c[:, None] ** 2) / st.s
    v = np.ones(c.size)
    tau = -st.mu[-1] * np.sqrt(np.maximum(1.0 - X[:, -1] / st.mu[-1], 0.0))
    nrm = np.hypot(v, tau)
    L = st.frac.size
    r2 = np.empty((L, 2, c.size))
    head = np.empty((2 + L, c.size))
    head[0], head[1] = v / nrm, tau / nrm
    for layer in range(L):
        r2[layer, :] = 1.0 - X[:, layer] / st.mu[layer]
        head[2 + layer] = -st.mu[layer] * r2[layer, 1]
    return Speeds(X, r2, head)


def secular_psv(st: IsoStack, c: np.ndarray, kh: np.ndarray, kernels: list[np.ndarray] | None = None) -> np.ndarray:
    """Pole-free P-SV secular function: the minor m_NT at the free top, shape (r, n).

    The vector m entering the top film has unit norm, so F is bounded (|F| <= the norm of the top
    film's NT row); without films F = m_NT / |m| of the substrate (its Rayleigh function).

    Parameters
    ----------
    st : IsoStack
    c : ndarray, shape (n,)
        Speeds below the substrate's shear speed, m/s.
    kh : ndarray, shape (r, n)
        Wavenumber x total film thickness at each (row, speed).
    kernels : list of ndarray (n, 5, 6, 6), optional
        :func:`psv_kernels` of each film below the top one at ``c`` (computed when not given; entry
        0 is not used: the top film's row is in closed form, :func:`top_row`).
    """
    return psv_at(st, psv_speeds(st, c), kh, kernels)


def psv_at(st: IsoStack, sp: Speeds, kh: np.ndarray, kernels: list[np.ndarray] | None = None) -> np.ndarray:
    """:func:`secular_psv` from its kh-independent parts ``sp`` (:func:`psv_speeds`) at kh (r, n)."""
    return psv_block(st, sp, np.ascontiguousarray(kh.T), kernels).T


def psv_block(st: IsoStack, sp: Speeds, kh: np.ndarray, kernels: list[np.ndarray] | None = None,
              wave_b: tuple[np.ndarray, np.ndarray, np.ndarray] | None = None) -> np.ndarray:
    """:func:`psv_at` speed-major: kh and F of shape (n, r) (n the speeds of ``sp``).

    ``wave_b``: C, S, g of the top film's shear wave at t = kh (:func:`wave_functions`, speed-major),
    when already computed (one film only; they are overwritten).
    """
    L = st.frac.size
    if L == 0:
        return np.broadcast_to(sp.head[5][:, None], kh.shape)
    m = sp.head[:6].T[:, None, :]                                          # (n, 1, 6), then (n, r, 6)
    for layer in range(L - 1, -1, -1):
        t = kh if st.frac[layer] == 1.0 else kh * st.frac[layer]            # (kh x 1.0 is kh, bit for bit)
        Ca, Sa, ga = _wave(sp.r2[layer, 0], t, True)
        if wave_b is not None and L == 1:
            Cb, Sb, gb = wave_b
        else:
            Cb, Sb, g = _wave(sp.r2[layer, 1], t, True)
            assert g is not None
            gb = g
        assert ga is not None
        if layer == 0:                                                     # the NT row only: F itself
            if L == 1:
                d, k2, k3, k4, k0 = (h[:, None] for h in sp.head[6:])
            else:
                k0, k2, k3, k4 = top_row(st.mu[0], st.lam[0] + 2 * st.mu[0], sp.X[:, :1], m)
                d = m[..., 5] - k0
            # g_a g_b k0 + C_a (C_b (m_NT - k0) + S_b k2) + S_a (C_b k3 + S_b k4), in place
            F = Cb * d
            T = Sb * k2
            F += T
            F *= Ca
            np.multiply(Cb, k3, out=Cb)
            np.multiply(Sb, k4, out=T)
            Cb += T
            Cb *= Sa
            F += Cb
            ga *= gb
            ga *= k0
            F += ga
            return F
        w = (ga * gb, Ca * Cb, Ca * Sb, Sa * Cb, Sa * Sb)
        K = psv_kernels(st.lam[layer], st.mu[layer], sp.X[:, layer]) if kernels is None else kernels[layer]
        Km = (K[:, None] * m[..., None, None, :]).sum(axis=-1)              # (n, 1 or r, 5, 6)
        m = sum(w[p][..., None] * Km[..., p, :] for p in range(5))
        m = m / np.sqrt((m * m).sum(axis=-1, keepdims=True))
    raise AssertionError("unreachable")


def secular_sh(st: IsoStack, c: np.ndarray, kh: np.ndarray) -> np.ndarray:
    """Pole-free SH secular function tau / |(v, tau)| at the free top, shape (r, n) (arguments: :func:`secular_psv`)."""
    return sh_at(st, sh_speeds(st, c), kh)


def sh_at(st: IsoStack, sp: Speeds, kh: np.ndarray) -> np.ndarray:
    """:func:`secular_sh` from its kh-independent parts ``sp`` (:func:`sh_speeds`) at kh (r, n)."""
    return sh_block(st, sp, np.ascontiguousarray(kh.T)).T


def sh_block(st: IsoStack, sp: Speeds, kh: np.ndarray, wave: tuple[np.ndarray, np.ndarray] | None = None
             ) -> np.ndarray:
    """:func:`sh_at` speed-major: kh and F of shape (n, r) (n the speeds of ``sp``).

    ``wave``: C, S of the film's shear wave at t = kh when already computed (one film only; not written).
    """
    v, tau = sp.head[0][:, None], sp.head[1][:, None]
    for layer in range(st.frac.size - 1, -1, -1):
        mu = st.mu[layer]
        if wave is not None and st.frac.size == 1:
            Cb, Sb = wave
        else:
            Cb, Sb, _ = _wave(sp.r2[layer, 1], kh if st.frac[layer] == 1.0 else kh * st.frac[layer], False)
        v, tau = Cb * v - Sb * tau / mu, sp.head[2 + layer][:, None] * Sb * v + Cb * tau
        nrm = np.hypot(v, tau)
        tau /= nrm
        if layer:
            v /= nrm
    return np.broadcast_to(tau, kh.shape)

