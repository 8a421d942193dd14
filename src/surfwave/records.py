"""Typed records of the front door's results: :class:`PointResult` and :class:`MaterialResult`.

They are :class:`typing.TypedDict`: at run time the results stay plain dicts with exactly the
keys documented here (nothing changes for a caller that indexes them), and a type checker
knows every key. Also importable as ``surfwave.api.PointResult`` and
``surfwave.api.MaterialResult``.

>>> from surfwave.records import MaterialResult, PointResult
>>> sorted(MaterialResult.__required_keys__)[:3]
['angle', 'c_L_par', 'c_L_perp']
>>> sorted(PointResult.__optional_keys__)
['angle', 'c2_limit', 'decay', 'min_acoustic_eig', 'penetration_depth', 'polarisation']
"""

# No ``from __future__ import annotations`` here: on Python 3.11 TypedDict reads NotRequired
# only from evaluated annotations (with strings every key would count as required).
from typing import Any, NotRequired, TypedDict

__all__ = ["LayeredResult", "MaterialResult", "PointResult"]

#: Values are NumPy arrays (shapes below); ``Any`` keeps the record free of a NumPy typing
#: dependency and lets MaterialResult hold Python scalars for one direction.
_Array = Any


class PointResult(TypedDict):
    """Result of :func:`surfwave.point`: a prestressed pair-potential model crystal.

    Reduced units (d0 = K = m = 1; tensors times the volume per atom V). Shapes: n strains;
    with an array of m angles (FCC, general solver) the per-direction keys gain a trailing
    axis of m; d = 3 (FCC) or 2 (triangular lattice).

    Attributes
    ----------
    d_over_d0, volume : ndarray, shape (n,)
        Stretch along the load direction (1), volume (area in 2D) per atom (d0^3 or d0^2).
    stress : ndarray, shape (n,) or (n, m)
        sigma_xx V (x = propagation), K d0^2.
    c2_L_par, c2_T_par, c2_L_perp, c2_T_perp, c2_SH : ndarray, shape (n,) or (n, m)
        Squared bulk sound speeds along x (par) and along the inward normal y (perp), K d0^2 / m;
        ``c2_SH`` (along x, polarised along z) is NaN in 2D.
    c2_R : ndarray, shape (n,) or (n, m)
        Squared surface-wave speed, K d0^2 / m (real part for a pseudo wave; NaN where none).
    wave_type : ndarray of str (object), shape (n,) or (n, m)
        :data:`surfwave.vocab.WAVE_TYPES`.
    reason : ndarray of str (object), shape (n,) or (n, m)
        Why ``c2_R`` is NaN (empty where it is not).
    stable : ndarray of bool, shape (n,)
        Long-wave (acoustic tensor) stability in every direction.
    C, S : ndarray, shape (n, [m,] d, d, d, d)
        V C and V S (Eq. A11) in the lab frame of the propagation, K d0^2.
    angle : ndarray, shape (n,) or (n, m), FCC only
        Propagation angle in the (001) surface, degrees from [100] toward [010].
    c2_limit : ndarray, shape (n,) or (n, m)
        Squared limiting speed v_L^2, K d0^2 / m (general solver: off the mirror directions,
        or with ``details``).
    polarisation, decay : ndarray of complex, shape (n, [m,] d)
        Surface displacement (unit norm, u2 real >= 0) and Stroh eigenvalues p of the partial
        waves (1); same condition as ``c2_limit``.
    penetration_depth : ndarray, shape (n,) or (n, m)
        1/e depth of the slowest-decaying partial wave, in wavelengths (1); same condition.
    min_acoustic_eig : ndarray, shape (n,)
        Lowest eigenvalue of V Q(n) over all directions, K d0^2 (only with ``min_eig``).
    """

    d_over_d0: _Array
    volume: _Array
    stress: _Array
    c2_L_par: _Array
    c2_T_par: _Array
    c2_L_perp: _Array
    c2_T_perp: _Array
    c2_SH: _Array
    c2_R: _Array
    wave_type: _Array
    reason: _Array
    stable: _Array
    C: _Array
    S: _Array
    angle: NotRequired[_Array]
    c2_limit: NotRequired[_Array]
    polarisation: NotRequired[_Array]
    decay: NotRequired[_Array]
    penetration_depth: NotRequired[_Array]
    min_acoustic_eig: NotRequired[_Array]


class MaterialResult(TypedDict):
    """Result of :func:`surfwave.material`: a real crystal, SI units.

    Python scalars (float, str, bool) for one direction; arrays of shape (m,) for m angles
    (``polarisation`` and ``decay``: (3,) or (m, 3)).

    Attributes
    ----------
    c_R : float or ndarray
        Surface-wave speed, m/s (real part for a pseudo wave; NaN where none).
    c_R_imag : float or ndarray
        Imaginary part of the complex speed of a pseudo wave, m/s (0 for a real wave).
    c_limit : float or ndarray
        Limiting speed v_L, m/s.
    c_L_par, c_T_par, c_SH, c_T_perp, c_L_perp, c_SH_perp : float or ndarray
        Bulk speeds along x1 (``L_par``, ``T_par``, ``SH``: polarised mostly along u1, u2, u3)
        and along the inward normal x2 (``T_perp``, ``L_perp``, ``SH_perp``: mostly u1, u2, u3),
        m/s: eigen-speeds of the Christoffel tensor of C + sigma0 delta, piezoelectrically
        stiffened on the piezoelectric route (:mod:`surfwave.solvers.bulk_waves`); NaN where
        imaginary.
    polarisation_L_par, polarisation_T_par, polarisation_SH, polarisation_T_perp, \
polarisation_L_perp, polarisation_SH_perp : ndarray, shape (3,) or (m, 3)
        Unit displacement (u1, u2, u3) of each bulk wave, lab frame, largest component positive.
    grazing : bool or ndarray of bool
        The surface wave is a bulk-like grazing wave, deeper than
        :data:`surfwave.real_crystals.stressed_wave.GRAZING_DEPTH` (50) wavelengths: do not
        design on it.
    wave_type : str or ndarray of str
        :data:`surfwave.vocab.WAVE_TYPES`.
    reason : str or ndarray of str
        Why ``c_R`` is NaN (empty where it is not).
    stable : bool or ndarray of bool
        Born stability and a positive acoustic tensor in every direction.
    polarisation, decay : ndarray of complex, shape (3,) or (m, 3)
        Surface displacement (lab frame, unit norm, u2 real >= 0) and Stroh eigenvalues p (1).
    penetration_depth : float or ndarray
        1/e depth of the slowest-decaying partial wave, in wavelengths (1).
    angle : float or ndarray
        Propagation angle, degrees from the surface's reference direction.
    method : str or ndarray of str
        Which solver path produced the speed.
    rho : float or ndarray
        Density of the stressed state, kg/m^3.
    toec : bool or ndarray of bool
        Whether the third-order (stressed-state) model was used.
    c_leaky, leaky_attenuation : float or ndarray
        Every crystal: the leaky wave radiating into the slowest bulk sheet, speed in m/s and
        attenuation in dB per wavelength (NaN where none or not computed: ``leaky=``).
    leaky_reason : str or ndarray of str
        Why ``c_leaky`` is NaN (empty where it is not).
    c_free, c_metallized : float or ndarray
        Piezoelectric route only (``piezo=``, ``permittivity=``, ``euler=``, ``cut=``,
        ``electrical=`` or a crystal of the piezoelectric database; so are the keys below):
        subsonic SAW speed with a free and with a metallized surface, m/s. On this route
        ``polarisation`` and ``decay`` have a fourth component (the potential phi, V per m of
        displacement) and ``c_limit`` is the stiffened limiting speed.
    K2 : float or ndarray
        Coupling 2 (c_free - c_metallized) / c_free (fraction, 1).
    c_leaky_free, c_leaky_metallized : float or ndarray
        Leaky SAW speed (omega / Re k) with a free and with a metallized surface, m/s, from one
        solve whatever ``electrical`` is (``c_leaky`` is the one of ``electrical``).
    K2_leaky : float or ndarray
        Coupling of the leaky SAW, 2 (c_leaky_free - c_leaky_metallized) / c_leaky_free (1);
        the coupling a device on a leaky cut (36Y-X LiTaO3, 64Y-X LiNbO3) uses.
    power_flow_angle : float or ndarray
        Beam-steering angle of the SAW, degrees.
    potential_share : float or ndarray
        Share of the electric potential in the polarisation (1).
    electrical : str or ndarray of str
        :data:`surfwave.vocab.ELECTRICAL`: the surface condition of ``c_R``.
    euler : ndarray, shape (3,) or (m, 3)
        Euler angles (phi, theta, psi) of the cut, degrees (NaN for a surface/direction call).
    model : str
        Which constant set and model produced the numbers.
    """

    c_R: _Array
    c_R_imag: _Array
    c_limit: _Array
    c_L_par: _Array
    c_T_par: _Array
    c_L_perp: _Array
    c_T_perp: _Array
    c_SH: _Array
    c_SH_perp: _Array
    polarisation_L_par: _Array
    polarisation_T_par: _Array
    polarisation_SH: _Array
    polarisation_T_perp: _Array
    polarisation_L_perp: _Array
    polarisation_SH_perp: _Array
    grazing: _Array
    wave_type: _Array
    reason: _Array
    stable: _Array
    polarisation: _Array
    decay: _Array
    penetration_depth: _Array
    angle: _Array
    method: _Array
    rho: _Array
    toec: _Array
    c_leaky: _Array
    leaky_attenuation: _Array
    leaky_reason: _Array
    c_free: NotRequired[_Array]
    c_metallized: NotRequired[_Array]
    K2: NotRequired[_Array]
    c_leaky_free: NotRequired[_Array]
    c_leaky_metallized: NotRequired[_Array]
    K2_leaky: NotRequired[_Array]
    power_flow_angle: NotRequired[_Array]
    potential_share: NotRequired[_Array]
    electrical: NotRequired[_Array]
    euler: NotRequired[_Array]
    model: NotRequired[_Array]


class LayeredResult(TypedDict):
    """Result of :func:`surfwave.layered`: guided modes of films on a substrate, SI units.

    Shapes: n kh values (or frequencies) by n_modes columns; each row holds that kh's modes in
    ascending speed, NaN-padded (and "" labels) where a row has fewer modes.

    Attributes
    ----------
    c : ndarray, shape (n, n_modes)
        Phase speeds, m/s (for a leaky mode: omega / Re k).
    mode : ndarray of str (object), shape (n, n_modes)
        Labels, continuous along kh: "R" (Rayleigh), "S1", "S2", ... (Sezawa) for the sagittal
        family, "L0", "L1", ... (Love) for the shear-horizontal one, "M0", "M1", ... where the
        motion does not decouple; a trailing "~" marks a leaky mode.
    group_velocity : ndarray, shape (n, n_modes)
        d omega / dk, m/s (NaN for leaky modes).
    K2 : ndarray, shape (n, n_modes)
        2 (c_free - c_metallized) / c_free of piezoelectric stacks (1), the two speeds of the same mode
        label at the same kh (at the same frequency with ``frequency`` input); NaN for elastic stacks.
    c_limit : float
        Limiting speed of the substrate (the slowest bulk wave's trace speed along x1), m/s.
    attenuation : ndarray, shape (n, n_modes)
        dB per wavelength of leaky modes; NaN for guided modes and when ``leaky`` is False.
    kh : ndarray, shape (n, n_modes)
        Wavenumber times total film thickness of each entry (1).
    frequency : ndarray, shape (n, n_modes)
        Frequency of each entry, Hz (NaN without films).
    reason : ndarray of str (object), shape (n,)
        Why a row holds no mode ("" where it holds one).
    power_flow_angle : ndarray, shape (n, n_modes)
        Angle of the depth-integrated power flow from x1 toward the in-plane normal x2 of the SAW
        frame, degrees (0 in a mirror plane; NaN for leaky modes).
    mode_limit : ndarray, shape (n, n_modes)
        Limiting speed of each entry's family, m/s (NaN where no mode): a guided mode lies below
        it. Where the motion decouples (a mirror plane) the sagittal modes (R, S1, ...) and the
        shear-horizontal ones (L0, ...) have different limits and ``c_limit`` is the lower one.
    """

    c: _Array
    mode: _Array
    group_velocity: _Array
    K2: _Array
    c_limit: _Array
    attenuation: _Array
    kh: _Array
    frequency: _Array
    reason: _Array
    power_flow_angle: _Array
    mode_limit: _Array


class SurfacePhononsResult(TypedDict):
    """Result of :func:`surfwave.surface_phonons`: the semi-infinite prestressed FCC crystal.

    Reduced units (d0 = K = m = 1): omega in sqrt(K/m), omega^2 in K/m, wavevectors in
    rad/d0. Shapes: n strains, n_q wavevectors, n_modes surface modes (the most found at
    any point; NaN-padded), m planes per principal layer (1 for (001), (111); 2 for (110)).

    Attributes
    ----------
    surface, loading, load_direction, potential : str
        What was computed.
    d_over_d0 : ndarray, shape (n,)
        Stretch along the load direction (1).
    q : ndarray, shape (n_q, 2)
        Reduced coordinates of the deformed primitive surface reciprocal lattice (1).
    q_cartesian : ndarray, shape (n, n_q, 2)
        In-plane wavevector along (e1, e3) of the surface frame (e1 along a1), rad/d0.
    q_distance : ndarray, shape (n, n_q)
        Cumulative length along the sampled q, rad/d0.
    path_labels : list of str
        High-symmetry labels of a path (empty for explicit q); ``path_index`` (len,) their rows.
    omega, omega2 : ndarray, shape (n, n_q, n_modes)
        Surface modes, ascending; ``omega`` = sign(omega^2) sqrt|omega^2| (negative: an
        imaginary frequency, an unstable surface mode). NaN: no further mode, or see
        ``q_reason``.
    decay : ndarray, shape (n, n_q, n_modes)
        Asymptotic amplitude ratio between successive planes (1; < 1).
    polarisation : ndarray, shape (n, n_q, n_modes, 3)
        Share of |U|^2 of the top plane along q^ (longitudinal), the inward normal and
        q^ x n (shear horizontal) (1; rows sum to 1).
    sector : ndarray of int8, shape (n, n_q, n_modes)
        +1 sagittal (even under the mirror through q and n), -1 shear horizontal (odd),
        0 no mirror at this q.
    band_edges, band_edges_omega2 : ndarray, shape (n, n_q, 3 m, 2)
        [min, max] of each bulk branch over the normal wavevector (projected bulk band),
        in signed omega and in omega^2.
    softest_q : ndarray, shape (n, 2)
        Reduced q of the lowest surface omega^2 among the sampled q (NaN: no surface mode).
    softest_omega2 : ndarray, shape (n,)
        That omega^2, K/m (negative: a soft surface mode).
    bulk_stable : ndarray of bool, shape (n,)
        Bulk stable over the zone mesh and in the long-wave limit.
    bulk_min_omega2 : ndarray, shape (n,)
        Lowest bulk omega^2 of that check (long-wave: the lowest acoustic-tensor eigenvalue,
        K d0^2/m), K/m.
    reason, q_reason : ndarray of str (object), shapes (n,) and (n, n_q)
        Why results are NaN (empty where they are not).
    layer_spacing : ndarray, shape (n,)
        Plane spacing h, d0.
    spectral_density : ndarray, shape (n, n_q, n_omega), only with ``omega``
        Top plane's -(2 omega/pi) Im Tr G_00(omega^2 + i eta), per sqrt(K/m); integrates to 3.
    omega_grid : ndarray, shape (n_omega,); eta : float
        The frequencies and broadening (K/m) used.
    """

    surface: str
    loading: str
    load_direction: str
    potential: str
    d_over_d0: _Array
    q: _Array
    q_cartesian: _Array
    q_distance: _Array
    path_labels: list
    path_index: _Array
    omega: _Array
    omega2: _Array
    decay: _Array
    polarisation: _Array
    sector: _Array
    band_edges: _Array
    band_edges_omega2: _Array
    softest_q: _Array
    softest_omega2: _Array
    bulk_stable: _Array
    bulk_min_omega2: _Array
    reason: _Array
    q_reason: _Array
    layer_spacing: _Array
    spectral_density: NotRequired[_Array]
    omega_grid: NotRequired[_Array]
    eta: NotRequired[float]


__all__ += ["SurfacePhononsResult"]
