"""The skeleton every stage script shares: open the log, compute each block, build the cube.

A block is one potential (and one direction where the stage has directions); the library
function computes it over the scene's whole strain grid at once. The script then finishes
the cube with :func:`surfwave.data.cube.finish` (space groups, provenance, atomic write).
"""
from __future__ import annotations

import itertools
import sys
from typing import Any, Callable, Mapping, TextIO

import numpy as np
import xarray as xr

from surfwave.data import cube

#: Block dimension -> key of the job parameters that lists its values.
_LABELS = {"potential": "potentials", "direction": "directions"}


def open_log(job_context: Any) -> None:
    """Send this process's stderr to the rule's log file (``job_context.log[0]``)."""
    sys.stderr = open(job_context.log[0], "w")


def block_cube(
    job: Mapping[str, Any],
    compute: Callable[..., Mapping[str, Any]],
    variables: Mapping[str, Any],
    by: tuple[str, ...] = ("potential", "direction"),
    log: TextIO | None = None,
    ragged: tuple[str, tuple[str, ...]] | None = None,
    **build_kwargs: Any,
) -> xr.Dataset:
    """Run ``compute`` for every block of a scene and assemble the cube.

    Parameters
    ----------
    job : mapping
        The job parameters (:func:`surfwave.pipeline.scenes.job_params`): ``potentials``,
        ``directions`` (when ``by`` has it) and ``d_over_d0``.
    compute : callable
        ``compute(potential, direction)`` (or ``compute(potential)``), returning arrays with
        the strain as leading axis, keyed like ``variables``.
    variables : mapping
        Metadata of the variables to keep (others are reported to ``log`` and dropped).
    by : tuple of str
        Block dimensions, from ``("potential", "direction")``.
    log : file, optional
        Where dropped arrays are reported (default: the current stderr, i.e. the log).
    ragged : (dim, variable names), optional
        A last axis whose length may differ between blocks (e.g. the rows of a decay sized
        per potential): those variables are padded with NaN to the longest, and ``dim`` gets
        the coordinate 0, 1, ..., n - 1.
    **build_kwargs
        Passed to :func:`surfwave.data.cube.build` (``coords``, ``skip``).

    Returns
    -------
    xarray.Dataset
        dims (*by, strain, ...).
    """
    log = sys.stderr if log is None else log
    labels = {b: list(job[_LABELS[b]]) for b in by}
    blocks: Mapping[tuple, Any] = _Blocks(list(itertools.product(*labels.values())),
                                          lambda key: cube.documented(compute(*key), variables, log))
    if ragged is not None:  # every block is needed to know the longest axis: computed now
        dim, names = ragged
        blocks = {key: dict(blocks[key]) for key in blocks}
        n = max(np.shape(b[v])[-1] for b in blocks.values() for v in names)
        for b in blocks.values():
            for v in names:
                b[v] = np.pad(b[v], [(0, 0)] * (np.ndim(b[v]) - 1) + [(0, n - np.shape(b[v])[-1])],
                              constant_values=np.nan)
        build_kwargs["coords"] = {**build_kwargs.get("coords", {}), dim: np.arange(n)}
    return cube.build(blocks, labels, job["d_over_d0"], variables, **build_kwargs)


class _Blocks(Mapping):
    """Blocks computed when :func:`surfwave.data.cube.build` reads them, and not kept: the
    cube is filled block by block, so at most one block's arrays live beside it (for 80000
    strain points of the elastic stage, 26 MB instead of 104 MB)."""

    def __init__(self, keys: list[tuple], compute: Callable[[tuple], Mapping[str, Any]]):
        self._keys, self._compute = keys, compute

    def __getitem__(self, key):
        if key not in self._keys:
            raise KeyError(key)
        return self._compute(key)

    def __contains__(self, key) -> bool:  # Mapping's default would compute the block
        return key in self._keys

    def __iter__(self):
        return iter(self._keys)

    def __len__(self) -> int:
        return len(self._keys)
