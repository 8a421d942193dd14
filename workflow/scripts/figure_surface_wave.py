"""Rules `figure_surface_wave_angles` and `figure_surface_wave_stress`: c_R and v_L against the
propagation angle (one panel per surface), or c_R against the applied stress (one panel per
material and direction), from results/<scene>/surface_wave.nc (surfwave.plots.surface_wave).
"""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots import surface_wave as plots

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
draw = {"angles": plots.speeds_vs_angle, "stress": plots.speeds_vs_stress}[snakemake.params.kind]  # noqa: F821
draw(open_cube(snakemake.input.cube), snakemake.output[0],  # noqa: F821
     title=f"scene {snakemake.wildcards.scene}")  # noqa: F821
