"""A hang guard for the bad-input tables: every refusal must come within seconds.

:func:`within` raises :class:`Hung` in the main thread when the block runs longer than its
limit (``signal.setitimer``; no plugin needed), so a regression that loops forever fails the
test instead of stalling the suite.
"""
from __future__ import annotations

import contextlib
import signal
from collections.abc import Iterator


class Hung(AssertionError):
    """The guarded block did not finish within its limit."""


@contextlib.contextmanager
def within(seconds: float, what: str = "") -> Iterator[None]:
    """Fail with :class:`Hung` if the block takes longer than ``seconds`` (wall clock)."""
    def alarm(signum, frame):
        raise Hung(f"no answer within {seconds:g} s: {what}")

    previous = signal.signal(signal.SIGALRM, alarm)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
