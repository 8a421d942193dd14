"""Figures drawn from the cubes."""
