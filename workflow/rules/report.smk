# The reproduction report: every printed number of the paper beside ours, and each claim
# tested against the cubes (surfwave.report.reproduction). Reads only the cubes the selected scenes make;
# missing ones are reported as "not computed". REPORT_TARGETS is what rule `all` builds:
# nothing when the selected scenes make no cube the report reads (a user's own scene alone
# leaves the reproduction report of the default scenes as it is).
from surfwave.pipeline.targets import report_inputs

REPORT_INPUTS = report_inputs({name: SCENES[name] for name in selected(config, SCENES)})
REPORT_TARGETS = ["results/report.md"] if REPORT_INPUTS else []


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
