"""The piezoelectric / Euler-angle questions of :func:`surfwave.material` (kept names; the work
is :func:`surfwave.resolve.resolve_material` and :func:`surfwave.case.material_result`).

There is one route: the resolver switches the piezoelectric part on where the call carries
``piezo=``, ``permittivity=``, ``euler=``, ``cut=`` or ``electrical=``, or names a crystal found
only in the piezoelectric database (``"LiNbO3"``, ``"quartz"``, ...). A crystal of the elastic
database (``"Cu"``, and ``"GaAs"`` unless a piezoelectric argument is given) keeps e off. A
non-piezoelectric crystal given with ``euler=`` is solved with e = 0 (the potential decouples;
the result equals the elastic solver's).
"""
from __future__ import annotations

from surfwave.case import material_result
from surfwave.resolve import piezo_wanted, resolve_material

__all__ = ["is_piezo_call", "material_piezo"]


def is_piezo_call(C11, *, piezo=None, permittivity=None, euler=None, cut=None, electrical=None) -> bool:
    """Whether :func:`surfwave.material` switches the piezoelectric part on
    (:func:`surfwave.resolve.piezo_wanted`)."""
    return piezo_wanted(C11, piezo, permittivity, euler, cut, electrical)


def material_piezo(C11=None, C12=None, C44=None, rho=None, direction=None, stress=0.0, surface=None, *,
                   voigt=None, angle=None, toec=None, piezo=None, permittivity=None, euler=None, cut=None,
                   electrical=None, leaky=None) -> dict:
    """:func:`surfwave.material` with the piezoelectric part switched on (same arguments).

    Returns the keys of :func:`surfwave.material` (``polarisation`` and ``decay`` with a fourth
    component, the potential; bulk speeds are piezoelectrically stiffened eigen-speeds; ``c_limit`` is
    the piezoelectrically stiffened limiting speed) plus ``c_free``, ``c_metallized``, ``K2``,
    ``power_flow_angle``, ``potential_share``, ``electrical``, ``model`` and ``euler`` ((m, 3)
    degrees, or NaN for a surface/direction orientation), from the one path
    (:func:`surfwave.case.material_result`).
    """
    return material_result(resolve_material(C11, C12, C44, rho, direction, stress, surface, voigt=voigt, angle=angle,
                                            toec=toec, piezo=piezo, permittivity=permittivity, euler=euler, cut=cut,
                                            electrical=electrical, leaky=leaky, piezoelectric=True))
