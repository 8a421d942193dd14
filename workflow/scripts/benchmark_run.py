"""Rules `benchmark_method` / `benchmark_workflow`: run benchmarks/bench_X.py OUTDIR.

Runs the script with this interpreter, BLAS/OpenMP threads pinned to the rule's threads,
output and errors to the log. By hand: python benchmarks/bench_X.py OUTDIR
"""
import os
import subprocess
import sys
from pathlib import Path

out = Path(snakemake.output[0])  # noqa: F821 (defined by Snakemake)
out.mkdir(parents=True, exist_ok=True)
threads = str(snakemake.threads)  # noqa: F821
env = dict(os.environ, OMP_NUM_THREADS=threads, OPENBLAS_NUM_THREADS=threads,
           MKL_NUM_THREADS=threads, MPLBACKEND="Agg")
with open(snakemake.log[0], "w") as log:  # noqa: F821
    subprocess.run([sys.executable, snakemake.input.script, str(out)],  # noqa: F821
                   stdout=log, stderr=subprocess.STDOUT, env=env, check=True)
