"""Rule `figure_dispersion`: omega(theta) of the triangular surface wave, one potential."""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.dispersion import plot_dispersion
from surfwave.plots.labels import potential_label

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
pot = snakemake.wildcards.potential  # noqa: F821
ds = open_cube(snakemake.input.cube).sel(potential=pot)  # noqa: F821
plot_dispersion(ds, snakemake.output[0],  # noqa: F821
                title=f"triangular lattice, {potential_label(pot)} (scene {snakemake.wildcards.scene})")  # noqa: F821
