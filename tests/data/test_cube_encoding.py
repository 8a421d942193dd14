"""Complex values readable by plain xarray; damaged cubes detected with one clear line.

References: the written values themselves (round trip), and the HDF5 format's own check of
a truncated file (its superblock records the end-of-file address).
"""

import numpy as np
import xarray as xr

from surfwave.data import cube
from surfwave.data.integrity import check_readable, set_aside_damaged


def _complex_cube():
    q = np.array([[0.1 + 0.2j, -0.3 + 0.0j]])
    return xr.Dataset(
        {"q1": (("strain", "theta"), q, {"long_name": "decay constant", "units": "1"}),
         "omega": (("strain", "theta"), np.ones((1, 2)), {"long_name": "omega", "units": "1"})},
        coords={"strain": [0.0], "theta": [0.5, 1.0]})


def test_plain_open_dataset_reads_numbers(tmp_path):
    """Plain xr.open_dataset (no engine) gives float parts along 'complex', CF-style labelled;
    open_cube gives the complex values back exactly."""
    ds = _complex_cube()
    path = cube.write(ds, tmp_path / "d.nc")
    with xr.open_dataset(path) as plain:
        assert plain.q1.dtype.kind == "f"
        assert plain.q1.dims == ("strain", "theta", "complex")
        assert list(plain["complex"].values) == ["real", "imag"]
        assert plain.q1.attrs["complex_dimension"] == "complex"
        assert plain.q1.attrs["units"] == "1"
        np.testing.assert_array_equal(plain.q1.sel(complex="imag").values, ds.q1.values.imag)
    back = cube.open_cube(path)
    assert back.q1.dtype.kind == "c" and "complex" not in back.dims
    np.testing.assert_array_equal(back.q1.values, ds.q1.values)
    assert "complex_dimension" not in back.q1.attrs
    xr.testing.assert_identical(back.omega, ds.omega)


def test_netcdf_tools_without_complex_support_read_it(tmp_path):
    """h5py (as any HDF5/netCDF tool) sees a plain float64 variable, no compound type."""
    import h5py

    path = cube.write(_complex_cube(), tmp_path / "d.nc")
    with h5py.File(path, "r") as fh:
        assert fh["q1"].dtype == np.float64 and fh["q1"].shape == (1, 2, 2)


def _truncated(tmp_path):
    path = cube.write(_complex_cube(), tmp_path / "scene" / "rayleigh.nc")
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])
    return path


def test_open_cube_names_damaged_file_and_rebuild_command(tmp_path):
    """A truncated cube gives one line: the file, what is wrong, the command that rebuilds it."""
    path = _truncated(tmp_path)
    try:
        cube.open_cube(path)
    except cube.DamagedCubeError as exc:
        msg = str(exc)
    assert "\n" not in msg and str(path) in msg and "truncated" in msg
    assert f"snakemake -j2 {path}" in msg


def test_damaged_cube_is_set_aside_for_rebuild(tmp_path):
    """set_aside_damaged (called by the Snakefile at parse time) moves a truncated cube out of
    the way, so Snakemake rebuilds it; a good cube is left alone."""
    bad = _truncated(tmp_path)
    good = cube.write(_complex_cube(), tmp_path / "scene" / "elastic.nc")
    assert check_readable(good) is None and "truncated" in check_readable(bad)
    lines = set_aside_damaged([bad, good, tmp_path / "missing.nc"])
    assert len(lines) == 1 and str(bad) in lines[0] and "rebuilds" in lines[0]
    assert not bad.exists() and bad.with_name("rayleigh.nc.damaged").exists() and good.exists()


def test_legacy_native_complex_cube_still_opens(tmp_path):
    """A cube written before the real/imag convention (native complex as an HDF5 compound,
    h5netcdf with invalid_netcdf) opens with open_cube as complex values (reference: the
    values written)."""
    import warnings

    import numpy as np
    import xarray as xr

    from surfwave.data.cube import open_cube

    q = np.array([1 + 2j, 3 - 1j, -0.5j])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # h5netcdf warns that the file is not plain netCDF
        xr.Dataset({"q1": ("theta", q)}).to_netcdf(tmp_path / "old.nc", engine="h5netcdf", invalid_netcdf=True)
    ds = open_cube(tmp_path / "old.nc")
    assert ds.q1.dtype.kind == "c" and np.array_equal(ds.q1.values, q)
