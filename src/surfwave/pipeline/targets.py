"""Which figures and report inputs a set of scenes allows (light: imported by the Snakefile).

Kept free of matplotlib and xarray so that parsing the workflow stays fast.
"""
from __future__ import annotations

from typing import Collection, Iterable

from surfwave.data.paper import load_paper_values
from surfwave.pipeline.scenes import CUBES

#: cubes the report's checks can read (bulk.nc feeds its own section, see report_inputs)
REPORT_CUBES = ("elastic", "rayleigh", "dispersion", "displacements", "entropy")
#: every cube the reproduction report reads (the quantities' file names: pipeline.scenes.CUBES)
CUBE_NAMES = (*REPORT_CUBES, "bulk")


def speeds_scenes(scenes: dict, names: Iterable[str]) -> list[str]:
    """Names (of ``names``) of the FCC scenes that make elastic and rayleigh cubes (Fig. 2)."""
    return [n for n in names if scenes[n].get("lattice") == "fcc" and scenes[n].get("angles") is None
            and {"elastic", "rayleigh"} <= set(scenes[n]["quantities"])]


#: What each output of a scene's figures job needs: (cubes read, library modules drawing it).
#: Output keys with a potential suffix (``dispersion_lj``) look up their prefix.
OUTPUT_NEEDS = {
    "speeds": (("elastic", "rayleigh"), ("plots.speeds",)),
    "table1": (("elastic", "rayleigh"), ("report.reproduction", "plots.speeds")),
    "dispersion": (("dispersion",), ("plots.dispersion",)),
    "theta_c": (("dispersion",), ("plots.dispersion",)),
    "displacements": (("displacements",), ("plots.dispersion", "plots.speeds")),
    "entropy": (("entropy",), ("plots.entropy",)),
    "surface_wave": (("surface_wave",), ("plots.surface_wave",)),
    "acoustoelastic": (("surface_wave",), ("report.acoustoelastic",)),
    "piezo_angles": (("surface_wave",), ("plots.piezo",)),
    "piezo_stress": (("surface_wave",), ("plots.piezo",)),
    "surface_phonons": (("surface_phonons",), ("plots.surface_phonons",)),
    "layered_dispersion": (("dispersion_layered",), ("plots.layered",)),
    "layered_k2": (("dispersion_layered",), ("plots.layered",)),
    "layered_stress": (("dispersion_layered",), ("plots.layered",)),
    "summary": ((), ("report.summary",)),  # reads every cube of the scene but crystal.nc
}


#: Report entry (caption file in workflow/report/, category) of each output kind (the key's
#: prefix) for `snakemake --report`; kinds not listed (tables, summary) get none.
REPORT_ENTRIES = {
    "speeds": ("speeds_vs_stress.rst", "Fig. 2: sound speeds versus stress"),
    "table1_png": ("table1_diff.rst", "Table I"),
    "dispersion": ("dispersion.rst", "Triangular lattice"),
    "theta_c": ("theta_c.rst", "Triangular lattice"),
    "displacements": ("fig3_displacements.rst", "Triangular lattice"),
    "entropy": ("entropy_vs_strain.rst", "Surface entropy"),
    "surface_wave_angles": ("surface_wave_angles.rst", "Real crystals"),
    "surface_wave_vs_stress": ("surface_wave_vs_stress.rst", "Real crystals"),
    "acoustoelastic_md": ("acoustoelastic.rst", "Real crystals"),
    "piezo_angles": ("piezo_vs_angle.rst", "Piezoelectric crystals"),
    "piezo_stress": ("piezo_vs_stress.rst", "Piezoelectric crystals"),
    "layered_dispersion": ("layered.rst", "Layered stacks"),
    "layered_k2": ("layered.rst", "Layered stacks"),
    "layered_stress": ("layered.rst", "Layered stacks"),
}
#: SLURM group of a scene's figures job (profiles/slurm names the groups of the cube rules):
#: the figures ride in the job of the first cube stage listed here that they read. Each of
#: these stages feeds only the figures job, so the group never has an outside job between
#: two of its members (which Snakemake refuses).
FIGURE_GROUPS = {
    "dispersion": "scene_dispersion",
    "entropy": "scene_entropy",
    "displacements": "scene_displacements",
    "bulk": "scene_bulk",
    "surface_wave": "scene_crystal",
    "dispersion_layered": "scene_layered",
}


def _kind(key: str, table: dict):
    return next((v for k, v in table.items() if key == k or key.startswith(f"{k}_")), None)


def report_entry(key: str) -> tuple[str, str] | None:
    """(caption file, category) of output ``key`` in the Snakemake report, or None."""
    return _kind(key, REPORT_ENTRIES)


def figure_group(cubes: Collection[str]) -> str:
    """SLURM group of a figures job that reads ``cubes`` (FIGURE_GROUPS, else the light chain)."""
    return next((g for q, g in FIGURE_GROUPS.items() if q in cubes), "scene_light")


def _need(key: str) -> tuple[tuple[str, ...], tuple[str, ...]]:
    need = _kind(key, OUTPUT_NEEDS)
    if need is None:
        raise KeyError(f"no entry for output {key!r} in OUTPUT_NEEDS")
    return need


def scene_outputs(scenes: dict, name: str) -> dict[str, str]:
    """Figures and tables of one scene (file names in ``results/<scene>/``), by output key.

    One job per scene draws them all (each job's start-up costs more than a figure). What a
    scene gets follows from its cubes: Fig. 2 (``speeds_vs_stress.png``) for FCC scenes with
    elastic and rayleigh cubes; Table I (Markdown, CSV, difference plot) for the scene named
    in ``paper_values.yaml``; ``dispersion_<potential>.png`` and ``theta_c.png`` from a
    dispersion cube; Fig. 3 (``fig3_displacements_<potential>.png``) from a displacements
    cube; ``entropy_vs_strain.png``; for real-crystal scenes ``surface_wave_angles.png``
    (three or more angles) and ``surface_wave_vs_stress.png`` + ``acoustoelastic.md/.csv``
    (two or more stresses; the table says so when the grid has no zero with a point on each
    side, which the central differences need); and ``summary.md`` for every scene that is
    not one of the paper's.

    Parameters
    ----------
    scenes : dict
        ``config["scenes"]`` after validation (defaults filled in).
    name : str
        The scene.

    Returns
    -------
    dict
        Output key (a Python identifier, e.g. ``dispersion_lj``) -> file name.
    """
    s = scenes[name]
    q, pots = set(s["quantities"]), s.get("potentials", [])
    out: dict[str, str] = {}
    if name in speeds_scenes(scenes, [name]):
        out["speeds"] = "speeds_vs_stress.png"
        if name == load_paper_values()["table1"]["scene"]:
            out.update(table1_md="table1.md", table1_csv="table1.csv", table1_png="table1_diff.png")
    if "dispersion" in q:
        out.update({f"dispersion_{p}": f"dispersion_{p}.png" for p in pots}, theta_c="theta_c.png")
    if "displacements" in q:
        out.update({f"displacements_{p}": f"fig3_displacements_{p}.png" for p in pots})
    if "entropy" in q:
        out["entropy"] = "entropy_vs_strain.png"
    if "surface_phonons" in q:
        out.update(surface_phonons_outputs(pots))
    if s.get("kind") == "crystal" and "surface_wave" in q:
        if len(s["angles"]) >= 3:
            out["surface_wave_angles"] = "surface_wave_angles.png"
        if len(s.get("stress") or []) >= 2:
            out.update(surface_wave_vs_stress="surface_wave_vs_stress.png",
                       acoustoelastic_md="acoustoelastic.md", acoustoelastic_csv="acoustoelastic.csv")
    if s.get("kind") == "piezo" and "surface_wave" in q:
        out.update(piezo_outputs(s))
    if s.get("kind") == "layered" and "dispersion_layered" in q:
        out.update(layered_outputs(s))
    if name not in paper_scenes():
        out["summary"] = "summary.md"
    return out


def surface_phonons_outputs(potentials) -> dict[str, str]:
    """Figures of a surface_phonons cube, per potential: dispersion over the bulk bands at
    three strains, the soft-mode map, the surface entropy against strain."""
    out = {}
    for p in potentials:
        out.update({f"surface_phonons_dispersion_{p}": f"surface_phonons_dispersion_{p}.png",
                    f"surface_phonons_soft_{p}": f"surface_phonons_soft_modes_{p}.png",
                    f"surface_phonons_entropy_{p}": f"surface_phonons_entropy_{p}.png"})
    return out


def piezo_outputs(s: dict) -> dict[str, str]:
    """Figures of a piezoelectric scene: ``piezo_vs_angle.png`` when an Euler angle is swept over three or
    more values, ``piezo_vs_stress.png`` with two or more stresses."""
    out = {}
    if s.get("euler") and max(len(v) for v in s["euler"].values()) >= 3:
        out["piezo_angles"] = "piezo_vs_angle.png"
    if len(s.get("stress") or []) >= 2:
        out["piezo_stress"] = "piezo_vs_stress.png"
    return out


def layered_outputs(s: dict) -> dict[str, str]:
    """Figures of a layered scene: ``dispersion_layered.png`` always, ``k2_layered.png`` for a
    piezoelectric stack, ``dispersion_layered_vs_stress.png`` with two or more film stresses."""
    out = {"layered_dispersion": "dispersion_layered.png"}
    if s.get("piezo"):
        out["layered_k2"] = "k2_layered.png"
    if len(s.get("film_stress") or []) >= 2:
        out["layered_stress"] = "dispersion_layered_vs_stress.png"
    return out


def scene_output_inputs(scenes: dict, name: str) -> tuple[dict[str, str], list[str]]:
    """Cubes (name -> file name in ``results/<scene>/``) and library modules (dotted) that
    the figures job of scene ``name`` reads: exactly what its outputs need (OUTPUT_NEEDS),
    so that a change reruns the job only where it can change an output."""
    keys = scene_outputs(scenes, name)
    # the summary reads every cube of the scene, in the scene's order
    cubes = {q: CUBES[q] for q in scenes[name]["quantities"]} if "summary" in keys else {}
    modules: list[str] = ["plots.figure_set", "pipeline.stage"]
    for key in keys:
        names, code = _need(key)
        cubes.update({c: CUBES[c] for c in names})
        modules += [m for m in code if m not in modules]
    return cubes, modules


def presentation_targets(scenes: dict, names: Iterable[str], results: str = "results") -> list[str]:
    """Every figure and table (``scene_outputs``) of the named scenes, as paths."""
    return [f"{results}/{n}/{f}" for n in names for f in scene_outputs(scenes, n).values()]


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
