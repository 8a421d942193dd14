"""Result cubes: labelled xarray Datasets with CF attributes and provenance, netCDF I/O.

The cubes are the public interface (docs/cubes.md): dims (potential, direction, strain),
(potential, strain, theta[, row]) or (potential, strain); ``strain`` = d/d0 - 1 with the
auxiliary coordinate ``d_over_d0``. Every numeric variable carries ``long_name`` and
``units``, string and flag variables a ``long_name``. Files are written atomically
(temporary file + ``os.replace``) with an explicit engine.

Complex values (``q1``, ``q2``, ``R1``, ``R2``, ``amplitude_ratio``, ``u``, ``v``) are
stored as real numbers with a trailing dimension ``complex`` of length 2 (coordinate
``["real", "imag"]``) and the variable attribute ``complex_dimension = "complex"``, so that
plain ``xr.open_dataset`` and netCDF tools that know nothing of complex numbers read
numbers (docs/cubes.md, "Complex values"); :func:`open_cube` returns them complex again.

Examples
--------
>>> import numpy as np
>>> meta = {"c2_R": {"long_name": "Rayleigh speed squared", "units": "K d0^2 / m", "dims": ()}}
>>> blocks = {("lj", "[100]"): {"c2_R": np.array([0.5, 0.6])}}
>>> ds = build(blocks, {"potential": ["lj"], "direction": ["[100]"]}, [0.99, 1.0], meta)
>>> ds.c2_R.dims, float(ds.strain[0])
(('potential', 'direction', 'strain'), -0.01)
"""
from __future__ import annotations

import datetime as _dt
import hashlib
import json
import subprocess
from pathlib import Path
from typing import Any, Final, Mapping, TextIO

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike

from surfwave import __version__
from surfwave.data.atomic import atomic_write
from surfwave.data.integrity import check_readable, rebuild_hint
from surfwave.data.variables import MODEL_COORDS
from surfwave.errors import DamagedCubeError, InputError

#: netCDF engine used on write and read: the netCDF-C library (netCDF4-python); on this
#: machine it writes a cube 4-5x and opens one 7x faster than h5netcdf.
ENGINE: Final = "netcdf4"
CONVENTIONS = "CF-1.10"
#: Trailing dimension holding the real and imaginary parts of a complex variable.
COMPLEX_DIM = "complex"
#: Variable attribute naming that dimension (the marker :func:`open_cube` decodes).
COMPLEX_ATTR = "complex_dimension"

#: Attributes of the coordinates (the one table: surfwave.data.variables).
COORDS = MODEL_COORDS


def strain_coords(d_over_d0: ArrayLike) -> dict[str, Any]:
    """Coordinates ``strain`` (index, = d/d0 - 1, rounded to 12 decimals) and ``d_over_d0``."""
    d = np.asarray(d_over_d0, dtype=float)
    strain = np.round(d - 1.0, 12)
    return {
        "strain": ("strain", strain, COORDS["strain"]),
        "d_over_d0": ("strain", d, COORDS["d_over_d0"]),
    }


def _as_var(values: np.ndarray):
    a = np.asarray(values)
    if a.dtype.kind in "OSU":
        a = a.astype(str)
    return a


def build(
    blocks: Mapping[tuple, Mapping[str, np.ndarray]],
    outer: Mapping[str, list],
    d_over_d0: ArrayLike,
    variables: Mapping[str, Mapping[str, Any]],
    coords: Mapping[str, Any] | None = None,
    skip: tuple[str, ...] = (),
) -> xr.Dataset:
    """Stack per-(outer label) results into one cube.

    Parameters
    ----------
    blocks : mapping
        (label, ...) -> {name: array with leading strain axis}; one key per combination of
        the ``outer`` labels, in the order of ``outer``'s dims.
    outer : mapping
        Outer dims and their labels, e.g. {"potential": [...], "direction": [...]}.
    d_over_d0 : array_like, shape (n,)
    variables : mapping
        name -> {"long_name", "units" (numeric only), "dims" (after the strain axis)}.
        Every array in ``blocks`` needs an entry, unless listed in ``skip``.
    coords : mapping, optional
        Extra index coordinates of inner dims, e.g. {"theta": theta, "row": rows}.
    skip : tuple of str
        Names in ``blocks`` not to write.

    Returns
    -------
    xarray.Dataset
        Dims outer + ("strain",) + each variable's inner dims.

    Raises
    ------
    InputError
        A variable without metadata, or a block missing.
    """
    dims = list(outer)
    labels = [list(outer[d]) for d in dims]
    shape = [len(x) for x in labels]
    keys = list(np.ndindex(*shape))
    names = None
    # Each block is copied into its slot as soon as it is read, so a lazy ``blocks`` (see
    # surfwave.pipeline.stage.block_cube) never holds more than one block besides the cube.
    filled: dict[str, np.ndarray] = {}
    strings: dict[str, list] = {}  # text: stacked at the end (the longest label sets the width)
    for idx in keys:
        key = tuple(labels[a][i] for a, i in enumerate(idx))
        if key not in blocks:
            raise InputError(f"no results for {dict(zip(dims, key))}")
        block = {k: v for k, v in blocks[key].items() if k not in skip}
        if names is None:
            names = list(block)
            missing = [n for n in names if n not in variables]
            if missing:
                raise InputError(f"variables without metadata (long_name, units, dims): {missing}")
        for n in names:
            value = _as_var(block[n])
            if value.dtype.kind == "U":
                strings.setdefault(n, []).append(value)
                continue
            if n not in filled:
                filled[n] = np.empty(shape + list(value.shape), dtype=value.dtype)
            elif filled[n].shape[len(shape):] != value.shape:
                raise InputError(f"variable {n!r} has shape {value.shape} for {dict(zip(dims, key))}, "
                                 f"{filled[n].shape[len(shape):]} for the first block")
            elif np.result_type(filled[n], value) != filled[n].dtype:
                filled[n] = filled[n].astype(np.result_type(filled[n], value))
            filled[n][idx] = value
        del block
    data_vars = {}
    for n in names or []:
        meta = dict(variables[n])
        inner = tuple(meta.pop("dims", ()))
        if inner[:1] == ("strain",):  # some modules list the leading strain axis too
            inner = inner[1:]
        arr = (filled[n] if n in filled else
               np.stack(strings[n]).reshape(shape + list(strings[n][0].shape)))
        vdims = tuple(dims) + ("strain",) + inner
        if arr.ndim != len(vdims):
            raise InputError(f"variable {n!r} has shape {arr.shape[len(dims):]}, expected dims {vdims[len(dims):]}")
        if arr.dtype.kind in "bU":
            meta.pop("units", None)
        data_vars[n] = (vdims, arr, meta)
    all_coords: dict[str, Any] = {d: (d, np.asarray(labels[a]), COORDS.get(d, {})) for a, d in enumerate(dims)}
    all_coords.update(strain_coords(d_over_d0))
    for name, values in (coords or {}).items():
        all_coords[name] = (name, np.asarray(values), COORDS.get(name, {}))
    return xr.Dataset(data_vars, coords=all_coords)


def add_space_group(ds: xr.Dataset, crystal: xr.Dataset) -> xr.Dataset:
    """Attach ``space_group`` from a crystal cube as a non-index coordinate of ``ds``.

    ``crystal`` has dims (potential, direction, strain); a ``ds`` without a direction dim
    (triangular cubes) gets the single direction's values.
    """
    sg = crystal["space_group"].sel(potential=ds["potential"].values)
    sg = sg.sel(strain=ds["strain"].values, method="nearest")
    if "direction" in ds.dims:
        sg = sg.sel(direction=ds["direction"].values)
    else:
        sg = sg.isel(direction=0, drop=True)
    sg = sg.drop_vars([c for c in sg.coords if c not in sg.dims])
    return ds.assign_coords(space_group=(sg.dims, sg.values.astype(str), dict(crystal["space_group"].attrs)))


def params_hash(params: Mapping[str, Any]) -> str:
    """sha256 (hex, first 16 characters) of the canonical JSON of a job's parameters."""
    text = json.dumps(dict(params), sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest()[:16]


def documented(result: Mapping[str, np.ndarray], variables: Mapping[str, Any], log: TextIO | None = None) -> dict:
    """The arrays of ``result`` that have metadata in ``variables``; the others are reported to ``log``."""
    dropped = sorted(k for k in result if k not in variables)
    if dropped and log is not None:
        print(f"not written (no metadata in VARIABLES): {dropped}", file=log)
    return {k: v for k, v in result.items() if k in variables}


def git_commit() -> str | None:
    """The commit of the surfwave source tree ("-dirty" if tracked files changed), or None."""
    here = Path(__file__).resolve().parent
    try:
        head = subprocess.run(["git", "-C", str(here), "rev-parse", "HEAD"], capture_output=True,
                              text=True, timeout=5, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", str(here), "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, timeout=5, check=True).stdout.strip()
    except (OSError, subprocess.SubprocessError):
        return None
    return head + ("-dirty" if dirty else "") if head else None


def provenance(
    ds: xr.Dataset,
    *,
    title: str,
    params: Mapping[str, Any],
    rule: str,
    method: str,
    extra: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """Set the global attributes (CF + provenance) of a cube and return it.

    ``params`` are the job's parameters (:func:`surfwave.pipeline.scenes.job_params`): they are
    recorded as the ``scene`` attribute (JSON) and hashed into ``config_hash``; their
    ``accuracy`` block is recorded as ``accuracy`` (JSON). Dicts in ``extra`` become JSON.
    """
    chash = params_hash(dict(params))
    now = _dt.datetime.now(_dt.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ")
    attrs = {
        "Conventions": CONVENTIONS,
        "title": title,
        "source": f"surfwave {__version__}",
        "history": f"{now}: written by Snakemake rule {rule!r} (surfwave {__version__}), config hash {chash}",
        "institution": "surfwave workflow",
        "references": "Rayleigh waves in prestressed crystals, Phys. Rev. B (seed paper); docs/physics/paper.md",
        "scene": json.dumps(dict(params), sort_keys=True),
        "scene_name": str(params.get("scene", "")),
        "config_hash": chash,
        "method": method,
        "accuracy": json.dumps(params.get("accuracy", {}), sort_keys=True),
        "units_note": "reduced units: d0 = 1, m = 1, K = phi''(d0) = 1",
    }
    commit = git_commit()
    if commit:
        attrs["git_commit"] = commit
    for k, v in (extra or {}).items():
        attrs[k] = json.dumps(v, sort_keys=True) if isinstance(v, (dict, list, tuple)) else v
    ds.attrs.update(attrs)
    return ds


def finish(ds: xr.Dataset, job_context: Any, *, what: str, method: str,
           crystal: str | Path | None = None) -> Path:
    """The common end of every stage script: space groups, provenance, atomic write.

    Parameters
    ----------
    ds : xarray.Dataset
        The cube (from :func:`build`).
    job_context : object
        Snakemake's ``snakemake`` object (or :func:`surfwave.pipeline.standalone.standalone`): uses
        ``params.job`` (:func:`surfwave.pipeline.scenes.job_params`), ``rule`` and ``output[0]``.
    what : str
        Cube name for the title, e.g. ``"elastic"``.
    method : str
        How the values were computed (the ``method`` attribute).
    crystal : path, optional
        The scene's ``crystal.nc``: its ``space_group`` becomes a coordinate of ``ds``.

    Returns
    -------
    pathlib.Path
        The written file.
    """
    job = job_context.params.job
    if crystal is not None:
        ds = add_space_group(ds, open_cube(crystal))
    ds = provenance(ds, title=f"surfwave {what} cube, scene {job['scene']}", params=job,
                    rule=job_context.rule, method=method)
    return write(ds, job_context.output[0])


def write(ds: xr.Dataset, path: str | Path) -> Path:
    """Write ``ds`` to ``path`` atomically (:func:`surfwave.data.atomic.atomic_write`).

    Readers never see a half-written cube and a killed job never leaves one at ``path``;
    temporary files of an earlier, killed write of the same path are removed first. The file gets the
    permissions of an ordinary new file under the current umask.
    """
    path = Path(path)
    for stale in path.parent.glob(f".{path.name}.*.tmp"):  # left by a killed writer of this
        stale.unlink(missing_ok=True)                       # file (one job writes each path)
    return atomic_write(path, lambda tmp: encode_complex(ds).to_netcdf(tmp, engine=ENGINE))


def encode_complex(ds: xr.Dataset) -> xr.Dataset:
    """Complex variables as real ones with a trailing dimension ``complex`` = [real, imag].

    Each encoded variable gets the attribute ``complex_dimension = "complex"`` (and keeps
    its ``long_name`` and ``units``); real variables are untouched.

    Parameters
    ----------
    ds : xarray.Dataset

    Returns
    -------
    xarray.Dataset
        A new dataset without complex dtypes (``ds`` itself when it has none).
    """
    names = [n for n, v in ds.variables.items() if v.dtype.kind == "c"]
    if not names:
        return ds
    out = ds.copy()
    for n in names:
        var = ds[n].variable
        parts = np.stack([var.values.real, var.values.imag], axis=-1)
        attrs = dict(var.attrs, **{COMPLEX_ATTR: COMPLEX_DIM})
        out[n] = (var.dims + (COMPLEX_DIM,), parts, attrs)
    return out.assign_coords({COMPLEX_DIM: (COMPLEX_DIM, np.array(["real", "imag"]),
                                            COORDS[COMPLEX_DIM])})


def decode_complex(ds: xr.Dataset) -> xr.Dataset:
    """Inverse of :func:`encode_complex`: variables marked ``complex_dimension`` become complex."""
    names = [n for n, v in ds.variables.items() if v.attrs.get(COMPLEX_ATTR) == COMPLEX_DIM
             and v.dims[-1:] == (COMPLEX_DIM,)]
    if not names:
        return ds
    out = ds.copy()
    for n in names:
        var = ds[n].variable
        values = var.values[..., 0] + 1j * var.values[..., 1]
        attrs = {k: v for k, v in var.attrs.items() if k != COMPLEX_ATTR}
        out[n] = (var.dims[:-1], values, attrs)
    if not any(COMPLEX_DIM in v.dims for v in out.variables.values() if v.dims != (COMPLEX_DIM,)):
        out = out.drop_vars(COMPLEX_DIM, errors="ignore")
    return out



def open_cube(path: str | Path, load: bool = True) -> xr.Dataset:
    """Open a result cube (explicit engine; complex values come back as complex).

    Raises
    ------
    DamagedCubeError
        One line naming the file, what is wrong and the command that rebuilds it.

    Examples
    --------
    >>> ds = open_cube("results/table1/rayleigh.nc")               # doctest: +SKIP
    >>> ds.c2_R.sel(potential="lj", direction="[110]", strain=0.0)  # doctest: +SKIP
    """
    try:
        ds = xr.open_dataset(path, engine=ENGINE)
    except FileNotFoundError:
        raise
    except (OSError, ValueError, RuntimeError) as exc:
        why = check_readable(path) or str(exc).splitlines()[0]
        raise DamagedCubeError(f"{path} is damaged ({why}); rebuild it: {rebuild_hint(path)}") from None
    if load:
        with ds:
            ds = ds.load()
    return index_plate_angles(decode_complex(_legacy_complex(ds)))


#: Coordinates on ``surface`` that :func:`open_cube` makes selectable (a piezoelectric plate's
#: SAW Euler angles, and the named cut): ``ds.sel(euler_theta=38.0)`` without ``swap_dims``.
PLATE_COORDS = ("euler_phi", "euler_theta", "cut")


def index_plate_angles(ds: xr.Dataset) -> xr.Dataset:
    """Give the plate coordinates on ``surface`` (:data:`PLATE_COORDS`) their own index.

    netCDF stores no index for a coordinate that is not a dimension; with one, a piezoelectric
    cube selects its plates by Euler angle (``ds.sel(euler_theta=38.0)``, chained for two
    angles: ``ds.sel(euler_phi=0.0).sel(euler_theta=38.0)``) while ``surface`` keeps its labels.
    Plain ``xr.open_dataset`` users call ``ds.set_xindex("euler_theta")`` themselves.

    Examples
    --------
    >>> import xarray as xr
    >>> ds = xr.Dataset(coords={"surface": ["Euler (0, 38)", "Euler (0, -26)"],
    ...                         "euler_theta": ("surface", [38.0, -26.0])})
    >>> str(index_plate_angles(ds).sel(euler_theta=-26.0).surface.values)
    'Euler (0, -26)'
    """
    for name in PLATE_COORDS:
        if name in ds.coords and ds[name].dims == ("surface",) and name not in ds.xindexes:
            ds = ds.set_xindex(name)
    return ds


def _legacy_complex(ds: xr.Dataset) -> xr.Dataset:
    """Complex values of cubes written before the real/imag convention (HDF5 compound
    members r, i, as h5netcdf wrote them) as complex arrays."""
    for name, var in ds.variables.items():
        if var.dtype.names == ("r", "i"):
            values = np.asarray(var.values)
            ds[name] = var.copy(data=values["r"] + 1j * values["i"])
    return ds
