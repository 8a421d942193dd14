"""Nearest-neighbour pair potentials in reduced units (d0 = 1, K = phi''(d0) = 1).

A potential is a :class:`PairPotential`: its energy and first two derivatives as
vectorised functions of the bond length r (in units of d0). New potentials join the
registry with :func:`register` and are then usable everywhere by name; no solver
needs to change.

Examples
--------
>>> from surfwave.model_crystals.potentials import get_potential
>>> lj = get_potential("lj")
>>> float(lj.d2phi(1.0))
1.0
"""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Callable

import numpy as np

from surfwave.errors import InputError

ArrayFn = Callable[[np.ndarray], np.ndarray]


@dataclass(frozen=True)
class PairPotential:
    """A pair potential phi(r) in reduced units.

    Attributes
    ----------
    name : str
        Registry key (``"harmonic"``, ``"lj"``, ...).
    phi, dphi, d2phi : callable
        phi(r), phi'(r), phi''(r) for r (any shape, units of d0); energies in K d0^2.
    description : str
        One line, shown by ``surfwave potentials``.
    params : dict
        Parameters that determine the potential (they enter cache keys).
    d3phi : callable or None
        Third derivative of phi, analytic; needed only for third-order elastic constants
        from pair sums (optional, so a potential can join without it).
    """

    name: str
    phi: ArrayFn
    dphi: ArrayFn
    d2phi: ArrayFn
    description: str = ""
    params: dict = field(default_factory=dict)
    d3phi: ArrayFn | None = None


_REGISTRY: dict[str, PairPotential] = {}


def register(potential: PairPotential) -> PairPotential:
    """Add ``potential`` to the registry under ``potential.name`` and return it."""
    _REGISTRY[potential.name] = potential
    return potential


def get_potential(name: str | PairPotential) -> PairPotential:
    """Return the registered potential called ``name`` (a PairPotential passes through).

    Raises
    ------
    InputError
        If no potential of that name is registered; the message lists the known ones.
    """
    if isinstance(name, PairPotential):
        return name
    try:
        return _REGISTRY[name]
    except (KeyError, TypeError):
        raise InputError(
            f"unknown potential {name!r}; known potentials: {sorted(_REGISTRY)}"
        ) from None


def available_potentials() -> list[str]:
    """Names of all registered potentials, sorted."""
    return sorted(_REGISTRY)


def _asarray(r):
    return np.asarray(r, dtype=float)


# Hooke spring phi_H = (1/2) K (r - d0)^2 (docs/physics/paper.md; the seed's Eq. 22 is garbled).
register(
    PairPotential(
        name="harmonic",
        phi=lambda r: 0.5 * (_asarray(r) - 1.0) ** 2,
        dphi=lambda r: _asarray(r) - 1.0,
        d2phi=lambda r: np.ones_like(_asarray(r)),
        d3phi=lambda r: np.zeros_like(_asarray(r)),
        description="Hooke spring, phi = (r - 1)^2 / 2",
    )
)

# Lennard-Jones 12-6 scaled so that phi''(1) = 1: phi = [r^-12 - 2 r^-6] / 72 (Eq. 23).
register(
    PairPotential(
        name="lj",
        phi=lambda r: (_asarray(r) ** -12 - 2.0 * _asarray(r) ** -6) / 72.0,
        dphi=lambda r: (_asarray(r) ** -7 - _asarray(r) ** -13) / 6.0,
        d2phi=lambda r: (13.0 * _asarray(r) ** -14 - 7.0 * _asarray(r) ** -8) / 6.0,
        d3phi=lambda r: (56.0 * _asarray(r) ** -9 - 182.0 * _asarray(r) ** -15) / 6.0,
        description="Lennard-Jones 12-6, phi = (r^-12 - 2 r^-6) / 72",
    )
)


def morse(alpha: float = 3.0) -> PairPotential:
    """Morse potential with phi''(1) = 1: phi = D [(1 - exp(-alpha (r - 1)))^2 - 1], D = 1/(2 alpha^2).

    Not used by the paper; it shows how a new potential joins (``register(morse(4.0))``).
    """
    depth = 1.0 / (2.0 * alpha**2)

    def e(r):
        return np.exp(-alpha * (_asarray(r) - 1.0))

    return PairPotential(
        name="morse" if alpha == 3.0 else f"morse{alpha:g}",
        phi=lambda r: depth * ((1.0 - e(r)) ** 2 - 1.0),
        dphi=lambda r: 2.0 * depth * alpha * (1.0 - e(r)) * e(r),
        d2phi=lambda r: 2.0 * depth * alpha**2 * e(r) * (2.0 * e(r) - 1.0),
        d3phi=lambda r: -2.0 * depth * alpha**3 * e(r) * (4.0 * e(r) - 1.0),
        description=f"Morse, alpha = {alpha:g}, phi''(1) = 1",
        params={"alpha": alpha},
    )


register(morse())
