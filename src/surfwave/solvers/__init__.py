"""Surface-wave solvers (elastic, piezoelectric, leaky)."""
