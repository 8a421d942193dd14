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
