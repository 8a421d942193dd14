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

from collections.abc import Mapping
from pathlib import Path


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

    done: set[str] = set()
    opened: dict = {}

    def cube(name):  # opened once, read variable by variable (large scenes stay small)
        if name not in opened:
            opened[name] = open_cube(cubes[name], load=False)
        return opened[name]

    if "speeds" in outputs:
        from surfwave.plots.speeds import LOADING_TITLES, fig2

        loading = LOADING_TITLES.get(spec["loading"], spec["loading"])
        fig2(cube("elastic"), cube("rayleigh"), outputs["speeds"],
             title=f"{spec['lattice'].upper()} (001) surface, {loading} (scene {scene})")
        done.add("speeds")
    if "table1_md" in outputs:
        from surfwave.plots.speeds import table1_figure
        from surfwave.report.reproduction import table1

        table1(cubes["elastic"], cubes["rayleigh"], outputs["table1_md"], outputs["table1_csv"],
               paper_values_path=paper_values)
        table1_figure(outputs["table1_csv"], outputs["table1_png"])
        done.update({"table1_md", "table1_csv", "table1_png"})
    dispersion, displacements = _suffixed(outputs, "dispersion"), _suffixed(outputs, "displacements")
    if dispersion or "theta_c" in outputs or displacements:
        from surfwave.plots.dispersion import plot_dispersion, plot_displacements, plot_theta_c
        from surfwave.plots.labels import potential_label
    for pot, path in dispersion.items():
        plot_dispersion(cube("dispersion").sel(potential=pot), path,
                        title=f"triangular lattice, {potential_label(pot)} (scene {scene})")
        done.add(f"dispersion_{pot}")
    if "theta_c" in outputs:
        ds = cube("dispersion")
        pots = [str(p) for p in ds["potential"].values]
        plot_theta_c([ds.sel(potential=p) for p in pots], outputs["theta_c"],
                     title=f"triangular lattice (scene {scene})", potential_labels=pots)
        done.add("theta_c")
    if displacements:
        from surfwave.plots.speeds import FIG3_ROWS, FIG3_THETA, nearest_indices

        ds = cube("displacements")
        ds = ds.isel(theta=nearest_indices(ds["theta"].values, FIG3_THETA), row=slice(0, FIG3_ROWS))
        for pot, path in displacements.items():
            plot_displacements(ds, path, potential=pot)
            done.add(f"displacements_{pot}")
    if "entropy" in outputs:
        from surfwave.plots.entropy import entropy_vs_strain

        entropy_vs_strain(cube("entropy"), outputs["entropy"],
                          title=f"surface entropy, triangular lattice (scene {scene})")
        done.add("entropy")
    if "surface_wave_angles" in outputs:
        from surfwave.plots.surface_wave import speeds_vs_angle

        speeds_vs_angle(cube("surface_wave"), outputs["surface_wave_angles"], title=f"scene {scene}")
        done.add("surface_wave_angles")
    if "surface_wave_vs_stress" in outputs:
        from surfwave.plots.surface_wave import speeds_vs_stress
        from surfwave.report.acoustoelastic import write_table

        speeds_vs_stress(cube("surface_wave"), outputs["surface_wave_vs_stress"], title=f"scene {scene}")
        write_table(cube("surface_wave"), outputs["acoustoelastic_md"], outputs["acoustoelastic_csv"])
        done.update({"surface_wave_vs_stress", "acoustoelastic_md", "acoustoelastic_csv"})
    if "piezo_angles" in outputs or "piezo_stress" in outputs:
        from surfwave.plots import piezo

        for key, draw in (("piezo_angles", piezo.speeds_vs_euler), ("piezo_stress", piezo.speeds_vs_stress)):
            if key in outputs:
                draw(cube("surface_wave"), outputs[key], title=f"scene {scene}")
                done.add(key)
    if any(k.startswith("layered_") for k in outputs):
        from surfwave.plots import layered

        for key, draw in (("layered_dispersion", layered.dispersion), ("layered_k2", layered.coupling),
                          ("layered_stress", layered.stress_shift)):
            if key in outputs:
                draw(cube("dispersion_layered"), outputs[key], title=f"scene {scene}")
                done.add(key)
    if "summary" in outputs:
        from surfwave.report.summary import write_summary

        write_summary(list(cubes.values()), outputs["summary"], scene)
        done.add("summary")
    for ds in opened.values():
        ds.close()
    unknown = set(outputs) - done
    if unknown:
        raise KeyError(f"draw_figure_set does not know how to write {sorted(unknown)}")
    return [Path(outputs[k]) for k in outputs]
