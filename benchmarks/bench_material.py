"""Cost of ``surfwave.material`` against the bare solver it wraps, per direction.

``material()`` resolves its arguments and calls the one path
(:func:`surfwave.real_crystals.stressed_wave.surface_wave`: stressed state, traction check,
Born stability, the Stroh solve, bulk speeds, long-wave stability); the bare solver is
:func:`surfwave.solvers.stroh.surface_wave` on the same wave-propagation tensors A (Pa, lab
frame), built once outside the timing. Both run in the same process, alternating call by
call, so machine load hits both alike; the figure of merit is the ratio of the medians
(the target of issue 21 item 2: <= 1.5).

Cases: Cu (001) unstressed (the default call), Cu (001) at 0.2 GPa along the propagation
(fixed constants), and with third-order constants; each with 200 angles in one call and with
one angle per call.

Run: ``PYTHONPATH=src python benchmarks/bench_material.py [--repeats N]`` (one core:
``OMP_NUM_THREADS=1``). Prints one line per case and the worst ratio.
"""
from __future__ import annotations

import argparse
import time

import numpy as np

import surfwave
from surfwave.real_crystals.materials import get_material
from surfwave.real_crystals.toec import deformed_axes, stressed_state
from surfwave.solvers import stroh
from surfwave.solvers.orientation import lab_axes
from surfwave.solvers.tensors import rotate2, rotate4


def _tensors(angles, stress: float, use_toec: bool):
    """A (Pa) and rho of Cu (001) at these angles: the bare solver's input (built from the
    solvers and toec modules only, so the script also times the code before the one path)."""
    cu = get_material("Cu")
    R = lab_axes("(001)", angles).reshape(-1, 3, 3)
    sigma = stress * np.einsum("ai,aj->aij", R[:, 0], R[:, 0])
    st = stressed_state(cu.voigt, cu.toec_voigt if use_toec else None, sigma, cu.rho)
    lab = deformed_axes(st["F"], R)
    s_lab = rotate2(sigma, lab)
    s_lab[:, 1, :] = s_lab[:, :, 1] = 0.0
    A = stroh.wave_propagation_tensor(rotate4(st["C_star"], lab) * 1e9, s_lab * 1e9)
    return A, st["rho"]


def _time(f) -> float:
    t0 = time.perf_counter()
    f()
    return time.perf_counter() - t0


def bench(n_angles: int, stress: float, use_toec: bool, repeats: int) -> tuple[float, float, float, float]:
    """(material, bare) median and min seconds per direction."""
    angles = np.linspace(0.0, 45.0, n_angles) if n_angles > 1 else 10.0
    A, rho = _tensors(angles, stress, use_toec)
    if n_angles == 1:
        A, rho = A[0], rho[0]
    api = lambda: surfwave.material("Cu", angle=angles, stress=stress, toec=use_toec)  # noqa: E731
    bare = lambda: stroh.surface_wave(A, rho)  # noqa: E731
    np.testing.assert_allclose(api()["c_R"], bare()["c"], rtol=1e-12)   # the same answer
    t_api, t_bare = [], []
    for _ in range(repeats):   # alternating: load on the machine hits both alike
        t_api.append(_time(api))
        t_bare.append(_time(bare))
    return (np.median(t_api) / n_angles, np.median(t_bare) / n_angles,
            np.min(t_api) / n_angles, np.min(t_bare) / n_angles)


def main(argv=None) -> float:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=200)
    args = parser.parse_args(argv)
    worst = 0.0
    print(f"{'case':44s} {'material us/dir':>16s} {'bare us/dir':>12s} {'ratio median':>13s} {'ratio min':>10s}")
    for stress, use_toec in ((0.0, False), (0.2, False), (0.2, True)):
        for n in (200, 1):
            reps = max(3, args.repeats // 20) if n > 1 else args.repeats
            m_med, b_med, m_min, b_min = bench(n, stress, use_toec, reps)
            case = f"Cu (001), {n} angle(s)/call, {stress} GPa{' TOEC' if use_toec else ''}"
            print(f"{case:44s} {m_med * 1e6:16.1f} {b_med * 1e6:12.1f} {m_med / b_med:13.2f} {m_min / b_min:10.2f}")
            worst = max(worst, m_med / b_med)
    print(f"worst ratio (medians): {worst:.2f}  (target <= 1.5)")
    return worst


if __name__ == "__main__":
    main()
