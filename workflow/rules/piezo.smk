# Piezoelectric scenes (`materials:` with `cuts:` or `euler:`): free and metallized SAW, K^2,
# leaky SAW and power flow over materials x cuts/Euler angles x electrical [x stress]
# (surfwave.real_crystals.piezo_sweep). They write the same cube name as the elastic
# real-crystal rule; the scene wildcard of this rule matches only piezoelectric scenes.
from surfwave.pipeline.piezo_scenes import piezo_job_params

PIEZO_SCENES = [n for n, s in SCENES.items() if s.get("kind") == "piezo"]
#: The piezoelectric database (piezoelectric scenes read it).
PIEZO_MATERIALS = "src/surfwave/real_crystals/piezoelectric.yaml"


ruleorder: piezo_wave > surface_wave


rule piezo_wave:
    """SAW speeds (free, metallized), K^2, leaky SAW, power flow of piezoelectric crystals."""
    input:
        code=code(
            "real_crystals.piezo_sweep",
            "real_crystals.piezo_wave",
            "solvers.leaky",
            "data.cube",
            "pipeline.stage",
        ),
        materials=PIEZO_MATERIALS,
    output:
        "results/{scene}/surface_wave.nc",
    log:
        "results/{scene}/logs/surface_wave.log",
    wildcard_constraints:
        scene="|".join(re.escape(n) for n in PIEZO_SCENES) or "(?!x)x",
    conda:
        CONDA_ENV
    params:
        job=lambda wildcards: piezo_job_params(SCENES[wildcards.scene]),
    script:
        "../scripts/piezo_wave.py"
