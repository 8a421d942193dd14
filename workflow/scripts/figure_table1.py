"""Rule `figure_table1`: Table I, paper beside ours (Markdown, CSV, difference plot).

By hand: python workflow/scripts/figure_table1.py  (reads results/table1/*.nc)
"""
import sys

from surfwave.plots.speeds import table1_figure
from surfwave.report.reproduction import table1

if "snakemake" not in globals():  # by hand: python workflow/scripts/figure_table1.py
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_table1")
sys.stderr = open(snakemake.log[0], "w")

table1(snakemake.input.elastic, snakemake.input.rayleigh, snakemake.output.md,
       snakemake.output.csv, paper_values_path=snakemake.input.values)
table1_figure(snakemake.output.csv, snakemake.output.png)
