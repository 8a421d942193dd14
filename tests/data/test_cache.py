"""Parameter cache: only missing points computed, atomic entries, concurrency, info/clear."""
from __future__ import annotations

import json
import multiprocessing as mp

import numpy as np
import pytest

from surfwave.data import cache
from surfwave.errors import InputError

KEY = {"lattice": "fcc", "loading": "uniaxial", "potential": "lj", "direction": "[100]",
       "method": "test", "supercell": 2}


class Counter:
    """A vectorised compute function that records how many points it was asked for."""

    def __init__(self):
        self.calls, self.points = 0, 0

    def __call__(self, d):
        self.calls += 1
        self.points += len(d)
        return {"y": d**2, "vec": np.stack([d, -d], axis=-1), "reason": np.array(["ok"] * len(d))}


def test_adding_strain_points_computes_only_new_ones(tmp_path):
    f = Counter()
    first = np.round(np.arange(0.90, 1.001, 0.02), 12)  # 6 points
    r = cache.cached_points("bulk", KEY, first, f, tmp_path)
    assert (f.calls, f.points) == (1, 6)
    np.testing.assert_allclose(r["y"], first**2)
    assert r["vec"].shape == (6, 2) and r["reason"].tolist() == ["ok"] * 6
    assert cache.info(tmp_path)["misses"] == 6
    # A scene that adds three points (and reorders) computes only those three, in one call.
    second = np.concatenate([first[::-1], [1.02, 1.04, 1.06]])
    r = cache.cached_points("bulk", KEY, second, f, tmp_path)
    assert (f.calls, f.points) == (2, 9)
    np.testing.assert_allclose(r["y"], second**2)
    info = cache.info(tmp_path)
    assert (info["hits"], info["misses"], info["entries"]) == (6, 3, 9)
    # Everything cached: compute is not called at all.
    cache.cached_points("bulk", KEY, second, f, tmp_path)
    assert f.calls == 2


def test_grid_values_hit_typed_values(tmp_path):
    """0.88 + 5 * 0.01 from a grid and the typed 0.93 are the same cache entry."""
    f = Counter()
    cache.cached_points("bulk", KEY, [0.88 + 5 * 0.01], f, tmp_path)
    cache.cached_points("bulk", KEY, [0.93], f, tmp_path)
    assert f.points == 1


def test_key_changes_recompute(tmp_path):
    f = Counter()
    cache.cached_points("bulk", KEY, [1.0], f, tmp_path)
    cache.cached_points("bulk", {**KEY, "supercell": 3}, [1.0], f, tmp_path)
    cache.cached_points("other", KEY, [1.0], f, tmp_path)
    assert f.points == 3
    assert cache.info(tmp_path)["kinds"] == {"bulk": 2, "other": 1}


def test_duplicates_computed_once(tmp_path):
    f = Counter()
    r = cache.cached_points("bulk", KEY, [1.0, 1.0, 0.9], f, tmp_path)
    assert f.points == 2 and r["y"].tolist() == [1.0, 1.0, 0.81]


def test_corrupt_and_partial_entries_are_recomputed(tmp_path):
    f = Counter()
    cache.cached_points("bulk", KEY, [0.9, 1.0], f, tmp_path)
    entries = sorted((tmp_path / "bulk").glob("*.npz"))
    entries[0].write_bytes(entries[0].read_bytes()[:40])  # truncated by a crash
    (tmp_path / "bulk" / ".tmp-killed.npz").write_bytes(b"PK\x03\x04garbage")  # killed mid-write
    r = cache.cached_points("bulk", KEY, [0.9, 1.0], f, tmp_path)
    assert f.points == 3 and r["y"].tolist() == [0.81, 1.0]
    assert cache.info(tmp_path)["stale_temporary"] == 1
    assert cache.clear(tmp_path) == 2
    assert cache.info(tmp_path)["entries"] == 0 and not (tmp_path / "bulk").exists()


def test_compute_failure_writes_nothing(tmp_path):
    def fail(d):
        raise RuntimeError("solver diverged")

    with pytest.raises(RuntimeError):
        cache.cached_points("bulk", KEY, [1.0], fail, tmp_path)
    assert cache.info(tmp_path)["entries"] == 0


def _writer(root, start, n):
    start.wait()
    for _ in range(n):
        cache.cached_points("race", KEY, np.linspace(0.9, 1.1, 21), lambda d: {"y": d * 2.0}, root)
        for f in (root / "race").glob("[0-9a-f]*.npz"):
            f.unlink(missing_ok=True)  # force rewrites of the same keys


def test_two_processes_writing_the_same_keys(tmp_path):
    ctx = mp.get_context("spawn")
    start = ctx.Event()
    procs = [ctx.Process(target=_writer, args=(tmp_path, start, 15)) for _ in range(2)]
    for p in procs:
        p.start()
    start.set()
    for p in procs:
        p.join(60)
        assert p.exitcode == 0
    # Whatever survived is complete and correct; nothing temporary is left behind.
    r = cache.cached_points("race", KEY, np.linspace(0.9, 1.1, 21), lambda d: {"y": d * 0.0}, tmp_path)
    good = r["y"] != 0.0
    np.testing.assert_allclose(r["y"][good], 2 * np.linspace(0.9, 1.1, 21)[good])
    assert cache.info(tmp_path)["stale_temporary"] == 0


def test_concurrent_readers_never_see_partial_entries(tmp_path):
    """Both processes finish the same grid; every stored entry is readable and right."""
    ctx = mp.get_context("spawn")
    start = ctx.Event()
    procs = [ctx.Process(target=_fill, args=(tmp_path, start)) for _ in range(2)]
    for p in procs:
        p.start()
    start.set()
    for p in procs:
        p.join(60)
        assert p.exitcode == 0
    f = Counter()
    r = cache.cached_points("fill", KEY, np.linspace(0.9, 1.1, 41), f, tmp_path)
    assert f.calls == 0
    np.testing.assert_allclose(r["y"], np.linspace(0.9, 1.1, 41) ** 2)


def _fill(root, start):
    start.wait()
    for k in range(1, 42, 4):
        cache.cached_points("fill", KEY, np.linspace(0.9, 1.1, 41)[:k],
                            lambda d: {"y": d**2}, root)
    cache.cached_points("fill", KEY, np.linspace(0.9, 1.1, 41), lambda d: {"y": d**2}, root)


def test_info_of_missing_root(tmp_path):
    assert cache.info(tmp_path / "none")["entries"] == 0
    assert cache.clear(tmp_path / "none") == 0


def test_start_run_resets_hit_counts(tmp_path):
    f = Counter()
    cache.cached_points("bulk", KEY, [1.0], f, tmp_path)
    cache.start_run(tmp_path)
    cache.cached_points("bulk", KEY, [1.0, 0.9], f, tmp_path)
    info = cache.info(tmp_path)
    assert (info["hits"], info["misses"]) == (1, 1)


def test_code_version_tracks_the_computing_modules():
    v = cache.code_version("phonons")
    assert v == cache.code_version("phonons") and len(v) == 16
    assert v != cache.code_version("symmetry")


def test_entries_are_readable_by_others_and_stats_reset_per_run(tmp_path):
    """mkstemp makes 0600 files; a cache shared by users (or a cluster) needs the umask's mode.
    start_run drops the hit/miss records of earlier runs (they would pile up forever)."""
    import os
    import stat

    old = os.umask(0o022)
    try:
        cache.cached_points("bulk", KEY, [1.0], Counter(), tmp_path)
    finally:
        os.umask(old)
    (entry,) = (tmp_path / "bulk").glob("*.npz")
    assert stat.S_IMODE(entry.stat().st_mode) == 0o644
    assert len(list((tmp_path / "stats").glob("*.json"))) == 1
    cache.start_run(tmp_path)
    assert list((tmp_path / "stats").glob("*.json")) == []
    cache.cached_points("bulk", KEY, [1.0, 1.01], Counter(), tmp_path)
    info = cache.info(tmp_path)
    assert (info["hits"], info["misses"], info["entries"]) == (1, 1, 2)


def test_chunks_are_stored_as_they_finish(tmp_path):
    """With chunk=2 a compute that dies on the third chunk leaves the first two stored; the
    rerun computes only the rest."""
    class Dies(Counter):
        def __call__(self, d):
            if self.calls == 2:
                raise KeyboardInterrupt("killed")
            return super().__call__(d)

    d = [0.95, 0.96, 0.97, 0.98, 0.99, 1.0]
    with pytest.raises(KeyboardInterrupt):
        cache.cached_points("bulk", KEY, d, Dies(), tmp_path, chunk=2)
    assert cache.info(tmp_path)["entries"] == 4 and cache.info(tmp_path)["stale_temporary"] == 0
    f = Counter()
    r = cache.cached_points("bulk", KEY, d, f, tmp_path, chunk=2)
    assert (f.calls, f.points) == (1, 2)
    np.testing.assert_allclose(r["y"], np.square(d))


# --------------------------------------------------------------------------- keys of the knobs
def _knob_variants(value):
    """Values a knob may take that must never share a cache entry with ``value``: for a
    float, the next representable double (a change in the last digit) and a 10 % change;
    for an int, +1; for a string (an enum), another string; None (auto) against 1."""
    if isinstance(value, bool):
        return [not value]
    if isinstance(value, int):
        return [value + 1]
    if isinstance(value, float):
        return [float(np.nextafter(value, np.inf)), value * 1.1]
    if isinstance(value, str):
        return [value + "_other"]
    if value is None:
        return [1]
    raise AssertionError(f"knob value {value!r} of an unexpected type")


def _default_jobs():
    """Job params (surfwave.pipeline.scenes.job_params) of every cached stage, with the
    schema's default accuracy knobs (workflow/schemas/config.schema.yaml) filled in."""
    from surfwave.pipeline.scenes import job_params, validate_config

    cfg = {"scenes": {
        "f": {"lattice": "fcc", "loading": "in_plane_hydrostatic", "potentials": ["lj"],
              "d_over_d0": [1.0], "quantities": ["elastic", "bulk"]},
        "t": {"lattice": "triangular", "loading": "uniaxial", "potentials": ["lj"],
              "d_over_d0": [1.0], "theta": [0.3], "quantities": ["dispersion", "entropy"]}}}
    scenes = validate_config(cfg)
    return {"bulk": job_params(scenes["f"], "bulk"), "dispersion": job_params(scenes["t"], "dispersion"),
            "entropy": job_params(scenes["t"], "entropy")}


@pytest.mark.parametrize("stage", ["bulk", "dispersion", "entropy"])
def test_every_accuracy_knob_changes_the_key(stage):
    """A cached value computed at one accuracy must never be served for another: the point
    digest of ``job_key(..., **knobs)`` changes with every knob of the stage (each knob of
    the schema's defaults, changed by +1, by 10 % or in its last binary digit). Reference:
    docs/architecture.md ("keyed by a hash of everything that determines the value ... accuracy
    settings") -- the supercell 2 / supercell 3 mix-up of issue 14 is the case caught."""
    job = _default_jobs()[stage]
    knobs = job["accuracy"]
    assert knobs, f"stage {stage} has no accuracy knobs in the schema"

    def digest(acc):
        key = cache.job_key(job, "model_crystals.phonons", "m", potential="lj", direction="[100]", **acc)
        return cache.point_key(stage, key, 1.0)[0]

    base = digest(knobs)
    assert digest(dict(knobs)) == base  # deterministic
    seen = {base}
    for name, value in knobs.items():
        for other in _knob_variants(value):
            d = digest({**knobs, name: other})
            assert d not in seen, f"{stage}: knob {name}={other!r} shares a key with another setting"
            seen.add(d)


def test_keys_distinguish_last_digit_and_type_of_values():
    """Floats enter the key by repr (all 17 significant digits): 3e-5 and the next double
    differ, and so do 2 and 2.0 (an int knob typed as a float is another setting); d/d0 is
    rounded to 12 decimals on purpose (grid values and typed values must meet, see
    test_grid_values_hit_typed_values), so a difference in its 11th decimal still counts."""
    k = dict(KEY, displacement=3e-5)
    base = cache.point_key("bulk", k, 1.0)[0]
    assert cache.point_key("bulk", dict(k, displacement=float(np.nextafter(3e-5, 1.0))), 1.0)[0] != base
    assert cache.point_key("bulk", dict(k, supercell=2.0), 1.0)[0] != base
    assert cache.point_key("bulk", k, 1.0 + 1e-11)[0] != base
    assert cache.point_key("bulk", k, 1.0 + 1e-14)[0] == base


def test_potential_parameters_enter_the_key():
    """Two registered potentials of the same family (Morse alpha 3 and 4) are different
    physics: their keys differ by name and parameters (PairPotential.params)."""
    from surfwave.model_crystals.potentials import morse

    a = cache.point_key("bulk", dict(KEY, potential=morse(3.0)), 1.0)[0]
    b = cache.point_key("bulk", dict(KEY, potential=morse(4.0)), 1.0)[0]
    assert a != b


# --- clear deletes only what is provably ours (issue 20, item 10) -----------------------

def _real_cache(root):
    cache.start_run(root)
    cache.cached_points("bulk", KEY, [0.9, 1.0], Counter(), root)
    cache.cached_points("entropy", KEY, [1.0], Counter(), root)
    return root


def test_new_store_has_marker_and_clear_removes_only_entries(tmp_path):
    """A store made by cached_points carries the marker; clear removes the 3 entries, the
    statistics and stray temporary files, keeps the marker (the store exists, empty)."""
    root = _real_cache(tmp_path / "cache")
    assert json.loads((root / cache.MARKER).read_text())["format"] == cache.FORMAT
    (root / "bulk" / ".tmp-killed12.npz").write_bytes(b"partial")
    assert cache.clear(root) == 3
    assert sorted(p.name for p in root.iterdir()) == [cache.MARKER]


def test_clear_refuses_a_results_directory(tmp_path):
    """`--root results` (cubes and figures of two scenes beside the cache): nothing deleted."""
    results = tmp_path / "results"
    _real_cache(results / "cache")
    files = [results / s / f for s in ("table1", "fig2") for f in ("bulk.nc", "figure.pdf")]
    for f in files:
        f.parent.mkdir(parents=True, exist_ok=True)
        f.write_bytes(b"CDF\x01 precious")
    before = sorted(p for p in results.rglob("*"))
    with pytest.raises(InputError, match=r"not a surfwave cache.*fig2/bulk.nc"):
        cache.clear(results)
    assert sorted(p for p in results.rglob("*")) == before


def test_clear_refuses_user_files_even_in_a_marked_store(tmp_path):
    """A user's .tex one level below a marked store (or at its root): refused, kept."""
    root = _real_cache(tmp_path / "cache")
    tex = root / "bulk" / "notes.tex"
    tex.write_text("\\section{mine}")
    with pytest.raises(InputError, match="bulk/notes.tex"):
        cache.clear(root)
    assert tex.exists() and len(list((root / "bulk").glob("*.npz"))) == 2
    mydata = tmp_path / "mydata"
    (mydata / "paper").mkdir(parents=True)
    (mydata / "paper" / "main.tex").write_text("x")
    with pytest.raises(InputError, match=r"no SURFWAVE_CACHE marker.*paper/main.tex"):
        cache.clear(mydata)
    assert (mydata / "paper" / "main.tex").read_text() == "x"


def test_unmarked_store_of_older_code(tmp_path):
    """A cache written before the marker existed (every name ours): accepted and cleared;
    one foreign file in it: refused. A marker of another format: refused."""
    root = _real_cache(tmp_path / "cache")
    (root / cache.MARKER).unlink()
    ok, why = cache.check_store(root)
    assert ok and "older surfwave" in why
    assert cache.clear(root) == 3
    root2 = _real_cache(tmp_path / "cache2")
    (root2 / cache.MARKER).unlink()
    (root2 / "README").write_text("mine")
    assert not cache.check_store(root2)[0]
    with pytest.raises(InputError):
        cache.clear(root2)
    (root2 / "README").unlink()
    (root2 / cache.MARKER).write_text('{"format": "something-else"}')
    with pytest.raises(InputError, match="format"):
        cache.clear(root2)
    assert len(list((root2 / "bulk").glob("*.npz"))) == 2


def test_existing_foreign_directory_is_not_marked(tmp_path):
    """Pointing the cache at a folder with user files works, but does not make it ours."""
    (tmp_path / "thesis.tex").write_text("x")
    cache.cached_points("bulk", KEY, [1.0], Counter(), tmp_path)
    assert not (tmp_path / cache.MARKER).exists()
    with pytest.raises(InputError):
        cache.clear(tmp_path)
    assert (tmp_path / "thesis.tex").exists()
