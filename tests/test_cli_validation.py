"""Bad command lines: exit code 2 and one line naming the argument and value, no traceback
(issue 20, item 9 and "Tracebacks and misleading messages"). Before this change --angle
0:inf:1 and nan:10:1 raised from numpy, 0:90:1e-12 and 0:1e9:1 tried to allocate 9e13 and
1e9 angles, and a Miller index of 1e20 ended in an OverflowError traceback."""
from __future__ import annotations

import pytest

from surfwave.cli import main


@pytest.mark.parametrize("args, fragment", [
    (["--angle", "0:inf:1"], "--angle must be finite numbers of degrees, got inf in '0:inf:1'"),
    (["--angle", "nan:10:1"], "--angle must be finite numbers of degrees, got nan"),
    (["--angle", "0:90:1e-12"], "--angle sweep '0:90:1e-12' has 9e+13 angles, more than the limit of 100000"),
    (["--angle", "0:900000:1"], "has 9e+05 angles, more than the limit"),
    (["--angle", "0:1e9:1"], "--angle 1000000000.0 degrees: angles beyond 1e+06 degrees"),
    (["--angle", "1e20"], "--angle 1e+20 degrees"),
    (["--direction", "[100000000000000000000 1 0]"], "Miller indices must not exceed"),
    (["--rho", "1e-300"], "rho = 1e-300 kg/m^3 lies outside"),
])
def test_material_bad_arguments(capsys, args, fragment):
    assert main(["material", "--material", "Cu", *args]) == 2
    err = capsys.readouterr().err
    assert fragment in err, err
    assert err.count("\n") == 1 and "Traceback" not in err


def test_scenes_bad_configfile(tmp_path, capsys):
    """`surfwave scenes` with a scene whose symmetric step is 1e-300 (before: ValueError from
    numpy) and a file with a duplicate scene key (before: the last one silently kept)."""
    bad = tmp_path / "bad.yaml"
    bad.write_text("scenes:\n  cu:\n    materials: [Cu]\n    surfaces: ['(001)']\n"
                   "    angles: {symmetric: true, step: 1.0e-300}\n")
    assert main(["scenes", "--configfile", str(bad)]) == 2
    err = capsys.readouterr().err
    assert "scene 'cu', key 'angles': step 1e-300" in err and "Traceback" not in err
    dup = tmp_path / "dup.yaml"
    dup.write_text("scenes:\n  cu:\n    materials: [Cu]\n    surfaces: ['(001)']\n"
                   "  cu:\n    materials: [Ag]\n    surfaces: ['(001)']\n")
    assert main(["scenes", "--configfile", str(dup)]) == 2
    assert "duplicate key 'cu' at line 5" in capsys.readouterr().err
