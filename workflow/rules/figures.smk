# Figures and tables: one job per scene draws all of them (surfwave.plots.figure_set.draw_figure_set),
# since each job's start-up (interpreter, xarray, matplotlib) costs more than a figure. What a
# scene gets follows from its cubes (surfwave.pipeline.targets.scene_outputs): Fig. 2 for FCC
# scenes, Table I beside the paper's numbers for the `table1` scene, the dispersion, theta_c,
# Fig. 3 and entropy figures for triangular scenes, the angle and stress figures and the
# acoustoelastic table for real crystals, and summary.md for every scene not the paper's.
# The rule `figures_<scene>` of each scene lists only the cubes and library modules its
# outputs need, so a change reruns it only where it can change what it draws.
# FIGURE_TARGETS is what rule `all` builds.
from surfwave.pipeline.targets import (
    figure_group,
    presentation_targets,
    scene_output_inputs,
    scene_outputs,
)

FIGURE_TARGETS = presentation_targets(SCENES, selected(config, SCENES))

for _scene in SCENES:
    _outputs = scene_outputs(SCENES, _scene)
    if not _outputs:
        continue
    _cubes, _modules = scene_output_inputs(SCENES, _scene)

    rule:
        """Every figure and table of the scene (surfwave.plots.figure_set.draw_figure_set)."""
        name:
            f"figures_{_scene}"
        input:
            **{k: f"results/{{scene}}/{f}" for k, f in _cubes.items()},
            values=PAPER_VALUES,
            code=code(*_modules, shallow=("plots.figure_set",)),
        output:
            **{
                k: report_output(k, f"results/{{scene}}/{f}", _scene)
                for k, f in _outputs.items()
            },
        log:
            "results/{scene}/logs/figures.log",
        wildcard_constraints:
            scene=re.escape(_scene),
        group:
            figure_group(_cubes)
        conda:
            CONDA_ENV
        params:
            spec={k: SCENES[_scene].get(k) for k in ("lattice", "loading")},
            cubes=list(_cubes),
        script:
            "../scripts/figures.py"


rule figure_stability_map:
    """Stability map of prestressed FCC, long-wave versus full-zone (phonopy); built by the
    benchmarks target, not by rule all (it computes its own grid)."""
    input:
        code=code("model_crystals.stability_map", "plots.stability", "data.cube"),
    output:
        nc="results/stability_map/stability_map.nc",
        png=report(
            "results/stability_map/stability_map.png",
            caption="../report/stability_map.rst",
            category="Stability",
        ),
    log:
        "results/stability_map/logs/stability_map.log",
    conda:
        CONDA_ENV
    threads: 1
    script:
        "../scripts/figure_stability_map.py"
