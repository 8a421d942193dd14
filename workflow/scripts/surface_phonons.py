"""Rule `surface_phonons`: semi-infinite FCC surface phonons, soft modes and surface entropy.

By hand (from the repository root): python workflow/scripts/surface_phonons.py SCENE [CONFIGFILE ...]
"""

from surfwave.data import cube
from surfwave.pipeline import stage
from surfwave.pipeline.surface_phonons_cube import surface_phonons_cube

if "snakemake" not in globals():  # standalone run for debugging
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("surface_phonons")
stage.open_log(snakemake)

ds = surface_phonons_cube(snakemake.params.job)
cube.finish(ds, snakemake, what="surface_phonons", crystal=snakemake.input.crystal,
            method="surface Green's function of the semi-infinite crystal by decimation of the layer "
            "force-constant blocks (surfwave.dynamics.fcc_surface_green); exact surface entropy by "
            "per-q log-determinants (surfwave.dynamics.fcc_surface_entropy)")
