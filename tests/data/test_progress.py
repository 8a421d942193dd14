"""Progress and cache reuse a user can see.

Reference: the counts of points actually passed to ``compute`` (recorded by the test's own
compute function) against the counts in the printed lines.
"""
import io

import numpy as np

from surfwave.data import cache
from surfwave.data.progress import Progress, summary_line


class _Tty(io.StringIO):
    def isatty(self):
        return True


def test_summary_line_format():
    assert (summary_line("bulk, scene x", 22, 14, 8, 3.14)
            == "bulk, scene x: 22 points, 14 from the cache, 8 computed in 3.1 s")


def test_cached_points_reports_hits_and_computed(tmp_path):
    """The per-job line counts what came from the cache and what was computed."""
    seen = []

    def compute(d):
        seen.extend(d.tolist())
        return {"y": d ** 2}

    cache.start_run(tmp_path)
    cache.cached_points("demo", {"potential": "lj"}, np.array([1.0, 2.0]), compute, tmp_path)
    log = io.StringIO()
    out = cache.cached_points("demo", {"potential": "lj"}, np.array([1.0, 2.0, 3.0, 4.0]), compute,
                              tmp_path, chunk=1, label="demo, scene s", log=log)
    np.testing.assert_array_equal(out["y"], [1.0, 4.0, 9.0, 16.0])
    assert seen == [1.0, 2.0, 3.0, 4.0]  # 3 and 4 computed once, 1 and 2 reused
    last = log.getvalue().splitlines()[-1]
    assert last.startswith("demo, scene s, lj: 4 points, 2 from the cache, 2 computed in ")
    lines = cache.run_summary(tmp_path)  # what the workflow prints at the end of a run
    assert lines[-1].startswith("demo, scene s: 4 points, 2 from the cache, 2 computed")


def test_progress_bar_on_terminal_lines_in_log():
    """A terminal gets a redrawn bar; a log file gets plain lines (here: every update)."""
    tty = _Tty()
    bar = Progress("bulk, scene x", 4, stream=tty, bar_after=0.0)
    for _ in range(4):
        bar.update()
    bar.close()
    text = tty.getvalue()
    assert text.count("\r") == 4 and "[" + "#" * 30 + "] 4/4" in text and text.endswith("\n")
    log = io.StringIO()
    plain = Progress("bulk, scene x", 4, stream=log, log_every=0.0)
    plain.update(2)
    plain.close()
    assert "\r" not in log.getvalue() and log.getvalue().startswith("bulk, scene x: 2/4 points in ")
    assert "left" in log.getvalue()


def test_solve_in_chunks_joins_what_one_call_returns():
    """Chunks of 3 over 10 points: the calls cover 0..10 once each in order, arrays are joined
    along axis 0 (nested dicts key by key), other values come from the first chunk; reference:
    the same function called once on all points."""
    from surfwave.data.progress import solve_in_chunks

    calls = []

    def solve(a, b):
        calls.append((a, b))
        x = np.arange(a, b, dtype=float)
        return {"free": {"c": x ** 2, "pol": np.stack([x, -x], axis=-1)}, "label": "same", "n": np.int64(1)}

    joined = solve_in_chunks(solve, 10, "test", chunk=3, stream=io.StringIO())
    assert calls == [(0, 3), (3, 6), (6, 9), (9, 10)]
    whole = solve(0, 10)
    np.testing.assert_array_equal(joined["free"]["c"], whole["free"]["c"])
    np.testing.assert_array_equal(joined["free"]["pol"], whole["free"]["pol"])
    assert joined["label"] == "same" and joined["n"] == 1
    calls.clear()
    solve_in_chunks(solve, 3, "test", chunk=3)
    assert calls == [(0, 3)]


def test_sweeps_in_chunks_equal_one_batch(monkeypatch):
    """The real-crystal sweeps run their points in chunks (progress on long grids). With chunks
    of 5 points the cubes equal those of one batch bit for bit (reference: the same sweep with
    the default chunk, every grid here smaller than one chunk): Cu (001) under stress with and
    without third-order constants, and rotated Y-cuts of LiNbO3 with both conditions."""
    import surfwave.data.progress as progress
    from surfwave.real_crystals.materials import get_material
    from surfwave.real_crystals.piezo_sweep import piezo_wave_sweep
    from surfwave.real_crystals.sweep import surface_wave_sweep

    def run():
        with np.errstate(invalid="ignore"):
            el = surface_wave_sweep([get_material("Cu")], ["(001)"], np.arange(0.0, 46.0, 5.0), stress=[-1.0, 1.0],
                                    loadings=["along"], toec=[False, True])
            pz = piezo_wave_sweep(["LiNbO3"], euler={"phi": [0.0], "theta": np.arange(-90.0, 91.0, 30.0),
                                                     "psi": [0.0]})
        return el, pz

    one = run()
    monkeypatch.setattr(progress, "CHUNK", 5)
    chunked = run()
    for a, b in zip(one, chunked):
        for name in list(a.data_vars) + list(a.coords):
            x, y = a[name].values, b[name].values
            if x.dtype.kind in "fc":
                np.testing.assert_array_equal(x, y, err_msg=name)
            else:
                assert (x == y).all(), name
