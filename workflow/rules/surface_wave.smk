# Real crystals (scenes with `materials:`): the general surface-wave solver over materials x
# surfaces x angles [x loading x toec x stress], its figures and the acoustoelastic table
# (one job per figure kind: each job's start-up costs more than its work).
# CRYSTAL_TARGETS is what rule `all` builds (surfwave.pipeline.targets.crystal_targets).
from surfwave.pipeline.targets import crystal_targets

CRYSTAL_TARGETS = crystal_targets(SCENES, selected(config, SCENES))


rule surface_wave:
    """Surface-wave speed, limiting speed, wave type and polarisation of real crystals."""
    input:
        code=code("continuum.crystal_scene", "data.cube", "pipeline.stage"),
        materials=MATERIALS,
    output:
        "results/{scene}/surface_wave.nc",
    log:
        "results/{scene}/logs/surface_wave.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("surface_wave"),
    script:
        "../scripts/surface_wave.py"


rule figure_surface_wave_angles:
    """c_R and v_L against the propagation angle, one panel per surface (unstressed)."""
    input:
        cube="results/{scene}/surface_wave.nc",
        code=code("plots.surface_wave", "pipeline.stage"),
    output:
        report(
            "results/{scene}/surface_wave_angles.png",
            caption="../report/surface_wave_angles.rst",
            category="Real crystals",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_surface_wave_angles.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_surface_wave.py"


rule surface_wave_stress:
    """c_R against the applied stress per material and direction (every loading and model),
    and the table of acoustoelastic coefficients (1/c_R) dc_R/dsigma at zero stress."""
    input:
        cube="results/{scene}/surface_wave.nc",
        code=code("plots.surface_wave", "report.acoustoelastic", "pipeline.stage"),
    output:
        png=report(
            "results/{scene}/surface_wave_vs_stress.png",
            caption="../report/surface_wave_vs_stress.rst",
            category="Real crystals",
            subcategory="{scene}",
        ),
        md=report(
            "results/{scene}/acoustoelastic.md",
            caption="../report/acoustoelastic.rst",
            category="Real crystals",
            subcategory="{scene}",
        ),
        csv="results/{scene}/acoustoelastic.csv",
    log:
        "results/{scene}/logs/surface_wave_stress.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/surface_wave_stress.py"
