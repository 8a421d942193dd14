"""Rule `entropy`: surface entropy of the triangular lattice, Eq. (25) estimate and exact value.

Each (potential, strain) point goes through the parameter cache (surfwave.data.cache).
By hand (from the repository root): python workflow/scripts/entropy.py SCENE [CONFIGFILE ...]
"""

from surfwave.data import cache, cube
from surfwave.data.variables import CUBES
from surfwave.dynamics import entropy
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("entropy")
stage.open_log(snakemake)

job = snakemake.params.job
tol = job["accuracy"]["tol"]


def compute(pot):
    key = cache.job_key(job, "dynamics.entropy", "entropy.surface_entropy", potential=pot, tol=tol)
    return cache.cached_points("entropy", key, job["d_over_d0"],
                               lambda d: entropy.surface_entropy(pot, d, tol=tol), snakemake.params.cache,
                               chunk=cache.CHUNK, label=f"entropy, scene {job['scene']}")


ds = stage.block_cube(job, compute, CUBES["entropy"], by=("potential",))
cube.finish(ds, snakemake, what="entropy", crystal=snakemake.input.crystal,
            method="classical harmonic surface entropy per surface atom (k_B): Eq. (25) "
            "estimate and the exact slab-minus-bulk limit")
