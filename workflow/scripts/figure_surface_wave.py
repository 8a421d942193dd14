"""Rule `figure_surface_wave_angles`: c_R and v_L against the propagation angle, one panel
per surface (surfwave.plots.surface_wave.speeds_vs_angle), from results/<scene>/surface_wave.nc.
"""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.surface_wave import speeds_vs_angle

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
speeds_vs_angle(open_cube(snakemake.input.cube), snakemake.output[0],  # noqa: F821
                title=f"scene {snakemake.wildcards.scene}")  # noqa: F821
