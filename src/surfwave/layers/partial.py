"""Per-layer Stroh eigen-solutions of a stack, in scaled units, split into decoupled families.

Every layer (and the substrate) is described by its generalised Stroh blocks Q, R, T (3 x 3
elastic, 4 x 4 with the potential as fourth component; :mod:`surfwave.solvers.piezo_stroh`),
lab frame x1 propagation, x2 inward normal. A partial wave U = a exp(ik(x1 + p x2)) carries the
generalised traction b = (R^T + p T) a on the planes x2 = const; [a; b] is an eigenvector of the
Stroh matrix N(X) with eigenvalue p, X = rho c^2 (mass on the mechanical components only).

Scaling: stiffnesses by ``sA`` (the largest |A| of the stack, Pa), permittivities by ``se``
(the largest |eps|, F/m), piezoelectric constants by sqrt(sA se); X_l = rho_l c^2 / sA.

Families: where every layer's blocks are block diagonal in the same partition of the components
(e.g. isotropic or mirror-symmetric stacks: sagittal (u1, u2) and shear-horizontal u3), the
problem splits exactly and each family is solved on its own (:func:`families`); this makes the
exactly degenerate crossings of modes of different families harmless.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from surfwave.layers.stack import Layer, Stack
from surfwave.solvers.impedance import limiting_x as elastic_limiting_x
from surfwave.solvers.piezo_stroh import generalised_tensor
from surfwave.solvers.piezo_stroh import limiting_x as piezo_limiting_x
from surfwave.solvers.piezo_tensors import EPS0

__all__ = ["Blocks", "Family", "eigen", "families", "scaled_blocks"]

#: Relative size below which a coupling block entry counts as zero (family detection).
COUPLING_TOL = 1e-12


@dataclass(frozen=True, eq=False)
class Blocks:
    """Scaled Stroh blocks of a stack.

    Attributes
    ----------
    Q, R, T : ndarray, shape (L + 1, n, n)
        Layers from the top down, then the substrate (index L); n = 3 or 4.
    rho : ndarray, shape (L + 1,)
        Densities, kg/m^3.
    frac : ndarray, shape (L,)
        Film thickness / total film thickness (0 where the total is 0).
    sA, se : float
        Stiffness scale (Pa) and permittivity scale (F/m; 1 for elastic stacks).
    eps0 : float
        Vacuum permittivity in scaled units.
    electrode_below : tuple of bool, length L
        A grounded electrode (phi = 0) on the interface under each film.
    Q3, R3 : ndarray, shape (L + 1, n, n)
        E_I3K1 and E_I3K2: the generalised stress on planes x3 = const (power flow along x3).
    n_mech : int
        3: components 0..2 are mechanical, component 3 (if n = 4) the potential.
    korn : ndarray, shape (L + 1,), optional
        Scaled lower bound kappa of each layer's strain energy per squared displacement gradient
        (:func:`korn_bounds`): a layer of thickness t (in 1/k) clamped on both faces has no mode with
        rho c^2 / sA below kappa (1 + (pi / t)^2) (used by :mod:`surfwave.layers.counting`).
    """

    Q: np.ndarray
    R: np.ndarray
    T: np.ndarray
    rho: np.ndarray
    frac: np.ndarray
    sA: float
    se: float
    eps0: float
    Q3: np.ndarray | None = None
    R3: np.ndarray | None = None
    electrode_below: tuple[bool, ...] = ()
    n_mech: int = 3
    korn: np.ndarray | None = None


@dataclass(frozen=True, eq=False)
class Family:
    """One decoupled family of components.

    Attributes
    ----------
    idx : tuple of int
        Components of the family (0, 1, 2 mechanical, 3 potential).
    kind : str
        "sagittal" (u1, u2 [, phi]), "sh" (u3 [, phi]) or "coupled" (all).
    prefix : str
        Label prefix of its modes: "R" (then "S1", "S2", ...) for sagittal, "L" for shear
        horizontal, "M" for coupled.
    X_limit : float
        Scaled limiting X of the substrate for this family (rho_s c_lim^2 / sA).
    """

    idx: tuple[int, ...]
    kind: str
    prefix: str
    X_limit: float

    @property
    def mech(self) -> np.ndarray:
        """Mass mask (1 on mechanical components), shape (nf,)."""
        return np.array([1.0 if i < 3 else 0.0 for i in self.idx])

    @property
    def phi(self) -> int | None:
        """Position of the potential in the family, or None."""
        return self.idx.index(3) if 3 in self.idx else None


def scaled_blocks(stack: Stack) -> Blocks:
    """The scaled Stroh blocks of every layer and the substrate (top film first, substrate last)."""
    layers: list[Layer] = [*stack.films, stack.substrate]
    A = np.stack([lay.A for lay in layers])
    sA = float(np.abs(A).max())
    if stack.piezo:
        eps = np.stack([np.asarray(lay.eps) for lay in layers])
        e = np.stack([np.asarray(lay.e) for lay in layers])
        se = float(max(np.abs(eps).max(), EPS0))
        E = generalised_tensor(A / sA, e / np.sqrt(sA * se), eps / se)
        Q, R, T = E[:, :, 0, :, 0], E[:, :, 0, :, 1], E[:, :, 1, :, 1]
        Q3, R3 = E[:, :, 2, :, 0], E[:, :, 2, :, 1]
    else:
        se = 1.0
        Q, R, T = A[:, :, 0, :, 0] / sA, A[:, :, 0, :, 1] / sA, A[:, :, 1, :, 1] / sA
        Q3, R3 = A[:, :, 2, :, 0] / sA, A[:, :, 2, :, 1] / sA
    H = stack.total_thickness
    frac = np.array([f.thickness / H if H > 0 else 0.0 for f in stack.films])
    return Blocks(Q=Q, R=R, T=T, Q3=Q3, R3=R3, electrode_below=tuple(f.electrode_below for f in stack.films),
                  rho=np.array([lay.rho for lay in layers]), frac=frac, sA=sA, se=se,
                  eps0=EPS0 / se, korn=korn_bounds(A, np.stack([lay.sigma for lay in layers])) / sA)


#: Voigt index pairs and the Mandel weights that make the 6 x 6 stiffness an isometry of strains.
_PAIRS = ((0, 0), (1, 1), (2, 2), (1, 2), (0, 2), (0, 1))
_MANDEL = np.array([1.0, 1.0, 1.0, np.sqrt(2.0), np.sqrt(2.0), np.sqrt(2.0)])


def korn_bounds(A: np.ndarray, sigma: np.ndarray) -> np.ndarray:
    """Lower bound kappa (Pa) of A:H:H / |H|^2 for displacement fields clamped on two parallel faces, per layer.

    With C = A - sigma delta (the layer's elastic constants) and e_min the smallest eigenvalue of C in
    Mandel form, C:eps:eps >= e_min |eps|^2; Korn's identity for fields vanishing on the faces
    (periodic along them), int |sym grad u|^2 = (int |grad u|^2 + int |div u|^2) / 2, and the
    prestress term sigma_jl H_ij H_il >= s_min |H|^2 (s_min the smallest eigenvalue of sigma) give
    int A:H:H >= (e_min / 2 + s_min) int |grad u|^2. A piezoelectric layer clamped and grounded on
    both faces only stiffens. The bound is not positive when the layer is not stable.

    Parameters
    ----------
    A : ndarray, shape (L, 3, 3, 3, 3)
        Wave-propagation tensors C + sigma delta, Pa.
    sigma : ndarray, shape (L, 3, 3)
        Prestress, Pa.

    Returns
    -------
    ndarray, shape (L,)
        kappa, Pa.
    """
    C = A - np.einsum("sjl,ik->sijkl", sigma, np.eye(3))
    i, j = np.array(_PAIRS).T
    Mn = C[:, i[:, None], j[:, None], i[None, :], j[None, :]] * np.outer(_MANDEL, _MANDEL)
    e_min = np.linalg.eigvalsh(0.5 * (Mn + np.swapaxes(Mn, -1, -2)))[:, 0]
    s_min = np.linalg.eigvalsh(0.5 * (sigma + np.swapaxes(sigma, -1, -2)))[:, 0]
    return 0.5 * e_min + np.minimum(s_min, 0.0)


def families(b: Blocks) -> list[Family]:
    """Partition the components into families that no layer couples (connected components).

    Returns
    -------
    list of Family
        Sorted by their first component.
    """
    n = b.Q.shape[-1]
    link = (np.abs(b.Q) + np.abs(b.R) + np.abs(np.swapaxes(b.R, -1, -2)) + np.abs(b.T)).max(axis=0)
    adj = link > COUPLING_TOL * link.max()
    groups: list[set[int]] = []
    for i in range(n):
        comp = {i}
        for g in [g for g in groups if any(adj[i, j] or adj[j, i] for j in g)]:
            comp |= g
            groups.remove(g)
        groups.append(comp)
    out = []
    for g in sorted(groups, key=min):
        idx = tuple(sorted(g))
        mech = [i for i in idx if i < 3]
        if not mech:
            continue                                             # a purely electric family carries no wave
        if set(mech) == {0, 1}:
            kind, prefix = "sagittal", "R"
        elif set(mech) == {2}:
            kind, prefix = "sh", "L"
        else:
            kind, prefix = "coupled", "M"
        out.append(Family(idx=idx, kind=kind, prefix=prefix, X_limit=_limit(b, idx)))
    return out


def _limit(b: Blocks, idx: tuple[int, ...]) -> float:
    """Scaled limiting X of the substrate restricted to the components ``idx``."""
    ix = np.ix_(idx, idx)
    Q, R, T = (M[-1][ix][None] for M in (b.Q, b.R, b.T))
    n_m = sum(i < 3 for i in idx)
    if len(idx) == 1:                                            # q + 2 p r + p^2 t, minimum over real p
        return float(Q[0, 0, 0] - R[0, 0, 0] ** 2 / T[0, 0, 0])
    if n_m == len(idx):
        return float(elastic_limiting_x(Q, R, T)[0][0])
    return float(piezo_limiting_x(Q, R, T, nm=n_m)[0])


def stroh_matrix(Q, R, T, X, mech) -> np.ndarray:
    """Stroh matrix N(X), shape (..., 2n, 2n), for blocks (n, n) and X (...,); mass on ``mech`` (n,)."""
    Ti = np.linalg.inv(T)
    RT = np.swapaxes(R, -1, -2)
    N1 = -Ti @ RT
    N3 = R @ Ti @ RT - Q
    X = np.asarray(X)
    shape = X.shape + (2 * Q.shape[-1],) * 2
    N = np.zeros(shape, dtype=np.result_type(X.dtype, float))
    n = Q.shape[-1]
    N[..., :n, :n] = N1
    N[..., :n, n:] = Ti
    N[..., n:, :n] = N3
    N[..., n:, n:] = np.swapaxes(N1, -1, -2)
    d = np.arange(n)
    N[..., n + d, d] += X[..., None] * mech
    return N


def eigen(Q, R, T, X, mech) -> tuple[np.ndarray, np.ndarray]:
    """Eigenvalues p and eigenvectors [a; b] of N(X), sorted by ascending Im p.

    The last n (Im p largest) decay into +x2 ("down"), the first n into -x2 ("up"); real p
    (bulk waves propagating in a layer) are split arbitrarily, which is harmless since their
    exponentials have modulus 1.

    Parameters
    ----------
    Q, R, T : ndarray, shape (n, n)
    X : ndarray, shape (m,)
        Scaled rho c^2 of this layer (complex for a leaky mode).
    mech : ndarray, shape (n,)

    Returns
    -------
    p : ndarray, shape (m, 2n), complex
    V : ndarray, shape (m, 2n, 2n), complex (columns, unit norm)
    """
    N = stroh_matrix(Q, R, T, X, mech)
    p, V = np.linalg.eig(N)
    order = np.argsort(p.imag, axis=-1, kind="stable")
    p = np.take_along_axis(p, order, axis=-1)
    V = np.take_along_axis(V, order[:, None, :], axis=-1)
    _degenerate_pairs(N, p, V, Q.shape[-1])
    return p, V


#: Two Stroh roots of one group closer than this (relative to 1 + |p|) are one double root.
DEGENERATE_TOL = 1e-7


def _degenerate_pairs(N: np.ndarray, p: np.ndarray, V: np.ndarray, n: int) -> None:
    """Replace (in place) the eigenvectors of double roots by an orthonormal basis of their eigenspace.

    An isotropic layer has a double root p_T (SV and SH partial waves) whenever the motion does
    not split into families; LAPACK then returns two eigenvectors of that eigenspace that may be
    almost parallel, which costs up to half the digits of the impedance. The eigenspace of a
    semisimple double root is the null space of N - p I: its two right singular vectors of
    smallest singular value are an exact, well-conditioned basis (both with the mean root). Pairs
    are looked for across both groups: above a film's shear speed the double root is real and the
    sort by Im p may put its two copies in different groups.
    """
    # candidate pairs, found at once: within 4 x the tolerance in some row (the in-place merges below
    # move a root by at most half the tolerance, twice at most, so no other pair can become close)
    with np.errstate(invalid="ignore"):
        gap = np.abs(p[:, :, None] - p[:, None, :]) <= 4.0 * DEGENERATE_TOL * (1.0 + np.abs(p[:, :, None]))
    cand = np.triu(gap.any(axis=0), 1)
    for i, j in zip(*np.nonzero(cand)):
        close = np.abs(p[:, i] - p[:, j]) <= DEGENERATE_TOL * (1.0 + np.abs(p[:, i]))
        if not close.any():
            continue
        rows = np.flatnonzero(close)
        vi, vj = V[rows, :, i], V[rows, :, j]
        cos = np.abs(np.einsum("mk,mk->m", np.conj(vi), vj)) / (np.linalg.norm(vi, axis=-1)
                                                               * np.linalg.norm(vj, axis=-1))
        rows = rows[cos > 0.5]                  # a well-conditioned pair is kept as LAPACK gave it
        if rows.size == 0:
            continue
        pm = 0.5 * (p[rows, i] + p[rows, j])
        A = N[rows] - pm[:, None, None] * np.eye(N.shape[-1])
        _, _, vh = np.linalg.svd(A)
        basis = np.conj(vh[:, -2:, :]).transpose(0, 2, 1)          # (r, 2n, 2)
        V[rows, :, i], V[rows, :, j] = basis[..., 0], basis[..., 1]
        p[rows, i] = p[rows, j] = pm
