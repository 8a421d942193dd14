"""Rule `figure_surface_wave_angles`: c_R and v_L against the propagation angle, one panel
per surface (surfwave.plots.surface_wave.speeds_vs_angle), from results/<scene>/surface_wave.nc.

By hand (from the repository root): python workflow/scripts/figure_surface_wave.py SCENE [CONFIGFILE ...]
"""

from surfwave.data.cube import open_cube
from surfwave.plots.surface_wave import speeds_vs_angle
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_surface_wave_angles")
stage.open_log(snakemake)
speeds_vs_angle(open_cube(snakemake.input.cube), snakemake.output[0],
                title=f"scene {snakemake.wildcards.scene}")
