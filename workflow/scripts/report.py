"""Rule `report_md`: results/report.md from the cubes and the paper's printed values.

By hand: python -m surfwave.report.reproduction results   (every cube found under results/)
"""
import sys

from surfwave.report.reproduction import write_report

if "snakemake" not in globals():  # by hand: python workflow/scripts/report.py
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("report_md")
sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
write_report(snakemake.input.cubes, snakemake.output[0],  # noqa: F821
             paper_values_path=snakemake.input.values)  # noqa: F821
