"""Bad scene configs (the scene door): each refused within seconds, one line per problem naming
scene, key and value, through the library call and through ``surfwave scenes --configfile``.

Issue 28 item 1: before this change a wrong-typed value of a key that takes several shapes
(``stress: "0.1"``, ``stress: null``, ``euler: {theta: "38"}``, ``theta: null``,
``d_over_d0: "0.95"``, ``directions: null``) made the schema message builder loop forever (its
``oneOf`` walk got the same error back when every branch was a type mismatch). Item 11: a binary
config file ended in UnicodeDecodeError and a YAML list in AttributeError. Item 9: d/d0 = 1e6 in
an FCC uniaxial scene ran the lateral solve for minutes. Issue 27: a piezoelectric scene without
``cuts``/``euler`` was told only "unknown key 'electrical'"; a mistyped key hid a mistyped material.
The fragments are this change's messages; the hang guard (:mod:`hang_guard`) fails a test that
takes more than a few seconds.
"""
from __future__ import annotations

import subprocess
import sys

import pytest
from hang_guard import within

from surfwave.cli import main
from surfwave.pipeline.scenes import SceneError, validate_config

LATTICE = {"lattice": "fcc", "loading": "uniaxial", "potentials": ["lj"], "quantities": ["elastic"],
           "d_over_d0": [1.0]}
CRYSTAL = {"materials": ["Cu"], "surfaces": ["(001)"]}
PIEZO = {"materials": ["LiNbO3"], "euler": {"theta": -52.0}}

# (scene, fragments of the one message)
TABLE = [
    ({**CRYSTAL, "stress": "0.1"}, ["key 'stress'", "value '0.1' is text", "a list of numbers",
                                    "a grid {start, stop, step}", "without quotes"]),
    ({**CRYSTAL, "stress": None}, ["key 'stress'", "value None is null", "a list of numbers"]),
    ({**PIEZO, "stress": None}, ["key 'stress'", "value None is null"]),
    ({**PIEZO, "euler": {"theta": "38"}}, ["key 'euler/theta'", "value '38' is text", "a number"]),
    ({**PIEZO, "euler": {"theta": None}}, ["key 'euler/theta'", "value None is null"]),
    ({**LATTICE, "d_over_d0": "0.95"}, ["key 'd_over_d0'", "value '0.95' is text"]),
    ({**LATTICE, "directions": None}, ["key 'directions'", "value None is null", "'[100]'"]),
    ({**LATTICE, "theta": None}, ["key 'theta'", "value None is null"]),
    ({**LATTICE, "d_over_d0": [1.0e6]}, ["key 'd_over_d0'", "d/d0 = 1e+06", "below 2"]),
    ({**LATTICE, "d_over_d0": [1.0e308]}, ["key 'd_over_d0'", "d/d0 = 1e+308"]),
    ({**CRYSTAL, "angles": {"symmetric": True, "step": "1"}}, ["key 'angles/step'", "'1' is text"]),
    ({**CRYSTAL, "angles": None}, ["key 'angles'", "value None is null", "'symmetric'"]),
    ({**CRYSTAL, "angles": "sym"}, ["key 'angles'", "value 'sym' is text", "'symmetric'"]),
    # a step so small that the point count overflows (before: OverflowError from int(inf))
    ({**LATTICE, "d_over_d0": {"start": 0.5, "stop": 1.9, "step": 5e-324}}, ["key 'd_over_d0'", "inf points exceed"]),
    ({**LATTICE, "d_over_d0": {"start": 0.5, "stop": 1.9, "step": 1e-300}}, ["1.4e+300 points exceed"]),
    ({**PIEZO, "euler": {"theta": True}}, ["key 'euler/theta'", "value True is true/false"]),
]


@pytest.mark.parametrize("scene, fragments", TABLE)
def test_bad_scene_is_one_line_within_seconds(scene, fragments):
    with within(5, str(scene)), pytest.raises(SceneError) as err:
        validate_config({"scenes": {"s": scene}})
    text = str(err.value)
    assert "\n" not in text and "scene 's'" in text, text
    for fragment in fragments:
        assert fragment in text, (fragment, text)


def write(tmp_path, scene: dict) -> str:
    import yaml

    path = tmp_path / "bad.yaml"
    path.write_text(yaml.safe_dump({"scenes": {"bad": scene}}))
    return str(path)


@pytest.mark.parametrize("scene, fragments", TABLE[:8])
def test_scenes_command_answers_within_seconds(tmp_path, capsys, scene, fragments):
    """The same scenes through ``surfwave scenes --configfile`` (main() in-process): exit 2, one line."""
    path = write(tmp_path, scene)
    with within(10, str(scene)):
        assert main(["scenes", "--configfile", path]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and "scene 'bad'" in err, err
    assert fragments[0] in err, err


def test_scenes_command_subprocess_does_not_hang(tmp_path):
    """One real process (the console entry point) on the first input that hung, with a timeout."""
    path = write(tmp_path, {**CRYSTAL, "stress": "0.1"})
    proc = subprocess.run([sys.executable, "-m", "surfwave", "scenes", "--configfile", path],
                          capture_output=True, text=True, timeout=60)
    assert proc.returncode == 2 and "value '0.1' is text" in proc.stderr, proc.stderr


@pytest.mark.parametrize("content, fragments", [
    (b"\x89PNG\r\n\x1a\n\x00\x00\x00\rIHDR\xff\xfe", ["is not a text file", "not UTF-8"]),
    (b"- scenes\n- run\n", ["holds a list, not a mapping", "'scenes'"]),
    (b"42\n", ["holds the single value 42, not a mapping"]),
    (b"scenes: [\n", ["is not valid YAML"]),
])
def test_scenes_command_bad_file(tmp_path, capsys, content, fragments):
    """A binary file (before: UnicodeDecodeError) and a YAML list (before: AttributeError)."""
    path = tmp_path / "bad.yaml"
    path.write_bytes(content)
    with within(10, repr(content)):
        assert main(["scenes", "--configfile", str(path)]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Traceback" not in err and "bad.yaml" in err, err
    for fragment in fragments:
        assert fragment in err, (fragment, err)


def test_config_not_a_mapping():
    with pytest.raises(SceneError, match="must be a mapping with the key 'scenes', got list"):
        validate_config(["scenes"])  # type: ignore[arg-type]


def problems(scene: dict) -> list[str]:
    with within(5, str(scene)), pytest.raises(SceneError) as err:
        validate_config({"scenes": {"s": scene}})
    text = str(err.value)
    return text.split("\n  - ")[1:] if "\n" in text else [text]


def test_piezo_keys_without_cuts_or_euler_say_what_the_kinds_need():
    """Issue 27: ``electrical`` without ``cuts``/``euler`` makes an elastic real-crystal scene; the
    message says so, names the kind that has ``electrical`` and what each kind needs."""
    found = problems({"materials": ["LiNbO3"], "electrical": ["free"]})
    text = "\n".join(found)
    assert "unknown key 'electrical' (a key of piezoelectric scenes, which have 'materials' with 'cuts' or " \
           "'euler')" in text, text
    assert "required key 'surfaces' is missing: the scene is read as an elastic real-crystal scene" in text
    assert "a piezoelectric scene ('materials' with 'cuts' or 'euler') needs materials and either cuts or euler" \
        in text
    # and the material, valid only in the piezoelectric database, is named as such
    assert "value 'LiNbO3': it is a crystal of the piezoelectric database" in text


def test_material_for_materials_gets_did_you_mean():
    found = problems({"material": ["LiNbO3"], "euler": {"theta": -52.0}})
    text = "\n".join(found)
    assert "'material' (did you mean 'materials', a key of" in text, text
    assert "read as a model-lattice scene (no 'materials' key)" in text


def test_every_problem_of_a_scene_at_once():
    """A mistyped key no longer hides a mistyped material (both in one run, did-you-mean each)."""
    found = problems({"materials": ["LiNbO"], "euler": {"theta": -52.0}, "electrcal": ["free"]})
    assert len(found) == 2, found
    assert "unknown key 'electrcal' (did you mean 'electrical'?)" in found[0]
    assert "key 'materials': value 'LiNbO'" in found[1] and "did you mean LiNbO3" in found[1]


def test_good_scenes_still_pass():
    out = validate_config({"scenes": {"a": {**CRYSTAL, "stress": [0.0, 0.1]}, "b": {**PIEZO, "stress": [0.1]},
                                      "c": {**LATTICE, "d_over_d0": [0.9, 1.0, 1.2], "directions": ["[100]"]}}})
    assert out["a"]["stress"] == [0.0, 0.1] and out["c"]["d_over_d0"] == [0.9, 1.0, 1.2]


def test_radians_note_for_a_scene(tmp_path, capsys):
    """Issue 27: a scene whose Euler angles all look like radians (theta 0.663 = 38 deg) runs in
    degrees, and ``surfwave scenes`` says so in one note line; degrees give no note."""
    path = write(tmp_path, {**PIEZO, "euler": {"theta": [0.663, 0.7]}})
    assert main(["scenes", "--configfile", path]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "Euler angles of scene 'bad'" in err and "0.7 rad = 40.11 deg" in err, err
    path = write(tmp_path, PIEZO)
    assert main(["scenes", "--configfile", path]) == 0
    assert capsys.readouterr().err == ""


def test_the_rest_of_a_broken_scene_is_checked_too():
    """Every problem in one run: a mistyped key, a mistyped material and a stress in Pa (the
    physical check of what is left of the scene) are reported together."""
    found = problems({"materials": ["LiNbO3", "LiNbO"], "euler": {"theta": -52.0}, "electrcal": ["free"],
                      "stress": [1.0e8]})
    text = "\n".join(found)
    assert len(found) == 3, found
    assert "unknown key 'electrcal'" in text and "value 'LiNbO'" in text and "looks like Pa" in text
    found = problems({**CRYSTAL, "materials": ["Coper"], "stress": [1.0e8]})
    assert len(found) == 1 and "did you mean" in found[0] and "Cu" in found[0]  # nothing left to check: one line
    found = problems({**LATTICE, "potential": ["lj"], "d_over_d0": [1.5e0, 3.0]})
    assert any("unknown key 'potential'" in f for f in found) and any("d/d0 = 3" in f for f in found), found
