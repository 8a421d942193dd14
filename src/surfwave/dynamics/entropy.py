"""Surface entropy of the prestressed triangular lattice (section III.C, corrected Eq. 25).

Classical harmonic crystal, entropies per surface atom in units of k_B, frequencies in
omega0 = (K/m)^(1/2) (reduced units of docs/physics/paper.md). Three quantities per strain:

* ``bulk_mean_log_omega`` = <ln(omega/omega0)> over all bulk modes (both branches, whole
  zone) = (1/4) <B(theta)>_theta with B(theta) = (1/2 pi) int ln det D(theta, p) dp, done
  exactly per theta by the Wiener-Hopf factor S (:mod:`surfwave.dynamics.surface_green`).
* ``S_surface_estimate``, corrected Eq. (25):
  <ln(omega_L omega_T / omega0^2)> - <ln(omega_R / omega0)> - bulk_mean_log_omega, with
  omega_L^2, omega_T^2 the two eigenvalues of A0 + A1 + A1^H (Eq. 4a: the bulk waves along x
  at normal wave-number q = 0, checked against the row matrices) and omega_R =
  (c_R/d_x) sin(theta) (Eq. 15). Both theta averages over [0, pi] are closed forms:
  omega_{L,T}^2 = (1 - cos theta)(a + b cos theta) and
  (1/pi) int_0^pi ln(a + b cos theta) dtheta = ln[(a + sqrt(a^2 - b^2))/2].
  c_R^2 is the Cauchy root, Eq. (20), of the long-wave speeds from the bond sums.
* ``S_surface_exact`` = (1/pi) int_0^pi s(theta) dtheta, s(theta) the exact surface entropy
  of the semi-infinite crystal at theta (:func:`surfwave.dynamics.surface_green.theta_log_dets`);
  no slab, so compression (where a free slab buckles) is no problem.

Quadrature: s and B are symmetric about theta = pi/2 and analytic on [0, pi/2] except
s(theta) = -(1/2) ln(theta) + analytic at theta -> 0 (the two translation zero modes:
freeing the surface gives -ln theta, clamping it +(1/2) ln theta). Subtracting
-(1/2) ln sin(theta), whose mean is known, leaves analytic integrands, so Gauss-Legendre on
[0, pi/2] converges exponentially; n nodes are doubled from 4 until |I_2n - I_n| plus a
rounding bound is <= tol (or rounding-limited, or n = N_THETA_MAX), and that sum is the
reported error of I_2n (conservative: I_2n is far better than I_n).

Stability (:func:`stability`): a strain whose bulk is unstable (acoustic tensor, zone scan,
or cyclic reduction) gives NaN everywhere; one whose bulk is stable but whose free surface
is not (a semi-infinite mode with omega^2 <= 0, or no Eq. 20 root in (0, c_T,par^2); the two
tests agree to 1e-11 in d/d0) gives NaN entropies and a valid bulk_mean_log_omega.
Harmonic: bulk limit d/d0 = 0.6945927 (s^3 - 12 s + 8 = 0, c_T,par = 0), surface limit
2 (3 - sqrt 7) = 0.7084974 (c_R = 0). LJ: surface 0.8936199 and 1.1139255, bulk 0.8930277
and 1.1141848 (LJ is stable again above d/d0 ~ 1.87, a branch not connected to d/d0 = 1).

Examples
--------
>>> from surfwave.dynamics.entropy import surface_entropy
>>> r = surface_entropy("harmonic", [1.0])
>>> round(float(r["bulk_mean_log_omega"][0]), 7), round(float(r["S_surface_exact"][0]), 6)
(0.4126784, 0.660737)
"""
from __future__ import annotations

from functools import lru_cache
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from surfwave.dynamics.surface_green import positive_definite2, theta_log_dets
from surfwave.dynamics.triangular import bond_force_constants, long_wave, row_matrices
from surfwave.model_crystals.lattices import build
from surfwave.model_crystals.potentials import PairPotential, get_potential

#: Names of the arrays :func:`surface_entropy` returns (metadata: surfwave.data.variables.CUBES["entropy"]).
OUTPUTS = ("S_surface_estimate", "S_surface_estimate_error", "bulk_mean_log_omega", "bulk_mean_log_omega_error",
           "S_surface_exact", "S_surface_exact_error", "n_theta", "reason")

#: Default first and largest Gauss-Legendre sizes of the adaptive theta quadrature.
N_THETA_START = 4
N_THETA_MAX = 4096
#: Resolution of the short-wave stability scan (theta x p grid over the zone).
ZONE_SCAN = 96
_EPS = np.finfo(float).eps


@lru_cache(maxsize=32)
def theta_rule(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Gauss-Legendre rule for the mean over theta in [0, pi/2].

    Returns
    -------
    theta : ndarray, shape (n,)
        Nodes in radians.
    weight : ndarray, shape (n,)
        Weights summing to 1, so ``(weight * f(theta)).sum()`` is the mean of f.
    """
    x, w = np.polynomial.legendre.leggauss(n)
    return 0.25 * np.pi * (x + 1.0), 0.5 * w


def _log_sin_mean() -> float:
    """(2/pi) int_0^{pi/2} ln sin(theta) dtheta = -ln 2."""
    return -np.log(2.0)


def theta_integrals(
    potential: str | PairPotential, d_over_d0: float, n_theta: int, levels: int | None = None
) -> dict[str, float | bool]:
    """bulk_mean_log_omega and S_surface_exact at one strain with a fixed quadrature.

    Parameters
    ----------
    potential : str or PairPotential
    d_over_d0 : float
        2 d_x / d0.
    n_theta : int
        Gauss-Legendre nodes on [0, pi/2].
    levels : int, optional
        Fixed cyclic-reduction depth (2^levels rows); default: to machine precision.

    Returns
    -------
    dict
        ``bulk_mean_log_omega`` (1), ``S_surface_exact`` (k_B), ``rounding`` (bound of the
        rounding error of S_surface_exact, k_B), ``bulk_ok``, ``surface_ok`` (bool: stable
        at every node).
    """
    theta, weight = theta_rule(n_theta)
    a0, a0s, a1 = row_matrices(potential, [d_over_d0], theta)
    r = theta_log_dets(a0[0], a0s[0], a1[0], levels=levels)
    bulk_ok = bool(r["bulk_ok"].all())
    surface_ok = bulk_ok and bool(r["surface_ok"].all())
    bulk = 0.25 * float(np.sum(weight * r["bulk_log_det"])) if bulk_ok else np.nan
    if surface_ok:
        smooth = r["s_theta"] + 0.5 * np.log(np.sin(theta))
        exact = float(np.sum(weight * smooth)) - 0.5 * _log_sin_mean()
        # cyclic reduction amplifies rounding in S by ~1/theta near Gamma (measured bound)
        rounding = float(np.sum(weight * r["s_rounding"] / theta))
    else:
        exact = rounding = np.nan
    return {"bulk_mean_log_omega": bulk, "S_surface_exact": exact, "rounding": rounding,
            "bulk_ok": bulk_ok, "surface_ok": surface_ok}


def _cauchy_root(potential: PairPotential, d_over_d0: float) -> tuple[float, float]:
    """Eq. (20) root and c_T,par^2 (both K d0^2 / m), no validity check (:func:`long_wave`)."""
    lw = long_wave(potential, [d_over_d0])
    return float(lw["c2_R_cauchy"][0]), float(lw["c2_T_par"][0])


def rayleigh_c2(potential: str | PairPotential, d_over_d0: float) -> float:
    """Long-wave Rayleigh speed squared, Cauchy case Eq. (20), K d0^2 / m.

    Returns NaN when the root is not a surface wave (c_R^2 outside (0, c_T,par^2)).
    For the harmonic lattice this equals Eq. (16).
    """
    root, c2_t = _cauchy_root(get_potential(potential), d_over_d0)
    return root if np.isfinite(root) and 0.0 < root < c2_t else np.nan


def band_edge_coefficients(potential: str | PairPotential, d_over_d0: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """omega_j^2(theta) = (1 - cos theta)(a_j + b_j cos theta), j = L (u), T (v); Eq. (4a).

    A0 + A1 + A1^H = 2 Phi_row (1 - cos 2 theta) + 2 (Phi_up + Phi_um)(1 - cos theta) is
    diagonal, so a = 4 Phi_row,jj + 2 (Phi_up + Phi_um)_jj and b = 4 Phi_row,jj.

    Returns
    -------
    a, b : ndarray, shape (n, 2)
        In K/m; column 0 longitudinal (x), column 1 transverse (y).
    """
    phi = bond_force_constants(potential, d_over_d0)  # (n, 3, 2, 2)
    row = np.diagonal(phi[:, 0], axis1=-2, axis2=-1)
    incl = np.diagonal(phi[:, 1] + phi[:, 2], axis1=-2, axis2=-1)
    return 4.0 * row + 2.0 * incl, 4.0 * row


def estimate_terms(potential: str | PairPotential, d_over_d0: float) -> dict[str, float]:
    """The two theta averages of Eq. (25), closed form, at one strain.

    Returns
    -------
    dict
        ``log_omega_LT`` = <ln(omega_L omega_T/omega0^2)>, ``log_omega_R`` =
        <ln(omega_R/omega0)> (NaN without a Rayleigh wave), ``c2_R`` (NaN without one) and
        ``c2_R_root`` (the raw Eq. 20 root); all averages over
        0 <= theta <= pi. ``log_omega_LT`` is NaN if omega_L^2 or omega_T^2 < 0 somewhere.
    """
    a, b = band_edge_coefficients(potential, [d_over_d0])
    a, b = a[0], b[0]
    if np.any(a <= np.abs(b)):
        lt = np.nan
    else:  # <ln(1 - cos)> = -ln 2 for each of the two factors, halved for omega
        lt = 0.5 * float(np.sum(np.log(0.5 * (a + np.sqrt(a * a - b * b))) - np.log(2.0)))
    root, c2_t = _cauchy_root(get_potential(potential), d_over_d0)
    ok = np.isfinite(root) and 0.0 < root < c2_t
    dx = 0.5 * d_over_d0
    lr = 0.5 * np.log(root / dx**2) - np.log(2.0) if ok else np.nan
    return {"log_omega_LT": lt, "log_omega_R": lr, "c2_R": root if ok else np.nan, "c2_R_root": root}


def stability(potential: str | PairPotential, d_over_d0: float, n_grid: int = ZONE_SCAN) -> tuple[str, str]:
    """Why the bulk, and why the free surface, are unstable at this strain ("" if stable).

    Bulk: the long-wave acoustic tensor in all directions and omega^2 > 0 on an
    n_grid x n_grid midpoint grid of the zone (theta in (0, pi/2), p in (0, 2 pi); the rest
    follows by symmetry). Surface (only asked if the bulk is stable): the semi-infinite
    crystal has no mode with omega^2 <= 0 (S - dA positive definite) at n_grid theta
    midpoints, and Eq. (20) gives a Rayleigh wave, 0 < c_R^2 < c_T,par^2.

    Returns
    -------
    bulk_reason, surface_reason : str
    """
    pot = get_potential(potential)
    min_eig = float(long_wave(pot, [d_over_d0])["min_acoustic_eig"][0])
    if not min_eig > 0.0:
        return (f"bulk unstable at d/d0 = {d_over_d0:.6g}: long-wave acoustic tensor eigenvalue "
                f"{min_eig:.3g} <= 0"), ""
    theta = (np.arange(n_grid) + 0.5) * (0.5 * np.pi / n_grid)
    p = (np.arange(n_grid) + 0.5) * (2.0 * np.pi / n_grid)
    a0, a0s, a1 = row_matrices(pot, [d_over_d0], theta)
    z = np.exp(1j * p)[:, None, None, None]
    d = a0[0][None] + a1[0][None] * z + np.conj(np.swapaxes(a1[0], -1, -2))[None] / z
    bad = ~positive_definite2(d)
    if bad.any():
        i, j = np.argwhere(bad)[0]
        return (f"bulk unstable at d/d0 = {d_over_d0:.6g}: omega^2 <= 0 at theta = {theta[j]:.3g}, "
                f"p = {p[i]:.3g}"), ""
    reasons = []
    r = theta_log_dets(a0[0], a0s[0], a1[0])
    if not r["bulk_ok"].all():
        return f"bulk unstable at d/d0 = {d_over_d0:.6g}: cyclic reduction lost positive definiteness", ""
    if not r["surface_ok"].all():
        j = int(np.flatnonzero(~r["surface_ok"])[0])
        reasons.append(f"surface unstable at d/d0 = {d_over_d0:.6g}: the semi-infinite crystal has a "
                       f"surface mode with omega^2 <= 0 (first at theta = {theta[j]:.3g})")
    root, c2_t = _cauchy_root(pot, d_over_d0)
    if not (np.isfinite(root) and 0.0 < root < c2_t):
        reasons.append(f"no Rayleigh wave at d/d0 = {d_over_d0:.6g}: Eq. (20) gives c_R^2 = "
                       f"{root:.3g} outside (0, c_T,par^2 = {c2_t:.3g})")
    return "", "; ".join(reasons)


def _one_strain(pot: PairPotential, d: float, tol: float, n_start: int, n_max: int) -> dict[str, Any]:
    out: dict[str, Any] = dict.fromkeys(
        ["S_surface_estimate", "S_surface_estimate_error", "bulk_mean_log_omega",
         "bulk_mean_log_omega_error", "S_surface_exact", "S_surface_exact_error"], np.nan)
    out["n_theta"] = 0
    bulk_reason, surface_reason = stability(pot, d)
    out["reason"] = bulk_reason or surface_reason
    if bulk_reason:
        return out
    n = n_start
    prev = theta_integrals(pot, d, n)
    while True:
        cur = theta_integrals(pot, d, 2 * n)
        n *= 2
        if not (cur["bulk_ok"] and prev["bulk_ok"]):
            out["reason"] = f"bulk unstable at d/d0 = {d:.6g}: cyclic reduction lost positive definiteness"
            out["n_theta"] = n
            return out
        floor = 16 * _EPS
        errs = {"bulk_mean_log_omega": abs(cur["bulk_mean_log_omega"] - prev["bulk_mean_log_omega"]) + floor}
        rounding = 0.0
        if not surface_reason and cur["surface_ok"] and prev["surface_ok"]:
            quad = abs(cur["S_surface_exact"] - prev["S_surface_exact"])
            rounding = cur["rounding"]
            errs["S_surface_exact"] = quad + rounding + floor
        worst = max(errs.values())
        # stop: converged, rounding-limited (more nodes only add rounding), or at the cap
        if worst <= tol or worst <= 2.0 * rounding or 2 * n > n_max:
            break
        prev = cur
    out["n_theta"] = n
    out["bulk_mean_log_omega"] = cur["bulk_mean_log_omega"]
    out["bulk_mean_log_omega_error"] = errs["bulk_mean_log_omega"]
    if surface_reason:
        return out
    if "S_surface_exact" not in errs:  # unstable at a quadrature node the scan missed
        out["reason"] = (f"surface unstable at d/d0 = {d:.6g}: the semi-infinite crystal has a "
                         "surface mode with omega^2 <= 0")
        return out
    out["S_surface_exact"] = cur["S_surface_exact"]
    out["S_surface_exact_error"] = errs["S_surface_exact"]
    est = estimate_terms(pot, d)
    if np.isfinite(est["log_omega_LT"]):
        out["S_surface_estimate"] = est["log_omega_LT"] - est["log_omega_R"] - out["bulk_mean_log_omega"]
        out["S_surface_estimate_error"] = out["bulk_mean_log_omega_error"] + 16 * _EPS
    else:  # cannot happen for a stable bulk (omega_L, omega_T are bulk frequencies)
        out["reason"] = f"omega_L^2 or omega_T^2 (Eq. 4a) <= 0 at d/d0 = {d:.6g}"
    return out


def surface_entropy(
    potential: str | PairPotential,
    d_over_d0: ArrayLike,
    tol: float = 1e-8,
    n_theta_start: int = N_THETA_START,
    n_theta_max: int = N_THETA_MAX,
) -> dict[str, np.ndarray]:
    """Surface entropy of the triangular lattice under uniaxial stress, per strain.

    Each strain is computed on its own (the result for [a, b] equals those for [a] and
    [b]), so a per-point cache may store them separately.

    Parameters
    ----------
    potential : str or PairPotential
        ``"harmonic"``, ``"lj"`` or any registered pair potential.
    d_over_d0 : float or array_like, shape (n,)
        2 d_x / d0 (1 = unstressed), in (0, 2).
    tol : float
        Target absolute error of the theta quadratures (k_B per surface atom for the
        entropies); the node count is doubled until the error estimate is below it.
    n_theta_start, n_theta_max : int
        First and largest Gauss-Legendre sizes on [0, pi/2].

    Returns
    -------
    dict of ndarray, each shape (n,)
        ``S_surface_estimate``, ``S_surface_estimate_error``, ``bulk_mean_log_omega``,
        ``bulk_mean_log_omega_error``, ``S_surface_exact``, ``S_surface_exact_error``
        (floats; entropies in k_B per surface atom, the mean log in ln omega0 units),
        ``n_theta`` (int) and ``reason`` (str, "" where everything is valid). Unstable
        strains give NaN with the reason, never an exception. Metadata: ``surfwave.data.variables.CUBES["entropy"]``.

    Raises
    ------
    InputError, GeometryError
        Unknown potential, or d/d0 outside (0, 2) (the geometry cannot exist).
    """
    pot = get_potential(potential)
    s = build("triangular", "uniaxial", None, "[10]", d_over_d0).d_over_d0  # validates
    rows = [_one_strain(pot, float(d), tol, n_theta_start, n_theta_max) for d in s]
    out = {k: np.array([r[k] for r in rows], dtype=float)
           for k in OUTPUTS if k not in ("reason", "n_theta")}
    out["n_theta"] = np.array([r["n_theta"] for r in rows], dtype=int)
    out["reason"] = np.array([r["reason"] for r in rows], dtype=str)
    return out
