"""Numerical surface lattice dynamics of the prestressed FCC (001) surface.

An independent check of the long-wave Rayleigh speed of Eq. (17) (:func:`surfwave.point`):
no elastic constant, S tensor or decay constant is used, only the bond force constants
Phi_b = phi'' r^r^ + (phi'/r)(1 - r^r^) (docs/physics/paper.md) of the prestressed crystal.

Lab frame: x = propagation, y = surface normal into the crystal, z = in-plane normal.
The crystal is a stack of (001) layers at y_n = n h (layer 0 is the free surface). For a
wave u(R) = U_n exp(i k x_R) on the atoms of layer n (U_n in C^3, m = 1)

    omega^2 U_n = A0 U_n + A1 U_{n+1} + A1^H U_{n-1}     (bulk layers)
    omega^2 U_0 = A0_surface U_0 + A1 U_1                (free surface layer)

with, over the 12 bonds b (each of the 6 of ``Crystal.bonds`` and its negative),

    A0 = sum_b Phi_b - sum_{b_y = 0} Phi_b e^{i k b_x},   A1 = -sum_{b_y > 0} Phi_b e^{i k b_x},
    A0_surface = A0 - sum_{b_y < 0} Phi_b.

With nearest-neighbour forces and sigma_yy = 0 the surface layer is in equilibrium at the bulk
spacing, so no relaxation enters. Both propagation directions lie in the mirror plane z -> -z,
so the xz and yz entries of the blocks vanish (checked) and the sagittal (x, y) motion is
solved alone; this also removes the shear-horizontal branch, which lies *below* the sagittal
surface wave for [110] ("supersonic_decoupled").

Off the mirror directions (any angle in the (001) surface, :func:`oriented_crystal`) the
bonds are rotated about the normal into the lab frame, the full 3 x 3 blocks are kept and
the surface wave is the lowest localised mode (it is subsonic there).

Method: a slab of N layers with a free top (layer 0) and a clamped bottom (U_N = 0), so
that only the top surface carries a surface wave and a compressed slab cannot buckle. Its
block-tridiagonal Hermitian matrix is sparse and banded; its lowest eigenpairs come from
shift-invert Lanczos about omega^2 = 0 (:func:`scipy.sparse.linalg.eigsh`; the dense-vector
band solver :func:`scipy.linalg.eig_banded` costs O(N^2) here). The surface mode is the
lowest one that is localised: its amplitude in the deeper half of the slab is below
``tail_tol`` of its maximum (1e-6); if not, N grows by the e-folds still missing (at least
x1.5), so N adapts to the decay length. The clamp then moves omega^2 by ~tail_tol^2
relative. The long-wave limit omega^2/k^2 = c_R^2 + a k + b k^2 + ... (k > 0) is taken by
Richardson extrapolation over k, k/2, k/4, ... The expansion has odd powers of k although
omega^2 is even in k: the wave reaches ~1/k deep, so the surface layers' discreteness
corrects c^2 at first order in k h (measured: linear term along [100], k^2 along [110]).

Units: m = K = d0 = 1; k in 1/d0, omega^2 in K/m, speeds squared in K d0^2/m.
"""
from __future__ import annotations

import dataclasses
from typing import Any, cast

import numpy as np
from scipy import sparse
from scipy.linalg import eigh
from scipy.sparse.linalg import eigsh

from surfwave.errors import InputError, SurfwaveError
from surfwave.model_crystals.lattices import Crystal, build
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers.orientation import lab_axes
from surfwave.vocab import Direction, Loading

#: Largest |xz|, |yz| entry of the layer blocks (relative to the largest entry) accepted as
#: "the sagittal motion decouples".
DECOUPLING_TOL = 1e-13
#: Largest slab (unknowns) solved with the dense eigensolver.
DENSE_MAX = 800


def bond_force_constants(crystal: Crystal, potential: str | PairPotential) -> np.ndarray:
    """Force-constant matrices Phi_b of the six bonds of ``crystal.bonds``.

    Parameters
    ----------
    crystal : Crystal
        FCC crystal (3D), bonds of shape (n, 6, 3) in d0, lab frame.
    potential : str or PairPotential

    Returns
    -------
    ndarray, shape (n, 6, 3, 3)
        Phi_b in K (Phi_{-b} = Phi_b).
    """
    pot = get_potential(potential)
    r = crystal.bonds
    length = np.linalg.norm(r, axis=-1)
    rhat = r / length[..., None]
    outer = rhat[..., :, None] * rhat[..., None, :]
    k_par = pot.d2phi(length)[..., None, None]
    k_perp = (pot.dphi(length) / length)[..., None, None]
    return k_par * outer + k_perp * (np.eye(r.shape[-1]) - outer)


def layer_matrices(crystal: Crystal, potential: str | PairPotential,
                   k: float) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Layer blocks A0, A0_surface, A1 of the (001)-layered crystal at wavevector k along x.

    Parameters
    ----------
    crystal : Crystal
        From ``build("fcc", ...)``; all strains of the crystal are processed.
    potential : str or PairPotential
    k : float
        In-plane wavevector along x, 1/d0.

    Returns
    -------
    A0, A0_surface, A1 : ndarray, shape (n, 3, 3), complex
        In K/m (omega^2 units). A0 and A0_surface are Hermitian.
    h : ndarray, shape (n,)
        Layer spacing, d0.
    """
    phi = bond_force_constants(crystal, potential)
    b = crystal.bonds
    h = np.abs(b[..., 1]).max(axis=-1)
    # the 12 bonds: +b and -b (same Phi); which layer each reaches
    bonds = np.concatenate([b, -b], axis=-2)  # (n, 12, 3)
    phis = np.concatenate([phi, phi], axis=-3)  # (n, 12, 3, 3)
    step = np.where(np.abs(bonds[..., 1]) < 1e-9 * h[:, None], 0, np.sign(bonds[..., 1]))
    phase = np.exp(1j * k * bonds[..., 0])[..., None, None]
    diag = phis.sum(axis=-3)
    a0 = diag - (np.where((step == 0)[..., None, None], phis * phase, 0)).sum(axis=-3)
    a1 = -(np.where((step == 1)[..., None, None], phis * phase, 0)).sum(axis=-3)
    a0s = a0 - np.where((step == -1)[..., None, None], phis, 0).sum(axis=-3)
    return a0, a0s, a1, h


def sagittal_blocks(a0: np.ndarray, a0s: np.ndarray, a1: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The (x, y) sub-blocks, after checking the z motion decouples (mirror z -> -z).

    Parameters
    ----------
    a0, a0s, a1 : ndarray, shape (..., 3, 3)

    Returns
    -------
    a0, a0s, a1 : ndarray, shape (..., 2, 2)

    Raises
    ------
    SurfwaveError
        If an xz or yz entry is not negligible.
    """
    for m in (a0, a0s, a1):
        scale = np.abs(m).max()
        cross = max(np.abs(m[..., :2, 2]).max(), np.abs(m[..., 2, :2]).max())
        if cross > DECOUPLING_TOL * scale:
            raise SurfwaveError(f"sagittal and z motion do not decouple (|coupling| = {cross:.3g})")
    return a0[..., :2, :2], a0s[..., :2, :2], a1[..., :2, :2]


def slab_matrix(a0: np.ndarray, a0s: np.ndarray, a1: np.ndarray, n_layers: int) -> sparse.csc_matrix:
    """Hermitian matrix of a slab with a free top layer and a clamped bottom (U_N = 0).

    Parameters
    ----------
    a0, a0s, a1 : ndarray, shape (d, d), complex
        Layer blocks at one strain and one k (d = 2 sagittal, or 3).
    n_layers : int
        N, the number of moving layers.

    Returns
    -------
    scipy.sparse.csc_matrix, shape (N d, N d), complex
        Block tridiagonal: diagonal A0 (A0_surface for layer 0), H[n, n+1] = A1,
        H[n+1, n] = A1^H; K/m.
    """
    top = sparse.csr_matrix(([1.0], ([0], [0])), shape=(n_layers, n_layers))
    upper = sparse.kron(sparse.eye(n_layers, k=1), a1)
    h = sparse.kron(sparse.eye(n_layers), a0) + sparse.kron(top, a0s - a0) + upper + upper.conj().T
    return h.tocsc()


def slab_modes(a0: np.ndarray, a0s: np.ndarray, a1: np.ndarray, n_layers: int, n_modes: int = 2,
               shift: float = 0.0) -> tuple[np.ndarray, np.ndarray]:
    """Lowest modes of the free-top, clamped-bottom slab of :func:`slab_matrix`.

    Shift-invert Lanczos about omega^2 = ``shift`` (sparse LU of the banded matrix, O(N)
    work); a shift just below the wanted eigenvalue makes Lanczos converge in a few steps.
    Slabs of at most ``DENSE_MAX`` unknowns use the dense Hermitian solver instead (the
    lowest n_modes; Lanczos needs many restarts there, as the low spectrum is dense).

    Returns
    -------
    omega2 : ndarray, shape (n_modes,)
        The n_modes eigenvalues nearest ``shift`` (the lowest, for a stable slab and shift 0),
        ascending, K/m.
    modes : ndarray, shape (n_modes, n_layers, d), complex
        Normalised eigenvectors, U_n per layer.
    """
    d = a0.shape[-1]
    h = slab_matrix(a0, a0s, a1, n_layers)
    if d * n_layers <= DENSE_MAX:
        w, v = eigh(h.toarray(), subset_by_index=[0, n_modes - 1])
        return w, v.T.reshape(n_modes, n_layers, d)
    v0 = np.ones(d * n_layers, dtype=complex)  # deterministic start
    w, v = eigsh(h, k=n_modes, sigma=shift, which="LM", v0=v0, tol=0.0, ncv=min(20, h.shape[0] - 1))
    order = np.argsort(w)
    return w[order], v[:, order].T.reshape(n_modes, n_layers, d)


def tail_ratio(mode: np.ndarray) -> float:
    """max |U_n| over the deeper half of the slab / max |U_n| overall (localisation measure)."""
    amp = np.linalg.norm(mode, axis=-1)
    return float(amp[amp.size // 2:].max() / amp.max())


def oriented_crystal(loading: Loading, potential: str | PairPotential, direction: str | float, d_over_d0: float,
                     load_direction: str | None = None) -> tuple[Crystal, bool]:
    """The prestressed FCC crystal in the lab frame of any propagation direction in (001).

    Parameters
    ----------
    loading : {"in_plane_hydrostatic", "uniaxial"}
    potential : str or PairPotential
    direction : str or float
        "[100]", "[110]" (mirror directions, built directly), any Miller direction in (001)
        or an angle in degrees from [100] toward [010].
    d_over_d0 : float
        Stretch along the load direction.
    load_direction : {None, "[100]", "[110]"}
        Uniaxial load direction (None: the propagation direction, then a mirror one).

    Returns
    -------
    crystal : Crystal
        Bonds and cell rotated about the (001) normal into the lab frame of the propagation.
    mirror : bool
        Whether the direction was built as a mirror direction (sagittal motion decouples).
    """
    if isinstance(direction, str) and direction in ("[100]", "[110]") and load_direction in (None, direction):
        return build("fcc", loading, potential, cast(Direction, direction), d_over_d0), True
    if loading == "in_plane_hydrostatic":
        load = "[100]"
    elif load_direction in ("[100]", "[110]"):
        load = load_direction
    else:
        raise InputError(f"uniaxial loading with propagation {direction!r} needs load_direction "
                         f"'[100]' or '[110]', got {load_direction!r}")
    crystal = build("fcc", loading, potential, cast(Direction, load), d_over_d0)
    rot = lab_axes("(001)", direction) @ lab_axes("(001)", load).T
    return dataclasses.replace(crystal, direction=str(direction), bonds=crystal.bonds @ rot.T,
                               cell=crystal.cell @ rot.T), False


def surface_mode(lattice: str, loading: Loading, potential: str | PairPotential, direction: str | float,
                 d_over_d0: float, k: float, tail_tol: float = 1e-6,
                 max_layers: int = 2**17, load_direction: str | None = None, shift: float = 0.0) -> dict:
    """The sagittal surface wave of the semi-infinite FCC (001) crystal at wavevector k.

    Parameters
    ----------
    lattice : {"fcc"}
    loading : {"in_plane_hydrostatic", "uniaxial"}
    potential : str or PairPotential
    direction : str or float
        "[100]", "[110]" (sagittal 2 x 2 blocks: the mirror decouples the z motion), or any
        direction in (001) as a Miller string or an angle in degrees from [100] (full 3 x 3
        blocks; the lowest localised mode is the surface wave).
    d_over_d0 : float
        Stretch along the load direction (1 = unstressed).
    k : float
        Wavevector along x, 1/d0, in (0, pi].
    tail_tol : float
        Localisation required of the selected mode (see :func:`tail_ratio`).
    max_layers : int
        Give up beyond this slab thickness.
    load_direction : {None, "[100]", "[110]"}
        See :func:`oriented_crystal`.
    shift : float
        Shift of the Lanczos solve (omega^2, K/m): 0, or a value just below the surface
        mode's omega^2 (the modes nearest it are searched; only speeds up the solve).

    Returns
    -------
    dict
        ``c2`` (omega^2/k^2, K d0^2/m), ``omega2`` (K/m), ``n_layers``, ``tail`` (tail ratio of
        the mode), ``surface_weight`` (fraction of |U|^2 in layer 0), ``mode`` (n_layers, 2)
        complex (u, v) per layer ((u, v, w) off the mirror directions), ``layer_spacing`` (d0), ``k``.

    Raises
    ------
    InputError
        Not FCC, non-scalar d_over_d0 or k outside (0, pi].
    SurfwaveError
        No localised mode among the lowest ones up to ``max_layers`` layers.
    """
    if lattice != "fcc":
        raise InputError(f"fcc_surface solves the FCC (001) surface only, got lattice {lattice!r}")
    if np.ndim(d_over_d0) != 0:
        raise InputError("d_over_d0 must be a scalar")
    if not 0 < k <= np.pi:
        raise InputError(f"k must lie in (0, pi], got {k!r}")
    crystal, mirror = oriented_crystal(loading, potential, direction, float(d_over_d0), load_direction)
    a0, a0s, a1, h = layer_matrices(crystal, potential, k)
    if mirror:
        a0, a0s, a1 = (m[0] for m in sagittal_blocks(a0, a0s, a1))
    else:
        a0, a0s, a1 = a0[0], a0s[0], a1[0]
    # e^{-kappa k y}: the deeper half starts ~14 e-folds down if kappa >= 1/2 (else grown)
    # (off the mirrors the wave reaches deeper, as the coupled SH motion decays slowly: 1.6 x)
    n_layers = int(np.ceil((60.0 if mirror else 96.0) / (k * h[0])))
    while n_layers <= max_layers:
        # off the mirrors the surface wave is the lowest mode: one Lanczos eigenpair suffices
        w, v = slab_modes(a0, a0s, a1, n_layers, n_modes=2 if mirror else 1, shift=shift)
        tails = [tail_ratio(mode) for mode in v]
        for omega2, mode, tail in zip(w, v, tails):
            if tail < tail_tol:
                weight = np.abs(mode) ** 2
                return {"c2": omega2 / k**2, "omega2": omega2, "n_layers": n_layers,
                        "tail": tail, "surface_weight": float(weight[0].sum() / weight.sum()),
                        "mode": mode, "layer_spacing": float(h[0]), "k": k}
        # too thin: if the lowest mode is decaying, scale N by the e-folds still missing
        grow = np.log(tail_tol) / np.log(tails[0]) if 0 < tails[0] < 0.1 else 2.0
        n_layers = int(np.ceil(n_layers * min(max(1.2 * grow, 1.5), 8.0)))
    raise SurfwaveError(f"no localised sagittal surface mode at d/d0 = {d_over_d0}, k = {k} "
                        f"with up to {max_layers} layers")


def surface_wave_speed(lattice: str, loading: Loading, potential: str | PairPotential,
                       direction: str | float, d_over_d0: float, k: float) -> float:
    """(omega/k)^2 of the sagittal surface wave at wavevector k along x, K d0^2/m.

    See :func:`surface_mode` for the parameters and the method.
    """
    return float(surface_mode(lattice, loading, potential, direction, d_over_d0, k)["c2"])


def long_wave_c2(lattice: str, loading: Loading, potential: str | PairPotential, direction: str | float,
                 d_over_d0: float, k: float = 0.4, levels: int = 5,
                 load_direction: str | None = None) -> dict:
    """Long-wave limit c_R^2 = lim_{k -> 0} omega^2/k^2 by Richardson extrapolation.

    For k > 0, c2(k) = c_R^2 + a k + b k^2 + ... (odd powers included, module docstring);
    with k_j = k / 2^j (j < levels) Richardson step j removes the k^j term.

    Parameters
    ----------
    lattice, loading, potential, direction, d_over_d0, load_direction
        As for :func:`surface_mode`.
    k : float
        Largest wavevector used, 1/d0.
    levels : int
        Number of wavevectors (>= 2); the result is exact to O(k^levels).

    Returns
    -------
    dict
        ``c2_R`` (K d0^2/m); ``error``: difference to the best extrapolation with one level
        less (an error estimate, conservative while the series converges); ``k`` (levels,)
        and ``c2_k`` (levels,) the raw data; ``n_layers`` (levels,) the slab thicknesses.
    """
    ks = k / 2.0 ** np.arange(levels)
    runs: list[dict[str, Any]] = []
    for kj in ks:  # each solve shifted just below the previous level's c^2 k^2 (faster Lanczos)
        shift = 0.0 if not runs else 0.98 * runs[-1]["c2"] * kj**2
        runs.append(surface_mode(lattice, loading, potential, direction, d_over_d0, kj,
                                 load_direction=load_direction, shift=shift))
    table = [np.array([r["c2"] for r in runs])]
    for j in range(1, levels):  # Richardson table in powers of k, ratio 2
        prev = table[-1]
        table.append((2.0**j * prev[1:] - prev[:-1]) / (2.0**j - 1.0))
    best = float(table[-1][0])
    return {"c2_R": best, "error": abs(best - float(table[-2][-1])), "k": ks,
            "c2_k": table[0], "n_layers": np.array([r["n_layers"] for r in runs])}
