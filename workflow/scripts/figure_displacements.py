"""Rule `figure_displacements`: Fig. 3, displacement patterns at zero stress, a few theta."""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.speeds import FIG3_ROWS, FIG3_THETA, nearest_indices
from surfwave.plots.dispersion import plot_displacements

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
pot = snakemake.wildcards.potential  # noqa: F821
ds = open_cube(snakemake.input.cube)  # noqa: F821
ds = ds.isel(theta=nearest_indices(ds["theta"].values, FIG3_THETA), row=slice(0, FIG3_ROWS))
plot_displacements(ds, snakemake.output[0], potential=pot)  # noqa: F821
