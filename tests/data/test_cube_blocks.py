"""Cubes filled block by block (cube.build) from blocks computed on demand (stage.block_cube)."""
from __future__ import annotations

import io

import numpy as np
import pytest

from surfwave.data import cube
from surfwave.errors import InputError
from surfwave.pipeline import stage

META = {
    "x": {"long_name": "a number", "units": "1", "dims": ()},
    "label": {"long_name": "a label", "dims": ()},
    "m": {"long_name": "a matrix", "units": "1", "dims": ("i", "j")},
}
D = [0.9, 1.0, 1.1]


def _block(p: int, d: int) -> dict:
    return {"x": np.arange(3) + 10 * p + d, "label": np.array(["a" * (1 + p + d)] * 3),
            "m": np.full((3, 2, 2), p - d, dtype=float)}


def test_filled_cube_equals_the_stacked_blocks():
    """Reference: numpy's stack of the same blocks (the previous implementation); labels of
    different widths keep their full text, an integer block followed by a float one is
    upcast as numpy's result_type says (not truncated)."""
    blocks = {(p, d): _block(p, d) for p in (0, 1) for d in (0, 1, 2)}
    blocks[(1, 2)]["x"] = blocks[(1, 2)]["x"] + 0.5
    ds = cube.build(blocks, {"potential": [0, 1], "direction": [0, 1, 2]}, D, META)
    for name in META:
        want = np.stack([blocks[k][name] for k in sorted(blocks)]).reshape(
            (2, 3) + blocks[(0, 0)][name].shape)
        assert np.array_equal(ds[name].values, want), name
    assert ds["x"].dtype == np.float64 and ds["label"].values[1, 2, 0] == "aaaa"
    assert ds["m"].dims == ("potential", "direction", "strain", "i", "j")


def test_block_of_another_shape_is_refused():
    """A block whose array has another shape than the first block's names the variable."""
    blocks = {(0,): _block(0, 0), (1,): dict(_block(1, 0), m=np.zeros((3, 3, 3)))}
    with pytest.raises(InputError, match="'m' has shape"):
        cube.build(blocks, {"potential": [0, 1]}, D, META)


def test_block_cube_computes_each_block_once_in_order():
    """stage.block_cube asks compute for each (potential, direction) once, in the order of
    the job's lists, and the cube holds what compute returned."""
    calls = []

    def compute(pot, direction):
        calls.append((pot, direction))
        return _block(pot, direction)

    job = {"potentials": [1, 0], "directions": [2, 0], "d_over_d0": D}
    ds = stage.block_cube(job, compute, META, log=io.StringIO())
    assert calls == [(1, 2), (1, 0), (0, 2), (0, 0)]
    assert np.array_equal(ds["x"].sel(potential=0, direction=2).values, _block(0, 2)["x"])
