"""The layered door of the real-crystal questions: the same input, the same refusal or answer.

:func:`surfwave.layered` resolves its substrate and films through the one door of
:func:`surfwave.material` (:func:`surfwave.resolve.resolve_constants`, :func:`surfwave.case.check_stress`,
:mod:`surfwave.validate`, :mod:`surfwave.real_crystals.catalog`). Reference for every refusal:
the words of :func:`surfwave.material` on the same input; the layered door adds only the layer's
name in front ("substrate: ", "film 0 (from the top): "). Reference for the answers: the
half-space solver behind :func:`surfwave.material` (itself checked against closed forms,
tests/solvers/), which a layered stack without films, or with a film of zero thickness, must
reproduce to rounding.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.layers import solve
from surfwave.real_crystals.piezo_materials import get_piezo_material
from surfwave.solvers.boundary import FREE, METALLIZED, Metallized
from surfwave.solvers.tensors import cubic_voigt

SI = cubic_voigt(165.7, 63.9, 79.6)
LN = get_piezo_material("LiNbO3")
LN_E, LN_EPS, LN_C = np.asarray(LN.e, float), np.asarray(LN.eps_r, float), np.asarray(LN.voigt, float)
NAN_EULER = (float("nan"), 38.0, 0.0)
FILM = "film 0 (from the top): "
#: The one-line note of an unverified constant set (ZnO) is the same at both doors; not tested here.
pytestmark = pytest.mark.filterwarnings("ignore:constant set")

#: (label, material() keyword arguments, layered substrate, layered keyword arguments). Each row
#: is one bad crystal asked both ways.
BAD_SUBSTRATES = [
    ("typo in a name", {"C11": "LiNbO"}, "LiNbO", {}),
    ("typo in a name, elastic", {"C11": "Cuu"}, "Cuu", {}),
    ("C in Pa", {"voigt": SI * 1e9, "rho": 2329.0}, {"voigt": SI * 1e9, "rho": 2329.0}, {}),
    ("C not symmetric", {"voigt": SI + np.eye(6, k=1), "rho": 2329.0}, {"voigt": SI + np.eye(6, k=1), "rho": 2329.0},
     {}),
    ("rho 1e-3", {"voigt": SI, "rho": 1e-3}, {"voigt": SI, "rho": 1e-3}, {}),
    ("rho 1e-3 of a named crystal", {"C11": "Si", "rho": 1e-3}, {"name": "Si", "rho": 1e-3}, {}),
    ("rho missing", {"voigt": SI}, {"voigt": SI}, {}),
    ("e x 1e6", {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E * 1e6, "permittivity": LN_EPS},
     {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E * 1e6, "permittivity": LN_EPS}, {}),
    ("eps_r < 1", {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E, "permittivity": 0.5 * np.eye(3)},
     {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E, "permittivity": 0.5 * np.eye(3)}, {}),
    ("NaN Euler angle", {"C11": "LiNbO3", "euler": NAN_EULER}, "LiNbO3", {"euler": NAN_EULER}),
    ("Euler angles as text", {"C11": "LiNbO3", "euler": "0 38 0"}, "LiNbO3", {"euler": "0 38 0"}),
    ("NaN direction", {"C11": "Si", "direction": float("nan")}, "Si", {"direction": float("nan")}),
    ("stress in Pa", {"C11": "Si", "stress": 2000.0}, "Si", {"stress": 2000.0}),
    ("stress NaN", {"C11": "Si", "stress": float("nan")}, "Si", {"stress": float("nan")}),
    ("stress True", {"C11": "Si", "stress": True}, "Si", {"stress": True}),
]


def _refusal(call) -> str:
    with pytest.raises(InputError) as exc:
        call()
    return str(exc.value)


@pytest.fixture
def no_mode_search(monkeypatch):
    """Refusals come before any computation: the mode search must not run."""
    def boom(*a, **k):
        raise AssertionError("computed before refusing")

    monkeypatch.setattr(solve, "family_modes", boom)


@pytest.mark.parametrize(("label", "mkw", "sub", "lkw"), BAD_SUBSTRATES, ids=[r[0] for r in BAD_SUBSTRATES])
def test_a_bad_substrate_is_the_same_refusal(label, mkw, sub, lkw, no_mode_search):
    """surfwave.layered refuses the substrate with the words of surfwave.material after "substrate: "
    (an unknown name: the same did-you-mean and list, the film database added at the end, which only
    the layered door knows)."""
    api = _refusal(lambda: surfwave.material(**mkw))
    lay = _refusal(lambda: surfwave.layered(sub, [], kh=[1.0], **lkw))
    if label.startswith("typo"):
        assert lay.startswith("substrate: " + api + "; film: ")
        assert "did you mean" in api
    else:
        assert lay == "substrate: " + api
    assert "\n" not in lay


#: (label, material() keyword arguments, film mapping (thickness added), substrate). The same bad
#: material as a film, where a film can carry it.
BAD_FILMS = [
    ("C in Pa", {"voigt": SI * 1e9, "rho": 2329.0}, {"voigt": SI * 1e9, "rho": 2329.0}, "Si"),
    ("rho 1e-3", {"voigt": SI, "rho": 1e-3}, {"voigt": SI, "rho": 1e-3}, "Si"),
    ("rho 1e-3 of a named crystal", {"C11": "Si", "rho": 1e-3}, {"name": "Si", "rho": 1e-3}, "Si"),
    ("e x 1e6", {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E * 1e6, "permittivity": LN_EPS},
     {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E * 1e6, "permittivity": LN_EPS}, "LiNbO3"),
    ("eps_r < 1", {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E, "permittivity": 0.5 * np.eye(3)},
     {"voigt": LN_C, "rho": 4700.0, "piezo": LN_E, "permittivity": 0.5 * np.eye(3)}, "LiNbO3"),
    ("NaN Euler angle", {"C11": "ZnO", "euler": NAN_EULER}, {"name": "ZnO", "euler": NAN_EULER}, "LiNbO3"),
    ("stress in Pa", {"C11": "Si", "stress": 2000.0}, {"name": "Si", "stress": 2000.0}, "Si"),
]


@pytest.mark.parametrize(("label", "mkw", "film", "sub"), BAD_FILMS, ids=[r[0] for r in BAD_FILMS])
def test_a_bad_film_is_the_same_refusal(label, mkw, film, sub, no_mode_search):
    """A film refused with the words of surfwave.material after "film 0 (from the top): "."""
    api = _refusal(lambda: surfwave.material(**mkw))
    lay = _refusal(lambda: surfwave.layered(sub, [{**film, "thickness": 1e-6}], euler=(0, 38, 0), kh=[1.0]))
    assert lay == FILM + api


def test_a_typo_in_a_film_name_suggests_films_and_crystals():
    """The did-you-mean of a film covers the film database too (the catalog's one search)."""
    text = _refusal(lambda: surfwave.layered("Si", [{"name": "fused SiO", "thickness": 1e-6}], kh=[1.0]))
    assert text.startswith(FILM + "unknown material 'fused SiO' (did you mean fused-SiO2?)")


def test_born_unstable_constants_have_the_same_reason():
    """C11 = 50, C12 = -80, C44 = 30 GPa: C11 + 2 C12 = -110 GPa < 0 (Born and Huang's cubic
    criterion). surfwave.material answers NaN with the Born reason; the layered door, which has no
    per-point answer for a layer, refuses with the same words (after the layer's name)."""
    C = cubic_voigt(50.0, -80.0, 30.0)
    api = surfwave.material(50.0, -80.0, 30.0, 5000.0, direction="[100]")
    lay = _refusal(lambda: surfwave.layered({"voigt": C, "rho": 5000.0}, [], kh=[1.0]))
    film = _refusal(lambda: surfwave.layered("Si", [{"voigt": C, "rho": 5000.0, "thickness": 1e-6}], kh=[1.0]))
    assert np.isnan(api["c_R"]) and "-110 GPa" in api["reason"]
    assert api["reason"] == "no stressed state: " + lay.removeprefix("substrate: ")
    assert film == FILM + lay.removeprefix("substrate: ")


#: (material() keyword arguments, layered substrate, layered keyword arguments). Good substrates.
GOOD = [
    ({"C11": "Si"}, "Si", {}),
    ({"C11": "Si", "direction": "[110]"}, "Si", {"direction": "[110]"}),
    ({"C11": "Cu", "direction": 30.0}, "Cu", {"direction": 30.0}),
    ({"C11": "Si", "stress": 0.5}, "Si", {"stress": np.diag([0.5, 0.0, 0.0])}),   # uniaxial along x1, fixed C
    ({"voigt": SI, "rho": 2329.0, "direction": 20.0}, {"voigt": SI, "rho": 2329.0}, {"direction": 20.0}),
    ({"C11": "LiNbO3", "euler": (0, 38, 0)}, "LiNbO3", {"euler": (0, 38, 0)}),
    ({"C11": "LiNbO3", "euler": (0, 38, 0), "electrical": "metallized"}, "LiNbO3",
     {"euler": (0, 38, 0), "electrical": "metallized"}),
    ({"C11": "GaAs", "euler": (0, 0, 45)}, "GaAs", {"euler": (0, 0, 45)}),
]


@pytest.mark.parametrize(("mkw", "sub", "lkw"), GOOD)
def test_a_good_substrate_is_the_same_answer(mkw, sub, lkw):
    """c_R of surfwave.material equals the slowest mode of surfwave.layered with no film (films=[],
    kh=[0]) and with a film of zero thickness, to rounding (measured: at most 5e-15 relative;
    the two doors reach the half-space through different solvers: the Stroh/piezoelectric
    half-space solver and the layered impedance recursion's mode search)."""
    ref = surfwave.material(**mkw)["c_R"]
    bare = surfwave.layered(sub, [], kh=[0.0], **lkw)
    thin = {"name": "SiO2", "thickness": 0.0, **({"permittivity": 3.8} if "euler" in lkw else {})}
    zero = surfwave.layered(sub, [thin], kh=[0.0, 1.0], **lkw)
    assert np.isfinite(ref)
    assert bare["c"][0, 0] == pytest.approx(ref, rel=1e-13, abs=0)
    np.testing.assert_allclose(zero["c"][:, 0], ref, rtol=1e-13, atol=0)


@pytest.mark.parametrize("boundary", [FREE, METALLIZED])
def test_the_stack_form_of_a_boundary_is_its_half_space_form(boundary):
    """A boundary's two forms are one condition: on a 4 x 4 impedance with the potential last and
    EPS0 = 1 (the half-space convention), stack_matrix(-i M) equals -i secular_matrix(M), on a
    random complex M (reference: the half-space form, used by the piezoelectric solvers checked in
    tests/solvers/)."""
    rng = np.random.default_rng(3)
    M = rng.normal(size=(5, 4, 4)) + 1j * rng.normal(size=(5, 4, 4))
    Zb, active = boundary.stack_matrix(-1j * M, 3, 1.0)
    np.testing.assert_array_equal(Zb, -1j * boundary.secular_matrix(M))
    assert active.tolist() == ([0, 1, 2, 3] if boundary.keeps_potential else [0, 1, 2])


class _Grounded(Metallized):
    """A condition the layered code has never seen by name: metallized physics under another name."""

    name = "grounded-test"


def test_the_layered_solver_asks_the_boundary_object():
    """surfwave.layered takes a Boundary object as electrical=, and a new subclass needs no edit of
    the layered code: a metallized condition under another name gives the metallized speeds
    exactly (reference: electrical="metallized", itself checked against the metallized half-space,
    tests/layers/test_layers_physics.py), and K^2 the same."""
    film = [{"name": "SiO2", "thickness": 1e-6, "permittivity": 3.8}]
    ref = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.5, 2.0], electrical="metallized")
    obj = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.5, 2.0], electrical=METALLIZED)
    new = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.5, 2.0], electrical=_Grounded())
    for r in (obj, new):
        for key in ("c", "K2", "group_velocity"):
            np.testing.assert_array_equal(r[key], ref[key])
    free = surfwave.layered("LiNbO3", film, euler=(0, 38, 0), kh=[0.5, 2.0], electrical=FREE)
    assert np.all(free["c"][:, 0] > ref["c"][:, 0])                # the metallized top is slower


def test_two_faults_the_same_first_refusal(no_mode_search):
    """A substrate with two faults (NaN Euler angle and constants in Pa) is refused for the same one
    by both doors: the orientation is checked before the constants, as surfwave.material does."""
    api = _refusal(lambda: surfwave.material(voigt=SI * 1e9, rho=2329.0, euler=NAN_EULER))
    lay = _refusal(lambda: surfwave.layered({"voigt": SI * 1e9, "rho": 2329.0}, [], euler=NAN_EULER, kh=[1.0]))
    assert lay == "substrate: " + api and "finite" in api


def test_the_cube_refuses_a_film_stress_in_pa_before_any_run(no_mode_search):
    """dispersion_cube: a film stress of 2000 GPa is refused with the one Pa bound's words before
    the first stack is solved (before, the valid stresses were solved first)."""
    from surfwave.layers.cube import dispersion_cube

    text = _refusal(lambda: dispersion_cube("Si", [{"name": "SiO2", "thickness": 1e-6}], [1.0],
                                            film_stress=[0.0, 2000.0]))
    assert text == _refusal(lambda: surfwave.material("Si", stress=2000.0)).replace("stress", "film_stress", 1)
