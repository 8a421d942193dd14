"""Real crystals: the materials database (measured constants with their sources), third-order
elastic constants and the stressed state they predict, acoustoelastic coefficients, and the
sweep that fills a real-crystal cube. They hand C and sigma to :mod:`surfwave.solvers`."""
