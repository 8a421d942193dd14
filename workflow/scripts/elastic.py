"""Rule `elastic`: stress, C, S, bulk sound speeds and stability (surfwave.continuum.elastic.properties).

By hand (from the repository root): python workflow/scripts/elastic.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.continuum import elastic

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("elastic")
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
blocks = {
    (pot, direction): cube.documented(
        elastic.properties(job["lattice"], job["loading"], pot, direction, job["d_over_d0"]),
        elastic.VARIABLES,
        sys.stderr,
    )
    for pot in job["potentials"]
    for direction in job["directions"]
}
ds = cube.build(blocks, {"potential": job["potentials"], "direction": job["directions"]},
                job["d_over_d0"], elastic.VARIABLES)
cube.finish(ds, snakemake, what="elastic", crystal=snakemake.input.crystal,
            method="analytic nearest-neighbour sums (docs/physics/paper.md Appendix, Eq. A11); long-wave "
            f"stability from the acoustic tensor over {elastic.STABILITY_DIRECTIONS} directions, "
            "refined locally")
