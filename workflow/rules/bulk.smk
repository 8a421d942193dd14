rule bulk:
    """phonopy sound speeds and full-zone stability, compared with elastic.nc (cached per point)."""
    input:
        crystal="results/{scene}/crystal.nc",
        elastic="results/{scene}/elastic.nc",
        code=code(
            "model_crystals.phonons",
            "model_crystals.sanity",
            "data.cache",
            "data.cube",
            "pipeline.stage",
        ),
    output:
        "results/{scene}/bulk.nc",
    log:
        "results/{scene}/logs/bulk.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("bulk"),
        cache=str(cache.DEFAULT_ROOT),
    script:
        "../scripts/bulk.py"
