rule elastic:
    """Stress, C, S, bulk sound speeds and long-wave stability (analytic)."""
    input:
        crystal="results/{scene}/crystal.nc",
        code=lambda wildcards: code(
            "model_crystals.elastic",
            "data.cube",
            "pipeline.stage",
            *(
                ["model_crystals.fcc_angles"]
                if SCENES[wildcards.scene].get("angles")
                else []
            ),
        ),
    output:
        "results/{scene}/elastic.nc",
    log:
        "results/{scene}/logs/elastic.log",
    conda:
        CONDA_ENV
    params:
        job=params_for("elastic"),
    script:
        "../scripts/elastic.py"
