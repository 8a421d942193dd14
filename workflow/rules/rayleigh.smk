rule rayleigh:
    """Rayleigh speed c_R^2 from Eq. (17) with root selection, and the wave type."""
    input:
        elastic="results/{scene}/elastic.nc",
        code=lambda wildcards: code(
            "solvers.rayleigh",
            "data.cube",
            "pipeline.stage",
            *(
                ["model_crystals.fcc_angles"]
                if SCENES[wildcards.scene].get("angles")
                else []
            ),
        ),
    output:
        "results/{scene}/rayleigh.nc",
    log:
        "results/{scene}/logs/rayleigh.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("rayleigh"),
    script:
        "../scripts/rayleigh.py"
