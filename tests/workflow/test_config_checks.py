"""Config problems Snakemake's own YAML reading hides, refused before any job (real Snakemake
runs, marker `workflow`; issue 20 items 2 and 5 and the messages list).

Snakemake reads config files with PyYAML: a repeated scene key keeps the last definition
silently, and 1.0e8 (no sign after e) is the text '1.0e8', which the schema refused with
"not valid under any of the given schemas". Before this change the first ran the last
definition, the second gave that message, and a user scene named like a default scene was
merged into it with errors about keys the user never wrote.
"""
from __future__ import annotations

import pytest
from test_workflow import make_workdir, smk

pytestmark = [pytest.mark.workflow, pytest.mark.xdist_group("workflow")]


def run_bad(tmp_path, text: str) -> str:
    wd = make_workdir(tmp_path)
    bad = tmp_path / "bad.yaml"
    bad.write_text(text)
    proc = smk(wd, "-n", "--configfile", "config/config.yaml", str(bad), check=False)
    assert proc.returncode != 0
    assert not (wd / "results").exists()  # no job ran
    return proc.stdout + proc.stderr


def test_duplicate_scene_key_is_refused(tmp_path):
    text = run_bad(tmp_path, "scenes:\n  mine:\n    materials: [Cu]\n    surfaces: ['(001)']\n"
                             "  mine:\n    materials: [Ag]\n    surfaces: ['(001)']\n")
    assert "bad.yaml" in text and "duplicate key 'mine' at line 5 (first defined at line 2)" in text


def test_text_float_stress_and_redefined_scene(tmp_path):
    text = run_bad(tmp_path, "scenes:\n"
                             "  mine:\n    materials: [Cu]\n    surfaces: ['(001)']\n    directions: ['[100]']\n"
                             "    stress: [0, 1.0e8]\n"
                             "  tiny_crystal:\n    lattice: fcc\n")
    assert "scene 'mine', key 'stress': value 100000000.0: stress must be in GPa" in text and "looks like Pa" in text
    assert "any of the given schemas" not in text
    assert "scene 'tiny_crystal' is defined in config/config.yaml and again in" in text


def test_wrong_typed_value_is_one_line_not_a_hang(tmp_path):
    """Issue 28 item 1: `stress: "0.1"` (a key of several shapes, every branch a type mismatch) made
    the schema message builder loop forever under `snakemake -n`; now one line within the timeout."""
    text = run_bad(tmp_path, "scenes:\n  mine:\n    materials: [Cu]\n    surfaces: ['(001)']\n"
                             "    stress: '0.1'\n")
    assert "scene 'mine', key 'stress': value '0.1' is text" in text and "a list of numbers" in text
