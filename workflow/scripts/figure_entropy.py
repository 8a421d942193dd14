"""Rule `figure_entropy`: surface entropy (Eq. 25 estimate and exact) versus strain."""
import sys

from surfwave.data.cube import open_cube
from surfwave.plots.entropy import entropy_vs_strain

if "snakemake" not in globals():  # by hand: python workflow/scripts/figure_entropy.py SCENE
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_entropy")
sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
entropy_vs_strain(open_cube(snakemake.input.cube), snakemake.output[0],  # noqa: F821
                  title=f"surface entropy, triangular lattice (scene {snakemake.wildcards.scene})")  # noqa: F821
