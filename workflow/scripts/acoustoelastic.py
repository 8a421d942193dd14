"""Rule `acoustoelastic_table`: acoustoelastic coefficients (1/c_R) dc_R/dsigma at zero stress,
with and without third-order constants, from results/<scene>/surface_wave.nc
(surfwave.report.acoustoelastic), as Markdown and CSV.
"""
import sys

from surfwave.data.cube import open_cube
from surfwave.report.acoustoelastic import write_table

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
write_table(open_cube(snakemake.input.cube), snakemake.output.md, snakemake.output.csv)  # noqa: F821
