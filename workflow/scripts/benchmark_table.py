"""Rule `benchmark_table`: results/benchmarks/README_table.md from the benchmark cubes.

By hand: python -c "from surfwave.report.benchmarks import benchmark_table; benchmark_table(['results/benchmarks/rayleigh'], '/dev/stdout')"
"""  # noqa: E501 (a command to copy)
import sys

from surfwave.report.benchmarks import benchmark_table

sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
benchmark_table(snakemake.input.dirs, snakemake.output[0])  # noqa: F821
