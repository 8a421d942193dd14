"""Rule `rayleigh`: Rayleigh speed c_R^2 (Eq. 17, root selection) and wave type (surfwave.point).

By hand (from the repository root): python workflow/scripts/rayleigh.py SCENE [CONFIGFILE ...]
"""
import sys

import surfwave
from surfwave import cube, rayleigh

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.scenes import standalone

    snakemake = standalone("rayleigh", inputs={"crystal": "results/{scene}/crystal.nc"})
sys.stderr = open(snakemake.log[0], "w")

job = snakemake.params.job
blocks = {}
for pot in job["potentials"]:
    for direction in job["directions"]:
        r = surfwave.point(job["lattice"], job["loading"], pot, direction, job["d_over_d0"])
        blocks[(pot, direction)] = {k: v for k, v in r.items() if k in rayleigh.VARIABLES}  # this stage's part
ds = cube.build(blocks, {"potential": job["potentials"], "direction": job["directions"]},
                job["d_over_d0"], rayleigh.VARIABLES)
ds = cube.add_space_group(ds, cube.open_cube(snakemake.input.crystal))
ds = cube.provenance(ds, title=f"surfwave rayleigh cube, scene {job['scene']}", params=job,
                     rule=snakemake.rule, method="Eq. (17) secular equation; root in "
                     "0 < rho c^2 < min(S_xyyx, S_xxxx) satisfying the unsquared boundary condition "
                     "with decaying partial waves")
cube.write(ds, snakemake.output[0])
