"""Parameter cache: only missing points computed, atomic entries, concurrency, info/clear."""
from __future__ import annotations

import multiprocessing as mp

import numpy as np
import pytest

from surfwave.data import cache

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
