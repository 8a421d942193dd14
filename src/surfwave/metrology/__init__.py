"""Thin-film metrology by surface waves: fit film parameters to measured dispersion points.

- :mod:`~surfwave.metrology.fit`: the generic least-squares fitter (values, covariance,
  correlations, warnings when parameters are not separable);
- :mod:`~surfwave.metrology.diagnostics`: the covariance, the separability warnings and the
  profile check of the linear uncertainties;
- :mod:`~surfwave.metrology.modes`: points of several modes in one fit;
- :mod:`~surfwave.metrology.love`: Love waves in an isotropic film on an isotropic half-space
  (closed form with exact sensitivities; the first forward model and a reference for tests);
- :mod:`~surfwave.metrology.layered_model`: the forward model of a film stack on a crystal
  through :func:`surfwave.layered`;
- :mod:`~surfwave.metrology.film`: :func:`fit_film`, the front door (``surfwave.fit_film``).
"""
