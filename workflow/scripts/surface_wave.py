"""Rule `surface_wave`: surface waves of real crystals over a scene's grid
(surfwave.real_crystals.sweep.surface_wave_sweep), written as results/<scene>/surface_wave.nc.

By hand (from the repository root): python workflow/scripts/surface_wave.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.pipeline import stage
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.sweep import METHOD, UNITS_NOTE, surface_wave_sweep
from surfwave.vocab import WAVE_TYPES

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("surface_wave")
stage.open_log(snakemake)

job = snakemake.params.job
ds = surface_wave_sweep([get_material(m) for m in job["materials"]], job["surfaces"], job["angles"],
                        stress=job["stress"], loadings=job["loading"], toec=job["toec"], directions=job["directions"],
                        tol=job["accuracy"].get("tol"))
for wave_type in WAVE_TYPES:
    print(f"{wave_type}: {int((ds.wave_type == wave_type).sum())} points", file=sys.stderr)
ds = cube.provenance(ds, title=f"surfwave surface_wave cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method=METHOD, extra={"units_note": UNITS_NOTE})
cube.write(ds, snakemake.output[0])
