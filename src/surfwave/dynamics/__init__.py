"""Lattice dynamics: the triangular lattice's surface dispersion and displacements, numerical
surface-mode solves (triangular and FCC), and the surface entropy."""
