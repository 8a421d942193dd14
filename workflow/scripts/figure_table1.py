"""Rule `figure_table1`: Table I, paper beside ours (Markdown, CSV, difference plot).

By hand: python workflow/scripts/figure_table1.py  (reads results/table1/*.nc)
"""
import sys
from types import SimpleNamespace

from surfwave.plots.speeds import table1_figure
from surfwave.report.reproduction import table1

if "snakemake" not in globals():  # standalone run for debugging
    r = "results/table1"
    snakemake = SimpleNamespace(
        input=SimpleNamespace(elastic=f"{r}/elastic.nc", rayleigh=f"{r}/rayleigh.nc",
                              values="src/surfwave/data/paper_values.yaml"),
        output=SimpleNamespace(md=f"{r}/table1.md", csv=f"{r}/table1.csv",
                               png=f"{r}/table1_diff.png"), log=["/dev/stderr"])
sys.stderr = open(snakemake.log[0], "w")

table1(snakemake.input.elastic, snakemake.input.rayleigh, snakemake.output.md,
       snakemake.output.csv, paper_values_path=snakemake.input.values)
table1_figure(snakemake.output.csv, snakemake.output.png)
