"""Trigonal 3m piezoelectric crystals (LiNbO3, LiTaO3) and the SAW Euler-angle rotation, for the tests.

Constants: Kovacs et al., "Improved material constants for LiNbO3 and LiTaO3", Proc. IEEE
Ultrasonics Symp. 1990, pp. 435-438 (the set the brief quotes; see the report for what could and
could not be checked). Voigt order 11, 22, 33, 23, 13, 12; e in C/m^2, relative permittivities.
"""
from __future__ import annotations

import numpy as np

from surfwave.solvers.leaky import EPS0

KOVACS = {
    "LiNbO3": dict(C11=198.39, C12=54.72, C13=65.13, C14=7.88, C33=227.90, C44=59.65,
                   e15=3.69, e22=2.42, e31=0.30, e33=1.77, eps11=44.30, eps33=27.90, rho=4628.0),
    "LiTaO3": dict(C11=233.1, C12=46.5, C13=83.6, C14=-10.5, C33=275.4, C44=95.1,
                   e15=2.64, e22=1.86, e31=-0.22, e33=1.71, eps11=42.6, eps33=42.8, rho=7454.0),
}

_VOIGT = {(0, 0): 0, (1, 1): 1, (2, 2): 2, (1, 2): 3, (2, 1): 3, (0, 2): 4, (2, 0): 4, (0, 1): 5, (1, 0): 5}


def trigonal_3m(name: str) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    """Crystal-axes tensors C (3,3,3,3) Pa, e (3,3,3) C/m^2, eps (3,3) F/m and rho kg/m^3 of a 3m crystal."""
    k = KOVACS[name]
    c11, c12, c13, c14, c33, c44 = (k[n] * 1e9 for n in ("C11", "C12", "C13", "C14", "C33", "C44"))
    c66 = 0.5 * (c11 - c12)
    V = np.array([[c11, c12, c13, c14, 0, 0], [c12, c11, c13, -c14, 0, 0], [c13, c13, c33, 0, 0, 0],
                  [c14, -c14, 0, c44, 0, 0], [0, 0, 0, 0, c44, c14], [0, 0, 0, 0, c14, c66]])
    e15, e22, e31, e33 = k["e15"], k["e22"], k["e31"], k["e33"]
    E = np.array([[0, 0, 0, 0, e15, -e22], [-e22, e22, 0, e15, 0, 0], [e31, e31, e33, 0, 0, 0]])
    C = np.empty((3, 3, 3, 3))
    e = np.empty((3, 3, 3))
    for (i, j), a in _VOIGT.items():
        e[:, i, j] = E[:, a]
        for (kk, ll), b in _VOIGT.items():
            C[i, j, kk, ll] = V[a, b]
    eps = EPS0 * np.diag([k["eps11"], k["eps11"], k["eps33"]])
    return C, e, eps, k["rho"]


def euler_lab_axes(phi, theta, psi) -> np.ndarray:
    """Our lab rows (x1, x2 = -x3_SAW, x3 = x2_SAW) in crystal axes from SAW Euler angles (deg, ZXZ).

    The SAW frame is a = Rz(psi) Rx(theta) Rz(phi) (passive rotations, rows = SAW axes in crystal
    axes; x3_SAW the outward normal), e.g. rotated Y-cut theta_Y, X propagation = (0, theta_Y - 90, 0).
    Array angles give shape (..., 3, 3).
    """
    p, t, s = (np.radians(np.asarray(x, dtype=float)) for x in (phi, theta, psi))
    p, t, s = np.broadcast_arrays(p, t, s)

    def rz(a):
        c, sn, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([c, sn, z], -1), np.stack([-sn, c, z], -1), np.stack([z, z, o], -1)], -2)

    def rx(a):
        c, sn, z, o = np.cos(a), np.sin(a), np.zeros_like(a), np.ones_like(a)
        return np.stack([np.stack([o, z, z], -1), np.stack([z, c, sn], -1), np.stack([z, -sn, c], -1)], -2)

    a = rz(s) @ rx(t) @ rz(p)
    return np.stack([a[..., 0, :], -a[..., 2, :], a[..., 1, :]], axis=-2)


def rotated(name: str, phi, theta, psi):
    """Lab-frame A (m,3,3,3,3) Pa, e (m,3,3,3), eps (m,3,3) and rho for Euler angles (arrays of shape (m,))."""
    C, e, eps, rho = trigonal_3m(name)
    R = np.atleast_3d(euler_lab_axes(phi, theta, psi)).reshape(-1, 3, 3)
    A = np.einsum("mai,mbj,mck,mdl,ijkl->mabcd", R, R, R, R, C)
    el = np.einsum("mai,mbj,mck,ijk->mabc", R, R, R, e)
    epl = np.einsum("mai,mbj,ij->mab", R, R, eps)
    return A, el, epl, rho
