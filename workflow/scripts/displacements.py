"""Rule `displacements`: row amplitudes u, v of the triangular surface wave (Fig. 3).

By hand (from the repository root): python workflow/scripts/displacements.py SCENE [CONFIGFILE ...]
"""
import numpy as np

from surfwave.data import cube
from surfwave.data.variables import CUBES
from surfwave.dynamics import dispersion
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("displacements")
stage.open_log(snakemake)

job = snakemake.params.job
theta = np.asarray(job["theta"])


def compute(pot):
    return dispersion.displacements(pot, job["d_over_d0"], theta, job["accuracy"]["n_rows"])


# Row counts sized from the decay length may differ between potentials: padded with NaN.
ds = stage.block_cube(job, compute, CUBES["displacements"], by=("potential",), ragged=("row", ("u", "v")),
                      coords={"theta": theta}, skip=("row",))
cube.finish(ds, snakemake, what="displacements", crystal=snakemake.input.crystal,
            method="row amplitudes U_I = Lambda^I U_0 from the exact decay constants q1, q2 "
            "(Eq. 6a) and omega (Eq. 15)")
