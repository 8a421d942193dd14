"""Piezoelectric scenes with third-order constants: the ``toec`` and ``toec_file`` keys.

References: the elastic real-crystal scenes' rules (surfwave.pipeline.crystal_scenes: toec needs
a stress grid, true needs a set), surfwave.real_crystals.toec_classes.toec_from_named's message
for wrong names, the piezoelectric database (only GaAs carries a set; LiNbO3 and quartz are
class 3m and 32), and Snakemake's params rule (a job reruns when its params change: the file's
content and hash are in them).
"""
from __future__ import annotations

import pytest

from surfwave.pipeline.piezo_scenes import check_piezo_scene, piezo_job_params
from surfwave.pipeline.scenes import validate_config
from surfwave.real_crystals.materials import get_material

GAAS = {"materials": ["GaAs"], "euler": {"phi": 0, "theta": 0, "psi": 45}, "stress": [-0.5, 0, 0.5]}


def _named(scale: float = 1.0, drop: str | None = None) -> str:
    vals = {k: scale * v for k, v in get_material("GaAs").toec.items() if k != drop}
    return "source: a test set\n" + "".join(f"{k}: {v!r}\n" for k, v in vals.items())


def test_toec_defaults_and_both_models():
    """No toec key: [false] (the scene as before); [false, true] for GaAs expands with its
    database set and no file."""
    scene, problems = check_piezo_scene("s", dict(GAAS))
    assert problems == [] and scene["toec"] == [False] and scene["toec_file"] is None
    scene, problems = check_piezo_scene("s", {**GAAS, "toec": [False, True]})
    assert problems == [] and scene["toec"] == [False, True]
    params = piezo_job_params(scene)
    assert params["toec"] == [False, True] and params["toec_file"] is None


@pytest.mark.parametrize("raw, fragment", [
    ({"materials": ["GaAs"], "euler": {"phi": 0}, "toec": [True]}, "key 'stress': 'toec' and 'toec_file' need"),
    ({"materials": ["LiNbO3"], "cuts": ["Y-Z LiNbO3"], "stress": [0.1], "toec": [True]},
     "key 'toec': value true needs third-order elastic constants"),
    ({**GAAS, "loading": ["along"]}, "key 'loading': not used by a piezoelectric scene"),
    ({**GAAS, "toec_file": "missing.yaml", "toec": [True]}, "key 'toec_file': value 'missing.yaml': cannot read"),
    ({**GAAS, "toec_file": "set.yaml"}, "key 'toec_file': value 'set.yaml' is not used with toec: [False]"),
    ({"materials": ["GaAs", "LiNbO3"], "euler": {"phi": 0}, "stress": [0.1], "toec": [True],
      "toec_file": "set.yaml"}, "different crystal classes ['-43m', '3m']"),
])
def test_bad_toec_input_is_one_clear_line(raw, fragment, tmp_path):
    """Each bad combination is refused by scene validation, one line naming scene and key."""
    (tmp_path / "set.yaml").write_text(_named())
    scene, problems = check_piezo_scene("s", raw, base_dir=tmp_path)
    assert scene is None and len(problems) == 1, problems
    assert problems[0].startswith("scene 's', key ") and fragment in problems[0], problems[0]


def test_wrong_names_reuse_the_library_message(tmp_path):
    """A file without C456, or with a trigonal name for cubic GaAs, gets toec_from_named's message;
    a file that is not a mapping is named."""
    for text, fragment in ((_named(drop="C456"), "class--43m third-order constants: missing ['C456']"),
                           (_named() + "C114: 1.0\n", "unknown ['C114']"),
                           ("- 1\n- 2\n", "must be a mapping of named third-order constants")):
        (tmp_path / "set.yaml").write_text(text)
        scene, problems = check_piezo_scene("s", {**GAAS, "toec": [True], "toec_file": "set.yaml"}, base_dir=tmp_path)
        assert scene is None and fragment in problems[0] and "key 'toec_file'" in problems[0], problems


def test_file_content_enters_the_params(tmp_path):
    """The params carry the file's constants and sha256: a changed file changes them (so the
    job reruns); the same content under the same path gives the same params."""
    path = tmp_path / "set.yaml"
    path.write_text(_named())
    raw = {**GAAS, "toec": [False, True], "toec_file": str(path)}   # absolute: base_dir not needed
    p1 = piezo_job_params(check_piezo_scene("s", raw)[0])
    assert p1["toec_file"]["constants"]["C111"] == -622.0 and p1["toec_file"]["constants"]["source"] == "a test set"
    assert p1 == piezo_job_params(check_piezo_scene("s", raw)[0])
    path.write_text(_named(0.9))
    p2 = piezo_job_params(check_piezo_scene("s", raw)[0])
    assert p2["toec_file"]["sha256"] != p1["toec_file"]["sha256"] and p2["toec_file"] != p1["toec_file"]


def test_relative_path_is_read_from_the_config_file_that_gives_it(tmp_path):
    """validate_config resolves a relative toec_file against the directory of the config file
    whose scene gives the key (not the working directory)."""
    (tmp_path / "sets").mkdir()
    (tmp_path / "sets" / "gaas.yaml").write_text(_named())
    cfg = tmp_path / "my.yaml"
    cfg.write_text("scenes:\n  g:\n    materials: [GaAs]\n    euler: {phi: 0, theta: 0, psi: 45}\n"
                   "    stress: [0.1]\n    toec: [true]\n    toec_file: sets/gaas.yaml\n")
    import yaml

    config = yaml.safe_load(cfg.read_text())
    scenes = validate_config(config, sources={"g": [str(cfg)]})
    assert scenes["g"]["toec_file"]["path"] == str((tmp_path / "sets" / "gaas.yaml").resolve())
