"""Physical sanity of numerically computed sound speeds.

The phonopy route (:mod:`surfwave.model_crystals.phonons`) and the analytic stress-derivative
route (:mod:`surfwave.model_crystals.elastic`, Eq. A11) compute the same long-wave sound speeds
for nearest-neighbour forces. When they disagree by more than any accuracy setting can
explain (the finite-displacement error is ~ amplitude^2 <= 1e-4 within the allowed
amplitudes), the phonopy numbers are not an answer: a displacement of 10 d0 once gave
c^2 ~ 1e194. Such points become NaN with a reason instead of silent garbage.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

SPEEDS = ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH")
#: Largest relative disagreement accepted: 100 times the worst finite-displacement error
#: the config allows (amplitude 1e-2 -> 1e-4).
RTOL = 1e-2


def check_bulk(bulk: xr.Dataset, analytic: xr.Dataset, rtol: float = RTOL) -> tuple[xr.Dataset, int]:
    """NaN the phonopy speeds of every point where they disagree with the analytic ones.

    Parameters
    ----------
    bulk : xarray.Dataset
        ``<speed>_phonopy``, ``stable_phonon``, ``reason``; dims (potential, direction, strain).
    analytic : xarray.Dataset
        The elastic cube (``<speed>``) on the same coordinates.
    rtol : float
        Disagreement accepted, relative to max(|analytic|, 1e-2 c2_L_par).

    Returns
    -------
    (xarray.Dataset, int)
        The checked cube (a copy) and the number of points flagged. Flagged points get NaN
        speeds, ``stable_phonon`` False and a ``reason`` naming the worst disagreement.
    """
    out = bulk.copy(deep=True)
    bad = xr.zeros_like(out["stable_phonon"], dtype=bool)
    worst = xr.zeros_like(out["stable_phonon"], dtype=float)
    scale_floor = 1e-2 * abs(analytic["c2_L_par"])
    for name in SPEEDS:
        if f"{name}_phonopy" not in out or name not in analytic:
            continue
        ref = analytic[name].sel(potential=out.potential, direction=out.direction)
        scale = np.maximum(np.abs(ref), scale_floor.sel(potential=out.potential, direction=out.direction))
        rel = abs(out[f"{name}_phonopy"] - ref) / scale
        computed = np.isfinite(out[f"{name}_phonopy"])
        implausible = computed & ~(rel <= rtol)  # NaN in rel (inf values) counts as implausible
        bad = bad | implausible
        worst = xr.where(implausible, np.maximum(worst, rel.fillna(np.inf)), worst)
    n = int(bad.sum())
    if n:
        for name in SPEEDS:
            if f"{name}_phonopy" in out:
                out[f"{name}_phonopy"] = out[f"{name}_phonopy"].where(~bad)
        out["stable_phonon"] = out["stable_phonon"] & ~bad
        msg = xr.apply_ufunc(np.vectorize(lambda w: f"phonopy speeds implausible: off the analytic "
                                                    f"long-wave speeds by {w:.3g} relative (accepted "
                                                    f"{rtol:g}); stability unknown"), worst)
        out["reason"] = xr.where(bad, msg, out["reason"]).assign_attrs(out["reason"].attrs)
    return out, n
