"""Result cubes: dims, CF attributes, provenance, complex/bool/str round trip, atomic write."""
from __future__ import annotations

import json
import os
import stat

import numpy as np
import pytest

from surfwave import __version__
from surfwave.data import cube
from surfwave.errors import InputError

META = {
    "c2_R": {"long_name": "Rayleigh speed squared", "units": "K d0^2 / m", "dims": ()},
    "wave_type": {"long_name": "kind of surface wave", "dims": ()},
    "stable": {"long_name": "stable", "units": "1", "dims": ()},
    "C": {"long_name": "V C_ijkl", "units": "K d0^2", "dims": ("i", "j", "k", "l")},
    "q1": {"long_name": "decay constant", "units": "1", "dims": ("strain", "theta")},
}
D = [0.88, 0.93, 1.0]


def blocks():
    out = {}
    for p in ("harmonic", "lj"):
        for d in ("[100]", "[110]"):
            out[(p, d)] = {"c2_R": np.array([0.1, 0.2, np.nan]),
                           "wave_type": np.array(["surface", "supersonic_decoupled", "none"], dtype=object),
                           "stable": np.array([True, True, False]),
                           "C": np.ones((3, 3, 3, 3, 3))}
    return out


def test_dims_coords_and_attrs():
    ds = cube.build(blocks(), {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D, META)
    assert ds.c2_R.dims == ("potential", "direction", "strain")
    assert ds.C.dims == ("potential", "direction", "strain", "i", "j", "k", "l")
    assert ds.strain.values.tolist() == [-0.12, -0.07, 0.0]  # no float drift in the index
    assert ds.d_over_d0.values.tolist() == D
    assert ds.c2_R.attrs["units"] == "K d0^2 / m" and "units" not in ds.wave_type.attrs
    assert "dims" not in ds.c2_R.attrs
    assert float(ds.c2_R.sel(potential="lj", direction="[110]", strain=-0.07)) == 0.2


def test_metadata_required():
    b = blocks()
    b[("harmonic", "[100]")]["mystery"] = np.zeros(3)
    with pytest.raises(InputError, match="mystery"):
        cube.build({("harmonic", "[100]"): b[("harmonic", "[100]")]},
                   {"potential": ["harmonic"], "direction": ["[100]"]}, D, META)


def test_leading_strain_dim_in_metadata_and_theta_coord():
    theta = np.array([0.1, 0.2])
    b = {("lj",): {"q1": np.full((3, 2), 1 + 2j)}}
    ds = cube.build(b, {"potential": ["lj"]}, D, META, coords={"theta": theta})
    assert ds.q1.dims == ("potential", "strain", "theta")
    assert ds.theta.attrs["units"] == "rad"


def test_roundtrip_provenance_and_atomic_write(tmp_path):
    ds = cube.build(blocks(), {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D, META)
    ds["q"] = (("potential", "strain"), np.full((2, 3), 1 - 1j), {"long_name": "complex", "units": "1"})
    params = {"scene": "t", "stage": "rayleigh", "d_over_d0": D, "accuracy": {"tol": 1e-8}}
    cube.provenance(ds, title="t", params=params, rule="rayleigh", method="m")
    path = cube.write(ds, tmp_path / "sub" / "rayleigh.nc")
    assert [p.name for p in path.parent.iterdir()] == ["rayleigh.nc"]  # no temporary left
    back = cube.open_cube(path)
    assert back.q.dtype.kind == "c" and back.q.values[0, 0] == 1 - 1j
    assert back.stable.dtype == bool and back.wave_type.values[0, 0, 1] == "supersonic_decoupled"
    for attr in ("Conventions", "title", "source", "history", "config_hash", "scene", "method", "accuracy"):
        assert attr in back.attrs
    assert back.attrs["source"] == f"surfwave {__version__}"
    assert "rayleigh" in back.attrs["history"] and back.attrs["config_hash"] in back.attrs["history"]
    assert json.loads(back.attrs["scene"]) == json.loads(json.dumps(params))
    assert json.loads(back.attrs["accuracy"]) == {"tol": 1e-8}
    assert back.attrs["config_hash"] == cube.params_hash(params)
    for name, var in back.data_vars.items():  # the interface checker's rule
        assert "long_name" in var.attrs
        if var.dtype.kind in "iufc":
            assert "units" in var.attrs, name


def test_failed_write_leaves_nothing(tmp_path, monkeypatch):
    ds = cube.build(blocks(), {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D, META)

    def boom(*a, **k):
        raise RuntimeError("disk full")

    monkeypatch.setattr(type(ds), "to_netcdf", boom)
    with pytest.raises(RuntimeError):
        cube.write(ds, tmp_path / "x.nc")
    assert list(tmp_path.iterdir()) == []


def test_write_mode_and_stale_temporaries(tmp_path):
    """A killed earlier write leaves `.x.nc.*.tmp`; the next write of x.nc removes it, and the
    cube is readable by others as an ordinary file would be (mkstemp alone gives 0600)."""
    ds = cube.build(blocks(), {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D, META)
    (tmp_path / ".x.nc.abc123.tmp").write_bytes(b"half a netCDF")
    (tmp_path / ".y.nc.abc123.tmp").write_bytes(b"another file's")
    old = os.umask(0o022)
    try:
        path = cube.write(ds, tmp_path / "x.nc")
    finally:
        os.umask(old)
    assert sorted(p.name for p in tmp_path.iterdir()) == [".y.nc.abc123.tmp", "x.nc"]
    assert stat.S_IMODE(path.stat().st_mode) == 0o644


def test_finish_writes_space_group_and_provenance(tmp_path):
    from types import SimpleNamespace

    crystal = cube.build({(p, d): {"space_group": np.array(["I4/mmm", "Fm-3m", "I4/mmm"])}
                          for p in ("harmonic", "lj") for d in ("[100]", "[110]")},
                         {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D,
                         {"space_group": {"long_name": "space group", "dims": ()}})
    cube.write(crystal, tmp_path / "crystal.nc")
    ds = cube.build(blocks(), {"potential": ["harmonic", "lj"], "direction": ["[100]", "[110]"]}, D, META)
    job = {"scene": "s", "stage": "rayleigh", "accuracy": {}}
    ctx = SimpleNamespace(params=SimpleNamespace(job=job), rule="rayleigh",
                          output=[str(tmp_path / "rayleigh.nc")])
    back = cube.open_cube(cube.finish(ds, ctx, what="rayleigh", method="m",
                                      crystal=tmp_path / "crystal.nc"))
    assert back.space_group.sel(potential="lj", direction="[110]").values[1] == "Fm-3m"
    assert back.attrs["title"] == "surfwave rayleigh cube, scene s" and back.attrs["method"] == "m"
    assert "'rayleigh'" in back.attrs["history"]


def test_add_space_group():
    crystal = cube.build({("lj", "[10]"): {"space_group": np.array(["Cmmm", "P6/mmm", "Cmmm"])}},
                         {"potential": ["lj"], "direction": ["[10]"]}, D,
                         {"space_group": {"long_name": "space group", "dims": ()}})
    ds = cube.build({("lj",): {"c2_R": np.zeros(3)}}, {"potential": ["lj"]}, D, META)
    ds = cube.add_space_group(ds, crystal)
    assert ds.space_group.dims == ("potential", "strain")
    assert ds.space_group.values.tolist() == [["Cmmm", "P6/mmm", "Cmmm"]]
