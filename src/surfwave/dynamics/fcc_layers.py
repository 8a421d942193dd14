"""Layer force-constant blocks of prestressed FCC crystals cut along (001), (111) or (110).

Generalises the (001) blocks of :mod:`surfwave.dynamics.fcc_surface` to any surface of the
nearest-neighbour FCC crystal and to an in-plane wavevector q in two dimensions. Same bond
model (Phi_b = phi'' r^r^ + (phi'/r)(1 - r^r^), :func:`~surfwave.dynamics.fcc_surface.bond_force_constants`)
and the same prestressed geometry (:func:`surfwave.model_crystals.lattices.build`).

Surface frame: e1 along the first primitive surface vector a1, e2 = n the normal pointing
into the crystal, e3 = e1 x n (in plane). The crystal is a stack of lattice planes at depth
n h (one atom per plane: FCC is a Bravais lattice); a bond b joins planes ``step`` = b.n / h
apart (an integer). With u(R) = U_l exp(i q.R) on plane l (m = 1),

    omega^2 U_l = sum_j D_j U_{l+j},  D_j = -sum_{b: step j} Phi_b e^{i q.b},
    D_0 = sum_b Phi_b - sum_{b: step 0} Phi_b e^{i q.b}      (over the 12 bonds +/- b),

and a plane l < m below the free surface lacks the bonds of step j < -l. The largest step m
is 1 for (001) and (111) and 2 for (110) (the bond along the (110) normal spans two planes),
so m planes form a principal layer: block size 3 m, nearest-neighbour coupled.

Stressed geometries (d_over_d0 = s is the stretch along the load direction):

* (001): :func:`build` as elsewhere (in-plane hydrostatic; uniaxial along [100] or [110]).
* (111), in-plane hydrostatic: stretch s in the plane and t along [111] with sigma_nn = 0.
  By the threefold axis the stress is s-isotropic in the plane with no shear, and
  sigma_nn = 0 holds when the six out-of-plane bonds sit at the minimum of phi (r = 1):
  s^2/3 + 2 t^2/3 = 1, so t = sqrt((3 - s^2)/2), 0 < s < sqrt 3, for every potential
  (checked against :func:`surfwave.model_crystals.elastic.stress` in the tests).
* (110), in-plane hydrostatic: equal in-plane stress along [1-10] (stretch s) and [001], zero
  normal stress, the two other stretches solved by Newton's method from s = 1.
* (111) uniaxial along [110] (a close-packed row of the (1-11) plane) and (110) uniaxial
  along [110] (in the (1-10) plane) or [100] (in the (011) plane): the uniaxially stressed
  crystal of :func:`build`, cut along a plane containing the load.

With sigma.n = 0 and bonds to the neighbouring planes only, the surface plane of (001) and
(111) is in equilibrium at the bulk positions. On (110) the normal bond spanning two planes
carries the force phi'(r) under stress, so the unrelaxed (110) surface is not in
equilibrium when stressed; the blocks are then those of the bulk-terminated geometry
(no relaxation), exact only at zero stress.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import cast

import numpy as np

from surfwave.dynamics.fcc_surface import bond_force_constants
from surfwave.errors import GeometryError, InputError
from surfwave.model_crystals.lattices import _FCC_HALF_NEIGHBOURS, Crystal, build
from surfwave.model_crystals.potentials import PairPotential, get_potential
from surfwave.solvers.orientation import lab_axes
from surfwave.validate import as_1d
from surfwave.vocab import Direction, Loading

_R2 = np.sqrt(2.0) / 2.0
#: Per (surface, loading, load direction): the lab construction, the crystal plane (hkl)
#: and the undeformed primitive surface vectors a1, a2 (crystal axes, d0).
_CUTS: dict[tuple[str, str], dict] = {
    ("(001)", "hydrostatic"): {"plane": (0, 0, 1), "a": _R2 * np.array([[1, 1, 0], [1, -1, 0]], float)},
    ("(001)", "[100]"): {"plane": (0, 0, 1), "a": _R2 * np.array([[1, 1, 0], [1, -1, 0]], float)},
    ("(001)", "[110]"): {"plane": (0, 0, 1), "a": _R2 * np.array([[1, 1, 0], [1, -1, 0]], float)},
    ("(111)", "[110]"): {"plane": (1, -1, 1), "a": _R2 * np.array([[1, 1, 0], [0, -1, -1]], float)},
    ("(111)", "hydrostatic"): {"plane": (1, 1, 1), "a": _R2 * np.array([[1, -1, 0], [0, 1, -1]], float)},
    ("(110)", "hydrostatic"): {"plane": (1, 1, 0), "a": np.array([[_R2, -_R2, 0], [0, 0, np.sqrt(2.0)]])},
    ("(110)", "[110]"): {"plane": (1, -1, 0), "a": np.array([[_R2, _R2, 0], [0, 0, np.sqrt(2.0)]])},
    ("(110)", "[100]"): {"plane": (0, 1, 1), "a": np.array([[0, _R2, -_R2], [np.sqrt(2.0), 0, 0]])},
}
SURFACES = ("(001)", "(111)", "(110)")
LOADINGS = ("in_plane_hydrostatic", "uniaxial")
#: Uniaxial load directions available per surface (the first is the default).
LOAD_DIRECTIONS = {"(001)": ("[100]", "[110]"), "(111)": ("[110]",), "(110)": ("[110]", "[100]")}
#: High-symmetry points of each surface Brillouin zone, reduced coordinates of (b1, b2).
#: (001): a1 along [110], a2 along [1-10] (square); (111): a1, a2 at 120 degrees
#: (hexagonal, K = (1/3, 1/3)); (110): a1 along the close-packed row, a2 across (rectangular).
SYMMETRY_POINTS = {
    "(001)": {"G": (0.0, 0.0), "X": (0.5, 0.0), "M": (0.5, 0.5)},
    "(111)": {"G": (0.0, 0.0), "M": (0.5, 0.0), "K": (1.0 / 3.0, 1.0 / 3.0)},
    "(110)": {"G": (0.0, 0.0), "X": (0.5, 0.0), "Y": (0.0, 0.5), "S": (0.5, 0.5)},
}
#: A bond's normal component must be an integer number of plane spacings to this tolerance.
STEP_TOL = 1e-9


@dataclass(frozen=True)
class SurfaceCrystal:
    """A prestressed FCC crystal cut along one surface, in the surface frame.

    Attributes
    ----------
    surface, loading, load_direction : str
        (``load_direction`` "none" for in-plane hydrostatic loading.)
    d_over_d0 : ndarray, shape (n,)
    crystal : Crystal
        The bulk crystal in its own lab frame (for phonopy and the stress).
    rotation : ndarray, shape (n, 3, 3)
        Rows e1, n, e3 of the surface frame in the crystal's lab frame.
    bonds : ndarray, shape (n, 6, 3)
        Half bond vectors in the surface frame, d0.
    steps : ndarray of int, shape (6,)
        Planes each bond spans (b.n / h), the same at every strain.
    spacing : ndarray, shape (n,)
        Plane spacing h, d0.
    cell2d : ndarray, shape (n, 2, 2)
        Rows a1, a2 in (e1, e3) components, d0.
    recip2d : ndarray, shape (n, 2, 2)
        Rows b1, b2 with a_i . b_j = 2 pi delta_ij, rad/d0.
    """

    surface: str
    loading: str
    load_direction: str
    d_over_d0: np.ndarray
    crystal: Crystal
    rotation: np.ndarray
    bonds: np.ndarray
    steps: np.ndarray
    spacing: np.ndarray
    cell2d: np.ndarray
    recip2d: np.ndarray

    @property
    def depth(self) -> int:
        """m, the largest plane step of a bond (planes per principal layer)."""
        return int(np.abs(self.steps).max())


#: Lab axes (rows, crystal axes) of the crystals built here for in-plane hydrostatic loading.
_HYDRO_AXES = {
    "(111)": np.array([[1.0, -1.0, 0.0], [1.0, 1.0, 1.0], [1.0, 1.0, -2.0]])
    / np.array([np.sqrt(2.0), np.sqrt(3.0), -np.sqrt(6.0)])[:, None],
    "(110)": np.array([[1.0, -1.0, 0.0], [1.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    / np.array([np.sqrt(2.0), np.sqrt(2.0), 1.0])[:, None],
}


def _crystal_111_hydrostatic(s: np.ndarray) -> Crystal:
    """FCC stretched by s in the (111) plane, t = sqrt((3 - s^2)/2) along [111] (module docstring)."""
    axes = _HYDRO_AXES["(111)"]
    t = np.sqrt((3.0 - s**2) / 2.0)
    stretch = np.column_stack([s, t, s])
    bonds = (_FCC_HALF_NEIGHBOURS @ axes.T)[None] * stretch[:, None, :]
    prim = _R2 * np.array([[0, 1, 1], [1, 0, 1], [1, 1, 0]], float)
    cell = (prim @ axes.T)[None] * stretch[:, None, :]
    return Crystal("fcc", "in_plane_hydrostatic", "[1-10]", s, bonds, cell,
                   np.abs(np.linalg.det(cell)), stretch)


def _stress_diag(bonds0: np.ndarray, stretch: np.ndarray, pot: PairPotential) -> np.ndarray:
    """V sigma_aa, shape (n, 3), of half bonds (nb, 3) under lab stretches (n, 3)."""
    r = bonds0[None] * stretch[:, None, :]
    length = np.linalg.norm(r, axis=-1)
    return np.einsum("nb,nba->na", pot.dphi(length) / length, r * r)


def _crystal_110_hydrostatic(s: np.ndarray, pot: PairPotential, tol: float = 1e-13) -> Crystal:
    """FCC under equal in-plane stress in (110): stretch s along [1-10], the stretches along [110]
    (normal, sigma_nn = 0) and [001] (sigma equal to that along [1-10]) by Newton's method with
    continuation from s = 1 in steps of at most 0.0025 (numerical Jacobian), vectorised over s.
    The stress-controlled path can end (a limit point of the stress, or a collapse): beyond it
    there is no such geometry (GeometryError)."""
    axes = _HYDRO_AXES["(110)"]
    b0 = _FCC_HALF_NEIGHBOURS @ axes.T
    t = np.ones((s.size, 2))
    steps = 1 + int(np.ceil(np.max(np.abs(s - 1.0), initial=0.0) / 0.0025))

    def residual(sk: np.ndarray, tk: np.ndarray) -> np.ndarray:
        sig = _stress_diag(b0, np.column_stack([sk, tk]), pot)
        return np.column_stack([sig[:, 1], sig[:, 0] - sig[:, 2]])

    ok = np.ones(s.size, bool)
    for k in range(1, steps + 1):
        sk = 1.0 + (s - 1.0) * k / steps
        for _ in range(50):
            f = residual(sk, t)
            if np.all(np.abs(f[ok]) < tol):
                break
            jac = np.empty((s.size, 2, 2))
            for j in range(2):
                dt = np.zeros_like(t)
                dt[:, j] = 1e-7
                jac[:, :, j] = (residual(sk, t + dt) - residual(sk, t - dt)) / 2e-7
            with np.errstate(all="ignore"):
                step = np.linalg.solve(jac, f[..., None])[..., 0]
            t -= np.clip(np.where(np.isfinite(step), step, 0.0), -0.1, 0.1)
            ok &= np.all(t > 0.05, axis=-1) & np.all(np.isfinite(t), axis=-1)
        ok &= np.all(np.abs(residual(sk, t)) < 1e3 * tol, axis=-1)
    if not ok.all():
        raise GeometryError(f"fcc (110) in_plane_hydrostatic with potential {pot.name!r}: no stretches with "
                            f"equal in-plane stress and sigma_nn = 0 at d/d0 = {s[~ok][0]:.6g} (the "
                            "stress-controlled path from d/d0 = 1 ends before it)")
    stretch = np.column_stack([s, t])
    bonds = b0[None] * stretch[:, None, :]
    prim = _R2 * np.array([[0, 1, 1], [1, 0, 1], [1, 1, 0]], float)
    cell = (prim @ axes.T)[None] * stretch[:, None, :]
    return Crystal("fcc", "in_plane_hydrostatic", "[1-10]", s, bonds, cell, np.abs(np.linalg.det(cell)), stretch)


def check_request(surface: str, loading: str, load_direction: str | None) -> str | None:
    """Validate (surface, loading, load direction); return the load direction used (None: in-plane
    hydrostatic).

    Raises
    ------
    InputError
        One line naming the offending value and the choices.
    """
    if surface not in SURFACES:
        raise InputError(f"unknown surface {surface!r}; choose one of {list(SURFACES)}")
    if loading not in LOADINGS:
        raise InputError(f"unknown loading {loading!r}; choose one of {list(LOADINGS)}")
    if loading == "in_plane_hydrostatic":
        if load_direction is not None:
            raise InputError("load_direction applies to uniaxial loading only")
        return None
    choices = LOAD_DIRECTIONS[surface]
    if load_direction is None:
        return choices[0]
    if load_direction not in choices:
        raise InputError(f"uniaxial load_direction {load_direction!r} is not in the {surface} surface "
                         f"for this model; choose one of {list(choices)}")
    return load_direction


def surface_crystal(surface: str, loading: str, potential: str | PairPotential, d_over_d0,
                    load_direction: str | None = None) -> SurfaceCrystal:
    """The prestressed FCC crystal cut along ``surface``, at one or several stretches.

    Parameters
    ----------
    surface : {"(001)", "(111)", "(110)"}
    loading : {"in_plane_hydrostatic", "uniaxial"}
    potential : str or PairPotential
    d_over_d0 : float or array_like, shape (n,)
        Stretch along the load direction (in-plane stretch for in-plane hydrostatic).
    load_direction : str, optional
        Uniaxial only: see :data:`LOAD_DIRECTIONS` (default: the first).

    Returns
    -------
    SurfaceCrystal

    Raises
    ------
    InputError, GeometryError
    """
    get_potential(potential)
    ld = check_request(surface, loading, load_direction)
    s = as_1d(d_over_d0)
    pot = get_potential(potential)
    if ld is None and surface == "(111)":
        bad = s[(s <= 0) | (s >= np.sqrt(3.0))]
        if bad.size:
            raise GeometryError(f"impossible geometry for fcc (111) in_plane_hydrostatic: d/d0 = {bad[0]:.6g} "
                                "(t^2 = (3 - (d/d0)^2)/2 must be positive, so 0 < d/d0 < sqrt 3)")
        crystal = _crystal_111_hydrostatic(s)
        axes = _HYDRO_AXES["(111)"]
    elif ld is None and surface == "(110)":
        bad = s[s <= 0]
        if bad.size:
            raise GeometryError(f"impossible geometry: d/d0 = {bad[0]:.6g} (a stretch must be positive)")
        crystal = _crystal_110_hydrostatic(s, pot)
        axes = _HYDRO_AXES["(110)"]
    else:
        lab = ld or "[100]"
        crystal = build("fcc", cast(Loading, loading), potential, cast(Direction, lab), s)
        axes = lab_axes("(001)", lab)
    cut = _CUTS[(surface, ld or "hydrostatic")]
    a_lab = (cut["a"] @ axes.T)[None] * crystal.stretch[:, None, :]  # (n, 2, 3) deformed a1, a2
    normal = np.cross(a_lab[:, 0], a_lab[:, 1])
    area = np.linalg.norm(normal, axis=-1)
    normal /= area[:, None]
    inward = (np.asarray(cut["plane"], float) @ axes.T)[None] / crystal.stretch  # F^-T (hkl): sign only
    normal *= np.sign(np.einsum("ni,ni->n", normal, inward))[:, None]
    e1 = a_lab[:, 0] / np.linalg.norm(a_lab[:, 0], axis=-1)[:, None]
    rot = np.stack([e1, normal, np.cross(e1, normal)], axis=1)  # (n, 3, 3)
    bonds = np.einsum("nbj,nij->nbi", crystal.bonds, rot)
    spacing = crystal.volume / area
    ratio = bonds[..., 1] / spacing[:, None]
    steps = np.rint(ratio)
    if np.abs(ratio - steps).max() > STEP_TOL or np.any(steps != steps[:1]):
        raise GeometryError(f"bonds do not join lattice planes of {surface} (internal error)")
    cell2d = np.einsum("nai,nji->naj", a_lab, rot[:, [0, 2]])
    recip2d = 2.0 * np.pi * np.swapaxes(np.linalg.inv(cell2d), -1, -2)
    return SurfaceCrystal(surface, loading, ld or "none", s, crystal, rot, bonds, steps[0].astype(int),
                          spacing, cell2d, recip2d)


def cartesian_q(sc: SurfaceCrystal, q_reduced: np.ndarray) -> np.ndarray:
    """In-plane wavevectors (e1, e3 components, rad/d0), shape (n, n_q, 2), from reduced (n_q, 2)."""
    return np.einsum("qa,nai->nqi", np.asarray(q_reduced, float), sc.recip2d)


def plane_blocks(sc: SurfaceCrystal, potential: str | PairPotential, q_cart: np.ndarray) -> dict:
    """Plane-to-plane blocks D_j, j = 0..m, and the bonds missing below a free surface.

    Parameters
    ----------
    sc : SurfaceCrystal
    potential : str or PairPotential
    q_cart : ndarray, shape (n, n_q, 2)
        In-plane wavevectors (e1, e3), rad/d0.

    Returns
    -------
    dict
        ``D`` (m + 1, n, n_q, 3, 3) complex: D_j (coupling of plane l to plane l + j; the
        coupling to l - j is D_j^H), K/m; ``missing`` (m, n, 1, 3, 3): sum of Phi_b over
        the bonds of step j < -l that plane l (l < m) lacks at a free surface.
    """
    phi = bond_force_constants(sc.crystal, potential)  # (n, 6, 3, 3), lab frame
    phi = np.einsum("nia,nbac,njc->nbij", sc.rotation, phi, sc.rotation)  # R Phi R^T
    bonds = np.concatenate([sc.bonds, -sc.bonds], axis=1)  # (n, 12, 3)
    phis = np.concatenate([phi, phi], axis=1)
    steps = np.concatenate([sc.steps, -sc.steps])
    m = sc.depth
    phase = np.exp(1j * np.einsum("nqi,nbi->nqb", q_cart, bonds[..., [0, 2]]))  # (n, n_q, 12)
    out = np.zeros((m + 1,) + q_cart.shape[:2] + (3, 3), complex)
    for j in range(m + 1):
        sel = steps == j
        out[j] = -np.einsum("nqb,nbij->nqij", phase[..., sel], phis[:, sel])
    out[0] += phis.sum(axis=1)[:, None]
    missing = np.zeros((m,) + q_cart.shape[:1] + (1, 3, 3))
    for layer in range(m):
        sel = steps < -layer
        missing[layer] = phis[:, sel].sum(axis=1)[:, None]
    return {"D": out, "missing": missing}


def principal_blocks(blocks: dict) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Principal-layer blocks (m planes each) of the semi-infinite crystal.

    Parameters
    ----------
    blocks : dict
        From :func:`plane_blocks`.

    Returns
    -------
    H00, H00_surface, H01 : ndarray, shape (n, n_q, 3m, 3m), complex
        Bulk diagonal block, the free-surface diagonal block (planes 0..m-1 lacking their
        bonds above the surface) and the coupling to the next principal layer deeper
        (H[P, P+1] = H01, H[P+1, P] = H01^H); K/m. Plane a of a layer is rows 3a..3a+2.
    """
    d = blocks["D"]
    m = d.shape[0] - 1
    lead = d.shape[1:3]
    h00 = np.zeros(lead + (3 * m, 3 * m), complex)
    h01 = np.zeros_like(h00)
    for a in range(m):
        for c in range(m):
            j = c - a
            h00[..., 3 * a:3 * a + 3, 3 * c:3 * c + 3] = d[j] if j >= 0 else np.conj(np.swapaxes(d[-j], -1, -2))
            if m + j <= m:
                h01[..., 3 * a:3 * a + 3, 3 * c:3 * c + 3] = d[m + j]
    h00s = h00.copy()
    for a in range(m):
        h00s[..., 3 * a:3 * a + 3, 3 * a:3 * a + 3] -= blocks["missing"][a]
    return h00, h00s, h01


def bulk_matrix(h00: np.ndarray, h01: np.ndarray, phi: np.ndarray) -> np.ndarray:
    """Bulk dynamical matrix of the layered crystal, H00 + H01 e^{i phi} + H01^H e^{-i phi}.

    Parameters
    ----------
    h00, h01 : ndarray, shape (..., d, d)
    phi : ndarray, shape (n_phi,)
        Phase per principal layer (k_perp m h), rad.

    Returns
    -------
    ndarray, shape (n_phi, ..., d, d)
        Hermitian, K/m. For m = 1 its eigenvalues are the bulk omega^2 at the 3D
        wavevector q + (phi / h) n.
    """
    z = np.exp(1j * np.asarray(phi, float)).reshape((-1,) + (1,) * h00.ndim)
    return h00[None] + h01[None] * z + np.conj(np.swapaxes(h01, -1, -2))[None] / z
