"""Surface phonons of the prestressed FCC crystal across the surface Brillouin zone.

:func:`surface_phonons` (exported as ``surfwave.surface_phonons``) puts together the layer
blocks of :mod:`surfwave.dynamics.fcc_layers` and the semi-infinite solution of
:mod:`surfwave.dynamics.fcc_surface_green`: for each strain and in-plane wavevector q it
returns the true surface modes (omega^2 below the projected bulk band or in its gaps), their
decay per plane and polarisation, the bulk band edges and optionally the top plane's
spectral density; per strain the softest surface mode and the bulk stability.

Mirror lines: where the sagittal plane (q, n) is a mirror of the stressed crystal, the
blocks split into an even (sagittal: along q and n) and an odd (shear-horizontal) sector,
each solved with its own bulk band. A sagittal surface wave that lies inside the odd bulk
band (the (001) [110] case, "supersonic_decoupled" in :func:`surfwave.point`) is then still
a true surface mode; off the mirror lines it would be a resonance.

Bulk stability per strain (``bulk_stable``): the bulk omega^2 on a zone mesh of the layered
crystal (in-plane q grid x normal phase) and the long-wave criterion of :func:`surfwave.point`
(strong ellipticity of C + sigma over all directions,
:func:`surfwave.solvers.long_wave.long_wave_stability`). A strain whose bulk is unstable
gets NaN surface results and a reason; so does a q whose projected bulk band dips below 0.
"""
from __future__ import annotations

import numpy as np

from surfwave.dynamics import fcc_layers as layers
from surfwave.dynamics.fcc_surface_green import bulk_band_edges, herm, spectral_density, surface_modes
from surfwave.errors import InputError
from surfwave.model_crystals.elastic import elastic_constants, stress
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.records import SurfacePhononsResult
from surfwave.solvers.long_wave import long_wave_stability

#: Default path per surface (labels of :data:`surfwave.dynamics.fcc_layers.SYMMETRY_POINTS`).
DEFAULT_PATHS = {"(001)": "GXMG", "(111)": "GMKG", "(110)": "GXSYG"}
#: Default path sampling: points per rad/d0 of path length.
DEFAULT_PATH_DENSITY = 8.0
#: Bulk zone mesh of the stability check: in-plane points per axis and normal phases.
STABILITY_MESH = (16, 16)
#: omega^2 (K/m) below which the bulk counts as unstable (round-off allowance).
BULK_TOL = 1e-10


def path_points(surface: str, path: str, recip2d: np.ndarray, density: float) -> tuple[np.ndarray, np.ndarray, list]:
    """Reduced wavevectors along a path of high-symmetry labels.

    Parameters
    ----------
    surface : str
    path : str
        Labels of :data:`~surfwave.dynamics.fcc_layers.SYMMETRY_POINTS` (e.g. "GXMG").
    recip2d : ndarray, shape (2, 2)
        Reciprocal vectors used to measure segment lengths, rad/d0.
    density : float
        Points per rad/d0 (each segment gets at least 2 intervals).

    Returns
    -------
    q : ndarray, shape (n_q, 2)
        Reduced coordinates, endpoints included once.
    index : ndarray of int, shape (len(path),)
        Position of each label in ``q``.
    labels : list of str
    """
    points = layers.SYMMETRY_POINTS[surface]
    bad = [c for c in path if c not in points]
    if bad or len(path) < 2:
        raise InputError(f"path {path!r} for {surface}: use at least two labels from {sorted(points)}")
    if not (np.isfinite(density) and density > 0):
        raise InputError(f"path_density must be a positive number, got {density!r}")
    chunks, index = [np.array([points[path[0]]])], [0]
    for a, b in zip(path[:-1], path[1:]):
        pa, pb = np.array(points[a]), np.array(points[b])
        length = float(np.linalg.norm((pb - pa) @ recip2d))
        n = max(2, int(np.ceil(length * density)))
        t = np.arange(1, n + 1)[:, None] / n
        chunks.append(pa + t * (pb - pa))
        index.append(index[-1] + n)
    return np.concatenate(chunks), np.array(index), list(path)


def _mirror_bases(sc: layers.SurfaceCrystal, qc: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Where (q, n) is a mirror plane of the bonds, and the even/odd bases.

    Returns
    -------
    mirror : ndarray of bool, shape (n, n_q)
    frame : ndarray, shape (n, n_q, 3, 3)
        Columns q^ (e1 at q = 0), n, p = q^ x n in surface-frame components.
    """
    norm = np.linalg.norm(qc, axis=-1)
    with np.errstate(all="ignore"):
        qh = np.where(norm[..., None] > 0, qc / norm[..., None], np.array([1.0, 0.0]))
    qhat = np.stack([qh[..., 0], 0 * qh[..., 0], qh[..., 1]], axis=-1)
    nrm = np.broadcast_to(np.array([0.0, 1.0, 0.0]), qhat.shape)
    p = np.cross(qhat, nrm)
    frame = np.stack([qhat, nrm, p], axis=-1)
    bonds = np.concatenate([sc.bonds, -sc.bonds], axis=1)  # (n, 12, 3)
    proj = np.einsum("nqi,nbi->nqb", p, bonds)
    image = bonds[:, None] - 2.0 * proj[..., None] * p[:, :, None, :]  # (n, n_q, 12, 3)
    dist = np.linalg.norm(image[:, :, :, None, :] - bonds[:, None, None, :, :], axis=-1).min(axis=-1)
    mirror = (dist.max(axis=-1) < 1e-9) & (norm > 0)
    return mirror, frame


def bulk_stability(sc: layers.SurfaceCrystal, potential: PairPotential) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bulk stability of the layered crystal per strain (module docstring).

    Parameters
    ----------
    sc : SurfaceCrystal
    potential : PairPotential

    Returns
    -------
    stable : ndarray of bool, shape (n,)
    min_omega2 : ndarray, shape (n,)
        Lowest of the zone-mesh omega^2 (K/m) and the lowest acoustic-tensor eigenvalue (K d0^2/m).
    reason : ndarray of str (object), shape (n,)
        Empty where stable.
    """
    nq, nphi = STABILITY_MESH
    g = (np.arange(nq) + 0.5) / nq - 0.5
    qr = np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)
    h00, _, h01 = layers.principal_blocks(layers.plane_blocks(sc, potential, layers.cartesian_q(sc, qr)))
    phi = 2.0 * np.pi * np.arange(nphi) / nphi
    z = np.exp(1j * phi).reshape(-1, 1, 1, 1, 1)
    w = np.linalg.eigvalsh(h00[None] + h01[None] * z + herm(h01)[None] / z)
    zone_min = w.min(axis=(0, 2, 3))
    # long-wave: the project's strong-ellipticity search (direction grid + local refinement)
    bonds = sc.crystal.bonds
    _, acoustic, _ = long_wave_stability(elastic_constants(bonds, potential), stress(bonds, potential))
    stable = (zone_min > -BULK_TOL) & (acoustic > BULK_TOL)
    reason = np.where(acoustic <= BULK_TOL, "bulk unstable in the long-wave limit (acoustic tensor not positive)",
                      np.where(zone_min <= -BULK_TOL, "bulk unstable at finite wavevector (zone mesh omega^2 < 0)", ""))
    return stable, np.minimum(zone_min, acoustic), reason.astype(object)


def _solve_group(h00: np.ndarray, h00s: np.ndarray, h01: np.ndarray, basis: np.ndarray) -> tuple[np.ndarray, dict]:
    """Band edges and surface modes of blocks projected on ``basis`` (N, 3m, k m)."""
    bt = herm(basis)
    a, s, c = bt @ h00 @ basis, bt @ h00s @ basis, bt @ h01 @ basis
    edges = bulk_band_edges(a, c)
    modes = surface_modes(a, s, c, edges)
    modes["vector"] = np.einsum("mij,mj->mi", basis[modes["problem"]], modes["vector"])
    return edges, modes


def _q_array(q: object) -> np.ndarray:
    q = np.asarray(q, dtype=float)
    if q.ndim == 1 and q.size == 2:
        q = q[None]
    if q.ndim != 2 or q.shape[1] != 2 or not np.all(np.isfinite(q)) or q.shape[0] == 0:
        raise InputError(f"q must be a finite (n, 2) array of reduced wavevectors or a path string, "
                         f"got shape {q.shape}")
    return q


def surface_phonons(potential: str | PairPotential, loading: str, d_over_d0, *, surface: str = "(001)",
                    q=None, path_density: float = DEFAULT_PATH_DENSITY, omega=None, eta: float = 1e-3,
                    load_direction: str | None = None) -> SurfacePhononsResult:
    """Surface phonons of the semi-infinite prestressed FCC crystal.

    Parameters
    ----------
    potential : str or PairPotential
    loading : {"in_plane_hydrostatic", "uniaxial"}
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the load direction (in-plane stretch for in-plane hydrostatic).
    surface : {"(001)", "(111)", "(110)"}
    q : array_like, shape (n_q, 2), or str, optional
        Reduced coordinates of the deformed crystal's primitive surface reciprocal lattice
        ((001): b1 along [110], b2 along [1-10]), or a path of high-symmetry labels
        (:data:`~surfwave.dynamics.fcc_layers.SYMMETRY_POINTS`). Default: :data:`DEFAULT_PATHS`.
    path_density : float
        Points per rad/d0 along a path (measured at the first strain).
    omega : array_like, shape (n_omega,), optional
        Frequencies (sqrt(K/m)) at which to return the top plane's spectral density.
    eta : float
        Broadening of the spectral density (imaginary part of omega^2, K/m).
    load_direction : str, optional
        Uniaxial load direction (:data:`~surfwave.dynamics.fcc_layers.LOAD_DIRECTIONS`).

    Returns
    -------
    SurfacePhononsResult
        See :class:`surfwave.records.SurfacePhononsResult` (shapes, units).

    Raises
    ------
    InputError
        Unknown names, bad q, path, omega or eta (before any computation).
    GeometryError
        A strain the geometry cannot take.

    Examples
    --------
    >>> import surfwave
    >>> r = surfwave.surface_phonons("lj", "in_plane_hydrostatic", 1.0, q=[[0.5, 0.5]])
    >>> round(float(r["omega"][0, 0, 0]), 6)
    1.414214
    """
    pot = get_potential(potential)
    layers.check_request(surface, loading, load_direction)
    if isinstance(q, str) or q is None:
        path = DEFAULT_PATHS[surface] if q is None else q
        layers.SYMMETRY_POINTS[surface]  # noqa: B018 (surface checked above)
    else:
        path = None
        qr = _q_array(q)
    if omega is not None:
        omega = np.asarray(omega, float)
        if omega.ndim != 1 or not np.all(np.isfinite(omega)) or np.any(omega < 0):
            raise InputError("omega must be a 1-D array of finite non-negative frequencies")
    if not (np.isfinite(eta) and eta > 0):
        raise InputError(f"eta must be a positive number, got {eta!r}")
    sc = layers.surface_crystal(surface, loading, pot, d_over_d0, load_direction)
    labels: list = []
    index = np.zeros(0, int)
    if path is not None:
        qr, index, labels = path_points(surface, path, sc.recip2d[0], path_density)
    n, nq, m = sc.d_over_d0.size, qr.shape[0], sc.depth
    qc = layers.cartesian_q(sc, qr)
    h00, h00s, h01 = layers.principal_blocks(layers.plane_blocks(sc, pot, qc))
    stable, bulk_min, reason = bulk_stability(sc, pot)
    mirror, frame = _mirror_bases(sc, qc)
    d = 3 * m
    eye_m = np.eye(m)
    full = np.broadcast_to(np.eye(d), (n, nq, d, d))
    even = np.einsum("ab,nqij->nqaibj", eye_m, frame[..., :2]).reshape(n, nq, d, 2 * m)
    odd = np.einsum("ab,nqij->nqaibj", eye_m, frame[..., 2:]).reshape(n, nq, d, m)
    edges_full = bulk_band_edges(h00, h01)  # (n, nq, d, 2)
    bad = (edges_full[..., 0, 0] < -BULK_TOL) | ~stable[:, None]  # no surface answer here
    found = []  # (flat index, omega2, vector, decay, sector)
    flat = np.arange(n * nq).reshape(n, nq)
    for sel, basis, sector in ((~mirror & ~bad, full, 0), (mirror & ~bad, even, 1), (mirror & ~bad, odd, -1)):
        if not sel.any():
            continue
        _, modes = _solve_group(h00[sel], h00s[sel], h01[sel], basis[sel])
        for k in range(modes["omega2"].size):
            found.append((flat[sel][modes["problem"][k]], modes["omega2"][k], modes["vector"][k],
                          modes["decay"][k], sector))
    counts = np.bincount([f[0] for f in found], minlength=n * nq) if found else np.zeros(n * nq, int)
    n_modes = max(int(counts.max(initial=0)), 1)
    omega2 = np.full((n * nq, n_modes), np.nan)
    decay = np.full((n * nq, n_modes), np.nan)
    pol = np.full((n * nq, n_modes, 3), np.nan)
    sect = np.zeros((n * nq, n_modes), np.int8)
    fill = np.zeros(n * nq, int)
    frame_flat = frame.reshape(n * nq, 3, 3)
    for i, lam, vec, dec, sector in sorted(found, key=lambda f: (f[0], f[1])):
        j = fill[i]
        fill[i] += 1
        omega2[i, j], decay[i, j], sect[i, j] = lam, dec ** (1.0 / m), sector
        top = vec[:3] @ frame_flat[i]  # components along q^, n, p
        pol[i, j] = np.abs(top) ** 2 / np.sum(np.abs(top) ** 2)
    shape = (n, nq)
    omega2, decay = omega2.reshape(shape + (n_modes,)), decay.reshape(shape + (n_modes,))
    pol, sect = pol.reshape(shape + (n_modes, 3)), sect.reshape(shape + (n_modes,))
    q_reason = np.full(shape, "", dtype=object)
    bad_q = edges_full[..., 0, 0] < -BULK_TOL
    q_reason[bad_q] = "projected bulk band has omega^2 < 0 at this q"
    q_reason[~stable] = reason[~stable, None]
    for arr in (omega2, decay, pol):
        arr[bad] = np.nan
    edges = np.where(bad[..., None, None], np.nan, edges_full)
    lowest = np.where(np.isfinite(omega2[..., 0]), omega2[..., 0], np.inf)
    iq = np.argmin(lowest, axis=1)
    soft = lowest[np.arange(n), iq]
    has = np.isfinite(soft)
    step = np.linalg.norm(np.diff(qc, axis=1), axis=-1)
    result: SurfacePhononsResult = {
        "surface": surface, "loading": loading, "load_direction": sc.load_direction, "potential": pot.name,
        "d_over_d0": sc.d_over_d0, "q": qr, "q_cartesian": qc,
        "q_distance": np.concatenate([np.zeros((n, 1)), np.cumsum(step, axis=1)], axis=1),
        "path_labels": labels, "path_index": index,
        "omega": np.sign(omega2) * np.sqrt(np.abs(omega2)), "omega2": omega2, "decay": decay,
        "polarisation": pol, "sector": sect,
        "band_edges": np.sign(edges) * np.sqrt(np.abs(edges)), "band_edges_omega2": edges,
        "softest_q": np.where(has[:, None], qr[iq], np.nan), "softest_omega2": np.where(has, soft, np.nan),
        "bulk_stable": stable, "bulk_min_omega2": bulk_min, "reason": reason, "q_reason": q_reason,
        "layer_spacing": sc.spacing,
    }
    if omega is not None:
        rho = spectral_density(h00, h00s, h01, omega, eta)
        result["spectral_density"] = np.where(bad[..., None], np.nan, rho)
        result["omega_grid"] = omega
        result["eta"] = float(eta)
    return result
