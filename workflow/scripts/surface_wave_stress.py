"""Rule `surface_wave_stress`: c_R against the applied stress (surfwave.plots.surface_wave) and the
acoustoelastic coefficients (1/c_R) dc_R/dsigma at zero stress, with and without third-order
constants (surfwave.report.acoustoelastic), from results/<scene>/surface_wave.nc.

By hand (from the repository root): python workflow/scripts/surface_wave_stress.py SCENE [CONFIGFILE ...]
"""

from surfwave.data.cube import open_cube
from surfwave.plots.surface_wave import speeds_vs_stress
from surfwave.report.acoustoelastic import write_table
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("surface_wave_stress")
stage.open_log(snakemake)
ds = open_cube(snakemake.input.cube)
speeds_vs_stress(ds, snakemake.output.png, title=f"scene {snakemake.wildcards.scene}")
write_table(ds, snakemake.output.md, snakemake.output.csv)
