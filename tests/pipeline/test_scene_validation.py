"""Bad scenes refused before any job, one line naming scene, key and value (issue 20, items
2-5 and 9 and the list "Tracebacks and misleading messages").

Each row is a scene the old code accepted (stress in Pa, unbounded tol, angle 1e20, an alias
of the same material, 90001 x 201 FCC angle points), crashed on (Miller index 1e20 ->
OverflowError; {symmetric: true, step: 1e-300} -> ValueError from numpy) or answered with a
misleading message (step 0 -> "'symmetric' was expected"; stress '1.0e8' as text -> "not
valid under any of the given schemas"). The fragments are the messages of this change.
"""
from __future__ import annotations

import pytest

from surfwave.pipeline import scenes
from surfwave.pipeline.scenes import SceneError, load_config, validate_config


def load_yaml(path):
    return scenes.load_yaml(path)


def config_sources(paths):
    return scenes.config_sources(paths)


def crystal(**over):
    scene = {"materials": ["Cu"], "surfaces": ["(001)"], "directions": ["[100]"]}
    scene.update(over)
    return scene


def fcc_angles(**over):
    scene = {"lattice": "fcc", "loading": "in_plane_hydrostatic", "potentials": ["lj"],
             "directions": [0.0, 45.0], "d_over_d0": [0.98, 1.0], "quantities": ["rayleigh"]}
    scene.update(over)
    return scene


@pytest.mark.parametrize("scene, fragments", [
    # 2. stress in Pa
    (crystal(stress=[0, 1.0e+8]), ["scene 's'", "key 'stress'", "value 100000000.0", "looks like Pa",
                                   "0.1 GPa"]),
    # stress written 1.0e8, which PyYAML (and so Snakemake) reads as the text '1.0e8'
    (crystal(stress=[0, "1.0e8"]), ["scene 's'", "key 'stress'", "looks like Pa"]),
    # 3. tol unbounded
    (crystal(accuracy={"surface_wave": {"tol": 1e-30}}), ["scene 's'", "accuracy/surface_wave/tol",
                                                          "1e-30", "minimum of 1e-14"]),
    (crystal(accuracy={"surface_wave": {"tol": 0.5}}), ["accuracy/surface_wave/tol", "0.5",
                                                        "maximum of 1e-06"]),
    # 4. an angle beyond float64 precision
    (crystal(directions=None, angles=[0, 1.0e+20]), ["scene 's'", "key 'angles'", "1e+20", "modulo 360"]),
    (fcc_angles(directions=[0.0, 1.0e20]), ["scene 's'", "key 'directions'", "1e+20", "modulo 360"]),
    # 5. two names of one material
    (crystal(materials=["Cu", "copper"]), ["scene 's'", "key 'materials'", "'Cu' and 'copper'", "same material"]),
    (crystal(materials=["Cu", "CU"]), ["'Cu' and 'CU'", "same material 'Cu'"]),
    # 9. the product of an FCC angle scene's grids
    (fcc_angles(directions={"start": 0, "stop": 90, "step": 0.001},
                d_over_d0={"start": 0.98, "stop": 1.0, "step": 0.0001}),
     ["scene 's'", "90001 angles x 201 d/d0", "limit of 100000"]),
    # messages: a Miller index that overflows int64
    (crystal(directions=["[100000000000000000000 1 0]"]), ["scene 's'", "key 'directions'",
                                                           "Miller indices must not exceed"]),
    # messages: symmetric angles with a step of 1e-300, 0, -1
    (crystal(directions=None, angles={"symmetric": True, "step": 1e-300}),
     ["scene 's'", "key 'angles'", "step 1e-300", "more than the limit"]),
    (crystal(directions=None, angles={"symmetric": True, "step": 0}),
     ["scene 's'", "angles/step", "value 0", "less than or equal to the minimum of 0"]),
    (crystal(directions=None, angles={"symmetric": True, "step": -1}),
     ["scene 's'", "angles/step", "value -1"]),
])
def test_bad_scene_one_line(scene, fragments):
    scene = {k: v for k, v in scene.items() if v is not None}
    with pytest.raises(SceneError) as err:
        validate_config({"scenes": {"s": scene}})
    text = str(err.value)
    for fragment in fragments:
        assert fragment in text, (fragment, text)
    assert "\n" not in text and "was expected" not in text and "any of the given schemas" not in text


def test_text_floats_are_read_as_numbers():
    """'1.0e-1' (a YAML 1.2 float PyYAML leaves as text) is the number 0.1 GPa."""
    out = validate_config({"scenes": {"s": crystal(stress=["-1.0e-1", 0, "1.0e-1"])}})
    assert out["s"]["stress"] == [-0.1, 0.0, 0.1]


def test_tol_in_range_and_the_default_pass():
    for acc in ({}, {"surface_wave": {"tol": 1e-9}}, {"surface_wave": {"tol": None}}):
        validate_config({"scenes": {"s": crystal(accuracy=acc)}})


def test_yaml_duplicate_scene_key_names_file_key_and_lines(tmp_path):
    f = tmp_path / "my.yaml"
    f.write_text("scenes:\n  cu:\n    materials: [Cu]\n    surfaces: ['(001)']\n"
                 "  cu:\n    materials: [Ag]\n    surfaces: ['(001)']\n")
    for read in (load_yaml, lambda p: load_config([p]), lambda p: config_sources([p])):
        with pytest.raises(SceneError) as err:
            read(f)
        assert str(f) in str(err.value) and "duplicate key 'cu' at line 5 (first defined at line 2)" in str(err.value)


def test_yaml_reads_yaml12_floats(tmp_path):
    f = tmp_path / "my.yaml"
    f.write_text("a: 1.0e8\nb: 1e-3\nc: -2E+2\nd: '1.0e8'\ne: 1.5\nf: 10\ng: (001)\n")
    assert load_yaml(f) == {"a": 1.0e8, "b": 1e-3, "c": -200.0, "d": "1.0e8", "e": 1.5, "f": 10, "g": "(001)"}


def test_redefined_default_scene_says_so(tmp_path):
    """A user scene named like a default scene is merged into it (Snakemake's merge); the
    problems that follow get a line naming both files."""
    default = scenes.SCHEMA_PATH.parents[2] / "config" / "config.yaml"
    mine = tmp_path / "my.yaml"
    mine.write_text("scenes:\n  crystals:\n    lattice: fcc\n    loading: in_plane_hydrostatic\n"
                    "    potentials: [lj]\n    d_over_d0: [1.0]\n    quantities: [elastic]\n")
    files = [default, mine]
    with pytest.raises(SceneError) as err:
        validate_config(load_config(files), sources=config_sources(files))
    assert f"scene 'crystals' is defined in {default} and again in {mine}" in str(err.value)
    assert "a name of its own" in str(err.value)
    # the same file twice (snakemake --configfile config/config.yaml) is one source
    assert all(len(v) == 1 for v in config_sources([default, default]).values())
