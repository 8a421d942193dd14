"""The one array validator (surfwave.validate.as_1d) and the per-point NaN contract."""
import numpy as np
import pytest

from surfwave.errors import InputError
from surfwave.validate import as_1d


def test_as_1d_shapes_and_messages_name_the_argument():
    assert as_1d(1.0).shape == (1,) and as_1d([0.9, 1.1]).tolist() == [0.9, 1.1]
    with pytest.raises(InputError, match=r"theta must be a scalar or a 1-D array, got shape \(2, 2\)"):
        as_1d(np.zeros((2, 2)), "theta")
    with pytest.raises(InputError, match="angles must be finite"):
        as_1d([0.0, np.nan], "angles")
    with pytest.raises(InputError, match="stress must be numbers"):
        as_1d(["a"], "stress")
    assert np.isnan(as_1d([1.0, np.nan], finite=False)[1])


def test_bulk_speeds_non_finite_point_is_nan_with_reason():
    """phonons.bulk_speeds is per point: a NaN strain gives NaN and its reason, the other
    point the same values as computed alone (the reference)."""
    from surfwave.model_crystals.phonons import bulk_speeds

    both = bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", [1.0, np.nan], zone_mesh=2)
    alone = bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", [1.0], zone_mesh=2)
    assert np.isnan(both["c2_T_par_phonopy"][1]) and "finite" in both["reason"][1]
    assert both["reason"][0] == "" and both["c2_T_par_phonopy"][0] == alone["c2_T_par_phonopy"][0]
    with pytest.raises(InputError, match="d_over_d0 must be a scalar or a 1-D array"):
        bulk_speeds("fcc", "in_plane_hydrostatic", "lj", "[100]", [[1.0]])
