"""The paper's model crystals: nearest-neighbour pair potentials on FCC and triangular lattices,
their prestressed geometries, stress and elastic constants (analytic and through phonopy),
symmetry (spglib), stability and the FCC angle sweeps. They hand C and sigma to
:mod:`surfwave.solvers`."""
