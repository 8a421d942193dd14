"""Rule `elastic`: stress, C, S, bulk sound speeds and stability (surfwave.elastic.properties).

By hand (from the repository root): python workflow/scripts/elastic.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave import cube, elastic

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.scenes import standalone

    snakemake = standalone("elastic", inputs={"crystal": "results/{scene}/crystal.nc"})
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
blocks = {
    (pot, direction): cube.documented(
        elastic.properties(job["lattice"], job["loading"], pot, direction, job["d_over_d0"]),
        elastic.VARIABLES,
    )
    for pot in job["potentials"]
    for direction in job["directions"]
}
ds = cube.build(blocks, {"potential": job["potentials"], "direction": job["directions"]},
                job["d_over_d0"], elastic.VARIABLES)
ds = cube.add_space_group(ds, cube.open_cube(snakemake.input.crystal))
ds = cube.provenance(ds, title=f"surfwave elastic cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method="analytic nearest-neighbour sums (PHYSICS.md Appendix, "
                     "Eq. A11); long-wave stability from the acoustic tensor over "
                     f"{elastic.STABILITY_DIRECTIONS} directions, refined locally")
cube.write(ds, snakemake.output[0])
