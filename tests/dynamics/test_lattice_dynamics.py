"""Tests of the numerical semi-infinite lattice-dynamics solve (surfwave.dynamics.triangular_surface).

References: Eq. (15) with c_R^2 of Eq. (16) (harmonic, closed form) or of Eq. (20) from the
bond sums (any potential); a brute-force bulk eigenvalue scan for the band bottom; the
long-wave transverse speed of Eq. (A14). The solver itself uses none of these formulas.
"""
from __future__ import annotations

import warnings

import numpy as np
import pytest

from surfwave.data.variables import CUBES
from surfwave.dynamics import dispersion as D
from surfwave.dynamics import triangular_surface as L
from surfwave.dynamics.triangular import row_matrices

#: LJ surface instabilities (c_R^2 = 0): roots of the Cauchy condition of Eq. (20) with the
#: bond sums written out by hand, derived in test_golden_constants.py; the LJ bulk goes
#: unstable only beyond them (0.8930277 and 1.1141848, brute-force direction scan, same file).
LJ_SURFACE = (0.89361985602, 1.11392551139)

D_SURFACE_HARMONIC = 0.70849737787  # c_R^2 = 0 of Eq. (16): 2(3 - sqrt 7) (test_golden_constants.py)


def eq16(d):
    """Eq. (16), harmonic triangular lattice."""
    x = 0.5 * np.asarray(d)
    return 5 * x**2 - x - np.sqrt(4 * x**5 + x**4 - 2 * x**3 + x**2)


def scene_theta(name, d):
    """theta grid of a scene: edges 1e-3 from 0 and pi, theta_c +- 1e-3 of each strain."""
    tc = D.solve(name, d, [1.0])["theta_c"]
    tc = tc[np.isfinite(tc) & (tc > 2e-3)]
    return np.unique(np.concatenate([[1e-3, 5e-3, np.pi / 20, np.pi / 8, np.pi / 4, np.pi / 2, 2.4,
                                      np.pi - 1e-3], tc - 1e-3, tc + 1e-3]))


def test_surface_edge_constant():
    """D_SURFACE_HARMONIC is where Eq. (16) changes sign."""
    assert eq16(D_SURFACE_HARMONIC * (1 - 1e-9)) < 0 < eq16(D_SURFACE_HARMONIC * (1 + 1e-9))


def test_harmonic_agrees_with_eq15_everywhere():
    """Acceptance bar: omega_lattice = (c_R/d_x) sin theta (Eq. 15 with Eq. 16) to 1e-6,
    including theta within 1e-3 of 0, pi and theta_c, and strains within 1% of the instability."""
    d = np.array([D_SURFACE_HARMONIC * 1.001, D_SURFACE_HARMONIC * 1.01, 0.8, 1.0, 1.3, 1.9])
    th = scene_theta("harmonic", d)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = L.surface_mode("harmonic", d, th)
    ref = np.sqrt(eq16(d))[:, None] / (0.5 * d[:, None]) * np.sin(th)
    dev = np.abs(r["omega_lattice"] / ref - 1)
    assert np.isfinite(dev).all() and dev.max() < 1e-6
    # the error estimate is honest: it bounds the actual deviation
    assert np.all(np.abs(r["omega_lattice"] - ref) <= r["omega_lattice_error"])
    assert np.all(r["n_surface_modes"] == 1)
    assert np.all(r["omega_lattice"] < r["omega_bulk_min"])


def test_triangular_scene_acceptance():
    """Acceptance bar on the ``triangular`` scene of config/config.yaml (its strains,
    theta grid and tolerance, both potentials), with theta 1e-3 from 0 and pi, theta_c +- 1e-3
    and strains 1% inside both surface instabilities added: omega_lattice agrees with Eq. (15)
    (``dispersion.solve``, c_R from the lattice quadratic; Eq. 16 for springs) to 1e-6,
    within its own error estimate, with a single bound mode below the bulk continuum."""
    from pathlib import Path

    from surfwave.pipeline import scenes

    cfg = scenes.load_config([Path(__file__).resolve().parents[2] / "config" / "config.yaml"])
    scene = scenes.validate_config(cfg)["triangular"]
    assert "dispersion" in scene["quantities"]
    tol = scene["accuracy"]["dispersion"]["tol"]
    extra = {"harmonic": [D_SURFACE_HARMONIC * 1.01], "lj": [LJ_SURFACE[0] * 1.01, LJ_SURFACE[1] * 0.99]}
    for name in scene["potentials"]:
        d = np.concatenate([scene["d_over_d0"], extra[name]])
        th = np.unique(np.concatenate([scene["theta"], scene_theta(name, d)]))
        r = L.surface_mode(name, d, th, tol=tol)
        ref = D.solve(name, d, th)["omega"]
        assert np.isfinite(ref).all()
        dev = np.abs(r["omega_lattice"] / ref - 1)
        assert np.isfinite(dev).all() and dev.max() < 1e-6, name
        assert np.all(np.abs(r["omega_lattice"] - ref) <= r["omega_lattice_error"]), name
        assert np.all(r["n_surface_modes"] == 1), name


def test_row_matrices_equal_phonopy_bulk_dynamical_matrix():
    """The row matrices (surfwave.dynamics.triangular, which both the analytic and the numerical solve
    use) against phonopy's bulk dynamical matrix from finite displacements of our pair forces
    (surfwave.model_crystals.phonons): A0 + A1 e^{ip} + A1^H e^{-ip} = D(k) at k = (theta/d_x, p/d_y), for a
    stressed LJ lattice where the prestress term phi'/r (1 - r^r^) of the in-row bond matters."""
    from surfwave.model_crystals.lattices import build
    from surfwave.model_crystals.phonons import dynamical_matrix, make_phonopy
    from surfwave.model_crystals.potentials import get_potential

    pot = get_potential("lj")
    for d in (0.95, 1.08):
        crystal = build("triangular", "uniaxial", pot, "[10]", [d])
        phonon, _ = make_phonopy(crystal, 0, pot, 3, 1e-4)
        dx, dy = d / 2, np.sqrt(1 - (d / 2) ** 2)
        th, p = np.array([0.3, 1.1, 2.6]), np.array([0.0, 0.7, -2.0])
        A0, _, A1 = row_matrices(pot, [d], th)
        for j, (t, q) in enumerate(zip(th, p)):
            rows = A0[0, j] + A1[0, j] * np.exp(1j * q) + A1[0, j].conj().T * np.exp(-1j * q)
            dyn = dynamical_matrix(phonon, np.array([t / dx, q / dy, 0.0]), crystal.cell3d()[0])
            np.testing.assert_allclose(rows, dyn[:2, :2], atol=1e-7)


def test_extreme_theta_nan_with_rounding_reason():
    """theta within 1e-9 of 0 or pi: omega^2 ~ theta^2 is below the rounding of the O(1) row
    matrices, so the numerical solve cannot decide; it must say so (NaN with that reason),
    not claim a bulk instability, and stay exact (Eq. 15) at 1e-3 from the ends."""
    th = np.array([1e-9, 1e-3, np.pi - 1e-3, np.pi - 1e-9])
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = L.surface_mode("harmonic", [1.0], th)
    assert np.isnan(r["omega_lattice"][0, [0, 3]]).all()
    assert all(x.startswith("theta too close to 0 or pi") for x in r["reason_lattice"][0, [0, 3]])
    ref = D.solve("harmonic", [1.0], th[1:3])["omega"]
    np.testing.assert_allclose(r["omega_lattice"][:, 1:3], ref, rtol=1e-8)


@pytest.mark.parametrize("name,d", [("lj", [0.8937 * 1.001, 0.95, 1.0, 1.05, 1.11]), ("morse", [0.9, 1.0, 1.2])])
def test_sine_law_beyond_the_paper(name, d):
    """Go beyond the paper: the numerical solve reproduces (c_R/d_x) sin theta, c_R from the
    long-wave elastic constants (Eq. 20 with Eq. A12), for anharmonic in-row bonds too."""
    th = scene_theta(name, np.asarray(d))
    r = L.surface_mode(name, d, th)
    assert np.isfinite(r["sine_law_deviation"]).all()
    assert np.abs(r["sine_law_deviation"]).max() < 1e-6
    np.testing.assert_allclose(r["c2_R_long_wave"], D.solve(name, d, [1.0])["c2_R"], rtol=1e-10)


def test_accuracy_knob():
    """Fewer decimation steps (a shallower crystal) give a larger error, and the error estimate
    still bounds it (reference: Eq. 15 with Eq. 16). Too shallow for the decay length: NaN."""
    d, th = [1.0], np.array([0.3, 1.5])
    exact = D.solve("harmonic", d, th)["omega"]
    errs = []
    for steps in (3, 5, 30):
        r = L.surface_mode("harmonic", d, th, n_steps=steps)
        errs.append(np.abs(r["omega_lattice"] / exact - 1).max())
        assert np.all(np.abs(r["omega_lattice"] - exact) <= r["omega_lattice_error"])
    assert errs[0] > errs[1] > errs[2] and errs[0] > 1e-3 and errs[2] < 1e-12
    shallow = L.surface_mode("harmonic", d, [0.02], n_steps=3)  # 8 rows, decay length ~70 rows
    assert np.isnan(shallow["omega_lattice"][0, 0]) and shallow["reason_lattice"][0, 0].startswith("no bound")


def test_band_bottom_against_brute_force():
    """bulk_band_bottom equals the minimum of the 2x2 bulk eigenvalues on a fine kappa grid,
    and at long waves (d/d0 <= 1) the transverse speed of Eq. (A14): c_T,par^2 = 2x^2 - 2x^4 + sigma V."""
    d, th = [0.8, 1.0, 1.5], np.array([1e-3, 0.4, 1.2, 2.0, 3.0])
    A0, _, A1 = row_matrices("harmonic", d, th)
    bottom = L.bulk_band_bottom(A0, A1)
    kap = np.linspace(0, np.pi, 20001)
    M = A0[..., None, :, :] + A1[..., None, :, :] * np.exp(1j * kap)[:, None, None] \
        + np.conj(np.swapaxes(A1, -1, -2))[..., None, :, :] * np.exp(-1j * kap)[:, None, None]
    brute = np.linalg.eigvalsh(M)[..., 0].min(axis=-1)
    np.testing.assert_allclose(bottom, brute, rtol=1e-3)  # brute grid is coarse near kappa = 0
    assert np.all(bottom <= brute + 1e-14)
    x = 0.5 * np.asarray(d)
    c2t = 2 * x**2 - 2 * x**4 + 4 * x**2 - 2 * x
    # under compression and at zero stress the slowest bulk wave at fixed k_x has k_y = 0 ...
    np.testing.assert_allclose(bottom[:2, 0] * (x[:2] / 1e-3) ** 2, c2t[:2], rtol=1e-5)
    # ... under strong tension an oblique transverse wave is slower (kappa != 0 at the bottom)
    assert bottom[2, 0] * (x[2] / 1e-3) ** 2 < 0.99 * c2t[2]


def test_invalid_points():
    """Unstable bulk or theta outside (0, pi): NaN with a reason, no warning."""
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        r = L.surface_mode("harmonic", [0.6, 1.0], [0.0, 0.5, 3.5])
    assert np.isfinite(r["omega_lattice"]).sum() == 1 and np.isfinite(r["omega_lattice"][1, 1])
    assert r["reason_lattice"][0, 1].startswith("bulk unstable") and r["reason_lattice"][1, 0] == "theta outside (0, pi)"
    # bulk stable but surface unstable (between c_T,par^2 = 0 and c_R^2 = 0): no bound mode at omega^2 > 0
    r = L.surface_mode("harmonic", [0.70], [0.5])
    assert np.isnan(r["omega_lattice"]).all() and r["reason_lattice"][0, 0].startswith("no bound")


def test_polarisation_and_metadata():
    """Sagittal polarisation in (0, 1); every output key documented in the dispersion cube's metadata."""
    r = L.surface_mode("harmonic", [1.0], [0.3, 1.0])
    assert np.all((r["polarisation"] > 0) & (r["polarisation"] < 1))
    for key in r:
        meta = CUBES["dispersion"][key]
        assert {"long_name", "dims"} <= set(meta) and ("units" in meta) != key.startswith("reason")
