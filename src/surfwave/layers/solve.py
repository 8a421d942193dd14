"""The public entry :func:`layered`: every guided mode of a stack of films on a crystal.

Inputs are resolved and checked by :func:`surfwave.layers.stack.resolve_stack` (one InputError
line, before anything is computed); the modes of each decoupled family come from
:func:`surfwave.layers.modes.family_modes`, their group velocities from
:func:`surfwave.layers.fields.mode_fields`, K^2 of a piezoelectric stack from a second solve with
the top metallized, and the leaky continuation (``leaky=True``) from :mod:`surfwave.layers.leaky`.
"""
from __future__ import annotations

from typing import cast

import numpy as np

from surfwave import validate
from surfwave.errors import InputError
from surfwave.layers.fields import mode_fields
from surfwave.layers.modes import family_modes, floor_unstable, label, label_family
from surfwave.layers.partial import Blocks, Family, families, scaled_blocks
from surfwave.layers.stack import Stack, resolve_stack
from surfwave.records import LayeredResult
from surfwave.solvers.boundary import FREE, METALLIZED, Boundary, Free, as_boundary

__all__ = ["MAX_KH", "checked_modes", "family_limits", "layered", "mode_limits", "mode_speeds", "solve_stack",
           "use_fast_path"]

#: Largest kh accepted (the speed grid grows with kh; beyond this the film is a half-space).
MAX_KH = 1000.0
REASON_NONE = "no guided mode below the substrate's limiting speed at this kh"
REASON_BUCKLED = ("no modes: the prestressed stack is unstable at this kh (surface buckling: its impedance has a "
                  "negative eigenvalue at low speed, i.e. a mode with omega^2 < 0)")


def checked_kh(kh) -> np.ndarray:
    """kh (wavenumber x total film thickness) as a checked 1-D float array, shape (n,): finite,
    in [0, MAX_KH]; anything else is one InputError line."""
    a = validate.real_array(kh, "kh").reshape(-1)
    if a.size == 0 or not np.all(np.isfinite(a)):
        raise InputError(f"kh must be finite numbers (wavenumber x total film thickness), got {kh!r}")
    if np.any(a < 0) or np.any(a > MAX_KH):
        raise InputError(f"kh must lie in [0, {MAX_KH:g}], got values from {a.min():g} to {a.max():g}")
    return a


def _family_solution(b: Blocks, fam: Family, kh: np.ndarray, electrical: str | Boundary) -> tuple[np.ndarray, ...]:
    """Speeds, group velocities and power-flow angles (k, n_f) of one family."""
    c = family_modes(b, fam, kh, electrical=electrical)
    vg = np.full(c.shape, np.nan)
    pf = np.full(c.shape, np.nan)
    ik, jm = np.nonzero(np.isfinite(c))
    if ik.size:
        r = mode_fields(b, fam, c[ik, jm], kh[ik], electrical)
        vg[ik, jm], pf[ik, jm] = r["group_velocity"], r["power_flow_angle"]
    return c, vg, pf


def solve_stack(stack: Stack, kh, electrical: str | Boundary = "free") -> dict:
    """Modes of a resolved stack at each kh, per family (no input checks beyond kh).

    Returns
    -------
    dict
        ``blocks`` (Blocks), ``families`` (list of Family), ``c``, ``group_velocity`` and
        ``power_flow_angle`` (lists of (k, n_f) arrays, one per family), ``c_limit`` (m/s).
    """
    kh = checked_kh(kh)
    b = scaled_blocks(stack)
    fams = families(b)
    cs, vgs, pfs = [], [], []
    for fam in fams:
        c, vg, pf = _family_solution(b, fam, kh, electrical)
        cs.append(c)
        vgs.append(vg)
        pfs.append(pf)
    c_lim = float(np.sqrt(min(f.X_limit for f in fams) * b.sA / b.rho[-1]))
    return {"blocks": b, "families": fams, "c": cs, "group_velocity": vgs, "power_flow_angle": pfs,
            "c_limit": c_lim}


def merge_families(fams: list[Family], cs: list[np.ndarray], extra: list[list[np.ndarray]]) -> tuple:
    """Columns of all families merged, ascending per row; labels; the extra arrays in the same order."""
    k = cs[0].shape[0] if cs else 0
    if not any(c.shape[1] for c in cs):
        return np.full((k, 0), np.nan), np.full((k, 0), "", dtype=object), [np.full((k, 0), np.nan) for _ in extra]
    # one block (1 + len(extra), k, columns): the speeds, then each extra array, families side by side
    block = np.stack([np.concatenate(cs, axis=1)] + [np.concatenate(x, axis=1) for x in extra])
    C = block[0]
    names = np.array([label(fam.prefix, j) for fam, c in zip(fams, cs) for j in range(c.shape[1])] + [""],
                     dtype=object)
    finite = np.isfinite(C)
    order = np.argsort(np.where(finite, C, np.inf), axis=1, kind="stable")
    block = np.take_along_axis(block, order[None], axis=2)
    n = int(np.count_nonzero(finite, axis=1).max(initial=0))
    code = np.where(np.isfinite(block[0, :, :n]), order[:, :n], -1)    # the column's label; "" where no mode
    return block[0, :, :n], names[code], [x[:, :n] for x in block[1:]]


def layered(substrate, films=(), *, euler=None, surface: str = "(001)", direction="[100]", kh=None,
            frequency=None, electrical: str | Boundary = "free", stress=None, leaky: bool = False,
            modes: int | None = None) -> LayeredResult:
    """Every guided mode of films on a crystal substrate, under in-plane prestress.

    Parameters
    ----------
    substrate : str or mapping
        As in :func:`surfwave.material`: a material name (elastic, piezoelectric or film
        database), ``{voigt (6, 6) GPa, rho[, piezo (3, 6) C/m^2, permittivity (3, 3)]}`` or an
        isotropic ``{E (GPa), nu, rho}``; crystal axes.
    films : sequence of mapping
        From the top down; each a material (``name`` or the keys above) plus ``thickness`` (m),
        optional ``euler`` (SAW Euler angles of the film's crystal axes, degrees; default: crystal
        axes = SAW lab axes, i.e. a c-axis film has its c axis along the normal) and ``stress``
        (GPa; a scalar is equibiaxial in the surface plane, a 3 x 3 tensor is in the SAW frame
        x1 = propagation, x2 = in-plane normal to it, x3 = outward normal); in a piezoelectric
        stack, optional ``permittivity`` (relative) and ``electrode_below`` (True: a thin grounded
        electrode on the interface under the film).
    euler : array_like (3,), optional
        SAW Euler angles of the substrate (instead of ``surface``/``direction``).
    surface, direction : str
        Substrate surface "(hkl)" and propagation direction "[uvw]" (or angle, degrees).
    kh : array_like, shape (n,)
        Wavenumber times the total film thickness, in [0, :data:`MAX_KH`].
    frequency : array_like, shape (n,), optional
        Frequencies (Hz) instead of ``kh``: each mode then has its own kh = 2 pi f H / c. Labels
        are then ranks within each family at that frequency (R, S1, ... by speed); a branch whose
        frequency falls with k (a backward wave, ``group_velocity`` < 0) meets one frequency two
        or three times, each a mode (:mod:`surfwave.layers.frequency`).
    electrical : {"free", "metallized"} or Boundary
        Top surface of a piezoelectric stack (``c`` is reported for this condition): a
        :class:`surfwave.solvers.boundary.Boundary` or its name.
    stress : float or array_like (3, 3), optional
        Substrate prestress, GPa, same conventions as a film's.
    leaky : bool
        Also continue modes above the substrate's limiting speed as leaky waves (complex speed):
        ``c`` is then the real phase speed and ``attenuation`` their loss.
    modes : int, optional
        Only the ``modes`` slowest guided modes of each family (e.g. 2: R and S1, L0 and L1);
        None (default): all. On isotropic stacks the search stops there (faster); otherwise the
        columns beyond are dropped (with ``leaky`` a leaky continuation counts as a mode of its family).

    Returns
    -------
    LayeredResult
        ``c`` (n, n_modes) m/s ascending per row, NaN-padded; ``mode`` labels; ``group_velocity``
        (m/s); ``power_flow_angle`` (degrees); ``K2`` (piezoelectric stacks; NaN otherwise);
        ``c_limit``; ``attenuation`` (dB per wavelength; NaN for guided modes and when ``leaky``
        is False); ``kh`` and ``frequency`` (n, n_modes); ``reason`` (n,); ``mode_limit`` (n,
        n_modes): the limiting speed of each mode's family (sagittal and shear-horizontal differ
        in a mirror plane; ``c_limit`` is the lower).

    Raises
    ------
    InputError
        Bad materials, thicknesses, stresses, kh or options (one line, before any computation).

    Examples
    --------
    >>> import numpy as np, surfwave
    >>> r = surfwave.layered("Si", [{"E": 70.0, "nu": 0.17, "rho": 2200.0, "thickness": 1e-6}],
    ...                      kh=[0.0, 1.0])
    >>> r["mode"][1].tolist()
    ['R', 'L0']
    >>> round(float(r["c"][0, 0]), 3)   # bare Si (001)[100] Rayleigh speed
    4917.858
    """
    stack = resolve_stack(substrate, films, euler=euler, surface=surface, direction=direction, stress=stress)
    boundary = as_boundary(electrical)
    if not isinstance(boundary, Free) and not stack.piezo:
        raise InputError(f"electrical={boundary.name!r} needs a piezoelectric layer or substrate")
    if not isinstance(leaky, (bool, np.bool_)):
        raise InputError(f"leaky must be True or False, got {leaky!r}")
    if (kh is None) == (frequency is None):
        raise InputError("give exactly one of kh (wavenumber x total film thickness) or frequency (Hz)")
    n_modes = checked_modes(modes)
    if frequency is not None:
        from surfwave.layers.frequency import at_frequency

        return cast(LayeredResult, at_frequency(stack, frequency, electrical=boundary, leaky=bool(leaky),
                                                modes=n_modes))
    return cast(LayeredResult, assemble(stack, checked_kh(kh), boundary, bool(leaky), n_modes))


def checked_modes(modes) -> int | None:
    """``modes`` of :func:`layered`: None or a positive integer; anything else is one InputError line."""
    if modes is None:
        return None
    if isinstance(modes, (bool, np.bool_)) or not isinstance(modes, (int, np.integer)) or modes < 1:
        raise InputError(f"modes must be a positive integer (the N slowest guided modes of each family) or None "
                         f"(all), got {modes!r}")
    return int(modes)


#: Set to False to force the general (Stroh) path on isotropic stacks too (tests compare the two).
FAST_ISOTROPIC = True


def use_fast_path(stack: Stack, leaky: bool = False) -> bool:
    """True when the isotropic fast path (:mod:`surfwave.layers.isotropic`) answers this stack."""
    from surfwave.layers.isotropic import eligible

    return FAST_ISOTROPIC and not leaky and eligible(stack)


def mode_speeds(stack: Stack, kh, labels, electrical: str = "free") -> np.ndarray:
    """Speeds of named guided modes only: the search of their families alone, no group velocity or K^2.

    The numbers are those of :func:`layered` for the same labels (the same family search and the
    same unstable rows); a fit evaluating one mode many times saves the other families' searches.

    Parameters
    ----------
    stack : Stack
    kh : array_like, shape (n,)
        Wavenumber x total film thickness.
    labels : str or sequence of str, length n
        The mode of every point (or one for all): "R", "S1", "L0", "M2", ... (guided modes).
    electrical : {"free", "metallized"}

    Returns
    -------
    ndarray, shape (n,)
        Phase speed, m/s; NaN where the mode does not exist (or the stack is unstable).
    """
    kh = checked_kh(kh)
    which = np.broadcast_to(np.asarray(labels, dtype=object), kh.shape)
    if use_fast_path(stack):
        from surfwave.layers.isotropic_record import labelled_speeds

        return labelled_speeds(stack, kh, which)
    out = np.full(kh.size, np.nan)
    if unstable_reason(stack):
        return out
    b = scaled_blocks(stack)
    fams = families(b)
    buckled = np.zeros(kh.size, dtype=bool)
    for fam in fams:
        buckled |= floor_unstable(b, fam, kh, electrical)
    prefix = np.array([_prefix(str(lab)) for lab in which], dtype=object)
    for fam in fams:
        if not (prefix == fam.prefix).any():
            continue
        # all kh: the grid of layered(); only the slowest mode asked for: the scan stops above it
        slowest = set(which[prefix == fam.prefix].tolist()) == {label(fam.prefix, 0)}
        c = family_modes(b, fam, kh, electrical=electrical, lowest=slowest)
        for j in range(c.shape[1]):
            hit = which == label(fam.prefix, j)
            out[hit] = c[hit, j]
    out[buckled] = np.nan
    return out


def _prefix(text: str) -> str:
    """Family prefix of a guided mode's label ("" for a leaky or unknown one: no such mode)."""
    return "" if text.endswith("~") else label_family(text)


def unstable_reason(stack: Stack) -> str:
    """Why the prestressed stack has no modes ("" when every layer is stable).

    A layer is unstable when some bulk wave has rho v^2 <= 0 under its prestress (the acoustic
    tensor (C_ijkl + sigma_jl delta_ik) n_j n_l not positive definite for some direction n:
    :func:`surfwave.solvers.long_wave.long_wave_stable`), e.g. a film compressed beyond its
    shear modulus.
    """
    from surfwave.solvers.long_wave import long_wave_stable

    layers = [*stack.films, stack.substrate]
    sig = np.stack([lay.sigma for lay in layers]) / 1e9
    C = np.stack([lay.A for lay in layers]) / 1e9 - np.einsum("sjl,ik->sijkl", sig, np.eye(3))
    ok = long_wave_stable(C, sig)
    bad = [("substrate" if i == len(layers) - 1 else f"film {i} (from the top)") for i in np.flatnonzero(~ok)]
    if not bad:
        return ""
    return (f"no modes: {', '.join(bad)} unstable under its prestress (a bulk wave has rho v^2 <= 0 for some "
            "direction: the stressed state buckles)")


def family_limits(b: Blocks, fams: list[Family]) -> dict[str, float]:
    """Limiting speed (m/s) of each family of the substrate, by label prefix ("R", "L", "M")."""
    return {fam.prefix: float(np.sqrt(fam.X_limit * b.sA / b.rho[-1])) for fam in fams}


def mode_limits(labels: np.ndarray, limits: dict[str, float]) -> np.ndarray:
    """The limiting speed of each entry's family, shape of ``labels`` (m/s; NaN where no mode).

    A guided mode lies below its family's limit; with decoupled families (a mirror plane) the
    sagittal (R, S1, ...) and shear-horizontal (L0, ...) limits differ, and ``c_limit`` is the
    lower of them.
    """
    out = np.full(labels.shape, np.nan)
    for lab in set(labels.ravel().tolist()) - {""}:
        out[labels == lab] = limits.get(label_family(lab), np.nan)
    return out


def empty_result(kh: np.ndarray, c_limit: float, reason: str) -> dict:
    """A result with no mode at any kh (shape (n, 0) arrays), ``reason`` at every row."""
    shape = (kh.size, 0)
    nan = np.full(shape, np.nan)
    return {"c": nan, "mode": np.full(shape, "", dtype=object), "group_velocity": nan.copy(), "K2": nan.copy(),
            "c_limit": c_limit, "attenuation": nan.copy(), "kh": nan.copy(), "frequency": nan.copy(),
            "reason": np.full(kh.size, reason, dtype=object), "power_flow_angle": nan.copy(), "mode_limit": nan.copy()}


def k2_pair(electrical: str | Boundary) -> tuple[Boundary, bool]:
    """The other condition of the K^2 pair (free, metallized) and whether ``electrical`` is the free one.

    K^2 = 2 (c_free - c_metallized) / c_free needs both; the solved condition is one of them.
    """
    free = isinstance(as_boundary(electrical), Free)
    return (METALLIZED if free else FREE), free


def assemble(stack: Stack, kh: np.ndarray, electrical: str | Boundary, leaky: bool, modes: int | None = None) -> dict:
    """The result record for a resolved stack at kh (n,) (all NaN with the reason if a layer is unstable).

    ``modes``: at most that many columns per family (None: all).
    """
    if use_fast_path(stack, leaky):
        from surfwave.layers.isotropic_record import kh_record

        return kh_record(stack, kh, modes)
    why = unstable_reason(stack)
    if why:
        return empty_result(kh, np.nan, why)
    sol = solve_stack(stack, kh, electrical)
    fams, cs, vgs = sol["families"], sol["c"], sol["group_velocity"]
    k2s = [np.full(c.shape, np.nan) for c in cs]
    if stack.piezo:
        other, free = k2_pair(electrical)
        for f, fam in enumerate(fams):
            if fam.phi is None:
                k2s[f] = np.zeros(cs[f].shape)
                continue
            c2 = family_modes(sol["blocks"], fam, kh, electrical=other)
            n = min(c2.shape[1], cs[f].shape[1])
            cf, cm = (cs[f], c2) if free else (c2, cs[f])
            k2 = np.full(cs[f].shape, np.nan)
            k2[:, :n] = 2.0 * (cf[:, :n] - cm[:, :n]) / cf[:, :n]
            k2s[f] = k2
    att = [np.full(c.shape, np.nan) for c in cs]
    lk = [np.where(np.isfinite(c), 0.0, np.nan) for c in cs]
    if leaky:
        from surfwave.layers.leaky import leaky_continuation

        cs, vgs, k2s, att, lk = leaky_continuation(sol, kh, electrical, cs, vgs, k2s, att)
    if modes is not None:
        cs, vgs, k2s, att, lk = ([x[:, :modes] for x in arrs] for arrs in (cs, vgs, k2s, att, lk))
    pfs = [np.pad(p, ((0, 0), (0, max(c.shape[1] - p.shape[1], 0))), constant_values=np.nan)[:, :c.shape[1]]
           for p, c in zip(sol["power_flow_angle"], cs)]
    C, labels, (vg, K2, A, L, PF) = merge_families(fams, cs, [vgs, k2s, att, lk, pfs])
    labels = np.where(L == 1.0, labels + "~", labels).astype(object)
    H = stack.total_thickness
    khm = np.broadcast_to(kh[:, None], C.shape).copy()
    freq = C * khm / (2 * np.pi * H) if H > 0 else np.full(C.shape, np.nan)
    reason = np.where(np.isfinite(C).any(axis=1), "", REASON_NONE).astype(object)
    buckled = np.zeros(kh.size, dtype=bool)
    for fam in fams:
        buckled |= floor_unstable(sol["blocks"], fam, kh, electrical)
    if buckled.any():
        C[buckled] = np.nan
        for arr in (vg, K2, A, PF):
            arr[buckled] = np.nan
        labels[buckled] = ""
        reason[buckled] = REASON_BUCKLED
    return {"c": C, "mode": labels, "group_velocity": vg, "K2": K2, "c_limit": sol["c_limit"],
            "attenuation": A, "kh": khm, "frequency": freq, "reason": reason, "power_flow_angle": PF,
            "mode_limit": mode_limits(labels, family_limits(sol["blocks"], fams))}
