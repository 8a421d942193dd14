"""The one table of cube variable metadata: CF ``long_name`` and ``units`` of every variable
and coordinate the workflow writes, per cube, and the variable's trailing dims.

Every stage draws from it (``workflow/scripts/*.py`` pass ``CUBES[<cube>]`` to the cube
builders; :func:`surfwave.real_crystals.sweep.surface_wave_sweep` and
:func:`surfwave.data.cube.build` take their coordinates' attributes from here); the computing
modules return plain arrays and hold no metadata, so a wording change here reruns the stages
but never invalidates the parameter cache. A variable name means one thing per cube; the same
name may carry a cube-specific long_name in another cube (``reason``, ``c2_R``).

``dims`` are the variable's own dimensions after the cube's leading ones (the builder adds
(potential, direction, strain) or (material, surface, angle, ...)); ``units`` is ``"1"`` for
dimensionless quantities and is dropped for booleans and strings. ``tests/test_vocab.py``
checks that the table covers every data variable of the default run.

>>> from surfwave.data.variables import CUBES
>>> CUBES["surface_wave"]["penetration_depth"]["units"]
'1'
"""

from __future__ import annotations

from typing import Any

__all__ = ["CUBES", "LAYERED_COORDS", "MODEL_COORDS", "PIEZO_WAVE_COORDS", "SURFACE_WAVE_COORDS"]

#: cube name -> variable name -> {"long_name", "units", "dims"}; the cube name is the file
#: name under results/<scene>/ (``rayleigh_angles``: the rayleigh.nc of an FCC angle scene).
CUBES: dict[str, dict[str, dict[str, Any]]] = {
    # results/<scene>/crystal.nc: symmetry of the prestressed lattice (surfwave.model_crystals.symmetry)
    "crystal": {
        "space_group": {"long_name": "space group (Hermann-Mauguin, spglib) of the prestressed lattice", "dims": ()},
        "space_group_number": {"long_name": "space group number (International Tables)", "units": "1", "dims": ()},
        "mirror_x": {"long_name": "lab-frame reflection x -> -x is a symmetry operation", "dims": ()},
        "mirror_z": {
            "long_name": "lab-frame reflection z -> -z is a symmetry operation (sagittal plane is a mirror)",
            "dims": (),
        },
        "cell": {
            "long_name": "primitive lattice vectors (rows) in the lab frame (2D lattices padded with "
                         "vacuum along z)",
            "units": "d0",
            "dims": ("vector", "xyz"),
        },
        "volume": {
            "long_name": "volume (area in 2D) per atom",
            "units": "d0^3 (d0^2 for the 2D triangular lattice)",
            "dims": (),
        },
    },
    # elastic.nc: stress, C, S, bulk speeds, stability (surfwave.model_crystals.elastic)
    "elastic": {
        "stress": {
            "long_name": "in-plane stress sigma0_xx times volume per atom, sigma0 V / (K d0^2)",
            "units": "1",
            "dims": (),
        },
        "c2_L_par": {
            "long_name": "squared longitudinal sound speed along x (propagation), rho c^2 = S_xxxx",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "c2_T_par": {
            "long_name": "squared transverse sound speed along x polarised along y, rho c^2 = S_xyyx",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "c2_L_perp": {
            "long_name": "squared longitudinal sound speed along y (surface normal), rho c^2 = S_yyyy",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "c2_T_perp": {
            "long_name": "squared transverse sound speed along y polarised along x, rho c^2 = S_xyxy",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "c2_SH": {
            "long_name": "squared shear-horizontal sound speed along x polarised along z, rho c^2 = S_xzzx",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "stable": {
            "long_name": "long-wave (acoustic tensor) stability over all propagation directions",
            "units": "1",
            "dims": (),
        },
        "min_acoustic_eig": {
            "long_name": "lowest eigenvalue of the acoustic tensor V Q(n) over all directions n",
            "units": "K d0^2",
            "dims": (),
        },
        "C": {
            "long_name": "elastic constants times volume per atom, V C_ijkl, lab frame",
            "units": "K d0^2",
            "dims": ("i", "j", "k", "l"),
        },
        "S": {
            "long_name": "stress derivatives (Eq. A11) times volume per atom, V S_ijkl, lab frame",
            "units": "K d0^2",
            "dims": ("i", "j", "k", "l"),
        },
        "volume": {
            "long_name": "volume (area in 2D) per atom",
            "units": "d0^3 (d0^2 for the 2D triangular lattice)",
            "dims": (),
        },
    },
    # bulk.nc: phonopy speeds and full-zone stability (surfwave.model_crystals.phonons), deviations from elastic.nc
    "bulk": {
        "c2_L_par_phonopy": {
            "long_name": "squared longitudinal sound speed along x (phonopy)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_T_par_phonopy": {
            "long_name": "squared transverse sound speed along x polarised along y (phonopy)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_L_perp_phonopy": {
            "long_name": "squared longitudinal sound speed along y, the normal (phonopy)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_T_perp_phonopy": {
            "long_name": "squared transverse sound speed along y polarised along x (phonopy)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_SH_phonopy": {
            "long_name": "squared sound speed along x polarised along z (phonopy; NaN in 2D)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "stable_phonon": {
            "long_name": "no imaginary frequency on the zone mesh nor at long waves",
            "units": "1",
            "dims": ("strain",),
        },
        "min_omega2": {
            "long_name": "lowest omega^2 on the zone mesh, Gamma excluded (refined if < 0)",
            "units": "K / m",
            "dims": ("strain",),
        },
        "min_omega2_q": {
            "long_name": "Cartesian lab-frame wave vector k of min_omega2, phase exp(i k.r)",
            "units": "rad / d0",
            "dims": ("strain", "xyz"),
        },
        "min_c2_phonopy": {
            "long_name": "lowest acoustic-tensor eigenvalue over all directions (phonopy)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "min_c2_direction": {
            "long_name": "unit propagation direction of min_c2_phonopy, lab frame",
            "units": "1",
            "dims": ("strain", "xyz"),
        },
        "supercell_used": {
            "long_name": "N of the N^dim supercell used (raised if images are ambiguous)",
            "units": "1",
            "dims": ("strain",),
        },
        "reason": {
            "long_name": "why a point has NaN phonopy values (empty if computed)",
            "dims": ("strain",),
        },
        "c2_L_par_deviation": {
            "long_name": "c2_L_par_phonopy minus the analytic c2_L_par of elastic.nc",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_T_par_deviation": {
            "long_name": "c2_T_par_phonopy minus the analytic c2_T_par of elastic.nc",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_L_perp_deviation": {
            "long_name": "c2_L_perp_phonopy minus the analytic c2_L_perp of elastic.nc",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_T_perp_deviation": {
            "long_name": "c2_T_perp_phonopy minus the analytic c2_T_perp of elastic.nc",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "c2_SH_deviation": {
            "long_name": "c2_SH_phonopy minus the analytic c2_SH of elastic.nc",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
    },
    # rayleigh.nc of a scene with mirror directions: Eq. (17) (surfwave.solvers.rayleigh)
    "rayleigh": {
        "c2_R": {
            "long_name": "squared Rayleigh (surface) wave speed, long-wave limit (Eq. 17)",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "wave_type": {
            "long_name": "kind of sagittal surface wave: surface, supersonic_decoupled (faster than "
                         "the SH bulk wave; exists by mirror symmetry) or none",
            "dims": (),
        },
        "reason": {"long_name": "why c2_R is NaN (empty if it is not)", "dims": ()},
        "kappa1": {"long_name": "first decay constant kappa of the surface wave (per k)", "units": "1", "dims": ()},
        "kappa2": {"long_name": "second decay constant kappa of the surface wave (per k)", "units": "1", "dims": ()},
    },
    # rayleigh.nc of an FCC angle scene (surfwave.model_crystals.fcc_angles)
    "rayleigh_angles": {
        "c2_R": {
            "long_name": "squared surface-wave speed, long-wave limit (Eq. 17 on mirror directions, "
                         "general anisotropic solver elsewhere; real part squared for a pseudo "
                         "surface wave)",
            "units": "K d0^2 / m",
            "dims": (),
        },
        "wave_type": {
            "long_name": "surface, supersonic_decoupled (faster than the SH bulk wave, exists by "
                         "mirror symmetry), pseudo (leaky, off the mirrors) or none",
            "dims": (),
        },
        "reason": {"long_name": "why c2_R is NaN (empty if it is not)", "dims": ()},
    },
    # dispersion.nc: analytic dispersion (surfwave.dynamics.dispersion) and its lattice-dynamics check
    # (surfwave.dynamics.triangular_surface)
    "dispersion": {
        "omega": {
            "long_name": "surface-wave angular frequency, Eq. 15, omega = (c_R/d_x) sin theta",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "q1": {
            "long_name": "first decay constant per row (rows decay as exp(-q I)), Eq. 6a; real q: the"
                         " slower one; complex: q1 = conj(q2) (+ i pi beyond pi - theta_c)",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "q2": {
            "long_name": "second decay constant per row, Re q2 > 0, Eq. 6a",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "R1": {
            "long_name": "polarisation ratio (a/c)^(1/2) U/V of the q1 wave (d_x U / d_y V for springs), Eq. 3a",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "R2": {
            "long_name": "polarisation ratio (a/c)^(1/2) U/V of the q2 wave, Eq. 3a",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "amplitude_ratio": {
            "long_name": "amplitude ratio V1/V2 of the two waves, Eq. 8a",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "theta_c": {
            "long_name": "crossover k d_x above which q1, q2 are complex (complex band is theta_c < "
                         "theta < pi - theta_c)",
            "units": "rad",
            "dims": ("strain",),
        },
        "omega_L": {
            "long_name": "frequency of the longitudinal bulk wave along the surface (q = 0), Eq. 4a",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "omega_T": {
            "long_name": "frequency of the transverse bulk wave along the surface (q = 0), Eq. 4a",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "c2_R": {
            "long_name": "squared Rayleigh speed from the lattice solution (Eq. 16 for springs)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "reason": {
            "long_name": "why the values at this point are NaN (empty when valid)",
            "dims": ("strain", "theta"),
        },
        "boundary_residual": {
            "long_name": "relative residual of the unsquared free-surface condition (Eqs. 7a-9a) at the Eq. 15 root",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "u": {
            "long_name": "row amplitude of the x displacement, u_IJ = u_I exp(i theta (I + 2J)), "
                         "normalised so max_I |(u_I, v_I)| = 1 and v_0 / i real positive",
            "units": "1",
            "dims": ("strain", "theta", "row"),
        },
        "v": {
            "long_name": "row amplitude of the y displacement (y into the crystal), same convention as u",
            "units": "1",
            "dims": ("strain", "theta", "row"),
        },
        "row": {"long_name": "row index below the surface (0 = surface row)", "units": "1", "dims": ("row",)},
        "omega_lattice": {
            "long_name": "surface-wave angular frequency from the numerical semi-infinite "
                         "lattice-dynamics solve (decimation)",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "omega_lattice_error": {
            "long_name": "error estimate of omega_lattice (extrapolated decimation truncation, root "
                         "bracket and rounding)",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "omega_bulk_min": {
            "long_name": "bottom of the bulk continuum at this k d_x",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "omega_sine_law": {
            "long_name": "(c_R/d_x) sin theta with c_R^2 from the long-wave elastic constants (Eq. 20)",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "theta"),
        },
        "sine_law_deviation": {
            "long_name": "omega_lattice / omega_sine_law - 1",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "c2_R_long_wave": {
            "long_name": "squared Rayleigh speed from Eq. 20 with the long-wave sound speeds of the "
                         "bond sums (Eqs. A7, A11, A12); NaN where Eq. 20 has no root in (0, "
                         "c2_T_par) (no long-wave Rayleigh wave)",
            "units": "K d0^2 / m",
            "dims": ("strain",),
        },
        "depth": {
            "long_name": "rows of crystal the decimation coupled to the surface (2^steps); NaN where "
                         "omega_lattice is NaN (see reason_lattice)",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "n_surface_modes": {
            "long_name": "number of bound surface modes below the bulk continuum; -1 where no scan "
                         "ran (bulk unstable, theta outside (0, pi) or at rounding) (-1: strain not "
                         "checked)",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "polarisation": {
            "long_name": "|v_0|^2 / (|u_0|^2 + |v_0|^2) of the surface row (1 = normal)",
            "units": "1",
            "dims": ("strain", "theta"),
        },
        "reason_lattice": {
            "long_name": "why omega_lattice is NaN (empty when valid)",
            "dims": ("strain", "theta"),
        },
        "omega_lattice_deviation": {
            "long_name": "omega_lattice minus omega (numerical minus analytic)",
            "units": "(K/m)^(1/2)",
            "dims": ("theta",),
        },
    },
    # entropy.nc: surface entropy (surfwave.dynamics.entropy)
    "entropy": {
        "S_surface_estimate": {
            "long_name": "surface entropy per surface atom, estimate of Eq. (25) corrected: "
                         "<ln(omega_L omega_T/omega0^2)> - <ln(omega_R/omega0)> - "
                         "<ln(omega/omega0)>_bulk, omega_R = (c_R/d_x) sin(theta) (Eq. 15, derived "
                         "for the harmonic lattice; for other pair potentials it is the definition "
                         "used, and checked against a semi-infinite lattice solve) with c_R^2 from "
                         "Eq. (20), omega_L, omega_T from Eq. (4a) at normal wave-number 0",
            "units": "k_B",
            "dims": ("strain",),
        },
        "S_surface_estimate_error": {
            "long_name": "error estimate of S_surface_estimate",
            "units": "k_B",
            "dims": ("strain",),
        },
        "bulk_mean_log_omega": {
            "long_name": "mean of ln(omega/omega0) over all bulk modes of the 2D lattice, omega0 = (K/m)^(1/2)",
            "units": "1",
            "dims": ("strain",),
        },
        "bulk_mean_log_omega_error": {
            "long_name": "error estimate of bulk_mean_log_omega",
            "units": "1",
            "dims": ("strain",),
        },
        "S_surface_exact": {
            "long_name": "exact classical harmonic surface entropy per surface atom of the "
                         "semi-infinite crystal (free (10) surface, lattice dynamics)",
            "units": "k_B",
            "dims": ("strain",),
        },
        "S_surface_exact_error": {
            "long_name": "error estimate of S_surface_exact",
            "units": "k_B",
            "dims": ("strain",),
        },
        "n_theta": {
            "long_name": "Gauss-Legendre nodes on [0, pi/2] used for the theta averages",
            "units": "1",
            "dims": ("strain",),
        },
        "reason": {
            "long_name": "why values are NaN at this strain (empty if all are valid)",
            "dims": ("strain",),
        },
    },
    # surface_phonons.nc: semi-infinite FCC surface phonons, soft modes, surface entropy
    # (surfwave.pipeline.surface_phonons_cube; surfwave.dynamics.fcc_surface_phonons)
    "surface_phonons": {
        "omega": {
            "long_name": "surface-mode angular frequency, sign(omega^2) sqrt|omega^2| (negative: "
                         "imaginary, an unstable surface mode), ascending, NaN-padded",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "q", "mode"),
        },
        "decay": {
            "long_name": "amplitude ratio of the surface mode between successive lattice planes",
            "units": "1",
            "dims": ("strain", "q", "mode"),
        },
        "polarisation": {
            "long_name": "share of the top plane's |U|^2 along q (longitudinal), the inward normal and q "
                         "x n (shear horizontal)",
            "units": "1",
            "dims": ("strain", "q", "mode", "component"),
        },
        "sector": {
            "long_name": "mirror sector: +1 sagittal (even), -1 shear horizontal (odd), 0 no mirror",
            "units": "1",
            "dims": ("strain", "q", "mode"),
        },
        "band_edges": {
            "long_name": "projected bulk band: min and max over the normal wavevector of each bulk "
                         "branch, signed omega",
            "units": "(K/m)^(1/2)",
            "dims": ("strain", "q", "branch", "edge"),
        },
        "q_reduced": {
            "long_name": "in-plane wavevector in reduced coordinates of the deformed surface reciprocal "
                         "lattice",
            "units": "1",
            "dims": ("strain", "q", "axis2"),
        },
        "q_distance": {
            "long_name": "length along the path of high-symmetry points",
            "units": "rad/d0",
            "dims": ("strain", "q"),
        },
        "spectral_density": {
            "long_name": "spectral density of the top plane's displacements, -(2 omega/pi) Im Tr G_00, "
                         "integrating to 3 over omega",
            "units": "(K/m)^(-1/2)",
            "dims": ("strain", "q", "frequency"),
        },
        "lowest_omega2": {
            "long_name": "omega^2 of the lowest surface mode at each q (NaN: none)",
            "units": "K/m",
            "dims": ("strain", "q"),
        },
        "softest_omega2": {
            "long_name": "lowest surface omega^2 along the path (negative: a soft surface mode)",
            "units": "K/m",
            "dims": ("strain",),
        },
        "bulk_stable": {
            "long_name": "bulk stable over the zone mesh and in the long-wave limit",
            "dims": ("strain",),
        },
        "reason": {
            "long_name": "why values are NaN at this strain (empty if all are valid)",
            "dims": ("strain",),
        },
        "S_surface_exact": {
            "long_name": "exact classical harmonic surface entropy per surface atom of the semi-infinite "
                         "crystal (log-determinant route)",
            "units": "k_B",
            "dims": ("strain",),
        },
        "S_surface_exact_error": {
            "long_name": "error estimate of S_surface_exact (Richardson over q grids)",
            "units": "k_B",
            "dims": ("strain",),
        },
        "S_surface_estimate": {
            "long_name": "Eq. (25)-type estimate <ln omega_1 omega_2 omega_3> - <ln omega_R> - 2 <ln "
                         "omega>_bulk (see docs/physics/surface-phonons.md)",
            "units": "k_B",
            "dims": ("strain",),
        },
        "bulk_mean_log_omega": {
            "long_name": "mean of ln(omega/omega0) over all bulk modes, omega0 = (K/m)^(1/2)",
            "units": "1",
            "dims": ("strain",),
        },
    },
    # surface_wave.nc of a real-crystal scene (surfwave.real_crystals.sweep; dims set by the builder)
    "surface_wave": {
        "c_R": {"long_name": "surface-wave speed (real part for a pseudo surface wave)", "units": "m s-1"},
        "c_R_imag": {
            "long_name": "imaginary part of the complex speed of a leaky pseudo surface wave (0 for a"
                         " true surface wave)",
            "units": "m s-1",
        },
        "c_limit": {
            "long_name": "limiting speed v_L: lowest bulk speed with a real slowness projection along"
                         " x1 (onset of bulk radiation)",
            "units": "m s-1",
        },
        "wave_type": {"long_name": "surface | supersonic_decoupled | pseudo | none"},
        "reason": {"long_name": "why no surface wave exists at the point (empty when one does)"},
        "polarisation": {
            "long_name": "surface displacement (u1, u2, u3) in the lab frame, complex, unit length, "
                         "phase such that u2 is real and >= 0",
            "units": "1",
        },
        "penetration_depth": {
            "long_name": "1/e depth of the slowest-decaying partial wave, 1/(2 pi min Im p), in wavelengths",
            "units": "1",
        },
        "decay": {
            "long_name": "Stroh eigenvalues p (Im p > 0) of the partial waves exp(ik(x1 + p x2)) of "
                         "the surface wave, ascending Im p (decoupled mirror wave: the two sagittal "
                         "ones, then the SH one or NaN), complex",
            "units": "1",
        },
        "rho": {"long_name": "density of the (stressed) crystal", "units": "kg m-3"},
        "c_leaky": {
            "long_name": "leaky SAW phase speed omega / Re k (radiating into the slowest bulk sheet only; "
                         "NaN where none; the exact wave at a supersonic_decoupled point)",
            "units": "m s-1",
        },
        "leaky_attenuation": {"long_name": "leaky SAW attenuation per wavelength", "units": "dB"},
        "leaky_reason": {"long_name": "why no leaky SAW is reported at the point (empty when one is)"},
        "symmetric_range": {
            "long_name": "width of the symmetry-reduced angle range [0, w]: the unstressed speeds "
                         "repeat mirror-symmetrically about multiples of w",
            "units": "degree",
        },
    },
    # surface_wave.nc of a piezoelectric scene (rule piezo_wave, surfwave.real_crystals.piezo_sweep; dims set
    # by the builder)
    "piezo_wave": {
        "c_R": {
            "long_name": "subsonic surface acoustic wave speed for the electrical condition (NaN where none)",
            "units": "m s-1",
        },
        "c_limit": {
            "long_name": "limiting speed: lowest trace speed along x1 of the piezoelectrically stiffened bulk waves",
            "units": "m s-1",
        },
        "K2": {"long_name": "electromechanical coupling K^2 = 2 (v_free - v_metallized) / v_free", "units": "1"},
        "c_leaky": {
            "long_name": "leaky SAW phase speed omega / Re k (radiating into the slowest bulk sheet "
                         "only; NaN where none)",
            "units": "m s-1",
        },
        "leaky_attenuation": {"long_name": "leaky SAW attenuation per wavelength", "units": "dB"},
        "power_flow_angle": {
            "long_name": "power-flow (beam-steering) angle of the SAW from x1 toward +x2 of the SAW frame (our +x3)",
            "units": "degree",
        },
        "potential_share": {
            "long_name": "electric share of the surface energy density, eps |phi|^2 / (rho c^2 |u|^2 + eps |phi|^2)",
            "units": "1",
        },
        "polarisation": {
            "long_name": "surface (u1, u2, u3, phi), lab frame, complex: |u| = 1, phase with u2 real "
                         ">= 0; phi in V per m of displacement",
            "units": "1",
        },
        "decay": {
            "long_name": "Stroh eigenvalues p (Im p > 0) of the four partial waves of the SAW, complex",
            "units": "1",
        },
        "penetration_depth": {
            "long_name": "1/e depth of the slowest-decaying partial wave, in wavelengths",
            "units": "1",
        },
        "wave_type": {"long_name": "surface | supersonic_decoupled | pseudo | none"},
        "reason": {"long_name": "why no subsonic SAW exists at the point (empty when one does)"},
        "leaky_reason": {"long_name": "why no leaky SAW is reported at the point (empty when one is)"},
        "rho": {"long_name": "density", "units": "kg m-3"},
    },
}

#: Bulk waves along x1 and x2 of a real crystal (surfwave.solvers.bulk_waves): the same variables in
#: both real-crystal cubes; ``polarisation_*`` carry a trailing ``bulk_component`` (u1, u2, u3).
_ALONG = {"L_par": ("x1", "u1 (quasi-longitudinal)"), "T_par": ("x1", "u2 (sagittal quasi-shear)"),
          "SH": ("x1", "u3 (shear-horizontal quasi-shear)"), "T_perp": ("x2", "u1 (quasi-shear)"),
          "L_perp": ("x2", "u2 (quasi-longitudinal)"), "SH_perp": ("x2", "u3 (quasi-shear)")}
_BULK_WAVES: dict[str, dict[str, Any]] = {}
for _name, (_axis, _pol) in _ALONG.items():
    _BULK_WAVES[f"c_{_name}"] = {
        "long_name": f"bulk wave along {_axis} polarised mostly along {_pol}: eigen-speed of the Christoffel "
                     "tensor of C + sigma0 delta (piezoelectrically stiffened in a piezoelectric crystal)",
        "units": "m s-1"}
    _BULK_WAVES[f"polarisation_{_name}"] = {
        "long_name": f"unit displacement (u1, u2, u3), lab frame, of the bulk wave c_{_name}, largest "
                     "component positive",
        "units": "1"}
CUBES["surface_wave"].update(_BULK_WAVES)
CUBES["piezo_wave"].update(_BULK_WAVES)
CUBES["piezo_wave"]["K2_leaky"] = {
    "long_name": "electromechanical coupling of the leaky SAW, 2 (c_leaky_free - c_leaky_metallized) / "
                 "c_leaky_free (NaN where either leaky root is missing)",
    "units": "1"}
for _el in ("free", "metallized"):
    CUBES["piezo_wave"][f"c_leaky_{_el}"] = {
        "long_name": f"leaky SAW phase speed omega / Re k with a {_el} surface, from the solve of both conditions "
                     "(also when the scene lists one electrical condition); NaN where none",
        "units": "m s-1"}
CUBES["piezo_wave"]["grazing"] = {
    "long_name": "subsonic SAW that is a bulk-like grazing wave (penetration depth above "
                 "surfwave.real_crystals.stressed_wave.GRAZING_DEPTH wavelengths): not usable as a surface wave"}
CUBES["surface_wave"]["grazing"] = dict(CUBES["piezo_wave"]["grazing"])

#: displacements.nc (row amplitudes, surfwave.dynamics.dispersion) carries a subset of the dispersion
#: cube's variables with the same metadata.
CUBES["displacements"] = {k: CUBES["dispersion"][k] for k in (
    "omega", "q1", "q2", "R1", "R2", "amplitude_ratio", "theta_c", "omega_L", "omega_T", "c2_R", "reason",
    "boundary_residual", "u", "v", "row")}

#: Coordinates of the model-lattice cubes (``angle``: FCC angle scenes only).
MODEL_COORDS: dict[str, dict[str, str]] = {
    "potential": {"long_name": "pair potential (surfwave.model_crystals.potentials registry name)"},
    "direction": {"long_name": "propagation direction x (crystal axes; [10]: triangular rows)"},
    "strain": {"long_name": "strain along the propagation direction, d/d0 - 1", "units": "1"},
    "d_over_d0": {"long_name": "stretch along the propagation direction, d/d0", "units": "1"},
    "theta": {"long_name": "reduced wave number theta = k d_x", "units": "rad"},
    "row": {"long_name": "atomic row below the surface (0 = surface row)", "units": "1"},
    "complex": {"long_name": "part of a complex number: real or imaginary"},
    "angle": {"long_name": "propagation angle in the (001) surface, from [100] toward [010]", "units": "degree"},
}

#: Coordinates of the real-crystal cube surface_wave.nc.
SURFACE_WAVE_COORDS: dict[str, dict[str, str]] = {
    "material": {"long_name": "crystal (surfwave.real_crystals.materials name)"},
    "surface": {"long_name": "surface plane, Miller indices in crystal axes"},
    "angle": {
        "long_name": "propagation angle from the surface's reference direction ((001): [100], (110): "
                     "[001], (111): [1-10]) toward n x reference",
        "units": "degree",
    },
    "direction": {"long_name": "propagation direction, Miller indices in crystal axes"},
    "loading": {
        "long_name": "stress kind: along / across the propagation (uniaxial), in-plane biaxial, or "
                     "axis_<hkl> uniaxial along a fixed crystal axis",
    },
    "toec": {
        "long_name": "constants of the stressed state from third-order elastic constants (false: "
                     "second-order constants of the natural state)",
    },
    "stress": {"long_name": "applied in-plane stress (negative = compression)", "units": "GPa"},
}

#: Coordinates of the piezoelectric cube (rule piezo_wave).
PIEZO_WAVE_COORDS: dict[str, dict[str, str]] = {
    "material": {"long_name": "piezoelectric constant set (surfwave.real_crystals.piezo_materials name)"},
    "surface": {"long_name": "the plate: a named cut, or SAW Euler angles (phi, theta) in degrees"},
    "angle": {
        "long_name": "propagation angle in the plate, psi - psi0 (psi0: the named cut's psi, else 0)",
        "units": "degree",
    },
    "cut": {"long_name": "named SAW cut (surfwave.real_crystals.piezo_materials.get_cut)"},
    "euler_phi": {"long_name": "SAW Euler angle phi (ZXZ, first rotation about crystal Z)", "units": "degree"},
    "euler_theta": {
        "long_name": "SAW Euler angle theta (about the new X; rotated Y cut by theta + 90)",
        "units": "degree",
    },
    "euler_psi": {
        "long_name": "SAW Euler angle psi (about the new Z: propagation in the plate), psi0 + angle",
        "units": "degree",
    },
    "electrical": {"long_name": "surface condition: free (open circuit, vacuum above) or metallized (phi = 0)"},
    "toec": {
        "long_name": "constants of the stressed state from third-order elastic constants (false: "
                     "second-order constants of the natural state; e and eps at natural values in both)",
    },
    "stress": {
        "long_name": "uniaxial prestress along the propagation direction (negative = compression)",
        "units": "GPa",
    },
}

#: dispersion_layered (films on a substrate, surfwave.layers.cube.dispersion_cube): every mode of a stack
#: against (film_stress, electrical, kh, mode label), SI units.
CUBES["dispersion_layered"] = {
    "c": {"long_name": "phase speed of the mode (omega / Re k for a leaky mode)", "units": "m s-1"},
    "group_velocity": {"long_name": "group velocity d omega / dk (energy velocity)", "units": "m s-1"},
    "K2": {"long_name": "electromechanical coupling 2 (c_free - c_metallized) / c_free", "units": "1"},
    "attenuation": {"long_name": "attenuation of a leaky mode per wavelength", "units": "dB"},
    "frequency": {"long_name": "frequency of the mode at this kh", "units": "Hz"},
    "power_flow_angle": {"long_name": "power-flow angle from x1 toward the in-plane normal (SAW frame x2)",
                         "units": "degree"},
    "c_limit": {"long_name": "limiting speed of the substrate (slowest bulk wave's trace speed along x1)",
                "units": "m s-1"},
    "mode_limit": {"long_name": "limiting speed of the mode's family (sagittal or shear-horizontal where the motion "
                   "decouples): a guided mode lies below it", "units": "m s-1"},
    "reason": {"long_name": "why a row holds no mode (empty where it holds one)"},
    "film_bulk_speed": {"long_name": "bulk wave speeds of each film along the propagation direction x1 "
                        "(unstressed), ascending", "units": "m s-1"},
}

#: Coordinates of the dispersion_layered cube.
LAYERED_COORDS: dict[str, dict[str, str]] = {
    "film_stress": {"long_name": "equibiaxial in-plane residual stress of every film (negative: compression)",
                    "units": "GPa"},
    "electrical": {"long_name": "electrical condition of the top surface"},
    "kh": {"long_name": "wavenumber times total film thickness", "units": "1"},
    "mode": {"long_name": "mode label: R Rayleigh, Sn Sezawa, Ln Love, Mn coupled; trailing ~ leaky"},
    "film": {"long_name": "film index from the top", "units": "1"},
    "sheet": {"long_name": "bulk sheet (ascending speed)", "units": "1"},
}
