"""Bad inputs through the library's door (the API): each refused within seconds with one line,
a named surfwave error (InputError, or GeometryError for a d/d0 no geometry can take), before
any computation.

Issue 28 item 11: before this change each row below ended in a numpy or Python traceback
(ValueError, TypeError, OverflowError) or, for d/d0 = 1e6 (item 9), ran the lateral
continuation for minutes (5e7 steps). The hang guard (:mod:`hang_guard`) fails a row that takes
longer than a few seconds. A new argument of the API should get its row here.
"""
from __future__ import annotations

import numpy as np
import pytest
from hang_guard import within

import surfwave
from surfwave.errors import GeometryError, InputError, SurfwaveError
from surfwave.solvers.rayleigh import rayleigh_c2

LN = "LiNbO3"

# (label, call, error class, fragment of the one-line message)
TABLE = [
    ("euler empty", lambda: surfwave.material(LN, euler=np.zeros((0, 3))), InputError,
     "at least one (phi, theta, psi) row"),
    ("euler text", lambda: surfwave.material(LN, euler="0 38 0"), InputError, "euler must be numbers, got text"),
    ("euler complex", lambda: surfwave.material(LN, euler=[0, 38j, 0]), InputError, "complex"),
    ("euler ragged", lambda: surfwave.material(LN, euler=[[0, 38, 0], [0, 1]]), InputError,
     "rows of different lengths"),
    ("euler mapping", lambda: surfwave.material(LN, euler={"theta": 38}), InputError, "got a mapping"),
    ("euler nan", lambda: surfwave.material(LN, euler=(0, np.nan, 0)), InputError, "must be finite"),
    ("euler shape", lambda: surfwave.material(LN, euler=(0, 38)), InputError, "got shape (2,)"),
    ("euler 1e20", lambda: surfwave.material(LN, euler=(0, 1e20, 0)), InputError, "modulo 360"),
    ("toec ragged", lambda: surfwave.material("Cu", stress=0.1, toec=[[1, 2], [3]]), InputError,
     "toec must be numbers in a regular array"),
    ("toec text value", lambda: surfwave.material("Cu", stress=0.1, toec=("a", 1, 2, 3, 4, 5)), InputError,
     "toec must be numbers, got text"),
    ("toec text", lambda: surfwave.material("Cu", stress=0.1, toec="abc"), InputError, "toec must be numbers"),
    ("point 1e308", lambda: surfwave.point("fcc", "uniaxial", "lj", "[100]", [1e308]), GeometryError,
     "d/d0 = 1e+308"),
    ("point 1e6", lambda: surfwave.point("fcc", "uniaxial", "lj", "[100]", [1e6]), GeometryError,
     "below 2"),
    ("point 1e6 general", lambda: surfwave.point("fcc", "uniaxial", "lj", 10.0, [1e6], load_direction="[100]"),
     GeometryError, "d/d0 = 1e+06"),
    ("rayleigh_c2 text", lambda: rayleigh_c2("abc", 1), InputError, "S must be numbers, got text"),
    ("rayleigh_c2 shape", lambda: rayleigh_c2(np.zeros((2, 2)), 1), InputError, "(..., 2, 2, 2, 2) or (..., 3, 3, 3, 3)"),
]


@pytest.mark.parametrize("label, call, error, fragment", TABLE, ids=[row[0] for row in TABLE])
def test_api_refuses_in_one_line_within_seconds(label, call, error, fragment):
    with within(5, label), pytest.raises(error) as err:
        call()
    text = str(err.value)
    assert isinstance(err.value, SurfwaveError) and "\n" not in text, text
    assert fragment in text, (fragment, text)


def test_euler_guard_is_shared():
    """The guard the API uses is the library's one function (a new door calls it too)."""
    from surfwave.solvers.euler import euler_lab_axes
    from surfwave.validate import euler_angles

    for bad in ("0 38 0", np.zeros((0, 3)), [[0, 1, 2], [3]]):
        with pytest.raises(InputError):
            euler_angles(bad)
        with pytest.raises(InputError):
            euler_lab_axes(bad)
    assert euler_angles([[0, -52, 0], [0, 38, 0]]).shape == (2, 3)


def test_continuation_stops_once_every_point_has_failed(monkeypatch):
    """Issue 28 item 9: the lateral continuation marched on after every point had failed (Newton
    called at each of its (d/d0 - 1)/0.02 steps). LJ along [110] at d/d0 = 1.9 fails part of the
    way (checked here: the point is reported failed); after that no Newton step may be taken."""
    from surfwave.model_crystals import lattices
    from surfwave.model_crystals.potentials import get_potential

    calls = []
    newton = lattices._newton

    def counting(*args, **kw):
        calls.append(args[1].size)
        return newton(*args, **kw)

    monkeypatch.setattr(lattices, "_newton", counting)
    s = np.array([1.9])
    t, failed = lattices._continuation(lattices._fcc_lab("[110]")[0] ** 2, s, get_potential("lj"), 1e-13, 60)
    steps = 1 + int(np.ceil(0.9 / 0.02))
    assert failed.all()
    assert len(calls) < steps and all(n > 0 for n in calls), (len(calls), steps)
