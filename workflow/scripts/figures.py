"""Rule `figures_<scene>`: every figure and table of one scene (surfwave.plots.figure_set.draw_figure_set).

By hand (from the repository root): python workflow/scripts/figures.py SCENE [CONFIGFILE ...]
"""
from surfwave.pipeline import stage
from surfwave.plots.figure_set import draw_figure_set

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figures_{scene}")
stage.open_log(snakemake)

draw_figure_set(dict(snakemake.output.items()),
           {name: snakemake.input[name] for name in snakemake.params.cubes},
           snakemake.wildcards.scene, snakemake.params.spec, paper_values=snakemake.input.values)
