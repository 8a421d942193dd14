"""The dispersion_layered cube: labelled, CF-attributed, and holding surfwave.layered's numbers."""
from __future__ import annotations

import numpy as np
import xarray as xr

import surfwave
from surfwave.data import cube
from surfwave.layers.cube import dispersion_cube


def test_cube_holds_the_api_numbers_and_reads_back(tmp_path):
    """Each (film_stress, kh, mode) entry equals surfwave.layered's value for that label; every variable
    and coordinate has long_name (and units when numeric: the rule of shared/tools/check_cubes.py); the
    file round-trips through netCDF."""
    films = [{"name": "SiO2", "thickness": 1e-6}]
    ds = dispersion_cube("Si", films, [0.5, 2.0], film_stress=[-0.5, 0.5])
    assert dict(ds.sizes)["film_stress"] == 2 and "R" in ds.mode.values
    r = surfwave.layered("Si", [{**films[0], "stress": 0.5}], kh=[0.5, 2.0])
    for i, row in enumerate(r["mode"]):
        for j, lab in enumerate(row):
            if lab:
                assert ds.c.sel(film_stress=0.5, electrical="free", mode=lab).values[i] == r["c"][i, j]
    for name in list(ds.data_vars) + list(ds.coords):
        need = {"long_name", "units"} if ds[name].dtype.kind in "iufc" else {"long_name"}   # labels: no units
        assert need <= set(ds[name].attrs), name
    ds = cube.provenance(ds, title="test", params={"scene": "t"}, rule="test", method="layers")
    path = cube.write(ds, tmp_path / "dispersion_layered.nc")
    back = xr.open_dataset(path, engine="h5netcdf")
    np.testing.assert_array_equal(back.c.values, ds.c.values)
    assert back.film_bulk_speed.shape == (1, 3)
