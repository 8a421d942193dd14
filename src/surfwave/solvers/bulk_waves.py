"""Bulk plane waves along the lab axes x1 and x2: speeds and polarisations, named by polarisation.

For a propagation direction n the plane-wave speeds are the eigenvalues of the Christoffel
(acoustic) tensor rho v^2 a = G(n) a with G_ik = A_ijkl n_j n_l, where A = C + sigma0 delta is
the wave-propagation tensor of the prestressed crystal (PHYSICS.md, "Beyond the paper"). In a
piezoelectric crystal the quasi-static field stiffens it:
G_ik += g_i g_k / (n . eps . n), g_i = e_pij n_p n_j (e the piezoelectric stress tensor, eps
the clamped permittivity).

Each direction has three waves. They are named by their polarisation: the wave whose
displacement lies most along the propagation is the quasi-longitudinal one, the other two are
quasi-shear waves named by the axis they are most polarised along. Along x1: ``L_par``
(mostly u1), ``T_par`` (mostly u2, the sagittal shear), ``SH`` (mostly u3); along x2:
``T_perp`` (mostly u1), ``L_perp`` (mostly u2), ``SH_perp`` (mostly u3). "Mostly" is decided
jointly: the assignment of the three waves to the three axes that maximises the sum of the
squared components (a tie where two waves share their largest component is resolved that way,
never by dropping a wave). Where two speeds coincide (a degenerate pair, e.g. the shears along
a cube axis) the pair's polarisations are rotated in their plane onto the lab axes.

These are the real crystal's speeds. The model crystals' speeds of the paper (Eq. A7,
:mod:`surfwave.model_crystals.elastic`) keep the paper's definitions (diagonal entries of S).

Examples
--------
>>> from surfwave.solvers.tensors import cubic_voigt, voigt_to_tensor
>>> C = voigt_to_tensor(cubic_voigt(168.4e9, 121.4e9, 75.4e9))      # Cu, Pa
>>> r = axis_waves(C[None], np.array([8960.0]))
>>> round(float(r["c_L_par"][0]), 1), round(float(r["c_T_par"][0]), 1)   # sqrt(C11/rho), sqrt(C44/rho)
(4335.3, 2900.9)
"""
from __future__ import annotations

import itertools

import numpy as np

from surfwave.solvers.tensors import cross

__all__ = ["AXIS_WAVES", "BULK_SPEEDS", "BULK_POLARISATIONS", "DEGENERATE_RTOL", "axis_waves", "christoffel"]

#: The waves along each lab axis: (direction index, name of the wave mostly polarised along x1, x2, x3).
AXIS_WAVES = ((0, ("L_par", "T_par", "SH")), (1, ("T_perp", "L_perp", "SH_perp")))
#: Speed keys (m/s), in the order of :data:`AXIS_WAVES`.
BULK_SPEEDS = tuple(f"c_{name}" for _, names in AXIS_WAVES for name in names)
#: Polarisation keys (unit displacement vectors in the lab frame), same order.
BULK_POLARISATIONS = tuple(f"polarisation_{name}" for _, names in AXIS_WAVES for name in names)
#: Relative gap of rho v^2 below which two waves count as degenerate (their polarisations are
#: then put onto the lab axes).
DEGENERATE_RTOL = 1e-9
_PERMS = np.array(list(itertools.permutations(range(3))))   # (6, 3): axis c -> wave perm[c]


def christoffel(A, n, e=None, eps=None) -> np.ndarray:
    """Christoffel tensor G_ik(n), piezoelectrically stiffened where ``e`` is given.

    Parameters
    ----------
    A : array_like, shape (m, 3, 3, 3, 3)
        Wave-propagation tensor (C + sigma0 delta), Pa.
    n : array_like, shape (3,) or (m, 3)
        Unit propagation direction (same frame as ``A``).
    e : array_like, shape (m, 3, 3, 3), optional
        Piezoelectric stress tensor e_pij, C/m^2.
    eps : array_like, shape (m, 3, 3), optional
        Permittivity, F/m (absolute); with ``e``.

    Returns
    -------
    ndarray, shape (m, 3, 3)
        G_ik, Pa (symmetric when A has the major symmetry).
    """
    A = np.asarray(A, dtype=float)
    n = np.broadcast_to(np.asarray(n, dtype=float), A.shape[:-4] + (3,))
    G = np.einsum("...ijkl,...j,...l->...ik", A, n, n)
    if e is not None:
        g = np.einsum("...pij,...p,...j->...i", np.asarray(e, dtype=float), n, n)
        en = np.einsum("...p,...pq,...q->...", n, np.asarray(eps, dtype=float), n)
        G = G + g[..., :, None] * g[..., None, :] / en[..., None, None]
    return G


def _axis_christoffel(A: np.ndarray, axis: int, e=None, eps=None) -> np.ndarray:
    """:func:`christoffel` along the lab axis ``axis`` (n = its unit vector), shape (m, 3, 3), Pa.

    With n a unit axis every sum of :func:`christoffel` has one non-zero term, the component
    itself (products with 1 and 0 and sums with 0 are exact): picking the components (+ 0.0,
    which turns a -0 into the +0 the sums give) is the same numbers without the sums' cost.
    """
    G = A[..., :, axis, :, axis] + 0.0
    if e is not None:
        g = np.asarray(e, dtype=float)[..., axis, :, axis] + 0.0
        en = np.asarray(eps, dtype=float)[..., axis, axis] + 0.0
        G = G + g[..., :, None] * g[..., None, :] / en[..., None, None]
    return G


def _align_degenerate(w: np.ndarray, V: np.ndarray) -> np.ndarray:
    """Rotate each degenerate pair of eigenvectors (columns of V) onto the lab axes.

    Within the plane of a pair, the first vector becomes the projection of the axis that lies
    most in the plane, the second completes the pair (orthonormal, in the plane).
    """
    V = V.copy()
    scale = np.maximum(np.abs(w).max(axis=-1), 1e-300)
    for a, b in ((0, 1), (1, 2)):
        deg = np.abs(w[:, b] - w[:, a]) <= DEGENERATE_RTOL * scale
        if not deg.any():
            continue
        U = V[deg][:, :, [a, b]]                                    # (k, 3, 2): basis of the plane
        P = U @ np.swapaxes(U, -1, -2)                              # projector onto the plane
        axis = np.argmax(np.einsum("kii->ki", P), axis=-1)          # the axis closest to the plane
        first = P[np.arange(len(axis)), :, axis]
        first /= np.linalg.norm(first, axis=-1, keepdims=True)
        normal = cross(U[:, :, 0], U[:, :, 1])
        second = cross(normal, first)
        V[np.flatnonzero(deg)[:, None], :, np.array([a, b])[None, :]] = np.stack([first, second], axis=1)
    return V


def _name_by_polarisation(V: np.ndarray) -> np.ndarray:
    """Wave index per lab axis, (m, 3): the permutation maximising sum_c V[c, wave(c)]^2."""
    score = (V ** 2)[:, np.arange(3)[None, :], _PERMS].sum(axis=-1)   # (m, 6)
    return _PERMS[np.argmax(score, axis=-1)]


def axis_waves(A, rho, e=None, eps=None) -> dict[str, np.ndarray]:
    """Speeds and polarisations of the three bulk waves along x1 and along x2, named by polarisation.

    Parameters
    ----------
    A : array_like, shape (m, 3, 3, 3, 3)
        Wave-propagation tensor C + sigma0 delta in the lab frame (x1 propagation, x2 inward
        normal), Pa.
    rho : array_like, shape (m,)
        Density, kg/m^3.
    e : array_like, shape (m, 3, 3, 3), optional
        Piezoelectric stress tensor e_pij, C/m^2, lab frame (stiffened speeds).
    eps : array_like, shape (m, 3, 3), optional
        Clamped permittivity, F/m, lab frame; with ``e``.

    Returns
    -------
    dict of ndarray
        :data:`BULK_SPEEDS` -> shape (m,), m/s (NaN where rho v^2 <= 0: no real bulk wave);
        :data:`BULK_POLARISATIONS` -> shape (m, 3), unit displacement (u1, u2, u3) in the lab
        frame, sign such that the largest component is positive (NaN with the speed).
    """
    A = np.asarray(A, dtype=float)
    rho = np.broadcast_to(np.asarray(rho, dtype=float), A.shape[:1])
    m = A.shape[0]
    # both axes in one stack (rows 0..m-1: x1, m..2m-1: x2): every step below is per row
    G = np.concatenate([_axis_christoffel(A, axis, e, eps) for axis, _ in AXIS_WAVES])
    G = 0.5 * (G + np.swapaxes(G, -1, -2))
    if m:
        w, V = np.linalg.eigh(G)
        V = _align_degenerate(w, V)
        which = _name_by_polarisation(V)                                   # (2m, 3): wave of each axis
    else:
        w, V, which = np.empty((0, 3)), np.empty((0, 3, 3)), np.empty((0, 3), dtype=int)
    rows = np.arange(2 * m)[:, None]
    x = w[rows, which] / np.concatenate([rho, rho])[:, None]               # (2m, 3) rho v^2 / rho
    vec = V[rows, :, which]                                                # (2m, 3 waves, 3 components)
    big = np.take_along_axis(vec, np.argmax(np.abs(vec), axis=-1)[..., None], axis=-1)[..., 0]
    vec = vec * np.sign(np.where(big == 0, 1.0, big))[..., None]
    real = x > 0
    speed = np.where(real, np.sqrt(np.where(real, x, 1.0)), np.nan)
    pol = np.where(real[..., None], vec, np.nan)
    out: dict[str, np.ndarray] = {}
    for a, (_, names) in enumerate(AXIS_WAVES):
        for c, name in enumerate(names):
            out[f"c_{name}"] = speed[a * m:(a + 1) * m, c].copy()
            out[f"polarisation_{name}"] = pol[a * m:(a + 1) * m, c].copy()
    return {key: out[key] for key in BULK_SPEEDS + BULK_POLARISATIONS}
