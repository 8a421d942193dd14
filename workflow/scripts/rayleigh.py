"""Rule `rayleigh`: Rayleigh speed c_R^2 (Eq. 17, root selection) and wave type from the
stress derivatives S of elastic.nc (surfwave.solvers.rayleigh.solve).

By hand (from the repository root): python workflow/scripts/rayleigh.py SCENE [CONFIGFILE ...]
"""

from surfwave.data import cube
from surfwave.data.variables import CUBES
from surfwave.pipeline import stage
from surfwave.solvers import rayleigh

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("rayleigh")
stage.open_log(snakemake)

job = snakemake.params.job
elastic = cube.open_cube(snakemake.input.elastic)


def solve(pot, direction):
    point = elastic.sel(potential=pot, direction=direction)
    # m = 1 per atom and S is V S, so rho = 1 gives c^2 in K d0^2/m.
    return rayleigh.solve(point["S"].values, 1.0, point["c2_SH"].values)


blocks = {}
if job.get("angles") is not None:  # FCC propagation angles: the general solver off the mirrors
    from surfwave.model_crystals import fcc_angles

    for pot in job["potentials"]:
        point = elastic.sel(potential=pot).transpose("angle", "strain", ...)
        result = fcc_angles.rayleigh_at_angles(point["C"].values, point["stress"].values,
                                               point["S"].values, job["angles"])
        for i, angle in enumerate(job["angles"]):
            blocks[(pot, angle)] = {k: v[i] for k, v in result.items()}
    ds = cube.build(blocks, {"potential": job["potentials"], "angle": job["angles"]},
                    job["d_over_d0"], CUBES["rayleigh_angles"])
else:
    ds = stage.block_cube(job, solve, CUBES["rayleigh"])
ds = ds.assign_coords(space_group=elastic["space_group"])
cube.finish(ds, snakemake, what="rayleigh",
            method="Eq. (17) secular equation; root in 0 < rho c^2 < min(S_xyyx, S_xxxx) "
            "satisfying the unsquared boundary condition with decaying partial waves"
            + ("; off the mirror angles the general Stroh surface-impedance solver"
               if job.get("angles") is not None else ""))
