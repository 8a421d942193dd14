"""Rule `figure_stability_map`: surfwave.plots.stability.main into results/stability_map/."""
import sys
from pathlib import Path

from surfwave.plots.stability import main

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
sys.stdout = sys.stderr
main(str(Path(snakemake.output.nc).parent))  # noqa: F821
