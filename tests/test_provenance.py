"""Which library files a stage depends on (rule inputs and cache code hashes)."""
from surfwave.data.provenance import module_closure


def test_module_closure_separates_stages():
    names = lambda *m: {p.rsplit("/", 1)[-1] for p in module_closure(*m)}  # noqa: E731
    crystal = names("continuum.symmetry", "data.cube")
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
