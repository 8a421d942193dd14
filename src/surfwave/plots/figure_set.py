"""Every figure and table of one scene, drawn in one process (the workflow's figures job).

What a scene gets, and which cubes and modules each output needs, is decided in
:mod:`surfwave.pipeline.targets` (``scene_outputs``); this module only draws. The plotting
modules are imported where an output needs them, so a job pays only for what it draws.

Examples
--------
>>> draw_figure_set({"theta_c": "results/triangular/theta_c.png"},
...            {"dispersion": "results/triangular/dispersion.nc"},
...            "triangular", {"lattice": "triangular", "loading": "uniaxial"})  # doctest: +SKIP
"""
from __future__ import annotations

from collections.abc import Callable, Mapping
from pathlib import Path
from typing import Any, NamedTuple


def _suffixed(outputs: Mapping[str, str], prefix: str) -> dict[str, str]:
    """``{potential: path}`` of the outputs named ``<prefix>_<potential>``."""
    return {k[len(prefix) + 1:]: v for k, v in outputs.items() if k.startswith(prefix + "_")}


def draw_figure_set(outputs: Mapping[str, str], cubes: Mapping[str, str], scene: str, spec: Mapping,
               paper_values: str | Path | None = None) -> list[Path]:
    """Write every output of a scene's figures job.

    Parameters
    ----------
    outputs : mapping
        Output key -> path, keys as :func:`surfwave.pipeline.targets.scene_outputs` names
        them (``speeds``, ``table1_md``/``_csv``/``_png``, ``dispersion_<potential>``,
        ``theta_c``, ``displacements_<potential>``, ``entropy``, ``surface_wave_angles``,
        ``surface_wave_vs_stress``, ``acoustoelastic_md``/``_csv``, ``layered_dispersion``,
        ``layered_k2``, ``layered_stress``, ``summary``).
    cubes : mapping
        Cube name (``elastic``, ``dispersion``, ...) -> path of the scene's cube.
    scene : str
        Scene name (titles, summary).
    spec : mapping
        The scene's config (``lattice``, ``loading`` are used in titles).
    paper_values : path, optional
        ``paper_values.yaml`` (Table I).

    Returns
    -------
    list of Path
        The files written, in the order of ``outputs``.

    Raises
    ------
    KeyError
        For an output key this function does not know (a new output kind must be drawn here).
    """
    from surfwave.data.cube import open_cube

    opened: dict[str, Any] = {}

    def cube(name: str) -> Any:  # opened once, read variable by variable (large scenes stay small)
        if name not in opened:
            opened[name] = open_cube(cubes[name], load=False)
        return opened[name]

    job = _Job(outputs, cubes, cube, scene, spec, paper_values)
    done: set[str] = set()
    for draw in _DRAWERS:
        done |= draw(job)
    for ds in opened.values():
        ds.close()
    unknown = set(outputs) - done
    if unknown:
        raise KeyError(f"draw_figure_set does not know how to write {sorted(unknown)}")
    return [Path(outputs[k]) for k in outputs]


class _Job(NamedTuple):
    """What every drawer of :func:`draw_figure_set` reads: its arguments and the cube opener."""

    outputs: Mapping[str, str]
    cubes: Mapping[str, str]
    cube: Callable[[str], Any]      # cube name -> the opened (lazily loaded) Dataset
    scene: str
    spec: Mapping
    paper_values: str | Path | None


def _speeds(job: _Job) -> set[str]:
    """Fig. 2 (``speeds``): squared speeds against strain of an FCC lattice scene."""
    if "speeds" not in job.outputs:
        return set()
    from surfwave.plots.speeds import LOADING_TITLES, fig2

    loading = LOADING_TITLES.get(job.spec["loading"], job.spec["loading"])
    fig2(job.cube("elastic"), job.cube("rayleigh"), job.outputs["speeds"],
         title=f"{job.spec['lattice'].upper()} (001) surface, {loading} (scene {job.scene})")
    return {"speeds"}


def _table1(job: _Job) -> set[str]:
    """Table I as Markdown, CSV and PNG (``table1_md``, ``table1_csv``, ``table1_png``)."""
    if "table1_md" not in job.outputs:
        return set()
    from surfwave.plots.speeds import table1_figure
    from surfwave.report.reproduction import table1

    out = job.outputs
    table1(job.cubes["elastic"], job.cubes["rayleigh"], out["table1_md"], out["table1_csv"],
           paper_values_path=job.paper_values)
    table1_figure(out["table1_csv"], out["table1_png"])
    return {"table1_md", "table1_csv", "table1_png"}


def _dispersion(job: _Job) -> set[str]:
    """Triangular-lattice dispersion per potential (``dispersion_<potential>``), the critical
    angles (``theta_c``) and the displacements per potential (``displacements_<potential>``)."""
    outputs, scene = job.outputs, job.scene
    dispersion, displacements = _suffixed(outputs, "dispersion"), _suffixed(outputs, "displacements")
    if not (dispersion or "theta_c" in outputs or displacements):
        return set()
    from surfwave.plots.dispersion import plot_dispersion, plot_displacements, plot_theta_c
    from surfwave.plots.labels import potential_label

    done = set()
    for pot, path in dispersion.items():
        plot_dispersion(job.cube("dispersion").sel(potential=pot), path,
                        title=f"triangular lattice, {potential_label(pot)} (scene {scene})")
        done.add(f"dispersion_{pot}")
    if "theta_c" in outputs:
        ds = job.cube("dispersion")
        pots = [str(p) for p in ds["potential"].values]
        plot_theta_c([ds.sel(potential=p) for p in pots], outputs["theta_c"],
                     title=f"triangular lattice (scene {scene})", potential_labels=pots)
        done.add("theta_c")
    if displacements:
        from surfwave.plots.speeds import FIG3_ROWS, FIG3_THETA, nearest_indices

        ds = job.cube("displacements")
        ds = ds.isel(theta=nearest_indices(ds["theta"].values, FIG3_THETA), row=slice(0, FIG3_ROWS))
        for pot, path in displacements.items():
            plot_displacements(ds, path, potential=pot)
            done.add(f"displacements_{pot}")
    return done


def _entropy(job: _Job) -> set[str]:
    """Surface entropy against strain (``entropy``)."""
    if "entropy" not in job.outputs:
        return set()
    from surfwave.plots.entropy import entropy_vs_strain

    entropy_vs_strain(job.cube("entropy"), job.outputs["entropy"],
                      title=f"surface entropy, triangular lattice (scene {job.scene})")
    return {"entropy"}


def _surface_phonons(job: _Job) -> set[str]:
    """FCC surface phonons: dispersion, soft-mode map and entropy per potential
    (``surface_phonons_*``, :func:`surfwave.pipeline.targets.surface_phonons_outputs`)."""
    phonon_figs = {k: v for k, v in job.outputs.items() if k.startswith("surface_phonons_")}
    if not phonon_figs:
        return set()
    from surfwave.plots.surface_phonons import draw_all

    return set(draw_all(job.cube("surface_phonons"), phonon_figs, job.scene))


def _real_crystals(job: _Job) -> set[str]:
    """Real-crystal speeds against angle (``surface_wave_angles``) and against stress
    (``surface_wave_vs_stress``) with the acoustoelastic table (``acoustoelastic_md``/``_csv``)."""
    outputs, title = job.outputs, f"scene {job.scene}"
    done = set()
    if "surface_wave_angles" in outputs:
        from surfwave.plots.surface_wave import speeds_vs_angle

        speeds_vs_angle(job.cube("surface_wave"), outputs["surface_wave_angles"], title=title)
        done.add("surface_wave_angles")
    if "surface_wave_vs_stress" in outputs:
        from surfwave.plots.surface_wave import speeds_vs_stress
        from surfwave.report.acoustoelastic import write_table

        speeds_vs_stress(job.cube("surface_wave"), outputs["surface_wave_vs_stress"], title=title)
        write_table(job.cube("surface_wave"), outputs["acoustoelastic_md"], outputs["acoustoelastic_csv"])
        done.update({"surface_wave_vs_stress", "acoustoelastic_md", "acoustoelastic_csv"})
    return done


def _piezo(job: _Job) -> set[str]:
    """Piezoelectric crystals: speeds and K^2 against Euler angle (``piezo_angles``) and stress
    (``piezo_stress``)."""
    if "piezo_angles" not in job.outputs and "piezo_stress" not in job.outputs:
        return set()
    from surfwave.plots import piezo

    done = set()
    for key, draw in (("piezo_angles", piezo.speeds_vs_euler), ("piezo_stress", piezo.speeds_vs_stress)):
        if key in job.outputs:
            draw(job.cube("surface_wave"), job.outputs[key], title=f"scene {job.scene}")
            done.add(key)
    return done


def _layered(job: _Job) -> set[str]:
    """Layered stacks: dispersion (``layered_dispersion``), K^2 against kh (``layered_k2``) and
    the film-stress shift (``layered_stress``)."""
    if not any(k.startswith("layered_") for k in job.outputs):
        return set()
    from surfwave.plots import layered

    done = set()
    for key, draw in (("layered_dispersion", layered.dispersion), ("layered_k2", layered.coupling),
                      ("layered_stress", layered.stress_shift)):
        if key in job.outputs:
            draw(job.cube("dispersion_layered"), job.outputs[key], title=f"scene {job.scene}")
            done.add(key)
    return done


def _summary(job: _Job) -> set[str]:
    """The scene's summary page (``summary``) over all its cubes."""
    if "summary" not in job.outputs:
        return set()
    from surfwave.report.summary import write_summary

    write_summary(list(job.cubes.values()), job.outputs["summary"], job.scene)
    return {"summary"}


#: The drawers, in the order the outputs are written (the summary last).
_DRAWERS: tuple[Callable[[_Job], set[str]], ...] = (_speeds, _table1, _dispersion, _entropy, _surface_phonons,
                                                    _real_crystals, _piezo, _layered, _summary)
