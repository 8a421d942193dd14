"""Rule `dispersion`: omega(theta), q1, q2 of the triangular lattice, checked by lattice dynamics.

The analytic solution (surfwave.dynamics.dispersion.solve) is cheap; the numerical lattice-dynamics
check (surfwave.dynamics.triangular_surface.surface_mode) goes through the parameter cache per strain.
By hand (from the repository root): python workflow/scripts/dispersion.py SCENE [CONFIGFILE ...]
"""
import sys

import numpy as np

from surfwave.data import cache, cube
from surfwave.dynamics import dispersion, triangular_surface as lattice_dynamics

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("dispersion", inputs={"crystal": "results/{scene}/crystal.nc"})
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
theta = np.asarray(job["theta"])
tol = job["accuracy"]["tol"]
meta = {**dispersion.VARIABLES, **lattice_dynamics.VARIABLES,
        "omega_lattice_deviation": {"long_name": "omega_lattice minus omega (numerical minus analytic)",
                                    "units": dispersion.VARIABLES["omega"]["units"], "dims": ("theta",)}}
blocks = {}
for pot in job["potentials"]:
    r = dispersion.solve(pot, job["d_over_d0"], theta)
    key = cache.job_key(job, "dynamics.triangular_surface", "lattice_dynamics.surface_mode", potential=pot,
                        theta=job["theta"], tol=tol)
    r.update(cache.cached_points(
        "surface_mode", key, job["d_over_d0"],
        lambda d: lattice_dynamics.surface_mode(pot, d, theta, tol=tol), snakemake.params.cache,
        chunk=cache.CHUNK,
        label=f"surface_mode, scene {job['scene']}"))
    r["omega_lattice_deviation"] = r["omega_lattice"] - r["omega"]
    blocks[(pot,)] = cube.documented(r, meta, sys.stderr)
ds = cube.build(blocks, {"potential": job["potentials"]}, job["d_over_d0"], meta,
                coords={"theta": theta})
cube.finish(ds, snakemake, what="dispersion", crystal=snakemake.input.crystal,
            method="analytic row-by-row solution (Eqs. 3a-15) checked by a numerical "
            "lattice-dynamics surface-mode solve")
