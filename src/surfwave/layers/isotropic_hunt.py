"""The isotropic scan's hunt for two roots in one grid cell: its parabolic step, and its first step apart.

The step itself (:func:`vertex`, :func:`near_miss`, :func:`trial_point`, :func:`shrink`) is written
once here and used by the hunt (:func:`surfwave.layers.isotropic_scan._hidden_pairs`) and by the two
functions below.

:func:`surfwave.layers.isotropic_scan._hidden_pairs` hunts each local minimum of |F| without a sign
change by parabolic steps. :func:`hunt_start` gives the speeds of its first step, and
:func:`hunt_settles` whether, with F there, it finds nothing and stops after that step; so the
first step can be evaluated elsewhere (:func:`surfwave.layers.isotropic_modes.both_families`
evaluates it with Newton's first round) and the hunt run only where it would go on.
"""
from __future__ import annotations

import numpy as np

__all__ = ["hunt_settles", "hunt_start", "near_miss", "shrink", "trial_point", "vertex"]


def vertex(cl: np.ndarray, cm: np.ndarray, ch: np.ndarray, gl: np.ndarray, gm: np.ndarray, gh: np.ndarray
           ) -> np.ndarray:
    """Speed of the vertex of the parabola through (cl, gl), (cm, gm), (ch, gh) (arrays, m/s; NaN if flat)."""
    a, b = cm - cl, cm - ch
    dh, dl = gm - gh, gm - gl
    return cm - 0.5 * (a * a * dh - b * b * dl) / (a * dh - b * dl)


def near_miss(cl: np.ndarray, cm: np.ndarray, ch: np.ndarray, gl: np.ndarray, gm: np.ndarray, gh: np.ndarray,
              x: np.ndarray) -> np.ndarray:
    """True where the parabola through the three points (vertex ``x``) puts its minimum above 0.7 gm:
    a dip that does not reach zero, not two roots."""
    a, b = cm - cl, cm - ch
    curv = ((gl - gm) / a - (gh - gm) / b) / (a - b)
    g_min = gm - curv * (cm - x) ** 2
    return np.isfinite(g_min) & (curv > 0) & (g_min > 0.7 * gm)


def trial_point(x: np.ndarray, cl: np.ndarray, cm: np.ndarray, ch: np.ndarray) -> np.ndarray:
    """The hunt's next speed: the vertex ``x``, or a golden-section point of the wider side where the
    vertex is not finite, outside (cl, ch) or within 1e-3 of the bracket from cm."""
    a, b = cm - cl, cm - ch
    gold = np.where(a > -b, cm - 0.382 * a, cm - 0.382 * b)
    bad = ~np.isfinite(x) | (x <= cl) | (x >= ch) | (np.abs(x - cm) < 1e-3 * (ch - cl))
    return np.where(bad, gold, x)


def shrink(cl: np.ndarray, cm: np.ndarray, ch: np.ndarray, gl: np.ndarray, gm: np.ndarray, gh: np.ndarray,
           x: np.ndarray, gx: np.ndarray) -> tuple[np.ndarray, ...]:
    """The bracket (cl, cm, ch) and its values (gl, gm, gh) after F's value ``gx`` at ``x``: x becomes the
    middle point where it is lower than gm, else the end on its side."""
    better, left = gx < gm, x < cm
    cl, ch = (np.where(better, np.where(left, cl, cm), np.where(left, x, cl)),
              np.where(better, np.where(left, cm, ch), np.where(left, ch, x)))
    gl, gh = (np.where(better, np.where(left, gl, gm), np.where(left, gx, gl)),
              np.where(better, np.where(left, gm, gh), np.where(left, gh, gx)))
    return cl, np.where(better, x, cm), ch, gl, np.where(better, gx, gm), gh


def hunt_start(cs: np.ndarray, Fs: np.ndarray) -> np.ndarray:
    """The speeds (m,) at which the hunt on ``cs``, ``Fs`` (m, 3) first evaluates F (its first step).

    ``cs``, ``Fs``: three consecutive grid speeds (m/s) around each local minimum of |F| and F there, as
    :func:`~surfwave.layers.isotropic_scan._hidden_pairs` takes them.
    """
    s = np.sign(Fs[:, 1])
    (cl, cm, ch), (gl, gm, gh) = cs.T.copy(), (Fs * s[:, None]).T.copy()
    with np.errstate(all="ignore"):
        x = vertex(cl, cm, ch, gl, gm, gh)
    return trial_point(x, cl, cm, ch)


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
        nl, cm1, nh, gl1, gm1, gh1 = shrink(cl, cm, ch, gl, gm, gh, x, gx)
        live = nh - nl > 1e-9 * cm1
        drop = near_miss(nl, cm1, nh, gl1, gm1, gh1, vertex(nl, cm1, nh, gl1, gm1, gh1))
        return bool(np.all(drop | ~live))
