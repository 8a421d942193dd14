"""Brute-force piezoelectric Rayleigh-wave speeds, free and metallized (test helper).

Independent of any library surface solver: for a trial speed v the partial waves
U = a exp(ik(x1 + p x2)) of the 4 x 4 generalised Christoffel problem
Gamma(p) a = [Q - X I' + p (R + R^T) + p^2 T] a = 0 (blocks of common.md, X = rho v^2 in the
mechanical block only) come from the 8 x 8 companion matrix; the four with Im p > 0 decay into
the crystal (x2 > 0). Generalised tractions b = (R^T + p T) a = (t_12, t_22, t_32, D_2)/(ik).
Boundary conditions at x2 = 0:
  metallized: b_1..3 = 0 and phi = a_4 = 0;
  free:       b_1..3 = 0 and D_2 continuous with the vacuum potential phi0 exp(ik x1) exp(k x2)
              (decays for x2 -> -inf): ik b_4 = -EPS0 d(phi)/dx2 = -EPS0 k phi0, with phi0 = a_4
              (phi continuous), so b_4 = i EPS0 a_4, i.e. rows (b_4 - i EPS0 a_4).
The speed is the minimum of |det| of the 4 x 4 boundary matrix (columns normalised), refined
by a bounded scalar minimisation. Subsonic (true) surface waves only.
"""
from __future__ import annotations

import numpy as np
from scipy.optimize import minimize_scalar

EPS0 = 8.8541878128e-12


def generalised_tensor(C, e, eps) -> np.ndarray:
    """E_iJKl (3, 4, 4, 3) from C (3,3,3,3) Pa, e_kij (3,3,3) C/m^2, eps (3,3) F/m (lab axes)."""
    E = np.zeros((4, 3, 4, 3))  # E[J, j, K, l]
    E[:3, :, :3, :] = C
    E[:3, :, 3, :] = np.einsum("lij->ijl", e)      # E_ij3l = e_lij
    E[3, :, :3, :] = e                             # E_3jkl = e_jkl
    E[3, :, 3, :] = -eps                           # E_3j3l = -eps_jl
    return E


def _boundary_det(v, E, rho, free: bool) -> float:
    Q, R, T = E[:, 0, :, 0], E[:, 0, :, 1], E[:, 1, :, 1]
    M = Q.copy()
    M[:3, :3] -= rho * v * v * np.eye(3)
    Ti = np.linalg.inv(T)
    A = np.block([[np.zeros((4, 4)), np.eye(4)], [-Ti @ M, -Ti @ (R + R.T)]])
    p, vec = np.linalg.eig(A)
    keep = np.argsort(-p.imag)[:4]
    if np.any(p[keep].imag <= 1e-10):
        return np.inf  # a bulk wave is radiated: not a true surface wave
    a = vec[:4, keep]
    b = (R.T[:, :, None] + p[keep][None, None, :] * T[:, :, None])
    b = np.einsum("JKm,Km->Jm", b, a)
    rows = np.vstack([b[:3] / 1e10, (b[3] - 1j * EPS0 * a[3]) / 1e-10 if free else a[3]])
    rows = rows / np.linalg.norm(rows, axis=0)
    return float(abs(np.linalg.det(rows)))


def saw_speed(C, e, eps, rho, v_lo, v_hi, free: bool, n: int = 400) -> float:
    """Subsonic piezoelectric Rayleigh-wave speed in [v_lo, v_hi] m/s (lab tensors, SI units)."""
    E = generalised_tensor(C, e, eps)
    grid = np.linspace(v_lo, v_hi, n)
    f = np.array([_boundary_det(v, E, rho, free) for v in grid])
    i = int(np.argmin(f))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, n - 1)]
    res = minimize_scalar(lambda v: _boundary_det(v, E, rho, free), bounds=(lo, hi), method="bounded",
                          options={"xatol": 1e-6})
    return float(res.x)
