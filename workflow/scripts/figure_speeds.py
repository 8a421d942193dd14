"""Rule `figure_speeds`: Fig. 2 (sound speeds squared and c_R^2 versus stress) of one scene.

By hand: python workflow/scripts/figure_speeds.py SCENE  (reads results/SCENE/*.nc)
"""
import sys

from surfwave.plots.speeds import LOADING_TITLES, fig2

if "snakemake" not in globals():  # by hand: python workflow/scripts/figure_speeds.py SCENE
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_speeds")
sys.stderr = open(snakemake.log[0], "w")

loading = LOADING_TITLES.get(snakemake.params.loading, snakemake.params.loading)
fig2(snakemake.input.elastic, snakemake.input.rayleigh, snakemake.output[0],
     title=f"{snakemake.params.lattice.upper()} (001) surface, {loading} "
           f"(scene {snakemake.wildcards.scene})")
