"""The electrical condition of a piezoelectric surface as an object: free, metallized.

A boundary turns the surface impedance of the half space into the matrix whose determinant
vanishes at a surface wave (the secular equation) and says what it leaves of the generalised
displacement (u1, u2, u3, phi) at the surface. The solvers ask the object
(:func:`surfwave.solvers.leaky.leaky_wave`, :func:`surfwave.solvers.piezo.piezo_surface_wave`,
and the top surface of a layered stack: :func:`surfwave.layers.recursion.boundary_matrix`,
:mod:`surfwave.layers.modes`, :mod:`surfwave.layers.fields`; a thin electrode on an interface
under a film: :meth:`Boundary.interface_rows`) instead of comparing condition names, so that
another condition (e.g. the surface impedance of a layer stack on the substrate) is one more
subclass of :class:`Boundary`.

Conventions: the impedance M = B A^-1 of the decaying partial waves is (m, 4, 4) with the
electric row and column last, scaled so that EPS0 = 1 (:mod:`surfwave.solvers.leaky`). A purely
elastic problem (M of shape (m, 3, 3)) has no electrical condition: every boundary returns M.

Examples
--------
>>> import numpy as np
>>> M = np.zeros((1, 4, 4), dtype=complex)
>>> complex(as_boundary("free").secular_matrix(M)[0, 3, 3]), as_boundary("metallized").secular_matrix(M).shape
(-1j, (1, 3, 3))
>>> as_boundary(METALLIZED) is METALLIZED, str(FREE)
(True, 'free')
"""
from __future__ import annotations

from abc import ABC, abstractmethod
from typing import ClassVar

import numpy as np

from surfwave.errors import InputError

__all__ = ["BOUNDARIES", "FREE", "METALLIZED", "Boundary", "Free", "Metallized", "as_boundary"]


class Boundary(ABC):
    """An electrical (and mechanical: traction-free) condition of the crystal's surface.

    Attributes
    ----------
    name : str
        The label of the results and cubes (``electrical`` coordinate).
    vacuum : bool
        True where the electric field continues into the vacuum above the surface (its
        energy belongs to the wave: power flow, potential share).
    """

    name: ClassVar[str]
    vacuum: ClassVar[bool]
    #: True where the potential at the surface is an unknown of the secular equation (its
    #: component is kept by :meth:`secular_matrix` and :meth:`stack_matrix`).
    keeps_potential: ClassVar[bool]

    @abstractmethod
    def secular_matrix(self, M: np.ndarray) -> np.ndarray:
        """The matrix whose determinant vanishes at a surface wave.

        Parameters
        ----------
        M : ndarray, shape (m, d, d), complex
            Surface impedance B A^-1 of the decaying partial waves (d = 4 piezoelectric, EPS0 =
            1 scaling; d = 3 elastic).

        Returns
        -------
        ndarray, shape (m, k, k)
            A new array (M is not modified); its null vector is the surface value of the first
            k components of (u1, u2, u3, phi), the others vanish.
        """

    @abstractmethod
    def stack_matrix(self, Z: np.ndarray, phi: int, eps0: float) -> tuple[np.ndarray, np.ndarray]:
        """The same condition on the top of a layered stack, in its Hermitian form.

        Parameters
        ----------
        Z : ndarray, shape (..., nf, nf), complex
            -i M, M the generalised surface impedance of one decoupled family of a layered stack
            (:func:`surfwave.layers.recursion.top_impedance`), Hermitian for real speeds below
            the substrate's limit.
        phi : int
            Position of the potential among the family's nf components.
        eps0 : float
            The vacuum permittivity in the stack's scaling.

        Returns
        -------
        Zb : ndarray, shape (..., na, na)
            The matrix whose singularity is a guided mode (a new array; Z is not modified).
        active : ndarray of int, shape (na,)
            Positions (within the family) of the components kept.
        """

    def interface_rows(self, M: np.ndarray, phi: int) -> np.ndarray | None:
        """The condition on an interface under a film of a layered stack (a thin electrode, no mass).

        Parameters
        ----------
        M : ndarray, shape (..., nf, nf), complex
            Impedance of what lies below the interface (b = M a there).
        phi : int
            Position of the potential among the nf components.

        Returns
        -------
        ndarray, shape (..., nf, 2 nf), or None
            Rows G with G [a; b] = 0 at the interface; None (the default) where the condition
            puts nothing on an interface (continuity, b = M a: no electrode).
        """
        return None

    def __str__(self) -> str:
        """The condition's name."""
        return self.name

    def __repr__(self) -> str:
        """``Free()``, ``Metallized()``."""
        return f"{type(self).__name__}()"


class Free(Boundary):
    """Open-circuit surface, vacuum above: traction-free, D2 continuous into the vacuum
    (M - i e4 e4^T in the EPS0 = 1 scaling)."""

    name = "free"
    vacuum = True
    keeps_potential = True

    def secular_matrix(self, M: np.ndarray) -> np.ndarray:  # noqa: D102 (documented on the base)
        M = M.copy()
        if M.shape[-1] == 4:
            M[:, 3, 3] -= 1j
        return M

    def stack_matrix(self, Z: np.ndarray, phi: int, eps0: float) -> tuple[np.ndarray, np.ndarray]:  # noqa: D102
        Z = Z.copy()
        Z[..., phi, phi] -= eps0                     # the vacuum above: -EPS0 on the potential's diagonal
        return Z, np.arange(Z.shape[-1])


class Metallized(Boundary):
    """A perfectly conducting, grounded film: traction-free, phi = 0 (the mechanical 3 x 3 block)."""

    name = "metallized"
    vacuum = False
    keeps_potential = False

    def secular_matrix(self, M: np.ndarray) -> np.ndarray:  # noqa: D102 (documented on the base)
        return M[:, :3, :3].copy()

    def stack_matrix(self, Z: np.ndarray, phi: int, eps0: float) -> tuple[np.ndarray, np.ndarray]:  # noqa: D102
        keep = np.array([i for i in range(Z.shape[-1]) if i != phi])
        return Z[..., keep[:, None], keep], keep

    def interface_rows(self, M: np.ndarray, phi: int) -> np.ndarray:
        """A grounded electrode on the interface: phi = 0 there (the normal D jumps by the electrode's
        charge), the mechanical state continuous: b_m - M_mm a_m = 0 and a_phi = 0."""
        nf = M.shape[-1]
        mech = np.array([i for i in range(nf) if i != phi])
        G = np.zeros(M.shape[:-2] + (nf, 2 * nf), dtype=complex)
        G[..., mech[:, None], mech[None, :]] = -M[..., mech[:, None], mech[None, :]]
        G[..., mech, nf + mech] = 1.0
        G[..., phi, phi] = 1.0
        return G


#: The two conditions, one instance each.
FREE, METALLIZED = Free(), Metallized()
#: Name -> boundary.
BOUNDARIES: dict[str, Boundary] = {b.name: b for b in (FREE, METALLIZED)}


def as_boundary(value: str | Boundary) -> Boundary:
    """A :class:`Boundary` from its name (``"free"``, ``"metallized"``) or itself.

    Raises
    ------
    InputError
        Anything else (the known names listed).
    """
    if isinstance(value, Boundary):
        return value
    if isinstance(value, str) and value in BOUNDARIES:
        return BOUNDARIES[value]
    raise InputError(f"electrical must be 'free' or 'metallized' (or a surfwave.solvers.boundary.Boundary), "
                     f"got {value!r}")
