"""The paper's printed numbers and claims: the one loader of ``paper_values.yaml``.

Light on purpose (yaml only): the Snakefile imports it through
:mod:`surfwave.pipeline.targets`.
"""
from __future__ import annotations

import copy
from functools import lru_cache
from importlib import resources
from pathlib import Path

import yaml

#: libyaml's parser where PyYAML was built with it (same safe constructor, ~10x faster).
SAFE_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


@lru_cache(maxsize=None)
def _packaged() -> dict:
    text = resources.files("surfwave").joinpath("data/paper_values.yaml").read_text()
    return yaml.load(text, Loader=SAFE_LOADER)


def load_paper_values(path: str | Path | None = None) -> dict:
    """The paper's printed numbers (``surfwave/data/paper_values.yaml`` unless ``path``).

    Returns
    -------
    dict
        A fresh copy each call (callers may modify it): ``paper``, ``table1`` (with its
        ``scene``), ``values`` and ``claims``, each with its source and tolerance.
    """
    if path is None:  # parsed once per process (the workflow's parse asks several times)
        return copy.deepcopy(_packaged())
    return yaml.load(Path(path).read_text(), Loader=SAFE_LOADER)
