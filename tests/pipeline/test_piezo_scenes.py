"""Piezoelectric scenes refuse what real-crystal scenes refuse (issue 20, items 2, 4 and 5),
through the same checks (surfwave.pipeline.crystal_scenes: unique_records, stress_grid,
check_angle_range). References: the refusal wording of the real-crystal scene checks, and the
piezoelectric database's aliases ("lithium niobate" is LiNbO3; "128YX" is "128Y-X LiNbO3")."""
from __future__ import annotations

import pytest

from surfwave.pipeline.piezo_scenes import check_piezo_scene

BAD = [
    ({"materials": ["LiNbO3"], "cuts": ["Y-Z LiNbO3"], "stress": [0, 1.0e8]}, "looks like Pa"),
    ({"materials": ["LiNbO3"], "euler": {"phi": 0, "theta": [0, 1.0e20], "psi": 0}}, "lose precision"),
    ({"materials": ["LiNbO3", "lithium niobate"], "cuts": ["Y-Z LiNbO3"]}, "name the same material"),
    ({"materials": ["LiNbO3"], "cuts": ["128Y-X", "128YX"]}, "name the same cut"),
]


@pytest.mark.parametrize("raw, fragment", BAD)
def test_bad_piezo_scene_is_one_clear_line(raw, fragment):
    scene, problems = check_piezo_scene("s", raw)
    assert scene is None and len(problems) == 1
    assert fragment in problems[0] and problems[0].startswith("scene 's', key ")


def test_valid_piezo_scene_still_expands():
    scene, problems = check_piezo_scene("s", {"materials": ["LiNbO3"], "cuts": ["Y-Z LiNbO3"],
                                              "stress": [-0.1, 0, 0.1]})
    assert problems == [] and scene["stress"] == [-0.1, 0.0, 0.1] and scene["cuts"] == ["Y-Z LiNbO3"]
