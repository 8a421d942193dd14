"""Which library source files a workflow stage runs: the rule inputs that make code changes
rerun exactly the affected jobs, and the code hash in parameter-cache keys.

Modules are named by their dotted path below the package (``"solvers.rayleigh"``,
``"data.cube"``). Imports are read statically with :mod:`ast`, so nothing is imported.

Examples
--------
>>> files = module_closure("solvers.rayleigh")
>>> [f.rsplit("surfwave/", 1)[1] for f in sorted(files)]  # doctest: +NORMALIZE_WHITESPACE
['__init__.py', 'errors.py', 'solvers/__init__.py', 'solvers/cubic.py', 'solvers/rayleigh.py',
 'validate.py', 'vocab.py']
"""
from __future__ import annotations

import ast
import functools
from pathlib import Path

#: The installed package's source folder (``src/surfwave``).
PACKAGE_DIR = Path(__file__).resolve().parents[1]


def _source(pkg: Path, name: str) -> Path | None:
    """File of module or package ``name`` (dotted) below ``pkg``, or None."""
    base = pkg.joinpath(*name.split("."))
    for path in (base.with_suffix(".py"), base / "__init__.py"):
        if path.is_file():
            return path
    return None


def module_closure(*modules: str, package_dir: str | Path | None = None,
                   shallow: tuple[str, ...] = ()) -> list[str]:
    """Source files of surfwave modules and of every surfwave module they import (transitively).

    Parameters
    ----------
    *modules : str
        Dotted module names below the package (``"solvers.rayleigh"``).
    package_dir : path, optional
        The package's source folder (default: this installation's).
    shallow : tuple of str
        Modules whose own file counts but whose imports are not followed: a dispatcher such
        as ``plots.figure_set``, which imports each plotting module only where an output needs
        it, and whose caller lists the modules its outputs need among ``modules``.

    Returns
    -------
    list of str
        Sorted file paths. Imports inside functions count, so a rule that lists
        ``module_closure("solvers.rayleigh")`` reruns when any code it runs changes. The
        package's ``__init__.py`` (the version) and the ``__init__.py`` of every subpackage
        on the way are included, but the top-level re-exports are not followed, nor the lazy
        re-exports of a module-level ``__getattr__``: they are conveniences for users, and each
        module imports what it needs explicitly (otherwise every stage would depend on every
        module). A listed module that does not exist is still returned, so Snakemake reports it
        as a missing input.
    """
    pkg = Path(package_dir or PACKAGE_DIR)
    todo, seen, files = list(modules), set(), {str(pkg / "__init__.py")}
    while todo:
        name = todo.pop()
        if name in seen:
            continue
        seen.add(name)
        parts = name.split(".")
        for i in range(1, len(parts)):  # parent packages' __init__ run on import
            init = pkg.joinpath(*parts[:i], "__init__.py")
            if init.is_file():
                files.add(str(init))
        path = _source(pkg, name)
        if path is None:
            if name in modules:
                files.add(str(pkg.joinpath(*parts).with_suffix(".py")))
            continue
        files.add(str(path))
        if name in shallow:
            continue
        todo += [m for m in _imported_modules(str(path), path.stat().st_mtime_ns, str(pkg))
                 if _source(pkg, m) is not None]
    return sorted(files)


@functools.lru_cache(maxsize=None)
def _imported_modules(path: str, mtime_ns: int, package_dir: str) -> tuple[str, ...]:
    """Dotted surfwave module names one source file imports (parsed once per file version).

    ``from surfwave.a import b`` yields both ``a`` and ``a.b`` (``b`` may be a module);
    names that are not modules are dropped by :func:`module_closure`.
    """
    tree = ast.parse(Path(path).read_text(), path)
    here = Path(path).resolve().relative_to(Path(package_dir).resolve()).parent.parts
    found: list[str] = []
    for node in _import_statements(tree.body):
        if isinstance(node, ast.ImportFrom):
            if node.level:  # relative: resolve against this file's package
                base = list(here[: len(here) - node.level + 1])
                mod = ".".join(base + ([node.module] if node.module else []))
            elif node.module and node.module.split(".")[0] == "surfwave":
                mod = node.module.partition(".")[2]
            else:
                continue
            if mod:
                found.append(mod)
            found += [f"{mod}.{a.name}" if mod else a.name for a in node.names]
        elif isinstance(node, ast.Import):
            found += [a.name.partition(".")[2] for a in node.names
                      if a.name.startswith("surfwave.")]
    return tuple(m for m in found if m and m != "__version__")


def _import_statements(body: list, top: bool = True):
    """Import statements in a statement list and the statement lists nested in it.

    Imports are statements, so only statement bodies are searched (not the expressions,
    most of the tree); the module-level ``__getattr__`` (lazy re-exports) is skipped.
    """
    for node in body:
        if isinstance(node, (ast.Import, ast.ImportFrom)):
            yield node
            continue
        if top and isinstance(node, ast.FunctionDef) and node.name == "__getattr__":
            continue
        for field in ("body", "orelse", "finalbody", "handlers", "cases"):
            inner = getattr(node, field, None)
            if isinstance(inner, list):
                yield from _import_statements(inner, top=False)
