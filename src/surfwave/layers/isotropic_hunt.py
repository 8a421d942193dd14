"""The first step of the isotropic scan's hunt for two roots in one grid cell, apart from the scan.

:func:`surfwave.layers.isotropic_scan._hidden_pairs` hunts each local minimum of |F| without a sign
change by parabolic steps. :func:`hunt_start` gives the speeds of its first step, and
:func:`hunt_settles` whether, with F there, it finds nothing and stops after that step; so the
first step can be evaluated elsewhere (:func:`surfwave.layers.isotropic_modes.both_families`
evaluates it with Newton's first round) and the hunt run only where it would go on.
"""
from __future__ import annotations

import numpy as np

__all__ = ["hunt_settles", "hunt_start"]


def hunt_start(cs: np.ndarray, Fs: np.ndarray) -> np.ndarray:
    """The speeds (m,) at which the hunt on ``cs``, ``Fs`` (m, 3) first evaluates F (its first step).

    ``cs``, ``Fs``: three consecutive grid speeds (m/s) around each local minimum of |F| and F there, as
    :func:`~surfwave.layers.isotropic_scan._hidden_pairs` takes them.
    """
    s = np.sign(Fs[:, 1])
    (cl, cm, ch), (gl, gm, gh) = cs.T.copy(), (Fs * s[:, None]).T.copy()
    with np.errstate(all="ignore"):
        a, b = cm - cl, cm - ch
        dh, dl = gm - gh, gm - gl
        x = cm - 0.5 * (a * a * dh - b * b * dl) / (a * dh - b * dl)
    gold = np.where(a > -b, cm - 0.382 * a, cm - 0.382 * b)
    bad = ~np.isfinite(x) | (x <= cl) | (x >= ch) | (np.abs(x - cm) < 1e-3 * (ch - cl))
    return np.where(bad, gold, x)


def hunt_settles(cs: np.ndarray, Fs: np.ndarray, x: np.ndarray, fx: np.ndarray) -> bool:
    """Whether the hunt on ``cs``, ``Fs`` (m, 3) finds nothing and stops after its first step, given F ``fx``
    (m,) at that step's speeds ``x`` (:func:`hunt_start`) to rounding.

    True only if this holds for F at both ends of the interval within 1e-9 of the largest |F| of the three
    grid points of each minimum around ``fx`` (the hunt's first comparison the same in it): then F
    evaluated otherwise (another route to the same function, equal to rounding) takes
    :func:`~surfwave.layers.isotropic_scan._hidden_pairs` the same way.
    """
    if x.size == 0:
        return True
    s = np.sign(Fs[:, 1])
    (cl, cm, ch), (gl, gm, gh) = cs.T.copy(), (Fs * s[:, None]).T.copy()
    gx0 = fx * s
    tol = 1e-9 * np.maximum(np.maximum(gl, gh), np.abs(gm))
    with np.errstate(all="ignore"):
        if not bool(np.all(gx0 > tol) & np.all(np.abs(gx0 - gm) > tol)):   # no hit; the same side of gm
            return False
        gx = gx0 + np.array([[-1.0], [1.0]]) * tol                      # (2, m): both ends
        better, left = gx0 < gm, x < cm
        nl = np.where(better, np.where(left, cl, cm), np.where(left, x, cl))
        nh = np.where(better, np.where(left, cm, ch), np.where(left, ch, x))
        gl1 = np.where(better, np.where(left, gl, gm), np.where(left, gx, gl))
        gh1 = np.where(better, np.where(left, gm, gh), np.where(left, gh, gx))
        cm1, gm1 = np.where(better, x, cm), np.where(better, gx, gm)
        live = nh - nl > 1e-9 * cm1
        a, b = cm1 - nl, cm1 - nh
        dh, dl = gm1 - gh1, gm1 - gl1
        x1 = cm1 - 0.5 * (a * a * dh - b * b * dl) / (a * dh - b * dl)
        curv = ((gl1 - gm1) / a - (gh1 - gm1) / b) / (a - b)
        g_min = gm1 - curv * (cm1 - x1) ** 2
        drop = np.isfinite(g_min) & (curv > 0) & (g_min > 0.7 * gm1)
        return bool(np.all(drop | ~live))
