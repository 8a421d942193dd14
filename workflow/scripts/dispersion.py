"""Rule `dispersion`: omega(theta), q1, q2 of the triangular lattice, checked by lattice dynamics.

The analytic solution (surfwave.dynamics.dispersion.solve) is cheap; the numerical lattice-dynamics
check (surfwave.dynamics.triangular_surface.surface_mode) goes through the parameter cache per strain.
By hand (from the repository root): python workflow/scripts/dispersion.py SCENE [CONFIGFILE ...]
"""

import numpy as np

from surfwave.data import cache, cube
from surfwave.data.variables import CUBES
from surfwave.dynamics import dispersion
from surfwave.dynamics import triangular_surface as lattice_dynamics
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("dispersion")
stage.open_log(snakemake)

job = snakemake.params.job
theta = np.asarray(job["theta"])
tol = job["accuracy"]["tol"]
meta = CUBES["dispersion"]


d_all = np.asarray(job["d_over_d0"], dtype=float)
sample = lattice_dynamics.check_sample(d_all, job["accuracy"]["check_points"])


def compute(pot):
    r = dispersion.solve(pot, d_all, theta)
    key = cache.job_key(job, "dynamics.triangular_surface", "lattice_dynamics.surface_mode", potential=pot,
                        theta=job["theta"], tol=tol)
    checked = cache.cached_points(
        "surface_mode", key, d_all[sample],
        lambda d: lattice_dynamics.surface_mode(pot, d, theta, tol=tol), snakemake.params.cache,
        chunk=cache.CHUNK,
        label=f"surface_mode, scene {job['scene']}")
    r.update(lattice_dynamics.scatter_sample(checked, sample, d_all.size))
    r["omega_lattice_deviation"] = r["omega_lattice"] - r["omega"]
    return r


ds = stage.block_cube(job, compute, meta, by=("potential",), coords={"theta": theta})
dev = np.abs(ds["omega_lattice_deviation"].values)
ds.attrs.update(
    lattice_check_points=f"{sample.size} of {d_all.size} strains (those nearest to the lattice d/d0 = "
                         f"1 + j {lattice_dynamics.CHECK_SPAN:g}/{job['accuracy']['check_points']}: "
                         "stable when the grid is extended); the others are NaN in omega_lattice, "
                         f"reason_lattice '{lattice_dynamics.REASON_NOT_CHECKED}'",
    lattice_check_d_over_d0=d_all[sample],
    lattice_check_max_abs_deviation=float(np.nanmax(dev)) if np.isfinite(dev).any() else np.nan,
)
cube.finish(ds, snakemake, what="dispersion", crystal=snakemake.input.crystal,
            method="analytic row-by-row solution (Eqs. 3a-15) checked by a numerical "
            "lattice-dynamics surface-mode solve")
