"""Films on a crystal substrate: every guided mode, prestress, leaky modes, film metrology.

Public entry points: :func:`surfwave.layered` (:mod:`surfwave.layers.solve`) and
:func:`surfwave.fit_film` (:mod:`surfwave.layers.fit`). Physics: docs/physics/layered.md.
"""
