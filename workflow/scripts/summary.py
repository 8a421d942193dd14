"""Rule `scene_summary`: results/<scene>/summary.md for a scene that is not the paper's."""
import sys

from surfwave.report.summary import write_summary

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
write_summary(snakemake.input.cubes, snakemake.output[0], snakemake.wildcards.scene)  # noqa: F821
