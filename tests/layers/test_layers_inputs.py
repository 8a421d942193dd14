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
    ([{"voigt": np.diag([1.0, 1, 1, 1, 1, -1]), "rho": 1000.0, "thickness": 1e-6}], {}, "not Born-stable"),
    ([{**SIO2, "thickness": 1e-6, "stress": [[0, 0, 0.1], [0, 0, 0], [0.1, 0, 0]]}], {}, "must lie in the surface plane"),
    ([{**SIO2, "thickness": 1e-6, "stress": [[0, 0, 0], [0, 0, 0], [0, 0, 1.0]]}], {}, "must lie in the surface plane"),
    ([{**SIO2, "thickness": 1e-6, "stress": 1e9}], {}, "looks like Pa"),
    ([{**SIO2, "thickness": 1e-6, "colour": "red"}], {}, "unknown keys"),
    ([{"name": "unobtainium", "thickness": 1e-6}], {}, "unknown material"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [-1.0]}, "kh must lie"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [np.nan]}, "finite"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "frequency": [1e9]}, "exactly one"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "electrical": "metallized"}, "piezoelectric"),
    ([{**SIO2, "thickness": 1e-6}], {"kh": [1.0], "stress": [[0, 0, 0], [0, 0, 0], [0, 0, 1.0]]}, "must lie in the surface plane"),
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


def test_film_database_records_have_sources():
    """Every film of films.yaml carries a cited source for each number, and its stiffness is positive definite."""
    from surfwave.layers.films import _film_db, available_films, lookup

    assert {"fused-SiO2", "Pt-film", "Si3N4", "sapphire"} <= set(available_films())
    for name, rec in _film_db().items():
        assert rec["sources"]["rho"] and ("C" in rec["sources"] or rec["sources"]["E"])
        assert np.linalg.eigvalsh(lookup(name)["voigt"])[0] > 0
    # a film called SiO2 is fused silica; a substrate called SiO2 is alpha-quartz (piezoelectric database)
    assert lookup("SiO2")["name"] == "fused-SiO2"
    assert lookup("SiO2", film=False)["name"].startswith("quartz")


def test_polycrystal_hill_average_is_between_bounds():
    """'Au-poly' is the Voigt-Reuss-Hill average of the Au crystal: isotropic, G between the Reuss and Voigt bounds."""
    from surfwave.layers.films import lookup
    from surfwave.real_crystals.materials import get_material

    C = lookup("Au-poly")["voigt"]
    c11, c12, c44 = (get_material("Au").constants[k] for k in ("C11", "C12", "C44"))
    G = C[3, 3]
    gv = (c11 - c12 + 3 * c44) / 5
    gr = 5 * (c11 - c12) * c44 / (4 * c44 + 3 * (c11 - c12))
    assert min(gv, gr) < G < max(gv, gr)
    assert C[0, 0] - C[0, 1] == pytest.approx(2 * G)


def test_stress_frames():
    """A scalar film stress s is equibiaxial in the surface plane: sigma = diag(s, 0, s) GPa in the solver's
    lab frame (x2 = inward normal carries none); a SAW-frame tensor (x3' outward) maps as x2 = -x3', x3 = x2'."""
    from surfwave.layers.stack import resolve_stack

    f = resolve_stack("Si", [{**SIO2, "thickness": 1e-6, "stress": -0.4}]).films[0]
    np.testing.assert_allclose(f.sigma, np.diag([-0.4, 0.0, -0.4]) * 1e9)
    s = np.array([[0.1, 0.2, 0.0], [0.2, 0.3, 0.0], [0.0, 0.0, 0.0]])
    g = resolve_stack("Si", [{**SIO2, "thickness": 1e-6, "stress": s}]).films[0]
    np.testing.assert_allclose(g.sigma, np.array([[0.1, 0, 0.2], [0, 0, 0], [0.2, 0, 0.3]]) * 1e9)
