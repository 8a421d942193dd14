"""The shared vocabularies of surfwave, defined once.

Each vocabulary is a :class:`typing.Literal` for annotations and a tuple of its values
(``typing.get_args`` of the Literal) for run-time checks, choices and schema enums. Every
other module, the config schema (``workflow/schemas/config.schema.yaml``) and the command
line take their values from here; ``tests/test_vocab.py`` checks that they agree.

>>> from surfwave.vocab import WAVE_TYPES, LOADINGS
>>> WAVE_TYPES
('surface', 'supersonic_decoupled', 'pseudo', 'none')
>>> LOADINGS
('uniaxial', 'in_plane_hydrostatic')
"""

from __future__ import annotations

from typing import Literal, get_args

__all__ = [
    "WaveType", "WAVE_TYPES", "SAGITTAL_WAVE_TYPES", "REAL_WAVE_TYPES",
    "Lattice", "LATTICES", "Loading", "LOADINGS", "Direction", "DIRECTIONS",
    "StressLoading", "STRESS_LOADINGS", "Electrical", "ELECTRICAL",
]

#: Kind of surface wave at a point:
#: ``surface`` (a true subsonic surface wave, below the limiting speed),
#: ``supersonic_decoupled`` (a sagittal wave above the SH bulk speed, decoupled from it by a
#: mirror plane; exact and real), ``pseudo`` (a leaky wave: complex speed, NaN where not
#: solved), ``none`` (no surface wave; the ``reason`` says why).
WaveType = Literal["surface", "supersonic_decoupled", "pseudo", "none"]
WAVE_TYPES: tuple[WaveType, ...] = get_args(WaveType)
#: The wave types of the sagittal long-wave solver (Eq. 17), which never reports ``pseudo``.
SAGITTAL_WAVE_TYPES: tuple[WaveType, ...] = ("surface", "supersonic_decoupled", "none")
#: The wave types with a real speed (the acoustoelastic coefficients are defined for them).
REAL_WAVE_TYPES: tuple[WaveType, ...] = ("surface", "supersonic_decoupled")

#: Pair-potential model lattices of the paper (surfwave.model_crystals.lattices).
Lattice = Literal["fcc", "triangular"]
LATTICES: tuple[Lattice, ...] = get_args(Lattice)

#: How a model lattice is prestressed: ``uniaxial`` along the propagation direction, or
#: ``in_plane_hydrostatic`` (sigma_xx = sigma_zz in the (001) surface plane; FCC only).
Loading = Literal["uniaxial", "in_plane_hydrostatic"]
LOADINGS: tuple[Loading, ...] = get_args(Loading)

#: Propagation directions of the model lattices ([10]: along the rows of the triangular lattice).
Direction = Literal["[100]", "[110]", "[10]"]
DIRECTIONS: tuple[Direction, ...] = get_args(Direction)

#: How stress is applied to a real crystal, always in the surface plane: ``along`` / ``across``
#: the propagation direction (uniaxial), ``biaxial`` (equal in-plane), or ``axis`` (uniaxial
#: along a fixed crystal axis, written ``axis_<hkl>`` in scenes and the API, e.g. ``axis_1-10``).
StressLoading = Literal["along", "across", "biaxial", "axis"]
STRESS_LOADINGS: tuple[StressLoading, ...] = get_args(StressLoading)

#: Electrical condition on the surface of a piezoelectric crystal: ``free`` (vacuum above,
#: normal D continuous) or ``metallized`` (potential zero at the surface).
Electrical = Literal["free", "metallized"]
ELECTRICAL: tuple[Electrical, ...] = get_args(Electrical)
