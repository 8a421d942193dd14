"""Shared test fixtures and helpers."""
from __future__ import annotations

import os

import numpy as np
import pytest
from hypothesis import settings

# CI runs the property tests with a fixed example sequence so a failure there reproduces
# locally (HYPOTHESIS_PROFILE=ci); interactive runs keep exploring new examples.
settings.register_profile("ci", derandomize=True, print_blob=True)
settings.load_profile(os.environ.get("HYPOTHESIS_PROFILE", "ci" if os.environ.get("CI") else "default"))

from surfwave.report.reproduction import load_paper_values  # noqa: E402 (after the profile)


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
