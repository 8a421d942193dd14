"""Rule `elastic`: stress, C, S, bulk sound speeds and stability (surfwave.model_crystals.elastic.properties).

By hand (from the repository root): python workflow/scripts/elastic.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.data.variables import CUBES
from surfwave.model_crystals import elastic
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("elastic")
stage.open_log(snakemake)

job = snakemake.params.job
if job.get("angles") is not None:  # FCC propagation angles in the (001) surface (degrees)
    from surfwave.model_crystals import fcc_angles

    blocks = {}
    for pot in job["potentials"]:
        out = fcc_angles.properties_at_angles(pot, job["angles"], job["d_over_d0"], job["loading"])
        for i, angle in enumerate(job["angles"]):
            blocks[(pot, angle)] = cube.documented({k: v[i] for k, v in out.items()},
                                                   CUBES["elastic"], sys.stderr)
    ds = cube.build(blocks, {"potential": job["potentials"], "angle": job["angles"]},
                    job["d_over_d0"], CUBES["elastic"])
else:
    ds = stage.block_cube(
        job, lambda pot, direction: elastic.properties(job["lattice"], job["loading"], pot, direction,
                                                       job["d_over_d0"]), CUBES["elastic"])
cube.finish(ds, snakemake, what="elastic", crystal=snakemake.input.crystal,
            method="analytic nearest-neighbour sums (docs/physics/paper.md Appendix, Eq. A11); long-wave "
            f"stability from the acoustic tensor over {elastic.STABILITY_DIRECTIONS} directions, "
            "refined locally")
