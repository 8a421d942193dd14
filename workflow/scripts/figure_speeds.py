"""Rule `figure_speeds`: Fig. 2 (sound speeds squared and c_R^2 versus stress) of one scene.

By hand: python workflow/scripts/figure_speeds.py SCENE  (reads results/SCENE/*.nc)
"""
import sys
from types import SimpleNamespace

from surfwave.plots.speeds import LOADING_TITLES, fig2

if "snakemake" not in globals():  # standalone run for debugging
    scene = sys.argv[1]
    snakemake = SimpleNamespace(
        input=SimpleNamespace(elastic=f"results/{scene}/elastic.nc",
                              rayleigh=f"results/{scene}/rayleigh.nc"),
        output=[f"results/{scene}/speeds_vs_stress.png"], log=["/dev/stderr"],
        params=SimpleNamespace(lattice="fcc", loading=sys.argv[2] if len(sys.argv) > 2 else ""),
        wildcards=SimpleNamespace(scene=scene))
sys.stderr = open(snakemake.log[0], "w")

loading = LOADING_TITLES.get(snakemake.params.loading, snakemake.params.loading)
fig2(snakemake.input.elastic, snakemake.input.rayleigh, snakemake.output[0],
     title=f"{snakemake.params.lattice.upper()} (001) surface, {loading} "
           f"(scene {snakemake.wildcards.scene})")
