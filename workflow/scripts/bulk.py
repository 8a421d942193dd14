"""Rule `bulk`: phonopy sound speeds and full-zone stability, deviation from elastic.nc.

Each (potential, direction, strain) point goes through the parameter cache (surfwave.cache).
By hand (from the repository root): python workflow/scripts/bulk.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave import cache, cube, phonons

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.scenes import standalone

    snakemake = standalone("bulk", inputs={"crystal": "results/{scene}/crystal.nc",
                                           "elastic": "results/{scene}/elastic.nc"})
    snakemake.params.cache = str(cache.DEFAULT_ROOT)
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
acc = job["accuracy"]
code = cache.code_version("phonons")  # entries of older code are never reused
blocks = {}
for pot in job["potentials"]:
    for direction in job["directions"]:
        key = {"code": code, "lattice": job["lattice"], "loading": job["loading"], "potential": pot,
               "direction": direction, "method": "phonopy", **acc}
        r = cache.cached_points(
            "bulk", key, job["d_over_d0"],
            lambda d: phonons.bulk_speeds(job["lattice"], job["loading"], pot, direction, d, **acc),
            snakemake.params.cache)
        blocks[(pot, direction)] = cube.documented(r, phonons.VARIABLES, sys.stderr)
ds = cube.build(blocks, {"potential": job["potentials"], "direction": job["directions"]},
                job["d_over_d0"], phonons.VARIABLES)
analytic = cube.open_cube(snakemake.input.elastic)
for name in ("c2_L_par", "c2_T_par", "c2_L_perp", "c2_T_perp", "c2_SH"):
    dev = ds[f"{name}_phonopy"] - analytic[name].sel(potential=ds.potential, direction=ds.direction)
    ds[f"{name}_deviation"] = dev.assign_attrs(
        long_name=f"{name}_phonopy minus the analytic {name} of elastic.nc", units=analytic[name].attrs["units"])
ds = cube.add_space_group(ds, cube.open_cube(snakemake.input.crystal))
print(cache.info(snakemake.params.cache), file=sys.stderr)
ds = cube.provenance(ds, title=f"surfwave bulk (phonopy) cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method="phonopy finite-displacement force constants from the "
                     "pair forces; speeds from the long-wave dynamical matrix; stability on a "
                     "Gamma-centred zone mesh")
cube.write(ds, snakemake.output[0])
