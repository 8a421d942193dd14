"""surfwave: Rayleigh (surface acoustic) waves in prestressed crystals.

Quick start
-----------
>>> import surfwave
>>> surfwave.point("fcc", "in_plane_hydrostatic", "lj", "[100]", [0.95, 1.0])["c2_R"].round(4)
array([0.3325, 0.317 ])
"""
from __future__ import annotations

__version__ = "0.1.0"

from surfwave.api import material, point  # noqa: E402
from surfwave.dynamics.fcc_surface_phonons import surface_phonons  # noqa: E402
from surfwave.layers.solve import layered  # noqa: E402
from surfwave.metrology.film import fit_film  # noqa: E402
from surfwave.solvers.rayleigh import rayleigh_c2  # noqa: E402

__all__ = ["__version__", "fit_film", "layered", "material", "point", "rayleigh_c2", "surface_phonons"]
