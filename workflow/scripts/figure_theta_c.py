"""Rule `figure_theta_c`: crossover theta_c versus d/d0, one curve per potential."""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.dispersion import plot_theta_c

if "snakemake" not in globals():  # by hand: python workflow/scripts/figure_theta_c.py SCENE
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_theta_c")
sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
ds = open_cube(snakemake.input.cube)  # noqa: F821
pots = [str(p) for p in ds["potential"].values]
plot_theta_c([ds.sel(potential=p) for p in pots], snakemake.output[0],  # noqa: F821
             title=f"triangular lattice (scene {snakemake.wildcards.scene})",  # noqa: F821
             potential_labels=pots)
