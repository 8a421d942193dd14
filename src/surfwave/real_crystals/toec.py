"""Third-order elastic constants: the stressed crystal's constants from a hyperelastic model.

Energy per unit *natural* (unstressed) volume, Brugger convention (Lagrangian strain
eta = (F^T F - I)/2, constants defined at the natural state):

    W(eta) = 1/2 C2_ijkl eta_ij eta_kl + 1/6 C3_ijklmn eta_ij eta_kl eta_mn

    T = dW/deta = C2 : eta + 1/2 C3 : eta : eta           (second Piola-Kirchhoff stress)
    sigma = F T F^T / J,  J = det F                         (Cauchy stress)
    C*_ijkl = F_ip F_jq F_kr F_ls (C2 + C3 : eta)_pqrs / J  (constants of the stressed state)
    rho = rho0 / J

C* are the second strain derivatives of the energy about the stressed state per unit
current volume (Wallace's C of the stressed crystal, the quantity Eq. A12 gives for pair
forces); the wave-propagation coefficients are A_ijkl = C*_ijkl + sigma_jl delta_ik.

Frames: every tensor is in the crystal axes. The deformation that carries a given Cauchy
stress is unique only up to a rotation; we take F symmetric (a pure stretch, F = U, no
rotation), so the crystal axes stay the laboratory axes to first order and a direction m0
of the natural crystal ends up along F m0, a plane of normal n0 along F^-T n0.

Voigt form of C3 (shape (6, 6, 6)): C3_IJK with I, J, K in 11, 22, 33, 23, 13, 12 (0-based
0..5), so that C3_ijklmn = C3_IJK with no factors of 2 (as tabulated: C111, C123, C456, ...).

Examples
--------
>>> import numpy as np
>>> from surfwave.solvers.tensors import cubic_voigt
>>> C2 = cubic_voigt(168.4, 121.4, 75.4)                         # Cu, GPa
>>> C3 = cubic_toec(-1271, -814, -50, -3, -780, -95)              # Hiki & Granato (1966)
>>> st = stressed_state(C2, C3, np.diag([0.1, 0.0, 0.0]), 8960.0)  # 100 MPa along [100]
>>> bool(st["ok"]), round(float(st["F"][0, 0] - 1.0), 7)
(True, 0.0014876)
"""
from __future__ import annotations

from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike

from surfwave.errors import InputError

# born_lowest, born_stable and PD_MARGIN stay importable from here (their home before wallace.py)
from surfwave.real_crystals.wallace import (  # noqa: F401
    PD_MARGIN,
    born_lowest,
    born_reason,
    born_stable,
    lowest_if_needed,
    wallace_tensor,
)
from surfwave.solvers.tensors import VOIGT_INDEX, VOIGT_PAIRS, cross, rotate4, tensor_to_voigt, voigt_to_tensor

#: Newton iterations of the deformation solve before it is declared failed.
MAX_ITERATIONS = 60
#: Default tolerance of the deformation solve on the Cauchy stress, GPa.
DEFAULT_TOL = 1e-9

# Symmetric basis tensors of the six Voigt components, shape (6, 3, 3).
_BASIS = np.zeros((6, 3, 3))
for _a, (_i, _j) in enumerate(VOIGT_PAIRS):
    _BASIS[_a, _i, _j] = _BASIS[_a, _j, _i] = 1.0
# The one non-zero (= 1) entry of each row (and, _BASIS being symmetric, column) of _BASIS[a]: index
# 3 where the row is zero. X @ _BASIS[a] is X's columns picked by it (and _BASIS[a] @ X X's rows), a
# zero column (row) appended to X standing for 3: the same numbers as the matrix products, without
# their cost (a product with 1 and sums with +0 are exact).
_BASIS_PICK = np.where(_BASIS.any(axis=-1), np.argmax(_BASIS, axis=-1), 3)     # (6, 3)
_PICK_ROWS = np.broadcast_to(np.arange(3)[None, :, None], (6, 3, 3))
_PICK_COLS = np.broadcast_to(_BASIS_PICK[:, None, :], (6, 3, 3))


def cubic_toec(C111: ArrayLike, C112: ArrayLike, C123: ArrayLike, C144: ArrayLike, C155: ArrayLike,
               C456: ArrayLike) -> np.ndarray:
    """Voigt third-order stiffness of a cubic crystal (classes 432, -43m, m-3m), cube axes.

    C144 pairs a normal strain with the shear in the plane perpendicular to it (C144 = C255
    = C366); C155 pairs it with a shear containing its axis (C155 = C166 = C244 = ...).

    Parameters
    ----------
    C111, C112, C123, C144, C155, C456 : float or array_like
        Brugger constants (any units; GPa throughout surfwave). Arrays broadcast.

    Returns
    -------
    ndarray, shape (..., 6, 6, 6)
        Fully symmetric in its three Voigt indices.
    """
    vals = np.broadcast_arrays(*(np.asarray(v, dtype=float) for v in (C111, C112, C123, C144, C155, C456)))
    c111, c112, c123, c144, c155, c456 = vals
    out = np.zeros(c111.shape + (6, 6, 6))

    def put(value, I, J, K):
        for p in {(I, J, K), (I, K, J), (J, I, K), (J, K, I), (K, I, J), (K, J, I)}:
            out[(...,) + p] = value

    for a in range(3):
        b, c = [k for k in range(3) if k != a]
        put(c111, a, a, a)
        put(c112, a, a, b)
        put(c112, a, a, c)
        put(c144, a, a + 3, a + 3)          # normal a with the shear of the plane normal to a
        put(c155, a, b + 3, b + 3)          # normal a with the shears whose plane contains a
        put(c155, a, c + 3, c + 3)
    put(c123, 0, 1, 2)
    put(c456, 3, 4, 5)
    return out


def toec_tensor(C3_voigt: ArrayLike) -> np.ndarray:
    """Full sixth-rank tensor C3_ijklmn from its Voigt form, shape (..., 6, 6, 6) -> (..., 3, 3, 3, 3, 3, 3)."""
    C3 = np.asarray(C3_voigt, dtype=float)
    if C3.shape[-3:] != (6, 6, 6):
        raise InputError(f"a Voigt third-order stiffness has shape (..., 6, 6, 6), got {C3.shape}")
    V = VOIGT_INDEX
    return C3[..., V[:, :, None, None, None, None], V[None, None, :, :, None, None], V[None, None, None, None, :, :]]


@lru_cache(maxsize=64)
def _full_index(data: bytes, shape: tuple[int, ...]) -> np.ndarray:
    """The full-index tensor of one Voigt C2 (6, 6) or C3 (6, 6, 6) given by its bytes, built once
    per set of constants (the same numbers: the same picks), read-only."""
    voigt = np.frombuffer(data, dtype=float).reshape(shape)
    full = voigt_to_tensor(voigt) if shape == (6, 6) else toec_tensor(voigt)
    full.setflags(write=False)
    return full


def _as_c2(C2) -> np.ndarray:
    C2 = np.asarray(C2, dtype=float)
    if C2.shape == (6, 6):
        return _full_index(C2.tobytes(), C2.shape)
    if C2.shape[-2:] == (6, 6) and (C2.ndim < 4 or C2.shape[-4:-2] != (3, 3)):
        return voigt_to_tensor(C2)
    if C2.shape[-4:] != (3, 3, 3, 3):
        raise InputError(f"C2 must have shape (..., 6, 6) or (..., 3, 3, 3, 3), got {C2.shape}")
    return C2


def _as_c3(C3) -> np.ndarray:
    C3 = np.asarray(C3, dtype=float)
    if C3.shape == (6, 6, 6):
        return _full_index(C3.tobytes(), C3.shape)
    if C3.shape[-3:] == (6, 6, 6):
        return toec_tensor(C3)
    if C3.shape[-6:] != (3,) * 6:
        raise InputError(f"C3 must have shape (..., 6, 6, 6) or (..., 3, 3, 3, 3, 3, 3), got {C3.shape}")
    return C3


def lagrangian_strain(F: ArrayLike) -> np.ndarray:
    """Lagrangian (Green) strain eta = (F^T F - I)/2, shape (..., 3, 3) -> (..., 3, 3)."""
    F = np.asarray(F, dtype=float)
    return 0.5 * (np.einsum("...ki,...kj->...ij", F, F) - np.eye(3))


def _tangent(C2, C3, eta) -> np.ndarray:
    """d^2 W / d eta^2 = C2 + C3 : eta, shape (..., 3, 3, 3, 3)."""
    C3m = C3.reshape(C3.shape[:-6] + (81, 9))
    contracted = (C3m @ eta.reshape(eta.shape[:-2] + (9, 1)))
    return C2 + contracted.reshape(contracted.shape[:-2] + (3, 3, 3, 3))


def _pk2(C2, C3, eta) -> np.ndarray:
    """T = C2 : eta + 1/2 C3 : eta : eta, shape (..., 3, 3)."""
    return np.einsum("...ijkl,...kl->...ij", 0.5 * (C2 + _tangent(C2, C3, eta)), eta)


def cauchy_stress(F: ArrayLike, C2: ArrayLike, C3: ArrayLike | None) -> np.ndarray:
    """Cauchy stress of the hyperelastic model at deformation F: sigma = F T F^T / J.

    Parameters
    ----------
    F : array_like, shape (..., 3, 3)
        Deformation gradient from the natural state, crystal axes.
    C2 : array_like, shape (..., 6, 6) or (..., 3, 3, 3, 3)
        Second-order constants at the natural state (GPa).
    C3 : array_like, shape (..., 6, 6, 6) or (..., 3, 3, 3, 3, 3, 3), or None
        Third-order (Brugger) constants (GPa); None means zero.

    Returns
    -------
    ndarray, shape (..., 3, 3)
        True (Cauchy) stress in the deformed state, GPa.
    """
    F = np.asarray(F, dtype=float)
    C2 = _as_c2(C2)
    return _cauchy(F, C2, np.zeros(C2.shape[:-4] + (3,) * 6) if C3 is None else _as_c3(C3))


def _cauchy(F: np.ndarray, C2: np.ndarray, C3: np.ndarray) -> np.ndarray:
    """:func:`cauchy_stress` of float F and full-index C2, C3 (GPa)."""
    T = _pk2(C2, C3, lagrangian_strain(F))
    return np.einsum("...ip,...pq,...jq->...ij", F, T, F) / np.linalg.det(F)[..., None, None]


def deformed_axes(F: ArrayLike, axes: ArrayLike) -> np.ndarray:
    """Lab axes carried by the deformation: rows x1 = F m0, x2 = F^-T n0, x3 = x1 x x2.

    The propagation direction is a material line (it follows F); the surface normal is a
    plane normal (it follows F^-T), so x1 . x2 = m0 . n0 = 0 stays exact.

    Parameters
    ----------
    F : array_like, shape (..., 3, 3)
        Deformation gradient from the natural state, crystal axes.
    axes : array_like, shape (..., 3, 3)
        Natural-state lab axes, rows (m0, n0, m0 x n0) in crystal axes
        (:func:`surfwave.solvers.orientation.lab_axes`).

    Returns
    -------
    ndarray, shape broadcast of (..., 3, 3)
        Orthonormal rows, crystal axes.
    """
    F = np.asarray(F, dtype=float)
    axes = np.asarray(axes, dtype=float)
    x1 = np.einsum("...ij,...j->...i", F, axes[..., 0, :])
    x2 = np.einsum("...ji,...j->...i", np.linalg.inv(F), axes[..., 1, :])
    x1 = x1 / np.linalg.norm(x1, axis=-1, keepdims=True)
    x2 = x2 / np.linalg.norm(x2, axis=-1, keepdims=True)
    return np.stack([x1, x2, cross(x1, x2)], axis=-2)


def stressed_constants(C2: ArrayLike, C3: ArrayLike | None, F: ArrayLike) -> np.ndarray:
    """Constants of the stressed state C*_ijkl = F_ip F_jq F_kr F_ls (C2 + C3 : eta)_pqrs / J.

    Parameters
    ----------
    C2 : array_like, shape (..., 6, 6) or (..., 3, 3, 3, 3)
        Natural-state second-order constants, GPa.
    C3 : array_like, shape (..., 6, 6, 6) or (..., 3, 3, 3, 3, 3, 3), or None
        Natural-state Brugger third-order constants, GPa; None means zero.
    F : array_like, shape (..., 3, 3)
        Deformation gradient from the natural state.

    Returns
    -------
    ndarray, shape (..., 3, 3, 3, 3)
        C*, GPa, crystal axes; has the full Voigt symmetry. With A = C* + sigma delta it gives
        the incremental equations of motion in the stressed state.
    """
    F = np.asarray(F, dtype=float)
    C2 = _as_c2(C2)
    return _push_forward(F, C2 if C3 is None else _tangent(C2, _as_c3(C3), lagrangian_strain(F)))


def _push_forward(F: np.ndarray, K: np.ndarray) -> np.ndarray:
    """F_ip F_jq F_kr F_ls K_pqrs / J, shape (..., 3, 3, 3, 3): :func:`stressed_constants` from the
    tangent K = C2 + C3 : eta (GPa) at F."""
    return rotate4(K, F) / np.linalg.det(F)[..., None, None, None, None]


def _stress_and_jacobian(F, C2, C3):
    """Cauchy stress (..., 3, 3) and its derivative along the 6 symmetric basis directions of F,
    (..., 6, 3, 3), plus the tangent C2 + C3 : eta (matrix products: einsum chains are slow)."""
    sigma, parts = _stress_parts(F, C2, C3)
    return sigma, _jacobian(parts), parts["K"]


def _stress_parts(F, C2, C3, strain=None) -> tuple[np.ndarray, dict]:
    """Cauchy stress (..., 3, 3) at F and the intermediate arrays its Jacobian (:func:`_jacobian`) reuses.

    ``strain``: (eta, K, T) at this F where already known (:func:`_strain_parts`), else computed.
    """
    eta, K, T = _strain_parts(F, C2, C3) if strain is None else strain
    J = np.linalg.det(F)
    Ft = np.swapaxes(F, -1, -2)
    sigma = F @ T @ Ft / J[..., None, None]
    return sigma, {"F": F, "Ft": Ft, "T": T, "J": J, "K": K, "sigma": sigma, "eta": eta}


def _strain_parts(F, C2, C3) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Lagrangian strain eta, tangent K = C2 + C3 : eta and PK2 stress T = (C2 + K)/2 : eta at F:
    the numbers of :func:`_pk2` (C2 + K and K + C2 are the same sum), kept for reuse."""
    eta = lagrangian_strain(F)
    K = _tangent(C2, C3, eta)
    return eta, K, np.einsum("...ijkl,...kl->...ij", 0.5 * (K + C2), eta)


def _jacobian(parts: dict, rows=None) -> np.ndarray:
    """d sigma / dF along the 6 symmetric basis directions, (..., 6, 3, 3), of the points ``rows``
    (all when None) from :func:`_stress_parts` (each point's numbers do not depend on the others)."""
    if rows is not None and rows.all():
        rows = None                                            # every point: no copies
    F, Ft, T, J, K, sigma = (parts[k] if rows is None else parts[k][rows] for k in ("F", "Ft", "T", "J", "K", "sigma"))
    Finv = np.linalg.inv(F)
    FtdF = _times_basis(Ft)                                    # Ft @ dF
    deta = 0.5 * (FtdF + np.swapaxes(FtdF, -1, -2))
    K6 = K.reshape(K.shape[:-4] + (1, 9, 9))
    dT = (K6 @ deta.reshape(deta.shape[:-2] + (9, 1))).reshape(deta.shape)
    dFTFt = _times_each(np.swapaxes(_times_basis(np.swapaxes(T, -1, -2)), -1, -2), Ft)     # (dF @ T) @ Ft
    FdT = (F @ np.swapaxes(dT, -3, -2).reshape(dT.shape[:-3] + (3, 18))).reshape(dT.shape[:-3] + (3, 6, 3))
    term = dFTFt + np.swapaxes(dFTFt, -1, -2) + _times_each(np.swapaxes(FdT, -3, -2), Ft)   # F @ dT @ Ft
    # tr(F^-1 dF) = Finv_pq (+ Finv_qp off the diagonal): the einsum over the basis' 0/1 entries
    # adds exact zeros to these, and + 0.0 gives a zero its +0 sign as the einsum's sum does
    trace = Finv[..., _VI, _VJ]
    trace[..., 3:] += Finv[..., _VJ[3:], _VI[3:]]
    trace += 0.0
    return term / J[..., None, None, None] - sigma[..., None, :, :] * trace[..., None, None]


def _times_each(X: np.ndarray, B: np.ndarray) -> np.ndarray:
    """X_a @ B for the six 3 x 3 matrices X_a of each point, (..., 6, 3, 3) @ (..., 3, 3): one (18, 3)
    by (3, 3) product per point instead of six 3 x 3 ones (each entry the same dot product, so the
    same numbers as ``X @ B[..., None, :, :]``)."""
    lead = X.shape[:-3]
    return (np.ascontiguousarray(X).reshape(lead + (18, 3)) @ B).reshape(lead + (6, 3, 3))


def _times_basis(X: np.ndarray) -> np.ndarray:
    """X @ _BASIS[a] for the six symmetric basis tensors, (..., 3, 3) -> (..., 6, 3, 3), by picking columns.

    Each column of _BASIS[a] holds one 1 or none, so each entry of the product is one entry of X
    or 0: the values of the matrix product (a product with 1 and sums with +0 are exact), as a
    C-contiguous array like the product's.
    """
    Xp = np.concatenate([X, np.zeros(X.shape[:-1] + (1,))], axis=-1)      # column 3 = 0
    return Xp[..., _PICK_ROWS, _PICK_COLS]


_VI = np.array([p[0] for p in VOIGT_PAIRS])
_VJ = np.array([p[1] for p in VOIGT_PAIRS])


def _voigt_vec(s) -> np.ndarray:
    """The six independent components of symmetric tensors, shape (..., 3, 3) -> (..., 6)."""
    return s[..., _VI, _VJ]


def deformation_for_stress(sigma: ArrayLike, C2: ArrayLike, C3: ArrayLike | None, *, tol: float = DEFAULT_TOL,
                           max_iterations: int = MAX_ITERATIONS) -> dict:
    """The symmetric deformation F that carries a given Cauchy stress, by damped Newton.

    Solves sigma(F) = F T(eta) F^T / J = sigma for F = F^T (pure stretch, no rotation: the
    rotation is arbitrary and this choice keeps the crystal axes as laboratory axes). Starts
    from linear elasticity, F = I + S2 : sigma; each step halves until the stress residual
    falls. A point fails (``ok`` False, F NaN, ``reason`` says why) if the iteration does not
    converge, if J <= 0, or if W stops being convex at the solution (C2 + C3 : eta not positive
    definite: the third-order model is past its stability limit, a solution would be spurious).

    Parameters
    ----------
    sigma : array_like, shape (..., 3, 3)
        Cauchy stress in the deformed state, crystal axes, GPa (symmetric).
    C2 : array_like, shape (6, 6) or (3, 3, 3, 3)
        Natural-state constants, GPa.
    C3 : array_like, shape (6, 6, 6) or (3, 3, 3, 3, 3, 3), or None
        Brugger third-order constants, GPa (None: zero, geometric nonlinearity only).
    tol : float
        Largest accepted stress residual, GPa.
    max_iterations : int

    Returns
    -------
    dict
        ``F`` (..., 3, 3), ``eta`` (..., 3, 3), ``ok`` (...,) bool, ``reason`` (...,) str
        ("" where ok), ``iterations`` (...,) int, ``residual`` (...,) GPa.
    """
    sol, _, _ = _deformation(_checked_sigma(sigma), _as_c2(C2), np.zeros((3,) * 6) if C3 is None else _as_c3(C3),
                          tol, max_iterations)
    return sol


def _checked_sigma(sigma: ArrayLike) -> np.ndarray:
    """sigma as a float array, shape (..., 3, 3), symmetric and finite (InputError otherwise)."""
    sigma = np.asarray(sigma, dtype=float)
    if sigma.shape[-2:] != (3, 3):
        raise InputError(f"sigma must have shape (..., 3, 3), got {sigma.shape}")
    sigma_t = np.swapaxes(sigma, -1, -2)         # np.allclose(sigma, sigma_t, atol=1e-12, rtol=0), cheaper
    with np.errstate(invalid="ignore"):                  # inf - inf: compared as equal below, as allclose does
        symmetric = np.all((np.abs(sigma - sigma_t) <= 1e-12) | (sigma == sigma_t))
    if not symmetric:
        raise InputError("sigma must be symmetric (a Cauchy stress)")
    if not np.all(np.isfinite(sigma)):
        raise InputError("sigma must be finite")
    return sigma


def _deformation(sigma: np.ndarray, C2: np.ndarray, C3: np.ndarray, tol: float,
                 max_iterations: int) -> tuple[dict, np.ndarray, np.ndarray]:
    """:func:`deformation_for_stress` on checked input, and the tangent C2 + C3 : eta at its F.

    Parameters
    ----------
    sigma : ndarray, shape (..., 3, 3)
        Checked Cauchy stress, GPa, crystal axes.
    C2 : ndarray, shape (3, 3, 3, 3)
        Natural-state constants, GPa.
    C3 : ndarray, shape (3, 3, 3, 3, 3, 3)
        Brugger third-order constants, GPa.
    tol : float
        Largest accepted stress residual, GPa.
    max_iterations : int

    Returns
    -------
    sol : dict
        As :func:`deformation_for_stress`.
    K : ndarray, shape (n, 3, 3, 3, 3)
        C2 + C3 : eta (GPa) at the last F of the iteration, n points flattened (the same
        numbers as :func:`_tangent` of the returned ``eta`` where ``ok``).
    J : ndarray, shape (n,)
        det F at that F (before the failed points' F is set to NaN).
    """
    shape = sigma.shape[:-2]
    target = _voigt_vec(sigma).reshape(-1, 6)
    n = target.shape[0]
    C2v = tensor_to_voigt(C2)
    eng = np.linalg.solve(C2v, target[..., None])[..., 0]            # engineering Voigt strain
    F = np.broadcast_to(np.eye(3), (n, 3, 3)).copy()
    F += np.einsum("na,aij->nij", eng * np.array([1, 1, 1, 0.5, 0.5, 0.5]), _BASIS)
    iterations = np.zeros(n, dtype=int)
    done = np.zeros(n, dtype=bool)
    residual = np.full(n, np.inf)
    with np.errstate(all="ignore"):
        strain = _strain_parts(F, C2, C3)     # (eta, K, T) at F, carried along with F from the line search
        for it in range(max_iterations + 1):
            s, parts = _stress_parts(F, C2, C3, strain)
            r = _voigt_vec(s) - target
            residual = np.max(np.abs(r), axis=-1)
            done |= residual <= tol
            active = ~done & np.isfinite(residual)
            if not active.any() or it == max_iterations:
                break                                                   # no Jacobian for the last check
            iterations[active] += 1
            jac = np.swapaxes(_voigt_vec(_jacobian(parts, active)), -1, -2)   # (m, 6 stress, 6 F), active only
            try:
                du = -np.linalg.solve(jac, r[active][..., None])[..., 0]
            except np.linalg.LinAlgError:
                du = -np.einsum("mab,mb->ma", np.linalg.pinv(jac), r[active])
            step = np.einsum("ma,aij->mij", du, _BASIS)
            # Full Newton step where it lowers the residual; step halving only for the others.
            every = bool(active.all())                          # then F and strain are updated in place
            F_a, res_a, tgt = (F, residual, target) if every else (F[active], residual[active], target[active])
            strain_a = strain if every else [x[active] for x in strain]
            todo = np.ones(len(F_a), dtype=bool)
            for alpha in (1.0, 0.5, 0.25, 0.125, 0.0625):
                trial = F_a[todo] + alpha * step[todo]
                strain_t = _strain_parts(trial, C2, C3)        # _cauchy(trial, C2, C3), its parts kept
                s_t = np.einsum("...ip,...pq,...jq->...ij", trial, strain_t[2], trial) / \
                    np.linalg.det(trial)[..., None, None]
                rt = np.max(np.abs(_voigt_vec(s_t) - tgt[todo]), axis=-1)
                better = np.isfinite(rt) & (rt < res_a[todo])
                idx = np.flatnonzero(todo)[better]
                F_a[idx] = trial[better]
                for x, x_t in zip(strain_a, strain_t):
                    x[idx] = x_t[better]
                todo[idx] = False
                if not todo.any():
                    break
            if not every:
                F[active] = F_a
                for x, x_a in zip(strain, strain_a):
                    x[active] = x_a
        eta, K, J = parts["eta"], parts["K"], parts["J"]    # F has not moved since this last evaluation
    reason = np.full(n, "", dtype=object)
    ok = done.copy()
    reason[~done] = [f"no homogeneous state of the third-order model found for this stress (Newton stalled at "
                     f"a stress residual of {x:.3g} GPa; beyond the model's limit stress)" for x in residual[~done]]
    bad_J = ok & ~(J > 0)
    reason[bad_J] = "deformation solve reached det F <= 0"
    ok &= ~bad_J
    rows = np.flatnonzero(ok)                       # convexity: only where a state was found
    convex, K_min = lowest_if_needed(tensor_to_voigt(K if rows.size == n else K[rows]))
    not_convex = np.zeros(n, dtype=bool)
    not_convex[rows[~convex]] = True
    reason[not_convex] = [
        f"energy not convex at the solved strain (lowest eigenvalue of C2 + C3:eta = {k:.3g} GPa): "
        "stress beyond the stability limit of the third-order model" for k in K_min[~convex]]
    ok &= ~not_convex
    F[~ok] = np.nan
    eta[~ok] = np.nan
    return {"F": F.reshape(shape + (3, 3)), "eta": eta.reshape(shape + (3, 3)),
            "ok": ok.reshape(shape), "reason": reason.astype(str).reshape(shape),
            "iterations": iterations.reshape(shape), "residual": residual.reshape(shape)}, K, J


def stressed_state(C2: ArrayLike, C3: ArrayLike | None, sigma: ArrayLike, rho0: float, *,
                   tol: float = DEFAULT_TOL) -> dict:
    """Deformation, constants and density of a crystal carrying the Cauchy stress sigma.

    Parameters
    ----------
    C2 : array_like, shape (6, 6) or (3, 3, 3, 3)
        Natural-state second-order constants, GPa, crystal axes.
    C3 : array_like, shape (6, 6, 6) or (3, 3, 3, 3, 3, 3), or None
        Brugger third-order constants, GPa. None gives the fixed-C model of the paper's
        approach applied to a real crystal: C* = C2, F = I, rho = rho0 (the stress enters
        only through A = C2 + sigma delta), so "with and without TOEC" is one switch.
    sigma : array_like, shape (..., 3, 3)
        Cauchy stress, GPa, crystal axes.
    rho0 : float
        Natural-state density, kg/m^3.
    tol : float
        Tolerance of the deformation solve, GPa.

    Returns
    -------
    dict
        ``F`` (..., 3, 3), ``C_star`` (..., 3, 3, 3, 3) GPa, ``rho`` (...,) kg/m^3, ``sigma``
        (..., 3, 3) GPa, ``ok`` (...,) bool, ``reason`` (...,) str. Where the deformation solve
        fails or the stressed crystal is not Born-stable (Wallace's B = C* + stress terms,
        :func:`wallace_tensor`, not positive definite), ``ok`` is False, the reason is given
        and F, C_star, rho are NaN.
    """
    sigma = np.asarray(sigma, dtype=float)
    if sigma.shape[-2:] != (3, 3):
        raise InputError(f"sigma must have shape (..., 3, 3), got {sigma.shape}")
    if not (np.isfinite(rho0) and rho0 > 0):
        raise InputError(f"density rho0 must be positive, got {rho0!r} kg/m^3")
    with np.errstate(invalid="ignore"):
        return _stressed_state(_as_c2(C2), C3, sigma, float(rho0), tol)


def _stressed_state(C2, C3, sigma, rho0, tol) -> dict:
    shape = sigma.shape[:-2]
    if C3 is None:
        F = np.broadcast_to(np.eye(3), shape + (3, 3)).copy()
        C_star = np.broadcast_to(C2, shape + (3, 3, 3, 3)).copy()
        rho = np.full(shape, float(rho0))
        ok = np.ones(shape, dtype=bool)
        reason = np.full(shape, "", dtype=object)
    else:
        # the constants converted once; C* from the tangent the deformation solve ends with
        # (the same numbers as stressed_constants(C2, C3, F), without recomputing them)
        sol, K, J = _deformation(_checked_sigma(sigma), C2, _as_c3(C3), tol, MAX_ITERATIONS)
        F, ok, reason = sol["F"], sol["ok"].copy(), sol["reason"].astype(object)
        C_star = _push_forward(F, K.reshape(shape + (3, 3, 3, 3)))
        rho = float(rho0) / J.reshape(shape)               # det F (NaN-masked below where not ok)
    # Born stability where a state exists (the others are not ok either way)
    rows = np.flatnonzero(ok)
    C_rows, s_rows = C_star.reshape(-1, 3, 3, 3, 3), np.broadcast_to(sigma, shape + (3, 3)).reshape(-1, 3, 3)
    if rows.size < ok.size:
        C_rows, s_rows = C_rows[rows], s_rows[rows]
    stable, born = lowest_if_needed(wallace_tensor(C_rows, s_rows))
    if not stable.all():
        lost = np.zeros(ok.size, dtype=bool)
        lost[rows[~stable]] = True
        lost = lost.reshape(shape)
        reason = np.array(reason, dtype=object)
        reason[lost] = [born_reason(b) for b in born[~stable]]
        ok = ok & ~lost
    F = np.where(ok[..., None, None], F, np.nan)
    C_star = np.where(ok[..., None, None, None, None], C_star, np.nan)
    rho = np.where(ok, rho, np.nan)
    return {"F": F, "C_star": C_star, "rho": rho, "sigma": sigma, "ok": ok,
            "reason": np.asarray(reason).astype(str)}


def pressure_derivatives(C2: ArrayLike, C3: ArrayLike, *, h: float = 1e-3, tol: float = 1e-12) -> np.ndarray:
    """Initial pressure derivatives dB_IJ/dP of the effective constants a crystal shows under pressure.

    Under hydrostatic pressure P (sigma = -P I) ultrasonic velocities measure Wallace's
    effective constants B (:func:`wallace_tensor` of the stressed state's C*): B11 = C*11 - P,
    B12 = C*12 + P, B44 = C*44 - P, ... (Voigt), the quantities tabulated as "pressure
    derivatives of the elastic constants" (e.g. McSkimin, Jayaraman and Andreatch 1967 for GaAs;
    McSkimin, Andreatch and Thurston 1965 for quartz). Central difference through the full
    deformation solve (:func:`stressed_state`), any symmetry; the derivative is dimensionless.
    With a cubic crystal it reproduces the closed forms, e.g. dB11/dP = -(C111 + 2 C112 + 2 C11 +
    2 C12) / (C11 + 2 C12).

    Parameters
    ----------
    C2 : array_like, shape (6, 6)
        Natural-state second-order constants, GPa, crystal axes.
    C3 : array_like, shape (6, 6, 6)
        Brugger third-order constants, GPa, the same axes.
    h : float
        Pressure step, GPa (the result's error is O(h^2) times the fourth-order terms).
    tol : float
        Tolerance of the deformation solve, GPa.

    Returns
    -------
    ndarray, shape (6, 6)
        dB_IJ/dP at P = 0, crystal axes (Voigt).

    Raises
    ------
    InputError
        Bad shapes, or no Born-stable stressed state at P = +-h.
    """
    P = np.array([-h, h])
    st = stressed_state(C2, np.asarray(C3, dtype=float), -P[:, None, None] * np.eye(3), 1.0, tol=tol)
    if not np.all(st["ok"]):
        raise InputError(f"no stressed state at P = +-{h} GPa: {list(st['reason'])}")
    B = wallace_tensor(st["C_star"], st["sigma"])
    return (B[1] - B[0]) / (2 * h)

