"""Rule `bulk`: phonopy sound speeds and full-zone stability, deviation from elastic.nc.

Each (potential, direction, strain) point goes through the parameter cache (surfwave.data.cache).
By hand (from the repository root): python workflow/scripts/bulk.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cache, cube
from surfwave.data.variables import CUBES
from surfwave.model_crystals import phonons, sanity
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("bulk")
stage.open_log(snakemake)

job = snakemake.params.job
acc = job["accuracy"]


def compute(pot, direction):
    key = cache.job_key(job, "model_crystals.phonons", "phonopy", potential=pot, direction=direction, **acc)
    return cache.cached_points(
        "bulk", key, job["d_over_d0"],
        lambda d: phonons.bulk_speeds(job["lattice"], job["loading"], pot, direction, d, **acc),
        snakemake.params.cache, chunk=cache.CHUNK,
        label=f"bulk, scene {job['scene']}")


ds = stage.block_cube(job, compute, CUBES["bulk"])
analytic = cube.open_cube(snakemake.input.elastic)
ds, n_implausible = sanity.check_bulk(ds, analytic)
if n_implausible:
    print(f"{n_implausible} points with implausible phonopy speeds set to NaN (see `reason`)", file=sys.stderr)
for name in ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH"):
    dev = ds[f"{name}_phonopy"] - analytic[name].sel(potential=ds.potential, direction=ds.direction)
    meta = CUBES["bulk"][f"{name}_deviation"]
    ds[f"{name}_deviation"] = dev.assign_attrs(long_name=meta["long_name"], units=meta["units"])
print(cache.info(snakemake.params.cache), file=sys.stderr)
cube.finish(ds, snakemake, what="bulk (phonopy)", crystal=snakemake.input.crystal,
            method="phonopy finite-displacement force constants from the pair forces; speeds "
            "from the long-wave dynamical matrix; stability on a Gamma-centred zone mesh")
