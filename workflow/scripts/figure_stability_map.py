"""Rule `figure_stability_map`: the FCC stability map (library), its cube and its figure."""
import sys

from surfwave.data import cube
from surfwave.model_crystals import stability_map as sm
from surfwave.plots.stability import plot_stability_map

if "snakemake" not in globals():  # by hand: python workflow/scripts/figure_stability_map.py
    from surfwave.pipeline.standalone import standalone

    snakemake = standalone("figure_stability_map")
sys.stderr = open(snakemake.log[0], "w")  # noqa: F821 (defined by Snakemake)
sys.stdout = sys.stderr
settings = {"scene": "stability_map", "d_over_d0": sm.DEFAULT_GRID.tolist(),
            "accuracy": {"supercell": sm.DEFAULT_SUPERCELL, "displacement": sm.DEFAULT_DISPLACEMENT,
                         "zone_mesh": sm.DEFAULT_ZONE_MESH, "tol": 1e-4}}
ds = sm.stability_map(tol=settings["accuracy"]["tol"])
ds = cube.provenance(ds, title="stability map of prestressed nearest-neighbour FCC", params=settings,
                     rule=snakemake.rule,  # noqa: F821
                     method=ds.attrs["method"])
cube.write(ds, snakemake.output.nc)  # noqa: F821
plot_stability_map(ds, snakemake.output.png)  # noqa: F821
