"""Rule `acoustoelastic`: c_R against the applied stress (surfwave.plots.surface_wave) and the
acoustoelastic coefficients (1/c_R) dc_R/dsigma at zero stress, with and without third-order
constants (surfwave.report.acoustoelastic), from results/<scene>/surface_wave.nc.
"""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.surface_wave import speeds_vs_stress
from surfwave.report.acoustoelastic import write_table

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
ds = open_cube(snakemake.input.cube)  # noqa: F821
speeds_vs_stress(ds, snakemake.output.png, title=f"scene {snakemake.wildcards.scene}")  # noqa: F821
write_table(ds, snakemake.output.md, snakemake.output.csv)  # noqa: F821
