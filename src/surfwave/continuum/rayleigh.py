"""Rayleigh (surface) wave velocity of a prestressed crystal, long-wave limit.

The sagittal problem along x on a surface normal to y, with mirror symmetry so that the
shear-horizontal motion decouples, depends on five stress derivatives (Eq. 17):

    a = S_xxxx, b = S_xyxy, c = S_xyyx, d = S_yyyy, f = S_yyxx,   X = rho c_R^2.

Partial waves u ~ exp(i k x - k kappa y) (y into the crystal) have

    b d kappa^4 - [b (c - X) + d (a - X) - (f + b)^2] kappa^2 + (a - X)(c - X) = 0,

and the free-surface condition, after dividing out the trivial factor (kappa_1 - kappa_2), is

    G(X) = A M + A N (s + p) - f M p + f N p^2 = 0,
    A = a - X, M = f (f + b) - d A, N = d b, s = kappa_1^2 + kappa_2^2, p = kappa_1 kappa_2.

Squaring away the sign of p gives the cubic Eq. (17), whose extra roots belong to p < 0
(partial waves that grow into the crystal). We find the roots of Eq. (17) in closed form,
keep those in 0 < X < min(a, c) whose two kappa have positive real part (complex allowed),
and accept one only if it satisfies the *unsquared* G(X) = 0 with p > 0.

The initial stress enters through S (Eq. A11); the traction condition uses C_iykl, which
equals S_iykl when sigma_yy = sigma_xy = 0 (free surface in equilibrium, docs/physics/paper.md).
"""
from __future__ import annotations

import itertools

import numpy as np

from surfwave.errors import SymmetryError

#: Metadata of the arrays this module produces.
VARIABLES: dict[str, dict] = {
    "c2_R": {"long_name": "squared Rayleigh (surface) wave speed, long-wave limit (Eq. 17)",
             "units": "K d0^2 / m", "dims": ()},
    "wave_type": {"long_name": "kind of sagittal surface wave: surface, supersonic_decoupled "
                  "(faster than the SH bulk wave; exists by mirror symmetry) or none",
                  "dims": ()},
    "reason": {"long_name": "why c2_R is NaN (empty if it is not)", "dims": ()},
    "kappa1": {"long_name": "first decay constant kappa of the surface wave (per k)",
               "units": "1", "dims": ()},
    "kappa2": {"long_name": "second decay constant kappa of the surface wave (per k)",
               "units": "1", "dims": ()},
}

WAVE_TYPES = ("surface", "supersonic_decoupled", "none")

REASON_SHEAR = "no surface wave: c_T,par^2 <= 0 (shear instability along the surface)"
REASON_PERP = "no surface wave: S_yyyy <= 0 or S_xyxy <= 0 (unstable normal to the surface)"
#: Relative size (of max |S|) above which a component breaking sagittal orthotropy is refused.
ORTHOTROPY_TOL = 1e-9

REASON_NOROOT = ("no root of Eq. (17) in 0 < rho c^2 < min(S_xxxx, S_xyyx) satisfies the "
                 "unsquared boundary condition with decaying partial waves")


def _real_cubic_roots(c3, c2, c1, c0) -> np.ndarray:
    """Real roots of c3 x^3 + c2 x^2 + c1 x + c0, vectorised; shape (..., 3), NaN-padded.

    Real arithmetic only: the trigonometric form where there are three real roots, Cardano's
    with real cube roots where there is one; then two Newton steps on the cubic. Points with
    a vanishing leading coefficient fall back to numpy.roots (rare: S_yyyy = S_xyxy).
    """
    c3, c2, c1, c0 = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (c3, c2, c1, c0)))
    scale = np.maximum(np.maximum(np.abs(c3), np.abs(c2)), np.maximum(np.abs(c1), np.abs(c0)))
    degenerate = np.abs(c3) <= 1e-13 * scale
    with np.errstate(all="ignore"):
        lead = np.where(degenerate, 1.0, c3)
        B, C, D = c2 / lead, c1 / lead, c0 / lead
        shift = B / 3.0
        p = C - B * shift
        q = (2.0 / 27.0) * B**3 - C * shift + D
        delta = 0.25 * q * q + p**3 / 27.0
        one = delta > 0
        sq = np.sqrt(np.where(one, delta, 0.0))
        y1 = np.cbrt(-0.5 * q + sq) + np.cbrt(-0.5 * q - sq)
        m = 2.0 * np.sqrt(np.where(one, 0.0, -p / 3.0))
        cos_arg = np.where(m > 0, 3.0 * q / (p * np.where(m > 0, m, 1.0)), 0.0)
        phi = np.arccos(np.clip(cos_arg, -1.0, 1.0)) / 3.0
        k = np.arange(3) * (2.0 * np.pi / 3.0)
        three = m[..., None] * np.cos(phi[..., None] - k)
        x = np.where(one[..., None], np.stack([y1, np.full_like(y1, np.nan), np.full_like(y1, np.nan)], -1), three)
        x = x - shift[..., None]
        Bx, Cx, Dx = B[..., None], C[..., None], D[..., None]
        for _ in range(2):  # Newton polish on the monic cubic
            f = ((x + Bx) * x + Cx) * x + Dx
            df = (3.0 * x + 2.0 * Bx) * x + Cx
            x = np.where(df != 0, x - f / df, x)
    if degenerate.any():
        for idx in zip(*np.nonzero(degenerate)):
            r = np.roots([c3[idx], c2[idx], c1[idx], c0[idx]])
            r = r[np.abs(r.imag) <= 1e-12 * np.maximum(1.0, np.abs(r))].real
            x[idx] = np.concatenate([r, np.full(3 - r.size, np.nan)])
    return x


def secular_coefficients(a, b, c, d, f) -> tuple[np.ndarray, ...]:
    """Coefficients (c3, c2, c1, c0) of Eq. (17) as a cubic polynomial in X = rho c_R^2.

    (X - c)[d (X - a) + f^2]^2 - b d (X - a)[(X - c) + b]^2.
    """
    g = f * f - d * a
    h = b - c
    c3 = d * d - b * d
    c2 = 2 * d * g - c * d * d - b * d * (2 * h - a)
    c1 = g * g - 2 * c * d * g - b * d * (h * h - 2 * a * h)
    c0 = -c * g * g + b * d * a * h * h
    return c3, c2, c1, c0


def decay_constants(X, a, b, c, d, f) -> tuple[np.ndarray, np.ndarray]:
    """The two decay constants kappa (principal square roots, Re >= 0) at X = rho c^2.

    Returns
    -------
    kappa1, kappa2 : complex ndarray, broadcast shape of the inputs
        Ordered so that |kappa1| >= |kappa2|.
    """
    X, a, b, c, d, f = (np.asarray(v, dtype=float) for v in (X, a, b, c, d, f))
    e = f + b
    bd = b * d
    with np.errstate(all="ignore"):
        s = (b * (c - X) + d * (a - X) - e * e) / bd
        p2 = (a - X) * (c - X) / bd
        root = np.sqrt((s * s - 4 * p2).astype(complex))
        k2a = (s + root) / 2
        k2b = np.where(np.abs(k2a) > 0, p2 / k2a, (s - root) / 2)  # Vieta: stable small root
    return np.sqrt(k2a.astype(complex)), np.sqrt(k2b.astype(complex))


def boundary_function(X, a, b, c, d, f) -> tuple[np.ndarray, np.ndarray]:
    """Unsquared free-surface condition G(X) with p = +sqrt(p^2), and its magnitude scale."""
    X, a, b, c, d, f = (np.asarray(v, dtype=float) for v in (X, a, b, c, d, f))
    e = f + b
    A = a - X
    M = f * e - d * A
    N = d * b
    with np.errstate(all="ignore"):
        s = (b * (c - X) + d * (a - X) - e * e) / N
        p = np.sqrt((A * (c - X) / N).astype(complex)).real
    terms = (A * M, A * N * (s + p), -f * M * p, f * N * p * p)
    G = sum(terms)
    scale = sum(np.abs(t) for t in terms)
    return G, scale


def _sagittal_components(S: np.ndarray) -> tuple[np.ndarray, ...]:
    """(a, b, c, d, f) = (S_xxxx, S_xyxy, S_xyyx, S_yyyy, S_yyxx), each shape S.shape[:-4]."""
    return S[..., 0, 0, 0, 0], S[..., 0, 1, 0, 1], S[..., 0, 1, 1, 0], S[..., 1, 1, 1, 1], S[..., 1, 1, 0, 0]


def _odd_index_components(d: int) -> tuple[list[tuple[int, ...]], tuple[np.ndarray, ...]]:
    """Components of S that vanish when the sagittal plane is orthotropic and a mirror.

    Orthotropy in the sagittal plane (x -> -x) removes those with an odd number of x
    indices among the sagittal ones; the mirror z -> -z (3D) those with an odd number of z.
    """
    comps = [c for c in itertools.product(range(d), repeat=4)
             if sum(i == 0 for i in c) % 2 == 1 or sum(i == 2 for i in c) % 2 == 1]
    return comps, tuple(np.array(col) for col in zip(*comps))


_ODD = {d: _odd_index_components(d) for d in (2, 3)}


def check_orthotropic(S: np.ndarray, rtol: float = ORTHOTROPY_TOL) -> None:
    """Raise :class:`SymmetryError` unless S is orthotropic in the sagittal plane (Eq. 17 applies).

    Eq. (17) needs x -> -x and (3D) z -> -z symmetry: every component with an odd number of
    x or of z indices must vanish (relative to max |S| of the point). General tensors belong to
    :func:`surfwave.continuum.stroh.surface_wave`.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d), d = 2 or 3
    rtol : float

    Raises
    ------
    SymmetryError
        Naming the largest offending components and their size relative to max |S|.
    """
    d = S.shape[-1]
    if d not in _ODD or S.shape[-4:] != (d,) * 4:
        raise SymmetryError(f"S must have shape (..., d, d, d, d) with d = 2 or 3, got {S.shape}")
    comps, idx = _ODD[d]
    flat = np.abs(S.reshape(S.shape[:-4] + (d**4,)))
    odd_flat = np.ravel_multi_index(idx, (d,) * 4)
    # one cheap pass: the largest odd component against max |S| of each point
    if not flat.size or not (flat[..., odd_flat].max(axis=-1) > rtol * flat.max(axis=-1)).any():
        return
    odd = flat[..., odd_flat]                                              # (..., n_odd)
    scale = flat.max(axis=-1)
    with np.errstate(all="ignore"):
        rel = odd / np.where(scale > 0, scale, 1.0)[..., None]
    if rel.max() > rtol:
        flat = rel.reshape(-1, len(comps))
        k = int(np.argmax(flat.max(axis=1)))
        worst = np.argsort(flat[k])[::-1][:4]
        names = ", ".join(f"S_{''.join('xyz'[i] for i in comps[j])} = {flat[k, j]:.2g}"
                          for j in worst if flat[k, j] > rtol)
        raise SymmetryError(
            "Eq. (17) needs a sagittal plane that is a mirror and orthotropic; at point "
            f"{np.unravel_index(k, S.shape[:-4]) if S.ndim > 4 else ()} these components do not vanish "
            f"(relative to max|S|): {names}. Use surfwave.continuum.stroh.surface_wave for general tensors."
        )


def _select_root(a, b, c, d, f, rtol: float = 1e-7) -> tuple[np.ndarray, np.ndarray]:
    """The admissible root X = rho c_R^2 of Eq. (17) and whether one exists (module docstring).

    Scale invariant: the five components are divided by their largest magnitude first (so
    constants in Pa, GPa or reduced units take the same path).
    """
    a, b, c, d, f = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (a, b, c, d, f)))
    unit = np.maximum.reduce([np.abs(a), np.abs(b), np.abs(c), np.abs(d), np.abs(f)])
    unit = np.where(unit > 0, unit, 1.0)
    a, b, c, d, f = (v / unit for v in (a, b, c, d, f))
    X = _real_cubic_roots(*secular_coefficients(a, b, c, d, f))  # (..., 3), NaN if not real
    A5 = [v[..., None] for v in (a, b, c, d, f)]
    a_, b_, c_, d_, f_ = A5
    with np.errstate(all="ignore"):
        inside = (X > 0) & (X < np.minimum(a_, c_)) & (b_ > 0) & (d_ > 0)
        # Both kappa have positive real part iff kappa^2 are complex conjugates or both positive
        # (p^2 > 0 holds inside); then p = kappa_1 kappa_2 = +sqrt(p^2) in G.
        bd = b_ * d_
        s_ = (b_ * (c_ - X) + d_ * (a_ - X) - (f_ + b_) ** 2) / bd
        p2 = (a_ - X) * (c_ - X) / bd
        decaying = (s_ * s_ < 4.0 * p2) | (s_ > 0)
        G, scale = boundary_function(X, *A5)
        ok = inside & decaying & (np.abs(G) <= rtol * scale)
        # Among admissible roots (normally exactly one), take the best boundary residual.
        badness = np.where(ok, np.abs(G) / scale, np.inf)
    best = np.argmin(badness, axis=-1)[..., None]
    has = np.take_along_axis(ok, best, -1)[..., 0]
    return np.take_along_axis(X, best, -1)[..., 0] * unit, has


def solve(S: np.ndarray, rho=1.0, c2_SH=None, rtol: float = 1e-7) -> dict[str, np.ndarray]:
    """Rayleigh velocity with root selection and wave type, vectorised over leading axes.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d), d = 2 or 3
        Stress derivatives (Eq. A11) in the lab frame (x propagation, y surface normal).
    rho : float or ndarray broadcastable to S.shape[:-4]
        Density in the units of S (1 when S is V S and m = 1).
    c2_SH : ndarray, optional
        Squared SH bulk speed; defaults to S_xzzx / rho for d = 3, none for d = 2.
    rtol : float
        Relative tolerance on the unsquared boundary condition G(X) = 0.

    Returns
    -------
    dict
        ``c2_R`` (float, NaN where none), ``wave_type`` (str), ``reason`` (str, "" if fine),
        ``kappa1``, ``kappa2`` (complex), all shape S.shape[:-4].
    """
    S = np.asarray(S, dtype=float)
    check_orthotropic(S)
    rho = np.asarray(rho, dtype=float)
    a, b, c, d, f = _sagittal_components(S)
    if c2_SH is None:
        c2_SH = S[..., 0, 2, 2, 0] / rho if S.shape[-1] == 3 else np.full(a.shape, np.nan)
    c2_SH = np.broadcast_to(np.asarray(c2_SH, dtype=float), a.shape)
    Xr, has = _select_root(a, b, c, d, f, rtol)
    K1, K2 = decay_constants(Xr, a, b, c, d, f)
    c2_R = np.where(has, Xr / rho, np.nan)
    nan_c = complex(np.nan, np.nan)
    reason = np.full(a.shape, "", dtype=object)
    reason = np.where(~has, REASON_NOROOT, reason)
    reason = np.where(~has & ((b <= 0) | (d <= 0)), REASON_PERP, reason)
    reason = np.where(~has & (c <= 0), REASON_SHEAR, reason)
    wave_type = np.where(has, np.where(np.isfinite(c2_SH) & (c2_R >= c2_SH), "supersonic_decoupled", "surface"), "none")
    return {
        "c2_R": c2_R,
        "wave_type": wave_type.astype(object),
        "reason": reason.astype(object),
        "kappa1": np.where(has, K1, nan_c),
        "kappa2": np.where(has, K2, nan_c),
    }


def rayleigh_c2(S: np.ndarray, rho=1.0) -> np.ndarray:
    """Squared Rayleigh speed from the stress derivatives; NaN where no surface wave exists.

    Parameters
    ----------
    S : ndarray, shape (..., d, d, d, d)
        Lab-frame stress derivatives (Eq. A11); times V with ``rho = 1`` in reduced units.
    rho : float or ndarray broadcastable to S.shape[:-4]

    Returns
    -------
    ndarray, shape S.shape[:-4]
        c_R^2 in the units of S / rho. Supersonic decoupled sagittal waves are included
        (see :func:`solve` for the wave type).

    Examples
    --------
    >>> import numpy as np
    >>> S = np.zeros((2, 2, 2, 2))        # isotropic, lambda = mu = 1
    >>> S[0,0,0,0] = S[1,1,1,1] = 3.0
    >>> S[0,1,0,1] = S[0,1,1,0] = S[1,1,0,0] = 1.0
    >>> round(float(rayleigh_c2(S)), 6)  # 2 - 2/sqrt(3)
    0.845299
    """
    S = np.asarray(S, dtype=float)
    check_orthotropic(S)
    X, has = _select_root(*_sagittal_components(S))
    return np.where(has, X / np.asarray(rho, dtype=float), np.nan)


def cauchy_c2(c2_L_par, c2_T_par, c2_L_perp, c2_T_perp) -> np.ndarray:
    """Eq. (20): c_R^2 from the four sound speeds when S_xyxy = S_yyxx (pair forces, sigma_yy = 0)."""
    with np.errstate(invalid="ignore", divide="ignore"):
        return 0.5 * (c2_L_par + c2_T_par) - 0.5 * np.sqrt(
            (c2_L_par - c2_T_par) ** 2 + 4.0 * c2_T_perp**3 / c2_L_perp
        )


def triangular_c2(d_over_d0) -> np.ndarray:
    """Eq. (16): (m / K d0^2) c_R^2 of the harmonic triangular lattice, x = d_x/d0 = d_over_d0/2."""
    x = 0.5 * np.asarray(d_over_d0, dtype=float)
    return 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)


def unstressed_residual(gamma, C11, C12, C44, C22=None) -> np.ndarray:
    """Eq. (21) residual, gamma = rho c_R^2 / C44 (Voigt constants; C22 defaults to C11).

    gamma^2 (gamma - C11/C44) - (C22/C44)(gamma - 1)[gamma - C11/C44 + C12^2/(C22 C44)]^2.
    """
    C22 = C11 if C22 is None else C22
    g = np.asarray(gamma, dtype=float)
    return g**2 * (g - C11 / C44) - (C22 / C44) * (g - 1) * (g - C11 / C44 + C12**2 / (C22 * C44)) ** 2
