"""Rule `elastic`: stress, C, S, bulk sound speeds and stability (surfwave.continuum.elastic.properties).

By hand (from the repository root): python workflow/scripts/elastic.py SCENE [CONFIGFILE ...]
"""

from surfwave.continuum import elastic
from surfwave.data import cube
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("elastic")
stage.open_log(snakemake)

job = snakemake.params.job
ds = stage.block_cube(
    job, lambda pot, direction: elastic.properties(job["lattice"], job["loading"], pot, direction,
                                                   job["d_over_d0"]), elastic.VARIABLES)
cube.finish(ds, snakemake, what="elastic", crystal=snakemake.input.crystal,
            method="analytic nearest-neighbour sums (docs/physics/paper.md Appendix, Eq. A11); long-wave "
            f"stability from the acoustic tensor over {elastic.STABILITY_DIRECTIONS} directions, "
            "refined locally")
