"""Shared test fixtures and helpers."""
from __future__ import annotations

import numpy as np
import pytest

from surfwave.report import load_paper_values


def load_table1() -> dict[str, np.ndarray]:
    """The paper's Table I as columns keyed like ``paper_values.yaml`` (the one copy of the
    paper's printed numbers: src/surfwave/data/paper_values.yaml, transcribed from the seed)."""
    t = load_paper_values()["table1"]
    rows = np.array(t["rows"], dtype=float)
    keys = ["d_over_d0"] + [c["key"] for c in t["columns"]]
    return {k: rows[:, i] for i, k in enumerate(keys)}


@pytest.fixture(scope="session")
def table1():
    return load_table1()
