"""Sensitivities dc/dp of guided modes of a stack, by implicit differentiation of the secular equation.

At a guided mode of family F the Hermitian boundary matrix Z(c, kh; p) of
:mod:`surfwave.layers.recursion` is singular: one of its eigenvalues, lam, vanishes. Along the mode,
lam(c(p), kh(c, p); p) = 0, so for any parameter p of the stack (a film's modulus, density,
thickness, stress, ...)

    dc/dp = -(d lam / d p) / (d lam / d c),

where d/dc includes kh's dependence on c when the points are given at fixed frequency
(kh = 2 pi f H / c, H the total film thickness, which a thickness parameter also moves). Both
partial derivatives are central differences of lam at the solved speed: no root search, so one
derivative costs two evaluations of the impedance recursion at the n points (a few ms), against a
full mode search of :func:`surfwave.layered` per step for finite differences of solved speeds.
The eigenvalue nearest zero is followed; the stiffness scale of the blocks (which may move with p)
multiplies lam, and its derivative drops out because lam = 0 at the mode.

What a parameter is stays with the caller: :func:`mode_sensitivities` takes a function that
builds the resolved :class:`surfwave.layers.stack.Stack` from a parameter vector
(:class:`surfwave.metrology.layered_model.LayeredModel` builds it from named film parameters).
Checked against finite differences of solved speeds in tests/layers/test_sensitivity.py.
"""
from __future__ import annotations

from collections.abc import Callable, Sequence

import numpy as np

from surfwave.errors import InputError
from surfwave.layers.modes import label_family
from surfwave.layers.partial import COUPLING_TOL, Blocks, Family, families, scaled_blocks
from surfwave.layers.recursion import boundary_matrix, top_impedance
from surfwave.layers.stack import Stack

__all__ = ["STEP_C", "family_prefix", "mode_sensitivities", "root_eigenvalue"]

#: Relative step of the central difference of lam in c.
STEP_C = 1e-7


def family_prefix(label: str) -> str:
    """The family prefix of a mode label of :func:`surfwave.layered`: "R"/"S1" -> "R", "L0" -> "L", "M2" -> "M".

    Raises
    ------
    InputError
        A leaky label ("...~", complex speed: not a root of the real secular equation) or an
        unknown one.
    """
    text = str(label)
    if text.endswith("~"):
        raise InputError(f"mode {text!r} is leaky: its sensitivities are not those of a guided mode")
    prefix = label_family(text)
    if not prefix:
        raise InputError(f"unknown mode label {text!r}: expected R, S<n>, L<n> or M<n>")
    return prefix


def _family(b: Blocks, prefix: str) -> Family:
    for fam in families(b):
        if fam.prefix == prefix:
            return fam
    raise InputError(f"the stack has no mode family {prefix!r} (its families: {[f.prefix for f in families(b)]})")


def root_eigenvalue(stack: Stack, prefix: str, c: np.ndarray, kh: np.ndarray, electrical: str = "free") -> np.ndarray:
    """The eigenvalue nearest zero of the boundary matrix of family ``prefix``, shape (n,).

    Parameters
    ----------
    stack : Stack
    prefix : {"R", "L", "M"}
        The family (:func:`family_prefix`).
    c : ndarray, shape (n,)
        Real phase speeds, m/s, below the family's limiting speed.
    kh : ndarray, shape (n,)
        Wavenumber times total film thickness at each speed.
    electrical : {"free", "metallized"}
        The top's electrical condition.

    Returns
    -------
    ndarray, shape (n,)
        Scaled (dimensionless) eigenvalue; zero at a guided mode. NaN where the recursion failed.
    """
    b = scaled_blocks(stack)
    return _root_eigenvalue(b, _family(b, prefix), c, kh, electrical)


def _root_eigenvalue(b: Blocks, fam: Family, c: np.ndarray, kh: np.ndarray, electrical: str) -> np.ndarray:
    """:func:`root_eigenvalue` from the scaled blocks and the family (shape (n,))."""
    M = top_impedance(b, fam, np.asarray(c, dtype=float), np.asarray(kh, dtype=float)[:, None])["M"][:, 0]
    Z, _ = boundary_matrix(b, fam, M, electrical)
    with np.errstate(all="ignore"):
        bad = ~np.isfinite(Z).all(axis=(-1, -2))
        w = np.linalg.eigvalsh(np.where(bad[:, None, None], 0.0, Z))
    lam = np.take_along_axis(w, np.argmin(np.abs(w), axis=-1)[:, None], axis=-1)[:, 0]
    lam[bad] = np.nan
    return lam


def _family_like(b: Blocks, fam: Family) -> Family:
    """``fam`` for the blocks ``b`` of a perturbed stack, when no layer of ``b`` couples its components to the
    others (the recursion uses only the components; the family's limiting speed is not needed here); else
    the family of that prefix from :func:`surfwave.layers.partial.families` (which computes the limits)."""
    link = (np.abs(b.Q) + np.abs(b.R) + np.abs(np.swapaxes(b.R, -1, -2)) + np.abs(b.T)).max(axis=0)
    adj = link > COUPLING_TOL * link.max()
    inside = np.zeros(adj.shape[0], dtype=bool)
    inside[list(fam.idx)] = True
    if not (adj[np.ix_(inside, ~inside)].any() or adj[np.ix_(~inside, inside)].any()):
        return fam
    return _family(b, fam.prefix)


def mode_sensitivities(stack_of: Callable[[np.ndarray], Stack], p, c, x, steps, *, family: str | Sequence[str],
                       variable: str = "kh", electrical: str = "free") -> np.ndarray:
    """dc/dp of guided modes at their solved speeds, by implicit differentiation, shape (n, m).

    Parameters
    ----------
    stack_of : callable
        ``stack_of(p) -> Stack``: the resolved stack for a parameter vector (m,).
    p : array_like, shape (m,)
        The parameters where the speeds were solved.
    c : array_like, shape (n,)
        Solved phase speeds of the modes, m/s (real: guided modes).
    x : array_like, shape (n,)
        kh (wavenumber x total film thickness) or frequency (Hz) of each point, per ``variable``.
    steps : array_like, shape (m,)
        Absolute step of the central difference of lam in each parameter (its units); e.g. 1e-6
        of the parameter's size.
    family : str or sequence of str, length n
        Each point's family prefix ("R", "L" or "M": :func:`family_prefix` of its mode label), or
        one for all.
    variable : {"kh", "frequency"}
        What ``x`` is. At fixed frequency kh = 2 pi f H / c moves with c and with the thickness.
    electrical : {"free", "metallized"}

    Returns
    -------
    ndarray, shape (n, m)
        dc/dp, m/s per unit of each parameter; NaN at points that are not finite or where the
        secular eigenvalue does not depend on c (not a simple root).
    """
    p = np.asarray(p, dtype=float).reshape(-1)
    c = np.asarray(c, dtype=float).reshape(-1)
    x = np.asarray(x, dtype=float).reshape(-1)
    steps = np.asarray(steps, dtype=float).reshape(-1)
    if x.shape != c.shape or steps.shape != p.shape:
        raise InputError(f"mode_sensitivities: c and x need one length, steps one per parameter; got {c.size}, "
                         f"{x.size}, {steps.size} and {p.size}")
    if variable not in ("kh", "frequency"):
        raise InputError(f"variable must be 'kh' or 'frequency', got {variable!r}")
    fams = np.broadcast_to(np.asarray(family, dtype=object), c.shape)
    J = np.full((c.size, p.size), np.nan)
    ok = np.isfinite(c) & np.isfinite(x)

    def kh_of(st: Stack, cc: np.ndarray, rows: np.ndarray) -> np.ndarray:
        if variable == "kh":
            return x[rows]
        return 2.0 * np.pi * x[rows] * st.total_thickness / cc

    prefixes = list(dict.fromkeys(fams[ok].tolist()))
    if not prefixes:
        return J
    st0 = stack_of(p)
    b0 = scaled_blocks(st0)
    perturbed = []                                       # (stack, blocks) at p + step and p - step, per parameter
    for j in range(p.size):
        pp, pm = p.copy(), p.copy()
        pp[j] += steps[j]
        pm[j] -= steps[j]
        sp, sm = stack_of(pp), stack_of(pm)
        perturbed.append(((sp, scaled_blocks(sp)), (sm, scaled_blocks(sm))))
    for prefix in prefixes:
        rows = np.flatnonzero(ok & (fams == prefix))
        cr = c[rows]
        hc = STEP_C * cr
        fam = _family(b0, prefix)
        lam_c = (_root_eigenvalue(b0, fam, cr + hc, kh_of(st0, cr + hc, rows), electrical)
                 - _root_eigenvalue(b0, fam, cr - hc, kh_of(st0, cr - hc, rows), electrical)) / (2.0 * hc)
        for j, ((sp, bp), (sm, bm)) in enumerate(perturbed):
            up = _root_eigenvalue(bp, _family_like(bp, fam), cr, kh_of(sp, cr, rows), electrical)
            down = _root_eigenvalue(bm, _family_like(bm, fam), cr, kh_of(sm, cr, rows), electrical)
            lam_p = (up - down) / (2.0 * steps[j])
            with np.errstate(all="ignore"):
                J[rows, j] = np.where(lam_c != 0, -lam_p / lam_c, np.nan)
    return J
