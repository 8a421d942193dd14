"""Bad inputs to surfwave.layered are refused with one InputError line before anything is computed."""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.layers import solve

SIO2 = {"E": 70.0, "nu": 0.17, "rho": 2200.0}


@pytest.mark.parametrize(("films", "kw", "match"), [
    ([{**SIO2, "thickness": -1e-6}], {}, "thickness must be >= 0"),
    ([{**SIO2, "thickness": float("nan")}], {}, "finite"),
    ([{**SIO2, "thickness": float("inf")}], {}, "finite"),
    ([{**SIO2, "thickness": 1.0}], {}, "in metres"),
    ([{**SIO2}], {}, "thickness .m. is missing"),
    ([{"E": 70.0, "nu": 0.5, "rho": 2200.0, "thickness": 1e-6}], {}, "Poisson"),
    ([{"E": 70.0, "nu": -1.0, "rho": 2200.0, "thickness": 1e-6}], {}, "Poisson"),
    ([{"E": 70e9, "nu": 0.2, "rho": 2200.0, "thickness": 1e-6}], {}, "looks like Pa"),
    ([{"voigt": np.diag([1.0, 1, 1, 1, 1, -1]), "rho": 1000.0, "thickness": 1e-6}], {}, "not positive definite"),
    ([{**SIO2, "thickness": 1e-6, "stress": [[0, 0, 0.1], [0, 0, 0], [0.1, 0, 0]]}], {}, "loads the surface"),
    ([{**SIO2, "thickness": 1e-6, "stress": [[0, 0, 0], [0, 0, 0], [0, 0, 1.0]]}], {}, "loads the surface"),
    ([{**SIO2, "thickness": 1e-6, "stress": 1e9}], {}, "looks like Pa"),
    ([{**SIO2, "thickness": 1e-6, "colour": "red"}], {}, "unknown keys"),
    ([{"name": "unobtainium", "thickness": 1e-6}], {}, "unknown material"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [-1.0]}, "kh must lie"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [np.nan]}, "finite"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "frequency": [1e9]}, "exactly one"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "electrical": "metallized"}, "piezoelectric"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "stress": [[0, 0, 0], [0, 0, 0], [0, 0, 1.0]]}, "loads the surface"),
    (["SiO2"], {"kh": [1.0]}, "mapping with a thickness"),
])
def test_refused_before_any_computation(films, kw, match, monkeypatch):
    """Each bad input raises InputError (one line, naming the problem) and no mode search runs."""
    def boom(*a, **k):
        raise AssertionError("computed before refusing")

    monkeypatch.setattr(solve, "family_modes", boom)
    kw = {"kh": [1.0], **kw}
    with pytest.raises(InputError, match=match) as exc:
        surfwave.layered("Si", films, **kw)
    assert "\n" not in str(exc.value)


def test_piezo_stack_needs_permittivity():
    """A film without permittivity on a piezoelectric substrate is refused (the potential must be solved in it)."""
    with pytest.raises(InputError, match="permittivity"):
        surfwave.layered("LiNbO3", [{**SIO2, "thickness": 1e-6}], euler=(0, 38, 0), kh=[1.0])
