"""Which figures and report inputs a set of scenes allows (light: imported by the Snakefile).

Kept free of matplotlib and xarray so that parsing the workflow stays fast.
"""
from __future__ import annotations

from surfwave.data.paper import load_paper_values

#: cubes the report's checks can read (bulk.nc feeds its own section, see report_inputs)
REPORT_CUBES = ("elastic", "rayleigh", "dispersion", "displacements", "entropy")
#: every cube the reproduction report reads (the quantities' file names: pipeline.scenes.CUBES)
CUBE_NAMES = (*REPORT_CUBES, "bulk")


def speeds_scenes(scenes: dict, names) -> list[str]:
    """Names (of ``names``) of the FCC scenes that make elastic and rayleigh cubes (Fig. 2)."""
    return [n for n in names if scenes[n].get("lattice") == "fcc" and scenes[n].get("angles") is None
            and {"elastic", "rayleigh"} <= set(scenes[n]["quantities"])]


def figure_targets(scenes: dict, names, results: str = "results") -> list[str]:
    """PNGs of the triangular-lattice figures the named scenes' cubes allow.

    dispersion -> dispersion_<potential>.png and theta_c.png; displacements ->
    fig3_displacements_<potential>.png; entropy -> entropy_vs_strain.png.
    """
    out = []
    for n in names:
        q, pots = set(scenes[n]["quantities"]), scenes[n].get("potentials", [])
        if "dispersion" in q:
            out += [f"{results}/{n}/dispersion_{p}.png" for p in pots] + [f"{results}/{n}/theta_c.png"]
        if "displacements" in q:
            out += [f"{results}/{n}/fig3_displacements_{p}.png" for p in pots]
        if "entropy" in q:
            out.append(f"{results}/{n}/entropy_vs_strain.png")
    return out


def crystal_targets(scenes: dict, names, results: str = "results") -> list[str]:
    """Figures and tables of the named real-crystal scenes (``materials:`` scenes).

    ``surface_wave_angles.png`` when a scene has three or more angles;
    ``surface_wave_vs_stress.png``, ``acoustoelastic.md`` and ``.csv`` (one job) when it has
    two or more stresses (the table says so when the grid has no zero with a point on
    each side, which the central differences need).
    """
    out = []
    for n in names:
        s = scenes[n]
        if s.get("kind") != "crystal" or "surface_wave" not in s["quantities"]:
            continue
        if len(s["angles"]) >= 3:
            out.append(f"{results}/{n}/surface_wave_angles.png")
        stress = s.get("stress") or []
        if len(stress) >= 2:
            out += [f"{results}/{n}/{f}" for f in ("surface_wave_vs_stress.png", "acoustoelastic.md",
                                                   "acoustoelastic.csv")]
    return out


def paper_scenes() -> list[str]:
    """The scenes the paper's reproduction report reads (named in ``paper_values.yaml``)."""
    pv = load_paper_values()
    names = [pv["table1"]["scene"]]
    for group in ("values", "claims"):
        for spec in pv[group].values():
            names += [s for s in (spec.get("scene"), spec.get("reference_scene")) if s]
    return list(dict.fromkeys(names))


def report_inputs(scenes: dict, results: str = "results") -> list[str]:
    """The cubes of the paper's scenes that the reproduction report reads.

    Only the scenes named in ``paper_values.yaml`` count: a user's own scene never feeds
    ``results/report.md`` (it gets ``results/<scene>/summary.md``), so running it leaves
    the reproduction report, and Snakemake's view of it, untouched.

    Parameters
    ----------
    scenes : dict
        ``config["scenes"]``: scene name -> {"quantities": [...], ...}.
    """
    pv = load_paper_values()
    wanted = {pv["table1"]["scene"]: {"elastic", "rayleigh"}}
    for group in ("values", "claims"):
        for spec in pv[group].values():
            for scene in (spec.get("scene"), spec.get("reference_scene")):
                if scene:
                    wanted.setdefault(scene, set()).update(REPORT_CUBES)
    for scene in list(wanted):  # the bulk section: phonopy against elastic.nc
        if "bulk" in scenes.get(scene, {}).get("quantities", []):
            wanted[scene].update({"bulk", "elastic"})
    out = []
    for scene, cubes in wanted.items():
        have = set(scenes.get(scene, {}).get("quantities", []))
        out += [f"{results}/{scene}/{c}.nc" for c in CUBE_NAMES if c in cubes and c in have]
    return sorted(set(out))


def summary_targets(scenes: dict, names, results: str = "results") -> list[str]:
    """``results/<scene>/summary.md`` for each named scene that is not one of the paper's."""
    paper = set(paper_scenes())
    return [f"{results}/{n}/summary.md" for n in names if n not in paper]
