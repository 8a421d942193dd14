"""Which library files a stage depends on (rule inputs and cache code hashes)."""
from surfwave.data.provenance import module_closure


def test_module_closure_separates_stages():
    names = lambda *m: {p.rsplit("/", 1)[-1] for p in module_closure(*m)}  # noqa: E731
    crystal = names("model_crystals.symmetry", "data.cube")
    assert {"symmetry.py", "lattices.py", "potentials.py", "cube.py", "__init__.py"} <= crystal
    assert "rayleigh.py" not in crystal
    assert "rayleigh.py" in names("api")


def test_module_closure_skips_lazy_reexports(tmp_path):
    """A module-level __getattr__ that imports a module lazily (PEP 562 re-export) does not make
    that module a dependency; an import inside an ordinary function does."""
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "a.py").write_text(
        "def f():\n    from . import b\n\n"
        "def __getattr__(name):\n    from . import c\n    return getattr(c, name)\n")
    for m in ("b", "c"):
        (tmp_path / f"{m}.py").write_text("")
    got = {p.rsplit("/", 1)[-1] for p in module_closure("a", package_dir=tmp_path)}
    assert got == {"__init__.py", "a.py", "b.py"}


def test_shallow_module_counts_without_its_imports(tmp_path):
    """A dispatcher listed as shallow is a dependency itself, but the modules it imports
    lazily are not (its caller lists the ones an output needs); without ``shallow`` they are."""
    (tmp_path / "__init__.py").write_text("")
    (tmp_path / "scene.py").write_text("def draw():\n    from . import speeds, entropy\n")
    (tmp_path / "speeds.py").write_text("from . import labels\n")
    for m in ("entropy", "labels"):
        (tmp_path / f"{m}.py").write_text("")
    names = lambda *m, **kw: {p.rsplit("/", 1)[-1] for p in module_closure(*m, package_dir=tmp_path, **kw)}  # noqa: E731
    assert names("scene", "speeds", shallow=("scene",)) == {"__init__.py", "scene.py", "speeds.py", "labels.py"}
    assert "entropy.py" in names("scene", "speeds")


def test_figures_jobs_depend_on_the_plotting_code_they_use():
    """The per-scene figures rule lists exactly the modules its outputs need
    (surfwave.pipeline.targets.OUTPUT_NEEDS): Fig. 2 of an FCC scene does not rerun when the
    entropy plot changes, and the triangular scene's figures do."""
    from pathlib import Path

    from surfwave.pipeline.scenes import load_config, validate_config
    from surfwave.pipeline.targets import scene_output_inputs

    scenes = validate_config(load_config([Path(__file__).parents[2] / "config" / "config.yaml"]))
    for scene, wanted, unwanted in (("fig2", "plots/speeds.py", "plots/entropy.py"),
                                    ("entropy", "plots/entropy.py", "plots/speeds.py")):
        _, modules = scene_output_inputs(scenes, scene)
        files = module_closure(*modules, shallow=("plots.figure_set",))
        assert any(f.endswith(wanted) for f in files) and not any(f.endswith(unwanted) for f in files)
        assert any(f.endswith("plots/figure_set.py") for f in files)


def test_statement_search_finds_every_import_of_the_package():
    """Reference: ``ast.walk`` over the whole tree (every node), minus the module-level
    ``__getattr__``; the statement-only search must find the same import nodes in every
    source file of the package."""
    import ast

    from surfwave.data import provenance

    files = sorted(provenance.PACKAGE_DIR.rglob("*.py"))
    assert len(files) > 20
    for f in files:
        tree = ast.parse(f.read_text(), str(f))
        lazy = {id(n) for top in tree.body if isinstance(top, ast.FunctionDef)
                and top.name == "__getattr__" for n in ast.walk(top)}
        ref = {id(n) for n in ast.walk(tree) if isinstance(n, (ast.Import, ast.ImportFrom)) and id(n) not in lazy}
        assert {id(n) for n in provenance._import_statements(tree.body)} == ref, f
