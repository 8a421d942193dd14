"""Rule `piezo_wave`: surface waves of piezoelectric crystals over a scene's grid
(surfwave.real_crystals.piezo_sweep.piezo_wave_sweep), written as results/<scene>/surface_wave.nc.

By hand (from the repository root): python workflow/scripts/piezo_wave.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.pipeline import stage
from surfwave.real_crystals.piezo_sweep import METHOD, UNITS_NOTE, piezo_wave_sweep
from surfwave.real_crystals.piezo_wave import stress_model

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("piezo_wave")
stage.open_log(snakemake)

job = snakemake.params.job
toec_file = job.get("toec_file")  # the file's content, read and checked at scene validation
ds = piezo_wave_sweep(job["materials"], cuts=job["cuts"], euler=job["euler"], electrical=job["electrical"],
                      stress=job["stress"], toec=job.get("toec", [False]),
                      toec_constants=toec_file["constants"] if toec_file else None)
for wave_type in ("surface", "supersonic_decoupled", "pseudo", "none"):
    print(f"{wave_type}: {int((ds.wave_type == wave_type).sum())} points", file=sys.stderr)
print(f"leaky: {int(ds.c_leaky.notnull().sum())} points", file=sys.stderr)
extra = {"units_note": UNITS_NOTE, "stress_model": stress_model(ds.toec.values if "toec" in ds.dims else [False])}
if toec_file:
    extra.update(toec_file=toec_file["path"], toec_file_sha256=toec_file["sha256"],
                 toec_source=str(toec_file["constants"].get("source", "not given")))
ds = cube.provenance(ds, title=f"surfwave piezoelectric surface_wave cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method=METHOD, extra=extra)
cube.write(ds, snakemake.output[0])
