"""The lattice-dynamics check of a dispersion scene on a sample of its strains.

References: the numerical solve :func:`surface_mode` run on every strain (the sampled
strains must carry exactly its values), the figure's own choice of strains (evenly spaced
indices, written out here), and the config schema's bounds for the new knob.
"""
import copy

import numpy as np
import pytest

from surfwave.dynamics import triangular_surface as ts
from surfwave.errors import InputError
from surfwave.pipeline import scenes
from surfwave.pipeline.scenes import SceneError, load_config, validate_config


def test_sample_holds_the_ends_the_figure_strains_and_nothing_twice():
    """2000 strains, 7 checked: the 7 evenly spaced indices and the 5 the dispersion figure
    draws (round(i (n - 1) / 4), i = 0..4), each once, sorted."""
    n = 2000
    idx = ts.check_sample(n, 7)
    figure = {round(i * (n - 1) / 4) for i in range(5)}
    even = {round(i * (n - 1) / 6) for i in range(7)}
    assert set(idx.tolist()) == figure | even
    assert np.all(np.diff(idx) > 0)
    # a short grid is checked everywhere (the paper's triangular scene: 5 strains)
    assert ts.check_sample(5).tolist() == [0, 1, 2, 3, 4]
    assert ts.check_sample(3, 1).tolist() == [0, 1, 2]
    with pytest.raises(InputError, match="got 0"):
        ts.check_sample(10, 0)


def test_scattered_sample_equals_the_full_solve_where_checked():
    """surface_mode on 3 of 7 strains, spread on the grid: the solve of all 7 at those
    strains (to rounding); NaN, -1 and the 'not checked (sample)' reason elsewhere."""
    d = np.linspace(0.94, 1.06, 7)
    theta = np.array([0.4, 1.2, 2.5])
    idx = np.array([0, 3, 6])
    full = ts.surface_mode("lj", d, theta)
    part = ts.scatter_sample(ts.surface_mode("lj", d[idx], theta), idx, d.size)
    other = np.setdiff1d(np.arange(d.size), idx)
    for name, arr in full.items():
        assert part[name].shape == np.shape(arr) and part[name].dtype == np.asarray(arr).dtype
        if np.asarray(arr).dtype.kind == "f":  # batch size changes rounding only (omega ~ 1)
            np.testing.assert_allclose(part[name][idx], np.asarray(arr)[idx], rtol=1e-12, atol=1e-14)
        else:
            np.testing.assert_array_equal(part[name][idx], np.asarray(arr)[idx])
    assert np.isnan(part["omega_lattice"][other]).all() and np.isnan(part["c2_R_long_wave"][other]).all()
    assert (part["n_surface_modes"][other] == -1).all()
    assert all(r.startswith("not checked (sample)") for r in part["reason_lattice"][other].ravel())


def test_check_points_knob_defaults_and_bound():
    """The schema fills the library default (DEFAULT_CHECK_POINTS) and refuses 0, naming it."""
    base = load_config([scenes.SCHEMA_PATH.parents[2] / "config" / "config.yaml"])
    cfg = copy.deepcopy(base)
    validate_config(cfg)
    assert cfg["scenes"]["triangular"]["accuracy"]["dispersion"]["check_points"] == ts.DEFAULT_CHECK_POINTS
    bad = copy.deepcopy(base)
    bad["scenes"]["triangular"]["accuracy"] = {"dispersion": {"check_points": 0}}
    with pytest.raises(SceneError, match="check_points"):
        validate_config(bad)
