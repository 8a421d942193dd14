"""The cache keys the workflow scripts build (not only the library's key function).

A script that leaves an accuracy knob out of its key makes two scenes with different knobs share
one cache entry (issue 27: with ``tol`` dropped from the entropy script's key, the 1e-9 cube was
served the 1e-2 results). Each script that uses the parameter cache is run here on its own job
parameters (surfwave.pipeline.scenes.job_params of the default config) with the cache lookup
replaced by a recorder that stops the script; every accuracy knob, and every grid the cached
function receives, must change the recorded key; the scene name must not (scenes share points).
"""
from __future__ import annotations

import copy
import runpy
from pathlib import Path
from types import SimpleNamespace

import pytest

from surfwave.data import cache
from surfwave.pipeline import stage
from surfwave.pipeline.scenes import job_params, load_config, validate_config

ROOT = Path(__file__).resolve().parents[2]
SCRIPTS = ROOT / "workflow" / "scripts"
#: script -> (scene of the default config, stage, job entries besides ``accuracy`` the cached
#: function receives, accuracy knobs that do not reach a cached point and why).
CASES = {
    "entropy": ("entropy", "entropy", (), {}),
    "bulk": ("table1", "bulk", (), {}),
    "dispersion": ("triangular", "dispersion", ("theta",),
                   {"check_points": "chooses which strains are checked; each point's key has its d/d0"}),
}


class _Recorded(Exception):
    """Raised by the recorder: the key is known, the script need not go on."""


def _key(script: str, job: dict, monkeypatch, tmp_path) -> dict:
    seen: list[dict] = []

    def record(kind, key, *args, **kwargs):
        seen.append(copy.deepcopy(key))
        raise _Recorded

    monkeypatch.setattr(cache, "cached_points", record)
    monkeypatch.setattr(stage, "open_log", lambda context: None)
    snake = SimpleNamespace(params=SimpleNamespace(job=job, cache=str(tmp_path / "cache")),
                            input=SimpleNamespace(), output=SimpleNamespace(), log=[str(tmp_path / "log")])
    with pytest.raises(_Recorded):
        runpy.run_path(str(SCRIPTS / f"{script}.py"), init_globals={"snakemake": snake})
    return seen[0]


def _other(value):
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return value * 3 + 1
    if isinstance(value, list):
        return [v * 1.5 for v in value]
    return f"{value}-other"


def test_every_caching_script_is_covered():
    """Each script that calls the parameter cache has a case here."""
    using = {p.stem for p in SCRIPTS.glob("*.py") if "cached_points" in p.read_text()}
    assert using == set(CASES)


@pytest.mark.parametrize("script", sorted(CASES))
def test_script_cache_key_holds_every_knob(script, monkeypatch, tmp_path):
    scene, stage_name, grids, exempt = CASES[script]
    job = job_params(validate_config(load_config([str(ROOT / "config" / "config.yaml")]))[scene], stage_name)
    base = _key(script, job, monkeypatch, tmp_path)
    assert job["accuracy"], "a caching stage has accuracy knobs"
    for knob, value in job["accuracy"].items():
        if knob in exempt:
            continue
        other = copy.deepcopy(job)
        other["accuracy"][knob] = _other(value)
        assert _key(script, other, monkeypatch, tmp_path) != base, f"{script}: accuracy {knob!r} not in the key"
    for name in grids:
        other = copy.deepcopy(job)
        other[name] = _other(job[name])
        assert _key(script, other, monkeypatch, tmp_path) != base, f"{script}: {name!r} not in the key"
    renamed = copy.deepcopy(job)
    renamed["scene"] = "another_scene"
    assert _key(script, renamed, monkeypatch, tmp_path) == base     # scenes share cached points
