"""Visible progress of long computations: a bar on a terminal, periodic lines in a log.

:class:`Progress` counts finished points. On a terminal (``stream.isatty()``) it redraws
one bar line once the work has run for ``bar_after`` seconds; otherwise (a Snakemake job's
log file) it writes a plain line at most every ``log_every`` seconds, so ``tail -f`` on the
log shows life. :func:`summary_line` is the per-job line,
"bulk, scene x: 22 points, 14 from the cache, 8 computed in 3.1 s". :func:`solve_in_chunks`
runs a vectorised solver over a long grid in chunks with progress (the real-crystal sweeps).

No dependency beyond the standard library (numpy only to join chunk results).
"""
from __future__ import annotations

import sys
import time
from typing import Any, Callable, TextIO


def summary_line(label: str, total: int, cached: int, computed: int, seconds: float) -> str:
    """The per-job summary: points, how many came from the cache, how many were computed and how long."""
    return (f"{label}: {total} points, {cached} from the cache, {computed} computed "
            f"in {seconds:.1f} s")


def _fmt_seconds(s: float) -> str:
    return f"{s:.0f} s" if s < 120 else f"{s / 60:.1f} min"


class Progress:
    """Progress of ``total`` points of work labelled ``label``.

    Parameters
    ----------
    label : str
        What is computed, e.g. ``"bulk, scene table1, lj [100]"``.
    total : int
        Points to compute.
    stream : file, optional
        Where to write (default: ``sys.stderr`` at the time of the call).
    bar_after, log_every : float
        Seconds before the first terminal bar, and between two log lines.
    """

    def __init__(self, label: str, total: int, stream: TextIO | None = None, bar_after: float = 2.0,
                 log_every: float = 10.0):
        self.label, self.total = label, int(total)
        self.stream = stream if stream is not None else sys.stderr
        self.bar_after, self.log_every = bar_after, log_every
        self.done = 0
        self.start = time.perf_counter()
        self._last_log = self.start
        self._drawn = False
        try:
            self.tty = bool(self.stream.isatty())
        except (AttributeError, ValueError):
            self.tty = False

    def update(self, n: int = 1) -> None:
        """Count ``n`` more finished points and show progress if due."""
        self.done += int(n)
        now = time.perf_counter()
        elapsed = now - self.start
        if self.tty and elapsed >= self.bar_after:
            self._bar(elapsed)
        elif not self.tty and now - self._last_log >= self.log_every:
            self._last_log = now
            self.write(f"{self.label}: {self.done}/{self.total} points in {_fmt_seconds(elapsed)}"
                        f"{self._eta(elapsed)}\n")

    def _eta(self, elapsed: float) -> str:
        if 0 < self.done < self.total:
            return f", about {_fmt_seconds(elapsed / self.done * (self.total - self.done))} left"
        return ""

    def _bar(self, elapsed: float) -> None:
        width = 30
        filled = int(width * self.done / max(self.total, 1))
        self.write(f"\r{self.label} [{'#' * filled}{'.' * (width - filled)}] "
                    f"{self.done}/{self.total} {_fmt_seconds(elapsed)}{self._eta(elapsed)}   ")
        self._drawn = True

    def close(self) -> float:
        """End the bar (newline on a terminal); return the seconds elapsed."""
        if self._drawn:
            self.write("\n")
            self._drawn = False
        return time.perf_counter() - self.start

    def write(self, text: str) -> None:
        """Write ``text`` to the progress stream and flush it (a closed stream is ignored)."""
        try:
            self.stream.write(text)
            self.stream.flush()
        except (OSError, ValueError):
            pass


#: Points per chunk of :func:`solve_in_chunks`: small enough that a leaky-wave chunk takes a few
#: seconds (progress shows) and its temporaries stay in the tens of MB, large enough that the
#: vectorised solvers run at full speed.
CHUNK = 2048


def solve_in_chunks(solve: Callable[[int, int], dict[str, Any]], n: int, label: str, *, chunk: int | None = None,
                    stream: TextIO | None = None) -> dict[str, Any]:
    """Run ``solve`` over consecutive slices of ``n`` points and join the results, showing progress.

    Parameters
    ----------
    solve : callable
        ``solve(start, stop)`` -> a dict whose values are arrays with leading length
        ``stop - start`` (joined along axis 0), nested dicts of such (joined key by key), or
        anything else (taken from the first chunk: the same for every chunk).
    n : int
        Number of points.
    label : str
        What is computed, for the progress lines (:class:`Progress`).
    chunk : int, optional
        Points per call (default :data:`CHUNK`, read at call time).
    stream : file, optional
        Where progress goes (default ``sys.stderr``).

    Returns
    -------
    dict
        As one ``solve(0, n)`` call would return it, for solvers whose points do not depend
        on each other.
    """
    chunk = CHUNK if chunk is None else int(chunk)
    if chunk < 1:
        raise ValueError(f"chunk must be >= 1, got {chunk}")
    if n <= chunk:
        return solve(0, n)
    bar = Progress(label, n, stream=stream)
    parts = []
    for start in range(0, n, chunk):
        stop = min(start + chunk, n)
        parts.append(solve(start, stop))
        bar.update(stop - start)
    bar.close()
    return _join(parts)


def _join(parts):
    first = parts[0]
    if isinstance(first, dict):
        return {k: _join([p[k] for p in parts]) for k in first}
    if hasattr(first, "ndim") and first.ndim > 0:
        import numpy as np

        return np.concatenate(parts, axis=0)
    return first
