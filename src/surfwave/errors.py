"""Every exception class of surfwave (one module: callers catch by these names)."""
from __future__ import annotations


class SurfwaveError(Exception):
    """Base class of every error surfwave raises on purpose."""


class GeometryError(SurfwaveError, ValueError):
    """A prestressed geometry that cannot exist (e.g. t^2 <= 0, a failed lateral solve)."""


class InputError(SurfwaveError, ValueError):
    """An argument outside what a function accepts (unknown name, wrong shape)."""


class SymmetryError(SurfwaveError):
    """A crystal lacks the mirror planes the surface-wave theory assumes."""


class SceneError(SurfwaveError, ValueError):
    """A configuration that cannot be run; the message names scene, key and value."""


class DamagedCubeError(InputError):
    """A result file that exists but cannot be read (truncated, not netCDF)."""


class PhonopyPointError(SurfwaveError):
    """Phonopy could not produce trustworthy force constants at one strain point."""


class ConstantsNote(UserWarning):
    """A one-line note that an unverified or provisional constant set is in use (a warning, not
    an error: the numbers are computed; the note says how far to trust the constants)."""
