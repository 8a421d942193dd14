# Speed/accuracy benchmarks: `snakemake -j2 benchmarks` (or `make bench`). Each
# benchmarks/bench_<name>.py that exists runs on one core into results/benchmarks/<name>/
# (a cube and a PNG); bench_workflow times the full reproduction and the no-op rerun,
# bench_large_scene a 20000-strain user scene; both take both cores. README_table.md
# collects them for the README.
from pathlib import Path

# benchmark -> library modules it exercises (inputs, so a code change reruns it)
BENCH_MODULES = {
    "rayleigh": ("api", "solvers.rayleigh", "report.benchmarks"),
    "stroh": ("solvers.stroh", "solvers.impedance", "solvers.rayleigh"),
    "piezo": (
        "solvers.piezo",
        "solvers.piezo_search",
        "solvers.stroh",
        "real_crystals.piezo_materials",
    ),
    "leaky": ("solvers.leaky", "solvers.stroh", "real_crystals.piezo_materials"),
    "point": (
        "api",
        "model_crystals.elastic",
        "solvers.long_wave",
        "model_crystals.lattices",
    ),
    "phonons": ("model_crystals.phonons",),
    "dispersion": ("dynamics.dispersion", "dynamics.triangular_surface"),
    "entropy": ("dynamics.entropy",),
    "toec": (
        "real_crystals.acoustoelastic",
        "real_crystals.toec",
        "real_crystals.materials",
    ),
    "material": (
        "api",
        "real_crystals.stressed_wave",
        "real_crystals.toec",
        "real_crystals.materials",
        "solvers.stroh",
    ),
    "fit": (
        "metrology.fit",
        "metrology.love",
        "metrology.film",
        "metrology.layered_model",
        "layers.sensitivity",
        "layers.solve",
        "api",
        "solvers.stroh",
    ),
    "layered": (
        "layers.solve",
        "layers.modes",
        "layers.partial",
        "layers.recursion",
        "layers.fields",
        "layers.stack",
        "layers.films",
        "layers.frequency",
        "layers.isotropic",
        "layers.isotropic_scan",
        "layers.isotropic_modes",
        "layers.isotropic_deriv",
        "layers.isotropic_record",
    ),
    "surface_phonons": (
        "dynamics.fcc_surface_phonons",
        "dynamics.fcc_surface_green",
        "dynamics.fcc_surface_entropy",
        "dynamics.fcc_layers",
        "dynamics.fcc_surface",
    ),
}
BENCH_METHODS = [
    name
    for name in BENCH_MODULES
    if Path(workflow.basedir, "benchmarks", f"bench_{name}.py").exists()
]
BENCH_DIRS = [f"results/benchmarks/{name}" for name in BENCH_METHODS]
if Path(workflow.basedir, "benchmarks", "bench_workflow.py").exists():
    BENCH_DIRS.append("results/benchmarks/workflow")
if Path(workflow.basedir, "benchmarks", "bench_large_scene.py").exists():
    BENCH_DIRS.append("results/benchmarks/large_scene")

#: Everything a whole-workflow run executes: a change anywhere reruns the workflow benchmarks.
WORKFLOW_FILES = sorted(
    str(p)
    for pattern in (
        "src/surfwave/**/*.py",
        "workflow/rules/*.smk",
        "workflow/scripts/*.py",
    )
    for p in Path(workflow.basedir).glob(pattern)
) + [str(Path(workflow.basedir, f)) for f in ("Snakefile", "config/config.yaml")]


wildcard_constraints:
    bench="|".join(BENCH_MODULES),


rule benchmarks:
    """Every benchmark, the README table and the (phonopy) stability map."""
    input:
        BENCH_DIRS,
        "results/benchmarks/README_table.md",
        "results/stability_map/stability_map.png",


rule benchmark_method:
    """One method's speed/accuracy sweep (one core, BLAS threads pinned to 1)."""
    input:
        script="benchmarks/bench_{bench}.py",
        code=lambda wildcards: code(*BENCH_MODULES[wildcards.bench]),
    output:
        directory("results/benchmarks/{bench}"),
    log:
        "results/benchmarks/logs/{bench}.log",
    conda:
        CONDA_ENV
    threads: 1
    script:
        "../scripts/benchmark_run.py"


rule benchmark_workflow:
    """Wall time of the full reproduction (empty results, -j2) and of the no-op rerun."""
    input:
        script="benchmarks/bench_workflow.py",
        code=WORKFLOW_FILES,
    output:
        directory("results/benchmarks/workflow"),
    log:
        "results/benchmarks/logs/workflow.log",
    conda:
        CONDA_ENV
    threads: 2
    script:
        "../scripts/benchmark_run.py"


rule benchmark_large_scene:
    """Wall time and peak memory of a 20000-strain user scene (-j2, 3 clean runs + no-op)."""
    input:
        script="benchmarks/bench_large_scene.py",
        scene="benchmarks/large_scene.yaml",
        code=WORKFLOW_FILES,
    output:
        directory("results/benchmarks/large_scene"),
    log:
        "results/benchmarks/logs/large_scene.log",
    conda:
        CONDA_ENV
    threads: 2
    script:
        "../scripts/benchmark_run.py"


rule benchmark_table:
    """Markdown table (method, knob, error, time, default and why) for the README."""
    input:
        dirs=BENCH_DIRS,
        code=code("report.benchmarks"),
    output:
        report(
            "results/benchmarks/README_table.md",
            caption="../report/benchmark_table.rst",
            category="Benchmarks",
        ),
    log:
        "results/benchmarks/logs/README_table.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/benchmark_table.py"
