"""The paper's printed numbers and claims: the one loader of ``paper_values.yaml``.

Light on purpose (yaml only): the Snakefile imports it through
:mod:`surfwave.pipeline.targets`.
"""
from __future__ import annotations

from functools import lru_cache
from importlib import resources
from pathlib import Path

import yaml


@lru_cache(maxsize=None)
def _packaged() -> str:
    return resources.files("surfwave").joinpath("data/paper_values.yaml").read_text()


def load_paper_values(path: str | Path | None = None) -> dict:
    """The paper's printed numbers (``surfwave/data/paper_values.yaml`` unless ``path``).

    Returns
    -------
    dict
        A fresh copy each call (callers may modify it): ``paper``, ``table1`` (with its
        ``scene``), ``values`` and ``claims``, each with its source and tolerance.
    """
    return yaml.safe_load(_packaged() if path is None else Path(path).read_text())
