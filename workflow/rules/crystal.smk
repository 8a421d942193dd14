rule crystal:
    """Prestressed cells, spglib space groups and the mirror planes Eq. (17) assumes."""
    input:
        code=code("model_crystals.symmetry", "data.cube", "pipeline.stage"),
    output:
        "results/{scene}/crystal.nc",
    log:
        "results/{scene}/logs/crystal.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("crystal"),
    script:
        "../scripts/crystal.py"
