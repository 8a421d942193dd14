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


def test_sample_is_the_strains_nearest_to_the_global_lattice():
    """The rule written out: lattice d/d0 = 1 + j 0.2/k inside the grid's range, each
    represented by its nearest grid strain (ties: the smaller), each index once, sorted."""
    d = np.round(np.linspace(0.90, 1.10, 2000), 12)
    idx = ts.check_sample(d, 7)
    h = 0.2 / 7
    lattice = [1 + j * h for j in range(-3, 4)]  # 0.914 .. 1.086, all inside [0.9, 1.1]
    assert idx.tolist() == sorted({int(np.argmin(np.abs(d - x))) for x in lattice})
    assert np.all(np.diff(idx) > 0)
    # the paper's triangular scene (5 strains 0.9 .. 1.1, the default 5 per 0.2): all of them
    assert ts.check_sample([0.90, 0.95, 1.0, 1.05, 1.10]).tolist() == [0, 1, 2, 3, 4]
    # order of the grid does not matter; a grid narrower than h checks one strain
    assert ts.check_sample([1.10, 0.90, 1.0], 2).tolist() == [0, 1, 2]
    assert ts.check_sample([1.01, 1.02], 5).tolist() == [0]
    with pytest.raises(InputError, match="got 0"):
        ts.check_sample(d, 0)


@pytest.mark.parametrize("old, new", [
    ({"start": 0.90, "stop": 1.10, "step": 0.005}, {"start": 0.80, "stop": 1.30, "step": 0.005}),
    ({"start": 0.95, "stop": 1.02, "step": 0.01}, {"start": 0.95, "stop": 1.20, "step": 0.01}),
    ({"start": 0.88, "stop": 1.10, "step": 0.001}, {"start": 0.50, "stop": 1.10, "step": 0.001}),
])
@pytest.mark.parametrize("k", [1, 5, 7, 18])
def test_extending_a_grid_keeps_its_sample_and_the_cache_serves_it(tmp_path, old, new, k):
    """Issue 20 item 12: the old sample re-spaced when the grid grew (4 of 18 checks from the
    cache). Now the checked strains of the old grid are a subset of those of the extended
    grid, and the parameter cache (the dispersion stage's path) serves every one of them:
    hits = old sample size, misses = the rest. Grids as the config builds them."""
    from surfwave.data import cache
    from surfwave.pipeline.grids import expand_grid

    d_old, d_new = expand_grid(old), expand_grid(new)
    s_old = set(np.round(d_old[ts.check_sample(d_old, k)], 12))
    s_new = set(np.round(d_new[ts.check_sample(d_new, k)], 12))
    assert s_old <= s_new, sorted(s_old - s_new)
    calls = []
    f = lambda d: calls.append(len(d)) or {"y": d}
    cache.cached_points("surface_mode", {"t": 1}, sorted(s_old), f, tmp_path)
    cache.cached_points("surface_mode", {"t": 1}, sorted(s_new), f, tmp_path)
    info = cache.info(tmp_path)
    assert (info["hits"], info["misses"]) == (len(s_old), len(s_new) - len(s_old))


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
