"""Third-order constants of piezoelectric crystals: the database's GaAs set, a caller's set.

References: the elastic real-crystal path (a second front end on the same physics) where the
potential decouples by symmetry (GaAs (001)[100]: K^2 = 0 exactly, so the piezoelectric and the
elastic solvers must give the same stressed wave); the three-fold axis of quartz (Euler phi and
phi + 120 deg are the same crystal, so every result must agree); the point-group builders of
toec_classes against toec.cubic_toec (an independent, hand-written cubic builder); the closed-form
cubic pressure derivatives dB11/dP = -(C111 + 2 C112 + 2 C11 + 2 C12)/(C11 + 2 C12),
dB12/dP = -(C123 + 2 C112 - C11 - C12)/(C11 + 2 C12), dB44/dP = -(C144 + 2 C155 + C11 + 2 C12 +
C44)/(C11 + 2 C12); and tensor covariance (a rotated crystal's derivatives are the rotated
derivatives).

The quartz "set" below is SYNTHETIC (invented numbers of the right size, invariant under class 32
by construction): no published quartz set was found in a stored source, and these tests check the
machinery, not quartz.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.piezo_materials import _build, get_piezo_material
from surfwave.real_crystals.toec import cubic_toec, pressure_derivatives
from surfwave.real_crystals.toec_classes import TOEC_NAMES, TRIGONAL_32_TOEC, checked_toec, rotate_toec, toec_from_named
from surfwave.solvers.piezo_tensors import point_group_generators
from surfwave.solvers.tensors import rotate4, tensor_to_voigt, voigt_to_tensor

#: Invented class-32 constants (GPa) for machinery tests only; NOT quartz's measured values.
SYNTHETIC_32 = dict(zip(TRIGONAL_32_TOEC, (-200.0, -350.0, 10.0, -160.0, -300.0, -50.0, -300.0, 20.0, -130.0,
                                           -270.0, -330.0, -800.0, -110.0, -280.0)))


@pytest.mark.parametrize("cls", sorted(TOEC_NAMES))
def test_named_builders_are_invariant_and_keep_the_named_values(cls):
    """Each class's builder: invariant under its generators (1e-10), named components as given."""
    rng = np.random.default_rng(3)
    vals = {k: float(v) for k, v in zip(TOEC_NAMES[cls], rng.normal(0.0, 300.0, len(TOEC_NAMES[cls])))}
    C3 = toec_from_named(cls, vals)
    for g in point_group_generators(cls):
        np.testing.assert_allclose(rotate_toec(C3, g), C3, atol=1e-10)
    for k, v in vals.items():
        assert C3[tuple(int(c) - 1 for c in k[1:])] == pytest.approx(v, abs=1e-10)
    np.testing.assert_array_equal(checked_toec(C3, cls), C3)


def test_cubic_class_builder_equals_the_hand_written_cubic_one():
    """-43m from the six names equals toec.cubic_toec (written component by component) for GaAs."""
    g = get_material("GaAs").toec
    np.testing.assert_allclose(toec_from_named("-43m", g), cubic_toec(**g), atol=1e-10)


def test_user_arrays_are_checked():
    """Wrong shape, Pa, not symmetric in I, J, K, or another axis setting (C114 with the sign of
    the half turn about Z, the quartz IEEE 1949/1978 trap): InputError naming the problem."""
    C3 = toec_from_named("32", SYNTHETIC_32)
    with pytest.raises(InputError, match="shape"):
        checked_toec(np.zeros((6, 6)), "32")
    with pytest.raises(InputError, match="Pa"):
        checked_toec(C3 * 1e9, "32")
    bad = C3.copy()
    bad[0, 0, 3] += 5.0
    with pytest.raises(InputError, match="order of I, J, K"):
        checked_toec(bad, "32")
    flipped = C3.copy()
    for p in {(0, 0, 3), (0, 3, 0), (3, 0, 0)}:
        flipped[p] = -flipped[p]                                     # C114 alone: no longer class 32
    with pytest.raises(InputError, match="class-32"):
        checked_toec(flipped, "32")
    half_turn = rotate_toec(C3, np.diag([-1.0, -1.0, 1.0]))         # the other setting: still class 32
    checked_toec(half_turn, "32")
    assert half_turn[0, 0, 3] == pytest.approx(-C3[0, 0, 3])


def test_gaas_database_toec_through_the_piezoelectric_path_equals_the_elastic_path():
    """GaAs (001)[100] (Euler (0, 0, 0)): the potential decouples from the sagittal wave, so the
    piezoelectric path with the database's third-order set gives the elastic path's stressed
    wave, -1 to 1 GPa along [100] (1e-12); free and metallized coincide (K^2 = 0)."""
    s = np.linspace(-1.0, 1.0, 5)
    pz = [surfwave.material("GaAs", euler=(0.0, 0.0, 0.0), stress=x, toec=True) for x in s]
    el = [surfwave.material("GaAs", surface="(001)", direction="[100]", stress=x, toec=True) for x in s]
    for p, e in zip(pz, el):
        assert p["c_R"] == pytest.approx(e["c_R"], rel=1e-12)
        assert p["c_metallized"] == pytest.approx(p["c_free"], rel=1e-12)
        assert p["model"].startswith("third-order constants")
    fixed = surfwave.material("GaAs", euler=(0.0, 0.0, 0.0), stress=1.0)
    assert abs(pz[-1]["c_R"] / fixed["c_R"] - 1) > 1e-4             # the set matters
    assert get_piezo_material("GaAs").sources["toec"].startswith("the elastic database's GaAs entry")


def test_callers_set_for_quartz_by_name_or_array_and_the_three_fold_axis():
    """A caller's class-32 set (synthetic) for ST-X quartz: by name and as an array give the same
    numbers; at zero stress it equals the fixed-constants result (F = I, 1e-12); under 0.1 GPa it
    differs from it; Euler phi and phi + 120 deg (the three-fold axis) agree to 1e-10."""
    C3 = toec_from_named("32", SYNTHETIC_32)
    eul = np.array([[0.0, 132.75, 0.0], [120.0, 132.75, 0.0]])
    by_name = surfwave.material("quartz", euler=eul, stress=np.array([0.0, 0.0]), toec=SYNTHETIC_32)
    fixed = surfwave.material("quartz", euler=eul, stress=np.array([0.0, 0.0]))
    np.testing.assert_allclose(by_name["c_free"], fixed["c_free"], rtol=1e-12)
    st = surfwave.material("quartz", euler=eul, stress=np.array([0.1, 0.1]), toec=SYNTHETIC_32)
    arr = surfwave.material("quartz", euler=eul, stress=np.array([0.1, 0.1]), toec=C3)
    for key in ("c_free", "c_metallized", "K2", "power_flow_angle"):
        np.testing.assert_array_equal(st[key], arr[key])
    np.testing.assert_allclose(st["c_free"][0], st["c_free"][1], rtol=1e-10)
    np.testing.assert_allclose(st["K2"][0], st["K2"][1], rtol=1e-8)
    f01 = surfwave.material("quartz", euler=eul, stress=np.array([0.1, 0.1]))
    assert abs(st["c_free"][0] / f01["c_free"][0] - 1) > 1e-5


def test_callers_set_is_refused_when_wrong():
    """Class-32 names for a crystal given by its constants (only the cubic six are understood by
    name there), a set of another class, unknown names; a cubic-six mapping works there and equals
    the tuple form."""
    with pytest.raises(InputError, match="here the cubic six"):
        surfwave.material(voigt=np.diag([100.0] * 3 + [40.0] * 3), rho=3000.0, piezo=np.zeros((3, 6)),
                          permittivity=np.eye(3), euler=(0, 0, 0), stress=0.1, toec=SYNTHETIC_32)
    with pytest.raises(InputError, match="unknown"):
        surfwave.material("quartz", cut="ST-X", stress=0.1, toec={**SYNTHETIC_32, "C456": 1.0})
    with pytest.raises(InputError, match="class-32"):
        surfwave.material("quartz", cut="ST-X", stress=0.1, toec=get_material("GaAs").toec_voigt)
    g = get_material("GaAs")
    kw = dict(voigt=g.voigt, rho=g.rho, piezo=np.zeros((3, 6)), permittivity=np.eye(3), euler=(0, 0, 0), stress=0.1)
    named = surfwave.material(**kw, toec=g.toec)
    ordered = surfwave.material(**kw, toec=tuple(g.toec[k] for k in ("C111", "C112", "C123", "C144", "C155", "C456")))
    assert named["c_R"] == ordered["c_R"] and named["toec"]


def test_database_reader_takes_a_toec_block():
    """A piezoelectric.yaml entry with a ``toec:`` block of its class's names (here a made-up
    entry, synthetic numbers) is built by toec_from_named and cited in sources["toec"]."""
    q = get_piezo_material("quartz")
    refs = {"made_up": "a synthetic reference for this test only, not a publication"}
    entry = {"formula": "SiO2", "crystal_class": "32", "setting": "test", "note": "test",
             "rho": {"value": q.rho, "source": "made_up"},
             "C": {**{k: q.constants[k] for k in ("C11", "C12", "C13", "C14", "C33", "C44")}, "source": "made_up"},
             "e": {"e11": q.constants["e11"], "e14": q.constants["e14"], "source": "made_up"},
             "eps_r": {"eps11": q.constants["eps11"], "eps33": q.constants["eps33"], "source": "made_up"},
             "toec": {**SYNTHETIC_32, "source": "made_up"}}
    m = _build("test-quartz", entry, refs)
    np.testing.assert_allclose(m.toec_voigt, toec_from_named("32", SYNTHETIC_32), atol=0)
    assert m.sources["toec"] == refs["made_up"]


def test_pressure_derivatives_closed_form_and_covariance():
    """GaAs: the general finite-difference derivatives equal the cubic closed forms (1e-6) and are
    zero where cubic symmetry says so; for the crystal turned about an arbitrary axis, the
    derivatives are the turned derivatives (1e-6)."""
    m = get_material("GaAs")
    d = pressure_derivatives(m.voigt, m.toec_voigt)
    c, t = m.constants, m.toec
    b3 = c["C11"] + 2 * c["C12"]
    closed = {(0, 0): -(t["C111"] + 2 * t["C112"] + 2 * c["C11"] + 2 * c["C12"]) / b3,
              (0, 1): -(t["C123"] + 2 * t["C112"] - c["C11"] - c["C12"]) / b3,
              (3, 3): -(t["C144"] + 2 * t["C155"] + c["C11"] + 2 * c["C12"] + c["C44"]) / b3}
    for ij, v in closed.items():
        assert d[ij] == pytest.approx(v, rel=1e-6), ij
    assert abs(d[0, 3]) < 1e-8 and abs(d[3, 4]) < 1e-8
    ax = np.array([1.0, 2.0, 2.0]) / 3.0
    a = 0.7
    K = np.array([[0, -ax[2], ax[1]], [ax[2], 0, -ax[0]], [-ax[1], ax[0], 0]])
    R = np.eye(3) + np.sin(a) * K + (1 - np.cos(a)) * K @ K
    C2r = tensor_to_voigt(rotate4(voigt_to_tensor(m.voigt), R))
    dr = pressure_derivatives(C2r, rotate_toec(m.toec_voigt, R))
    np.testing.assert_allclose(dr, tensor_to_voigt(rotate4(voigt_to_tensor(d), R)), atol=1e-6)
