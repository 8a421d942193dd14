# Figures of the reproduction: Fig. 2 for every selected FCC scene with
# elastic and rayleigh cubes, Table I (paper beside ours) for the `table1` scene, and for
# triangular scenes the dispersion, theta_c, Fig. 3 (displacements) and entropy figures.
# FIGURE_TARGETS is what rule `all` builds.
from surfwave.pipeline.targets import figure_targets, speeds_scenes
from surfwave.continuum.potentials import available_potentials
from surfwave.data.paper import load_paper_values

#: The scene Table I is compared with (held in paper_values.yaml beside the table itself).
TABLE1_SCENE = load_paper_values()["table1"]["scene"]

FIGURE_TARGETS = [
    f"results/{name}/speeds_vs_stress.png"
    for name in speeds_scenes(SCENES, selected(config, SCENES))
]
if TABLE1_SCENE in speeds_scenes(SCENES, selected(config, SCENES)):
    FIGURE_TARGETS += [
        f"results/{TABLE1_SCENE}/table1.md",
        f"results/{TABLE1_SCENE}/table1.csv",
        f"results/{TABLE1_SCENE}/table1_diff.png",
    ]
FIGURE_TARGETS += figure_targets(SCENES, selected(config, SCENES))


wildcard_constraints:
    potential="|".join(available_potentials()),


rule figure_speeds:
    """Fig. 2: bulk sound speeds squared and c_R^2 versus stress, one panel per potential."""
    input:
        elastic="results/{scene}/elastic.nc",
        rayleigh="results/{scene}/rayleigh.nc",
        code=code("plots.speeds"),
    output:
        report(
            "results/{scene}/speeds_vs_stress.png",
            caption="../report/speeds_vs_stress.rst",
            category="Fig. 2: sound speeds versus stress",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_speeds.log",
    conda:
        CONDA_ENV
    params:
        lattice=lambda wildcards: SCENES[wildcards.scene]["lattice"],
        loading=lambda wildcards: SCENES[wildcards.scene]["loading"],
    script:
        "../scripts/figure_speeds.py"


rule figure_table1:
    """Table I: the paper's printed numbers beside ours (Markdown, CSV, difference plot)."""
    input:
        elastic=f"results/{TABLE1_SCENE}/elastic.nc",
        rayleigh=f"results/{TABLE1_SCENE}/rayleigh.nc",
        values=PAPER_VALUES,
        code=code("report.reproduction", "plots.speeds"),
    output:
        md=f"results/{TABLE1_SCENE}/table1.md",
        csv=f"results/{TABLE1_SCENE}/table1.csv",
        png=report(
            f"results/{TABLE1_SCENE}/table1_diff.png",
            caption="../report/table1_diff.rst",
            category="Table I",
        ),
    log:
        f"results/{TABLE1_SCENE}/logs/figure_table1.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_table1.py"


rule figure_dispersion:
    """Triangular surface-wave dispersion omega(theta) at several strains, one potential."""
    input:
        cube="results/{scene}/dispersion.nc",
        code=code("plots.dispersion", "data.cube"),
    output:
        report(
            "results/{scene}/dispersion_{potential}.png",
            caption="../report/dispersion.rst",
            category="Triangular lattice",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_dispersion_{potential}.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_dispersion.py"


rule figure_theta_c:
    """Crossover theta_c (q complex above it) versus d/d0, every potential."""
    input:
        cube="results/{scene}/dispersion.nc",
        code=code("plots.dispersion", "data.cube"),
    output:
        report(
            "results/{scene}/theta_c.png",
            caption="../report/theta_c.rst",
            category="Triangular lattice",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_theta_c.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_theta_c.py"


rule figure_displacements:
    """Fig. 3: surface-wave displacement patterns at zero stress, a few theta, one potential."""
    input:
        cube="results/{scene}/displacements.nc",
        code=code("plots.dispersion", "data.cube"),
    output:
        report(
            "results/{scene}/fig3_displacements_{potential}.png",
            caption="../report/fig3_displacements.rst",
            category="Triangular lattice",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_displacements_{potential}.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_displacements.py"


rule figure_entropy:
    """Surface entropy (Eq. 25 estimate and exact) versus strain."""
    input:
        cube="results/{scene}/entropy.nc",
        code=code("plots.entropy", "data.cube"),
    output:
        report(
            "results/{scene}/entropy_vs_strain.png",
            caption="../report/entropy_vs_strain.rst",
            category="Surface entropy",
            subcategory="{scene}",
        ),
    log:
        "results/{scene}/logs/figure_entropy.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/figure_entropy.py"


rule figure_stability_map:
    """Stability map of prestressed FCC, long-wave versus full-zone (phonopy); built by the
    benchmarks target, not by rule all (it computes its own grid)."""
    input:
        code=code("continuum.stability_map", "plots.stability", "data.cube"),
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
