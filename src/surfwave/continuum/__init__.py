"""Continuum physics of the prestressed crystal: pair potentials, geometries, stress and
elastic constants, bulk and surface wave speeds, phonopy checks, stability, symmetry."""
