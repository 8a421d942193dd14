"""A second route to the guided modes of an elastic stack: Chebyshev collocation (test helper).

Independent of the library's recursion: each layer and a deep slice of the substrate (clamped at
depth ``depth`` in units of 1/k) is discretised on Chebyshev-Gauss-Lobatto points; in z = k x2
the equations of motion read T u'' + i (R + R^T) u' - Q u = -rho c^2 u (blocks Q, R, T of
A_ijkl, x1 propagation, x2 inward normal), the traction on x2 = const is proportional to
i R^T u + T u'. Rows at the top node: traction free; at each interface: continuity of u and of
the traction; at the bottom node: u = 0. The generalised eigenproblem L u = -c^2 M u gives
every mode of the truncated stack at once (scipy.linalg.eig); the substrate truncation costs
exp(-2 k depth Im p) relative, negligible for depth = 40 and a mode that is not near cut-off.
"""
from __future__ import annotations

import numpy as np
from scipy.linalg import eig


def cheb(n: int) -> tuple[np.ndarray, np.ndarray]:
    """Chebyshev-Gauss-Lobatto points x (n + 1,) in [-1, 1] and the differentiation matrix (Trefethen)."""
    x = np.cos(np.pi * np.arange(n + 1) / n)
    c = np.ones(n + 1)
    c[0] = c[-1] = 2.0
    c *= (-1.0) ** np.arange(n + 1)
    X = np.tile(x, (n + 1, 1)).T
    dX = X - X.T
    D = np.outer(c, 1 / c) / (dX + np.eye(n + 1))
    D -= np.diag(D.sum(axis=1))
    return x, D


def collocation_speeds(A_layers, rho_layers, t_layers, A_sub, rho_sub, *, n_layer=24, n_sub=90,
                       depth=40.0) -> np.ndarray:
    """All real speeds c (m/s) of the truncated stack at one kh, ascending.

    Parameters
    ----------
    A_layers : list of (3, 3, 3, 3) Pa, top first; rho_layers : list of kg/m^3;
    t_layers : list of k h_l (1); A_sub, rho_sub : the substrate; depth : k times the substrate slice.
    """
    As = [*A_layers, A_sub]
    rhos = [*rho_layers, rho_sub]
    ts = [*t_layers, depth]
    ns = [n_layer] * len(A_layers) + [n_sub]
    sA = max(np.abs(A).max() for A in As)
    sizes = [3 * (n + 1) for n in ns]
    off = np.concatenate([[0], np.cumsum(sizes)])
    tot = off[-1]
    L = np.zeros((tot, tot), dtype=complex)
    M = np.zeros((tot, tot))
    trac = []
    for l, (A, rho, t, n) in enumerate(zip(As, rhos, ts, ns)):
        Q, R, T = A[:, 0, :, 0] / sA, A[:, 0, :, 1] / sA, A[:, 1, :, 1] / sA
        x, D = cheb(n)
        D = D * (-2.0 / t)                       # node 0 = top of the layer (z = 0), node n = bottom
        I3 = np.eye(3)
        Dk = np.kron(D, I3)
        D2k = Dk @ Dk
        blk = np.kron(np.eye(n + 1), T) @ D2k + 1j * np.kron(np.eye(n + 1), R + R.T) @ Dk \
            - np.kron(np.eye(n + 1), Q)
        s = slice(off[l], off[l + 1])
        L[s, s] = blk
        M[s, s] = np.eye(3 * (n + 1)) * rho / sA
        tr = 1j * np.kron(np.eye(n + 1), R.T) + np.kron(np.eye(n + 1), T) @ Dk     # traction rows
        trac.append(tr)
    def rows(l, node):
        return slice(off[l] + 3 * node, off[l] + 3 * node + 3)
    # top free
    r = rows(0, 0)
    L[r, :] = 0
    L[r, off[0]:off[1]] = trac[0][0:3]
    M[r, :] = 0
    for l in range(len(As) - 1):
        rb, rt = rows(l, ns[l]), rows(l + 1, 0)
        for rr in (rb, rt):
            L[rr, :] = 0
            M[rr, :] = 0
        L[rb, rb] = np.eye(3)
        L[rb, rt] = -np.eye(3)
        L[rt, off[l]:off[l + 1]] = trac[l][3 * ns[l]:3 * ns[l] + 3]
        L[rt, off[l + 1]:off[l + 2]] = -trac[l + 1][0:3]
    r = rows(len(As) - 1, ns[-1])
    L[r, :] = 0
    M[r, :] = 0
    L[r, r] = np.eye(3)
    w = eig(L, -M, right=False)
    w = w[np.isfinite(w)]
    w = w[(np.abs(w.imag) < 1e-8 * np.abs(w.real)) & (w.real > 0)].real
    return np.sort(np.sqrt(w))
