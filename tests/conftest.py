"""Shared test fixtures and helpers."""
from __future__ import annotations

import csv
from importlib import resources

import numpy as np
import pytest


def load_table1() -> dict[str, np.ndarray]:
    """The paper's Table I as columns (source: src/surfwave/data/table1.csv, transcribed from the seed)."""
    text = resources.files("surfwave").joinpath("data/table1.csv").read_text()
    rows = [line for line in text.splitlines() if line and not line.startswith("#")]
    reader = csv.DictReader(rows)
    data = list(reader)
    return {k: np.array([float(r[k]) for r in data]) for k in reader.fieldnames}


@pytest.fixture(scope="session")
def table1():
    return load_table1()
