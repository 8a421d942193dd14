"""Rule `crystal`: space group and mirror planes of every prestressed cell of a scene.

By hand (from the repository root): python workflow/scripts/crystal.py SCENE [CONFIGFILE ...]
"""
import sys

from surfwave.data import cube
from surfwave.data.variables import CUBES
from surfwave.model_crystals import symmetry
from surfwave.pipeline import stage

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("crystal")
stage.open_log(snakemake)

job = snakemake.params.job


def analyse(pot, direction):
    stats = {}
    r = symmetry.crystal_symmetry(job["lattice"], job["loading"], pot, direction,
                                  job["d_over_d0"], **job["accuracy"], stats=stats)
    symmetry.require_mirrors(r, job["d_over_d0"], f"scene {job['scene']!r}, {job['lattice']} "
                             f"{job['loading']} {direction}, potential {pot!r}: ")
    groups = {g: int((r["space_group"] == g).sum()) for g in dict.fromkeys(r["space_group"].tolist())}
    print(f"{pot} {direction}: space groups (points) {groups}; mirrors x, z present; "
          f"{stats['classes']} symmetry classes, {stats['spglib_calls']} spglib calls "
          f"({stats['in_doubt']} cells near a special strain)", file=sys.stderr)
    return r


ds = stage.block_cube(job, analyse, CUBES["crystal"])
cube.finish(ds, snakemake, what="crystal",
            method=symmetry.METHOD + " (one-atom primitive cell; 2D lattices padded with vacuum)")
