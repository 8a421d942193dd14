"""The stage skeleton that every cube script uses (surfwave.pipeline.stage.block_cube)."""
import io

import numpy as np

from surfwave.pipeline.stage import block_cube

VARIABLES = {"u": {"long_name": "row amplitude", "units": "1", "dims": ("row",)},
             "w": {"long_name": "per strain", "units": "1", "dims": ()}}


def test_blocks_stack_by_potential_and_ragged_rows_pad_with_nan():
    """Two potentials whose decay needs 2 and 4 rows: the cube has 4 rows, the shorter block
    NaN beyond its own (reference: the arrays padded by hand), and the row coordinate 0..3.
    An array without metadata is reported in the log and not written."""
    rows = {"a": 2, "b": 4}

    def compute(pot):
        n = rows[pot]
        return {"u": np.arange(3 * n, dtype=float).reshape(3, n), "w": np.full(3, float(n)),
                "scratch": np.zeros(3)}

    job = {"potentials": ["a", "b"], "d_over_d0": [0.9, 1.0, 1.1]}
    log = io.StringIO()
    ds = block_cube(job, compute, VARIABLES, by=("potential",), log=log, ragged=("row", ("u",)))
    assert dict(ds.sizes) == {"potential": 2, "strain": 3, "row": 4}
    assert ds["row"].values.tolist() == [0, 1, 2, 3]
    ref_a = np.full((3, 4), np.nan)
    ref_a[:, :2] = np.arange(6.0).reshape(3, 2)
    np.testing.assert_array_equal(ds.u.sel(potential="a").values, ref_a)
    np.testing.assert_array_equal(ds.u.sel(potential="b").values, np.arange(12.0).reshape(3, 4))
    assert ds.w.sel(potential="b").values.tolist() == [4.0] * 3
    assert "scratch" not in ds and "scratch" in log.getvalue()
