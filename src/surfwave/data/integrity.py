"""Damaged result files: detect them before any job reads them (light: no xarray).

A cube that was cut short (disk full, copied halfway, killed outside the atomic write)
would otherwise make every later figure or report job fail with an HDF5 traceback. The
workflow calls :func:`set_aside_damaged` while it parses: each damaged cube is renamed to
``<name>.damaged`` (kept for inspection), so that Snakemake sees it missing and rebuilds it
together with everything downstream.
"""
from __future__ import annotations

import os
from pathlib import Path
from typing import Iterable


def check_readable(path: str | Path) -> str | None:
    """Why ``path`` is not a readable netCDF-4/HDF5 file, or None when it is.

    h5py refuses files without the HDF5 signature and truncated files (the superblock
    records the end-of-file address, which must not lie beyond the file's size); walking
    the object tree reads every group and variable header.
    """
    import h5py

    try:
        with h5py.File(path, "r") as fh:
            fh.visit(lambda name: None)
    except (OSError, ValueError, RuntimeError, KeyError) as exc:
        text = str(exc).splitlines()[0] if str(exc) else type(exc).__name__
        return text
    return None


def rebuild_hint(path: str | Path) -> str:
    """The command that rebuilds a workflow output from scratch."""
    return f"rm {path} && snakemake -j2 {path}"


def set_aside_damaged(paths: Iterable[str | Path]) -> list[str]:
    """Rename every damaged file among ``paths`` to ``<file>.damaged``.

    Parameters
    ----------
    paths : iterable of path
        Existing or missing files (missing ones are skipped).

    Returns
    -------
    list of str
        One line per damaged file: its name, what is wrong, and that it will be rebuilt.
    """
    lines = []
    for path in sorted(Path(p) for p in paths):
        if not path.is_file():
            continue
        why = check_readable(path)
        if why is None:
            continue
        aside = path.with_name(path.name + ".damaged")
        os.replace(path, aside)
        lines.append(f"surfwave: {path} is damaged ({why}); moved to {aside.name}, "
                     f"this run rebuilds it")
    return lines
