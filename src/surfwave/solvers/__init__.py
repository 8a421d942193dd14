"""Wave solvers that take constants in and give waves out: elastic (and, with the piezoelectric
extension, electric) tensors of a crystal plus its prestress, in a lab frame, to bulk speeds,
long-wave stability, the Rayleigh speed of Eq. (17) and the general (Stroh) surface wave.

Nothing here knows where the constants came from: a pair potential
(:mod:`surfwave.model_crystals`) or a measured crystal (:mod:`surfwave.real_crystals`)."""
