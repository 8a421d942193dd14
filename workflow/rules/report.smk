# The reproduction report: every printed number of the paper beside ours, and each claim
# tested against the cubes (surfwave.report.reproduction). It reads the paper's scenes only
# (named in paper_values.yaml), whatever `run` selects, so a user's own scene never rewrites
# it; missing cubes are reported as "not computed". A user scene gets its own
# results/<scene>/summary.md (from its figures job). REPORT_TARGETS is what rule `all` builds.
from surfwave.pipeline.targets import paper_scenes, report_inputs

REPORT_INPUTS = report_inputs(SCENES)
REPORT_TARGETS = []
if REPORT_INPUTS and set(paper_scenes()) & set(selected(config, SCENES)):
    REPORT_TARGETS.append("results/report.md")


rule report_md:
    """results/report.md from the cubes and src/surfwave/data/paper_values.yaml."""
    input:
        cubes=REPORT_INPUTS,
        values=PAPER_VALUES,
        code=code("report.reproduction"),
    output:
        report(
            "results/report.md",
            caption="../report/report_md.rst",
            category="Reproduction report",
        ),
    log:
        "results/logs/report.log",
    conda:
        CONDA_ENV
    script:
        "../scripts/report.py"
