"""Scene checks of the ``surface_phonons`` quantity (FCC scenes): the surfaces and load directions."""
from __future__ import annotations

from surfwave.dynamics.fcc_layers import LOAD_DIRECTIONS, SURFACES

#: Surfaces of a scene that asks for surface_phonons without naming any.
DEFAULT_SURFACES = ["(001)"]


def check_surfaces(where: str, raw: dict, directions: list[str]) -> list[str]:
    """Problems (one line each) of a scene's ``surfaces`` for the surface_phonons quantity.

    Parameters
    ----------
    where : str
        "scene 'name'" for the messages.
    raw : dict
        The scene as written (schema defaults filled in).
    directions : list of str
        The scene's valid directions: for uniaxial loading the load directions.
    """
    problems = []
    for surface in raw.get("surfaces", DEFAULT_SURFACES):
        if surface not in SURFACES:
            problems.append(f"{where}, key 'surfaces': value {surface!r} is not available for surface_phonons; "
                            f"choose from {list(SURFACES)}")
        elif raw["loading"] == "uniaxial" and not set(directions) & set(LOAD_DIRECTIONS[surface]):
            problems.append(f"{where}, key 'surfaces': value {surface!r} contains none of the load directions "
                            f"{directions}; it takes {list(LOAD_DIRECTIONS[surface])}")
    return problems
