"""Rule `displacements`: row amplitudes u, v of the triangular surface wave (Fig. 3).

By hand (from the repository root): python workflow/scripts/displacements.py SCENE [CONFIGFILE ...]
"""
import sys

import numpy as np

from surfwave.data import cube
from surfwave.dynamics import dispersion

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("displacements")
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
theta = np.asarray(job["theta"])
results = {(pot,): dispersion.displacements(pot, job["d_over_d0"], theta, job["accuracy"]["n_rows"])
           for pot in job["potentials"]}
# Row counts sized from the decay length may differ between potentials: pad with NaN.
n_rows = max(r["u"].shape[-1] for r in results.values())
for r in results.values():
    pad = [(0, 0)] * (r["u"].ndim - 1) + [(0, n_rows - r["u"].shape[-1])]
    for name in ("u", "v"):
        r[name] = np.pad(r[name], pad, constant_values=np.nan)
ds = cube.build(results, {"potential": job["potentials"]}, job["d_over_d0"], dispersion.VARIABLES,
                coords={"theta": theta, "row": np.arange(n_rows)}, skip=("row",))
cube.finish(ds, snakemake, what="displacements", crystal=snakemake.input.crystal,
            method="row amplitudes U_I = Lambda^I U_0 from the exact decay constants q1, q2 "
            "(Eq. 6a) and omega (Eq. 15)")
