"""Soft surface modes of prestressed FCC: whether a surface mode reaches omega^2 < 0 before the bulk.

Walking out from d/d0 = 1 (compression and tension) in steps, each strain is checked twice
with :func:`surfwave.surface_phonons`: the bulk (zone mesh of the layered crystal and the
long-wave acoustic tensor, ``bulk_stable``) and the free surface (the lowest true surface
mode over a reduced-q mesh of the surface zone, plus the high-symmetry path, must have
omega^2 > 0). The first failing step is bisected for each criterion separately, so the
result says which goes first and where: ``d_surface`` before ``d_bulk`` would be a surface
instability that neither the long-wave theory nor the bulk scan can see.
"""
from __future__ import annotations

from collections.abc import Callable

import numpy as np

from surfwave.dynamics.fcc_surface_phonons import DEFAULT_PATHS, surface_phonons
from surfwave.errors import SurfwaveError
from surfwave.model_crystals.potentials import PairPotential

#: Default reduced-q mesh (n x n midpoints) of the surface check.
N_MESH = 16


def q_mesh(n: int = N_MESH) -> np.ndarray:
    """n x n midpoint mesh of reduced q over the surface zone, shape (n^2, 2)."""
    g = (np.arange(n) + 0.5) / n - 0.5
    return np.stack(np.meshgrid(g, g, indexing="ij"), axis=-1).reshape(-1, 2)


def surface_check(potential: str | PairPotential, loading: str, d_over_d0, surface: str,
                  load_direction: str | None = None, n_mesh: int = N_MESH) -> dict:
    """Bulk flag and softest surface mode over mesh + path at each strain.

    Returns
    -------
    dict of ndarray, shape (n,)
        ``bulk_stable`` (bool; False also where the geometry does not exist),
        ``softest_omega2`` (K/m; NaN where the bulk is unstable or no surface mode),
        ``softest_q`` (n, 2) reduced.
    """
    s = np.atleast_1d(np.asarray(d_over_d0, float))
    q = np.concatenate([q_mesh(n_mesh), _path(surface)])
    out = {"bulk_stable": np.zeros(s.size, bool), "softest_omega2": np.full(s.size, np.nan),
           "softest_q": np.full((s.size, 2), np.nan)}
    for i, si in enumerate(s):
        try:
            r = surface_phonons(potential, loading, si, surface=surface, q=q, load_direction=load_direction)
        except SurfwaveError:  # no geometry (e.g. the uniaxial lateral solve fails)
            continue
        out["bulk_stable"][i] = r["bulk_stable"][0]
        out["softest_omega2"][i] = r["softest_omega2"][0]
        out["softest_q"][i] = r["softest_q"][0]
    return out


def _path(surface: str) -> np.ndarray:
    from surfwave.dynamics.fcc_layers import SYMMETRY_POINTS

    pts = np.array([SYMMETRY_POINTS[surface][c] for c in DEFAULT_PATHS[surface]])
    t = np.linspace(0.0, 1.0, 17)[1:, None]
    return np.concatenate([a + t * (b - a) for a, b in zip(pts[:-1], pts[1:])])


def _bisect(flag: Callable[[float], bool], good: float, bad: float, tol: float) -> float:
    """The bad end of [good, bad] bracketing where ``flag`` turns False, to ``tol``."""
    while abs(bad - good) > tol:
        mid = 0.5 * (good + bad)
        if flag(mid):
            good = mid
        else:
            bad = mid
    return bad


def first_instabilities(potential: str | PairPotential, loading: str, surface: str = "(001)",
                        load_direction: str | None = None, step: float = 0.01, tol: float = 1e-4,
                        search: tuple[float, float] = (0.6, 1.6), n_mesh: int = N_MESH) -> dict:
    """First bulk and first surface instability below and above d/d0 = 1.

    Parameters
    ----------
    potential, loading, surface, load_direction
        As for :func:`surfwave.surface_phonons`.
    step, tol : float
        Walk step and bisection tolerance in d/d0.
    search : (float, float)
        Strains examined.
    n_mesh : int
        Reduced-q mesh of the surface check.

    Returns
    -------
    dict
        ``d_bulk`` (compress, tension): the first d/d0 whose bulk is unstable (or whose
        geometry does not exist), NaN if none within ``search``; ``d_surface``: the first d/d0
        with a surface mode at omega^2 <= 0 while the bulk is still stable (NaN: none before
        the bulk goes); ``first`` per side ("bulk", "surface" or "none"); ``softest_inside``
        per side: (lowest surface omega^2, its reduced q, d/d0) at the last step walked
        before the first instability; ``soft_mode`` per side: (omega^2, reduced q, d/d0) of
        the softest surface mode at ``d_surface`` (NaN where the bulk went first).
    """
    def check(d: float) -> tuple[bool, bool]:
        r = surface_check(potential, loading, d, surface, load_direction, n_mesh)
        bulk_ok = bool(r["bulk_stable"][0])
        w2 = r["softest_omega2"][0]
        return bulk_ok, bulk_ok and not (np.isfinite(w2) and w2 <= 0)

    d_bulk, d_surf, first, inside, soft = [], [], [], [], []
    for sign, bound in ((-1.0, search[0]), (1.0, search[1])):
        prev, d = 1.0, 1.0 + sign * step
        db = ds = np.nan
        kind = "none"
        while sign * (d - bound) <= 0:
            if not check(d)[1]:
                x = _bisect(lambda v: check(v)[1], prev, d, tol)
                if check(x)[0]:  # the bulk is still stable where the surface fails
                    ds, kind = x, "surface"
                    while sign * (d - bound) <= 0 and check(d)[0]:
                        d += sign * step
                    if sign * (d - bound) <= 0:
                        db = _bisect(lambda v: check(v)[0], d - sign * step, d, tol)
                else:
                    db, kind = _bisect(lambda v: check(v)[0], prev, d, tol), "bulk"
                break
            prev, d = d, d + sign * step
        r = surface_check(potential, loading, prev, surface, load_direction, n_mesh)
        inside.append((float(r["softest_omega2"][0]), r["softest_q"][0].tolist(), float(prev)))
        if kind == "surface":  # the soft mode itself, just past the surface limit
            r = surface_check(potential, loading, ds, surface, load_direction, n_mesh)
            soft.append((float(r["softest_omega2"][0]), r["softest_q"][0].tolist(), float(ds)))
        else:
            soft.append((np.nan, [np.nan, np.nan], np.nan))
        d_bulk.append(float(db))
        d_surf.append(float(ds))
        first.append(kind)
    return {"d_bulk": d_bulk, "d_surface": d_surf, "first": first, "softest_inside": inside,
            "soft_mode": soft}
