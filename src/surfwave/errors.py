"""Exception and warning classes of surfwave."""
from __future__ import annotations


class SurfwaveError(Exception):
    """Base class of every error surfwave raises on purpose."""


class GeometryError(SurfwaveError, ValueError):
    """A prestressed geometry that cannot exist (e.g. t^2 <= 0, a failed lateral solve)."""


class InputError(SurfwaveError, ValueError):
    """An argument outside what a function accepts (unknown name, wrong shape)."""


class SymmetryError(SurfwaveError):
    """A crystal lacks the mirror planes the surface-wave theory assumes."""


class SurfwaveWarning(UserWarning):
    """Warnings of surfwave (turned into errors in the test suite)."""
