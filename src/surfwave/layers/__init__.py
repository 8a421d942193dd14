"""Films on a crystal substrate: every guided mode, prestress, leaky modes, film metrology.

Public entry point: :func:`surfwave.layered` (:mod:`surfwave.layers.solve`); sensitivities dc/dp of
its guided modes by implicit differentiation (:mod:`surfwave.layers.sensitivity`), which the film
fit :func:`surfwave.fit_film` (:mod:`surfwave.metrology`) uses. Physics: docs/physics/layered.md.
"""
