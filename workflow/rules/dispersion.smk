rule dispersion:
    """Triangular surface-wave dispersion, analytic, checked by lattice dynamics (cached per point)."""
    input:
        crystal="results/{scene}/crystal.nc",
        code=code(
            "dynamics.dispersion",
            "dynamics.triangular_surface",
            "data.cache",
            "data.cube",
            "pipeline.stage",
        ),
    output:
        "results/{scene}/dispersion.nc",
    log:
        "results/{scene}/logs/dispersion.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("dispersion"),
        cache=str(cache.DEFAULT_ROOT),
    script:
        "../scripts/dispersion.py"


rule displacements:
    """Row displacement amplitudes u, v of the triangular surface wave (Fig. 3)."""
    input:
        crystal="results/{scene}/crystal.nc",
        code=code("dynamics.dispersion", "data.cube", "pipeline.stage"),
    output:
        "results/{scene}/displacements.nc",
    log:
        "results/{scene}/logs/displacements.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("displacements"),
    script:
        "../scripts/displacements.py"
