# Layered scenes (`substrate:` with `films:`): every guided mode of films on a crystal substrate
# over orientations x film stresses x electrical x kh (surfwave.pipeline.layered_scenes.scene_cube,
# surfwave.layers.cube.dispersion_cube), written as results/<scene>/dispersion_layered.nc.
from surfwave.pipeline.layered_scenes import layered_job_params

LAYERED_SCENES = [n for n, s in SCENES.items() if s.get("kind") == "layered"]
#: The material databases a stack may name (films, piezoelectric, elastic crystals).
LAYERED_MATERIALS = [
    "src/surfwave/layers/films.yaml",
    PIEZO_MATERIALS,
    MATERIALS,
]


rule layered:
    """Every mode of a film stack: phase and group speed, K^2, leaky loss, against kh."""
    input:
        code=code("pipeline.layered_scenes", "layers.cube", "data.cube", "pipeline.stage"),
        materials=LAYERED_MATERIALS,
    output:
        "results/{scene}/dispersion_layered.nc",
    log:
        "results/{scene}/logs/dispersion_layered.log",
    wildcard_constraints:
        scene="|".join(re.escape(n) for n in LAYERED_SCENES) or "(?!x)x",
    conda:
        CONDA_ENV
    params:
        job=lambda wildcards: layered_job_params(SCENES[wildcards.scene]),
    script:
        "../scripts/layered.py"
