"""Rule `entropy`: surface entropy of the triangular lattice, Eq. (25) estimate and exact value.

Each (potential, strain) point goes through the parameter cache (surfwave.cache).
By hand (from the repository root): python workflow/scripts/entropy.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave import cache, cube, entropy

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.scenes import standalone

    snakemake = standalone("entropy", inputs={"crystal": "results/{scene}/crystal.nc"})
    snakemake.params.cache = str(cache.DEFAULT_ROOT)
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
tol = job["accuracy"]["tol"]
code = cache.code_version("entropy")  # entries of older code are never reused
blocks = {}
for pot in job["potentials"]:
    key = {"code": code, "lattice": job["lattice"], "loading": job["loading"], "potential": pot,
           "method": "entropy.surface_entropy", "tol": tol}
    r = cache.cached_points("entropy", key, job["d_over_d0"],
                            lambda d: entropy.surface_entropy(pot, d, tol=tol), snakemake.params.cache)
    blocks[(pot,)] = cube.documented(r, entropy.VARIABLES, sys.stderr)
ds = cube.build(blocks, {"potential": job["potentials"]}, job["d_over_d0"], entropy.VARIABLES)
ds = cube.add_space_group(ds, cube.open_cube(snakemake.input.crystal))
ds = cube.provenance(ds, title=f"surfwave entropy cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method="classical harmonic surface entropy per surface atom "
                     "(k_B): Eq. (25) estimate and the exact slab-minus-bulk limit")
cube.write(ds, snakemake.output[0])
