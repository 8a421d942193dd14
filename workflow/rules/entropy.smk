rule entropy:
    """Surface entropy of the triangular lattice: Eq. (25) estimate and exact (cached per point)."""
    input:
        crystal="results/{scene}/crystal.nc",
        code=code("dynamics.entropy", "data.cache", "data.cube", "pipeline.stage"),
    output:
        "results/{scene}/entropy.nc",
    log:
        "results/{scene}/logs/entropy.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("entropy"),
        cache=str(cache.DEFAULT_ROOT),
    script:
        "../scripts/entropy.py"
