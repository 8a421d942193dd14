"""Sensitivities dc/dp of guided modes by implicit differentiation of the secular equation
(surfwave.layers.sensitivity, reached through the fit's forward model LayeredModel.jacobian).

Reference: central differences of the speeds that surfwave.layered itself solves (a full mode search
at each perturbed parameter), an independent route that never differentiates the secular eigenvalue.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError
from surfwave.layers.sensitivity import family_prefix
from surfwave.metrology.fit import finite_difference_jacobian
from surfwave.metrology.layered_model import explicit_film, film_value, layered_model

FILM = {"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6, "stress": -0.3}


@pytest.mark.parametrize(("names", "mode", "variable", "x"), [
    (["E", "rho", "nu", "stress"], "R", "kh", np.linspace(0.3, 3.0, 5)),
    (["E", "rho"], "L0", "kh", np.array([0.5, 2.0, 4.0])),
    (["E", "thickness"], "R", "frequency", np.linspace(2e8, 8e8, 4)),
])
def test_implicit_sensitivities_match_finite_differences(names, mode, variable, x):
    """dc/dp = -(d lam/dp)/(d lam/dc) equals central differences of solved speeds (steps eps^(1/3) of each
    parameter's size) to 1e-6 of the column's largest entry, for the Rayleigh (sagittal) and Love (SH) families,
    against kh and against frequency (where kh = 2 pi f H / c moves with c and with the thickness)."""
    model = layered_model("Si", [FILM], names, mode=mode, variable=variable)
    p = {n: film_value(FILM, n) for n in names}
    J = model.jacobian(p, x, names)
    fd = finite_difference_jacobian(model, p, x, names)
    assert np.all(np.isfinite(J))
    for j in range(len(names)):
        np.testing.assert_allclose(J[:, j], fd[:, j], rtol=0, atol=1e-6 * np.abs(fd[:, j]).max())


@pytest.mark.parametrize("electrical", ["free", "metallized"])
def test_piezoelectric_stack_sensitivities(electrical):
    """A SiO2-like film on LiNbO3 (SAW Euler angles 0, 38, 0; one coupled family with the potential, mode M0):
    with a free top (the vacuum's -eps0 on the potential) and a metallized one, dc/dp of E, rho and the film's
    stress equals central differences of solved speeds to 1e-6 of each column's largest entry."""
    film = {"E": 73.0, "nu": 0.17, "rho": 2200.0, "thickness": 5e-7, "permittivity": 3.9}
    names = ["E", "rho", "stress"]
    model = layered_model("LiNbO3", [film], names, mode="M0", euler=(0, 38, 0), electrical=electrical)
    p = {"E": 73.0, "rho": 2200.0, "stress": 0.2}
    kh = np.array([0.3, 1.0, 2.0])
    J = model.jacobian(p, kh, names)
    fd = finite_difference_jacobian(model, p, kh, names)
    for j in range(len(names)):
        np.testing.assert_allclose(J[:, j], fd[:, j], rtol=0, atol=1e-6 * np.abs(fd[:, j]).max())


def test_named_film_thickness_sensitivity():
    """A film by name is written as explicit constants (fused silica: isotropic E, nu, rho from the film
    database); with the mode given as a column the family comes from the solver's label; dc/dh at fixed
    frequency matches central differences of solved speeds to 1e-6 and is negative (a slow film: a thicker one
    lowers the speed, as perturbation theory's mass and stiffness loading says)."""
    film = explicit_film({"name": "SiO2", "thickness": 1e-6})
    assert {"E", "nu", "rho"} <= set(film) and "name" not in film
    model = layered_model("Si", [{"name": "SiO2", "thickness": 1e-6}], ["thickness"], mode=0, variable="frequency")
    f = np.array([3e8, 9e8])
    J = model.jacobian({"thickness": 1e-6}, f, ["thickness"])
    fd = finite_difference_jacobian(model, {"thickness": 1e-6}, f, ["thickness"])
    np.testing.assert_allclose(J, fd, rtol=1e-6)
    assert np.all(J < 0)


def test_family_labels():
    """Labels map to the families of surfwave.layered; leaky modes have no real-root sensitivity."""
    assert [family_prefix(s) for s in ("R", "S1", "L0", "M3")] == ["R", "R", "L", "M"]
    with pytest.raises(InputError, match="leaky"):
        family_prefix("R~")
    assert not hasattr(layered_model("Si", [FILM], ["E"], leaky=True), "jacobian")


def test_one_family_search_equals_layered():
    """The fit's forward model at kh searches only the measured modes' families (layers.solve.mode_speeds): its
    speeds equal those of the full surfwave.layered solve, bit for bit, NaN where the mode is absent, for a
    two-film stack (reference: the labelled columns of surfwave.layered's record)."""
    films = [FILM, {"E": 200.0, "nu": 0.24, "rho": 3200.0, "thickness": 3e-7}]
    kh = np.linspace(0.2, 5.0, 9)
    full = surfwave.layered("Si", films, kh=kh)
    labels = ["R", "S1", "L0", "L1"] * 2 + ["R"]
    model = layered_model("Si", films, ["E"], mode=labels)
    got = model({"E": FILM["E"]}, kh)
    ref = np.array([row_c[list(row_l).index(lab)] if lab in list(row_l) else np.nan
                    for row_c, row_l, lab in zip(full["c"], full["mode"], labels)])
    np.testing.assert_array_equal(got, ref)
    assert np.isnan(ref).any() and np.isfinite(ref).sum() >= 6
