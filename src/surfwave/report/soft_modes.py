"""What a surface-phonon cube says about soft surface modes: a claim with its evidence.

The question of issue 29: does prestress soften a surface mode at finite q before any bulk
mode goes soft? A ``surface_phonons.nc`` cube answers it on its own strain grid: per potential
and cut, the strains whose bulk is stable (``bulk_stable``), the softest surface omega^2 along
the path at each (``softest_omega2``) and where along the path it lies (``lowest_omega2``,
``q_reduced``). The finer answer (a bisection in d/d0 between grid points) is
:func:`surfwave.dynamics.fcc_soft_modes.first_instabilities`; docs/physics/surface-phonons.md
lists what it finds.
"""
from __future__ import annotations

import numpy as np
import xarray as xr

__all__ = ["soft_mode_lines"]


def _q_text(ds: xr.Dataset, sel: dict) -> str:
    """Reduced wavevector of the softest surface mode at one (potential, cut, strain)."""
    low = ds["lowest_omega2"].isel(sel).values
    if not np.isfinite(low).any():
        return "q unknown"
    q = ds["q_reduced"].isel(sel).values[int(np.nanargmin(low))]
    return f"q = ({q[0]:.3g}, {q[1]:.3g}) in reduced coordinates"


def soft_mode_lines(ds: xr.Dataset) -> list[str]:
    """Markdown lines: per potential and cut, whether a surface mode goes soft while the bulk
    is stable on the cube's strain grid, with the strain, omega^2 and q as evidence.

    Parameters
    ----------
    ds : xarray.Dataset
        A ``surface_phonons.nc`` cube (dims potential, cut, strain, q, ...) with
        ``bulk_stable``, ``softest_omega2`` (K/m), ``lowest_omega2`` and ``q_reduced``.

    Returns
    -------
    list of str
        A heading and one line per (potential, cut); empty if the cube lacks these variables.

    Examples
    --------
    >>> ds = xr.Dataset(
    ...     {"bulk_stable": (("potential", "cut", "strain"), [[[False, True, True]]]),
    ...      "softest_omega2": (("potential", "cut", "strain"), [[[np.nan, 0.01, -0.002]]]),
    ...      "lowest_omega2": (("potential", "cut", "strain", "q"), [[[[np.nan] * 2, [0.02, 0.01], [0.1, -0.002]]]]),
    ...      "q_reduced": (("potential", "cut", "strain", "q", "axis2"), np.full((1, 1, 3, 2, 2), 0.5))},
    ...     coords={"potential": ["lj"], "cut": ["(001)"], "d_over_d0": ("strain", [0.9, 1.0, 1.1])})
    >>> for part in soft_mode_lines(ds)[2].split(", at "):
    ...     print(part)
    - lj, (001): a surface mode goes soft while the bulk is stable
    d/d0 = 1.1 (omega^2 = -0.002 K/m, q = (0.5, 0.5) in reduced coordinates)
    """
    need = ("bulk_stable", "softest_omega2", "lowest_omega2", "q_reduced")
    if not all(v in ds for v in need):
        return []
    d = ds["d_over_d0"].values
    out = ["#### Soft surface modes (a claim from this cube's strain grid)", ""]
    for ip, pot in enumerate(ds["potential"].values):
        for ic, cut in enumerate(ds["cut"].values):
            stable = ds["bulk_stable"].values[ip, ic].astype(bool)
            w2 = ds["softest_omega2"].values[ip, ic]
            where = f"- {pot}, {cut}: "
            if not stable.any():
                out.append(where + "the bulk is unstable at every strain of the grid")
                continue
            soft = np.flatnonzero(stable & np.isfinite(w2) & (w2 <= 0))
            if soft.size:
                i = int(soft[np.argmin(np.abs(d[soft] - 1.0))])
                sel = {"potential": ip, "cut": ic, "strain": i}
                out.append(where + f"a surface mode goes soft while the bulk is stable, at d/d0 = {d[i]:.6g} "
                           f"(omega^2 = {w2[i]:.3g} K/m, {_q_text(ds, sel)})")
                continue
            ends = sorted({int(np.flatnonzero(stable)[0]), int(np.flatnonzero(stable)[-1])})
            edge = "; ".join(f"{w2[i]:.3g} K/m at d/d0 = {d[i]:.6g} "
                             f"({_q_text(ds, {'potential': ip, 'cut': ic, 'strain': i})})" for i in ends)
            out.append(where + "no surface mode goes soft while the bulk is stable on this grid "
                       f"(bulk stable for d/d0 = {d[stable].min():.6g} ... {d[stable].max():.6g}); the softest "
                       f"surface omega^2 at the last stable strains: {edge}")
    return out + ["", "Between grid points, `surfwave.dynamics.fcc_soft_modes.first_instabilities` bisects "
                  "in d/d0 (docs/physics/surface-phonons.md: on (001) and (111) the surface goes first by "
                  "at most 0.008 in d/d0, always where a long-wave c_R vanishes too).", ""]
