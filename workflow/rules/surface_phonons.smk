rule surface_phonons:
    """Semi-infinite FCC surface phonons, soft surface modes and exact surface entropy."""
    input:
        crystal="results/{scene}/crystal.nc",
        code=code("pipeline.surface_phonons_cube", "data.cube", "pipeline.stage"),
    output:
        "results/{scene}/surface_phonons.nc",
    log:
        "results/{scene}/logs/surface_phonons.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("surface_phonons"),
    script:
        "../scripts/surface_phonons.py"
