"""Surface-wave solvers: leaky (pseudo) waves with attenuation (more to come from the integrator)."""
