"""Atomic file writes: a temporary file in the target's directory, then ``os.replace``.

Readers never see a half-written file and a killed writer never leaves one at the target
path (at most a temporary file, which the caller may clean up by its name pattern). Used by
the result cubes (:mod:`surfwave.data.cube`) and the parameter cache (:mod:`surfwave.data.cache`).
"""
from __future__ import annotations

import os
import tempfile
from pathlib import Path
from typing import Callable


def file_mode() -> int:
    """Permissions of a new file under the current umask (what ``open(..., "w")`` gives;
    ``mkstemp`` alone gives 0600, but results and a shared cache are for everyone to read)."""
    mask = os.umask(0)
    os.umask(mask)
    return 0o666 & ~mask


def atomic_write(
    path: str | Path,
    write: Callable[[Path], object],
    *,
    prefix: str | None = None,
    suffix: str = ".tmp",
    fsync: bool = False,
) -> Path:
    """Write ``path`` atomically through ``write(temporary_path)``.

    Parameters
    ----------
    path : str or Path
        Target file; its directory is created if needed.
    write : callable
        Called with the temporary path (same directory, so ``os.replace`` is atomic); it
        writes the whole file there.
    prefix, suffix : str
        Name pattern of the temporary file (default prefix ``".<name>."``): callers that
        clean up after killed writers glob for it.
    fsync : bool
        Flush the temporary file to disk before the rename (durability across a crash of
        the machine, not only of the process).

    Returns
    -------
    pathlib.Path
        ``path``.
    """
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}." if prefix is None else prefix,
                               suffix=suffix, dir=path.parent)
    os.close(fd)
    try:
        write(Path(tmp))
        if fsync:
            with open(tmp, "rb+") as fh:
                os.fsync(fh.fileno())
        os.chmod(tmp, file_mode())
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise
    return path
