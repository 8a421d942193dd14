"""Bad command lines (the CLI's door): exit code 2 and one line naming the option and the value,
within seconds, no traceback; and the stress sweep and radians note of this change.

Issue 28 item 2: ``--euler 0 0:1e9:1 0`` filled the memory, ``0:1e6:1`` ran past the 100,000-point
cap that --angle and the scenes enforce, ``0:nan:1``, ``0:inf:1`` and ``0:360:1e-20`` ended in
tracebacks; item 9/11: ``point --d-over-d0 1e6`` ran for minutes and ``1e308`` ended in an
OverflowError. Each row runs ``main()`` in-process (no interpreter start) under the hang guard.
"""
from __future__ import annotations

import json

import pytest
from hang_guard import within

import surfwave
from surfwave.cli import main

LN = ["material", "--material", "LiNbO3"]
CU = ["material", "--material", "Cu"]
POINT = ["point", "--lattice", "fcc", "--loading", "uniaxial", "--potential", "lj", "--direction", "[100]"]

# (argv, fragment of the one-line error)
TABLE = [
    ([*LN, "--euler", "0", "0:nan:1", "0"], "--euler must be finite numbers of degrees, got nan in '0:nan:1'"),
    ([*LN, "--euler", "0", "0:inf:1", "0"], "--euler must be finite numbers of degrees, got inf"),
    ([*LN, "--euler", "0", "0:360:1e-20", "0"], "--euler sweep '0:360:1e-20' has 3.6e+22 angles, more than the "
                                                "limit of 100000"),
    ([*LN, "--euler", "0", "0:1e9:1", "0"], "--euler 1000000000.0 degrees: angles beyond 1e+06 degrees"),
    ([*LN, "--euler", "0", "0:1e6:1", "0"], "--euler sweep '0:1e6:1' has 1e+06 angles, more than the limit"),
    ([*LN, "--euler", "0", "x", "0"], "--euler must be a number or START:STOP:STEP in degrees, got 'x'"),
    ([*LN, "--euler", "0", "-inf:0:1", "0"], "--euler must be finite numbers of degrees, got -inf"),
    ([*LN, "--euler", "0:1:1", "0:1:1", "0"], "only one Euler angle may be a sweep"),
    ([*CU, "--angle", "0:nan:1"], "--angle must be finite numbers of degrees, got nan"),
    ([*CU, "--angle", "1e5:100001:1e-12"], "--angle sweep '1e5:100001:1e-12' has 1e+12 angles"),
    ([*CU, "--stress", "0:1e9:1"], "--stress 1000000000.0 GPa lies beyond 100000 GPa: it looks like Pa"),
    ([*CU, "--stress", "-inf:0:1"], "--stress must be finite numbers of GPa, got -inf"),
    ([*CU, "--stress", "0:1:1e-9"], "--stress sweep '0:1:1e-9' has 1e+09 stresses, more than the limit"),
    ([*CU, "--stress", "0", "0.1:0.2:0.1"], "not a sweep among other values"),
    ([*CU, "--stress", "a", "b"], "--stress must be a number or START:STOP:STEP in GPa, got 'a'"),
    ([*CU, "--angle", "0:90:45", "--stress", "0", "0.1"], "one sweep at a time"),
    ([*POINT, "--d-over-d0", "1e308"], "d/d0 = 1e+308"),
    ([*POINT, "--d-over-d0", "1e6"], "d/d0 = 1e+06"),
    ([*POINT, "--d-over-d0", "nan"], "d_over_d0 must be finite"),
]


@pytest.mark.parametrize("argv, fragment", TABLE, ids=[" ".join(row[0][3:]) for row in TABLE])
def test_cli_refuses_in_one_line_within_seconds(capsys, argv, fragment):
    with within(5, " ".join(argv)):
        assert main(argv) == 2
    captured = capsys.readouterr()
    err = captured.err
    assert err.count("\n") == 1 and "Traceback" not in err and captured.out == "", err
    assert fragment in err, (fragment, err)


def test_stress_sweep_matches_the_api_point_by_point(capsys):
    """Issue 27: ``--stress -0.1 0 0.1`` and ``--stress -0.1:0.1:0.1`` give one row per stress,
    each equal to :func:`surfwave.material` at that stress (the one computation)."""
    for tokens in (["-0.1", "0", "0.1"], ["-0.1:0.1:0.1"]):
        assert main([*CU, "--direction", "[100]", "--stress", *tokens, "--json"]) == 0
        rows = json.loads(capsys.readouterr().out)
        assert [r["stress"] for r in rows] == pytest.approx([-0.1, 0.0, 0.1], abs=1e-15)
        for r in rows:
            ref = surfwave.material("Cu", direction="[100]", stress=r["stress"])
            assert r["c_R"] == pytest.approx(ref["c_R"], rel=1e-12)
    assert rows[0]["c_R"] < rows[1]["c_R"] < rows[2]["c_R"]  # the stress is applied (2009 < 2012 < 2015 m/s)
    assert main([*LN, "--cut", "128Y-X", "--stress", "-0.1", "0.1"]) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[1].split()[:3] == ["stress", "v_free", "v_met"] and len(out) == 4
    ref = surfwave.material("LiNbO3", cut="128Y-X", stress=0.1)
    assert out[3].split()[1] == f"{ref['c_free']:.2f}"


def test_nine_stresses_are_still_the_tensor(capsys):
    tensor = ["0.1", "0", "0", "0", "0", "0", "0", "0", "0"]
    assert main([*CU, "--direction", "[100]", "--stress", *tensor, "--json"]) == 0
    row = json.loads(capsys.readouterr().out)
    assert row["c_R"] == pytest.approx(surfwave.material("Cu", direction="[100]", stress=0.1)["c_R"], rel=1e-12)


def test_radians_note(capsys):
    """Issue 27: ``--euler 0 0.663 0`` (38 degrees in radians) is taken as degrees, with one note."""
    assert main([*LN, "--euler", "0", "0.663", "0"]) == 0
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "0.663 rad = 37.99 deg" in err and err.startswith("note:"), err
    assert main([*LN, "--euler", "0", "38", "0"]) == 0
    assert capsys.readouterr().err == ""
