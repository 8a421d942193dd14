# Real crystals (scenes with `materials:`): the general surface-wave solver over materials x
# surfaces x angles [x loading x toec x stress]. Its figures and the acoustoelastic table are
# drawn by the scene's figures job (figures.smk).


rule surface_wave:
    """Surface-wave speed, limiting speed, wave type and polarisation of real crystals."""
    input:
        code=code(
            "real_crystals.sweep",
            "real_crystals.materials",
            "data.cube",
            "pipeline.stage",
        ),
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
