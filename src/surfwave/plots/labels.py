"""Words and mathtext shared by the figures: potentials by name, axis labels in one style."""
from __future__ import annotations

#: Names a reader knows, for the registered potentials of the paper.
POTENTIAL_NAMES = {"harmonic": "harmonic (Hooke) springs", "lj": "Lennard-Jones 12-6"}
THETA_OVER_PI = r"$\theta/\pi = k d_x/\pi$"
OMEGA = r"$\omega\ /\ (K/m)^{1/2}$"


def potential_label(name: str) -> str:
    """A potential's name for a title or legend: "Lennard-Jones 12-6", not "lj".

    Registered potentials other than the paper's get their registry description up to the
    formula (e.g. "Morse, alpha = 3"); unknown names are returned unchanged.
    """
    name = str(name)
    if name in POTENTIAL_NAMES:
        return POTENTIAL_NAMES[name]
    try:
        from surfwave.model_crystals.potentials import get_potential

        text = get_potential(name).description
    except Exception:  # an unregistered label: show it as given
        return name
    parts = [p.strip() for p in text.split(",") if "phi" not in p]
    return ", ".join(parts) or name
