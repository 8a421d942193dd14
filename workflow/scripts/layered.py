"""Rule `layered`: every guided mode of a film stack over a scene's grid
(surfwave.pipeline.layered_scenes.scene_cube), written as results/<scene>/dispersion_layered.nc.

By hand (from the repository root): python workflow/scripts/layered.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.pipeline import stage
from surfwave.pipeline.layered_scenes import METHOD, UNITS_NOTE, scene_cube

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("layered")
stage.open_log(snakemake)

job = snakemake.params.job
ds = scene_cube(job)
for mode in ds["mode"].values:
    print(f"mode {mode}: {int(ds.c.sel(mode=mode).notnull().sum())} points", file=sys.stderr)
print(f"no mode: {int((ds.reason != '').sum())} rows", file=sys.stderr)
ds = cube.provenance(ds, title=f"surfwave dispersion_layered cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method=METHOD, extra={"units_note": UNITS_NOTE})
cube.write(ds, snakemake.output[0])
