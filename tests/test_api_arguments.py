"""Bad arguments of surfwave.material and surfwave.point: one InputError naming the argument
and the value (issue 20, "Tracebacks and misleading messages", item 6).

Before this change each row either passed silently (rho=1e-300 gave c_R = inf labelled
`surface`; voigt of strings was converted; an empty angle array), raised a bare TypeError or
ValueError (rho as a string or list, an angle list with 'x'), or said something misleading
(a voigt with NaN: "must be symmetric"). The expected fragments are this module's messages.
"""
from __future__ import annotations

import numpy as np
import pytest

import surfwave
from surfwave.errors import InputError

CU = dict(C11=168.4, C12=121.4, C44=75.4)
NAN_VOIGT = np.diag([168.4, 168.4, 168.4, 75.4, 75.4, 75.4])
NAN_VOIGT[0, 1] = np.nan


@pytest.mark.parametrize("kwargs, fragment", [
    (dict(CU, rho="8960"), "rho must be one number (kg/m^3), got '8960'"),
    (dict(CU, rho=[8960, 8960]), "rho must be one number"),
    (dict(CU, rho=1e-300), "rho = 1e-300 kg/m^3 lies outside [1, 1e+12]"),
    (dict(CU, rho=-5.0), "density rho must be positive and finite, got -5.0"),
    (dict(voigt=[["1"] * 6] * 6, rho=8960), "voigt must be numbers, got text"),
    (dict(voigt=np.eye(6) * (1 + 1j), rho=8960), "voigt must be real numbers, got complex"),
    (dict(voigt=NAN_VOIGT, rho=8960), "voigt must be finite, got nan at row 1, column 2"),
    (dict(C11="Cu", C12=121.4, C44=75.4, rho=8960), "do not also give C12"),
    (dict(C11=168.4, C12="121.4", C44=75.4, rho=8960), "C12 must be one number (GPa), got '121.4'"),
    (dict(CU, rho=8960, angle=[0, "x"]), "angle must be numbers, got text: [0, 'x']"),
    (dict(CU, rho=8960, angle=[]), "angle must hold at least one angle"),
    (dict(CU, rho=8960, angle=np.array([])), "angle must hold at least one angle"),
    (dict(CU, rho=8960, angle=[0.0, 1e20]), "angle = 1e+20 degrees: angles beyond 1e+06 degrees"),
    (dict(CU, rho=8960, direction=np.nan), "direction must be finite"),
    (dict(CU, rho=8960, stress="1e8"), "stress must be numbers, got text: '1e8'"),
    (dict(CU, rho=8960, direction="[100000000000000000000 1 0]"), "Miller indices must not exceed"),
])
def test_material_bad_arguments_one_clean_line(kwargs, fragment):
    with pytest.raises(InputError) as err:
        surfwave.material(**kwargs)
    assert fragment in str(err.value), str(err.value)
    assert "\n" not in str(err.value)


def test_voigt_asymmetry_names_the_components():
    C = np.diag([168.4, 168.4, 168.4, 75.4, 75.4, 75.4])
    C[0, 1] = 121.4
    with pytest.raises(InputError, match=r"C12 = 121.4 but C21 = 0.0"):
        surfwave.material(voigt=C, rho=8960)


def test_density_range_keeps_the_scaled_units_habit():
    """rho = 1e9 with constants in GPa (c^2 in units of C/rho) stays allowed: 2:1:1 cubic
    constants give rho c_R^2 / C44 = (3 - sqrt 3)/2 along [100] (nearest-neighbour FCC,
    Eq. 17), the value the docstring example prints."""
    r = surfwave.material(2.0, 1.0, 1.0, 1e9, "[100]")
    assert r["c_R"] ** 2 == pytest.approx((3 - 3**0.5) / 2, rel=1e-9)


@pytest.mark.parametrize("direction, fragment", [
    ([0.0, "x"], "direction must be numbers, got text"),
    ([], "direction must hold at least one angle"),
    (1e20, "direction = 1e+20 degrees"),
])
def test_point_bad_angles(direction, fragment):
    with pytest.raises(InputError) as err:
        surfwave.point("fcc", "in_plane_hydrostatic", "lj", direction, 1.0)
    assert fragment in str(err.value)
