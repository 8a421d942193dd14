"""Rule `scene_summary`: results/<scene>/summary.md for a scene that is not the paper's.

By hand (from the repository root): python workflow/scripts/summary.py SCENE [CONFIGFILE ...]
"""
from surfwave.pipeline import stage
from surfwave.report.summary import write_summary

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("scene_summary")
stage.open_log(snakemake)

write_summary(snakemake.input.cubes, snakemake.output[0], snakemake.wildcards.scene)
