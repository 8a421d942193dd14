"""Persistent parameter database: expensive per-point results, computed once.

One small ``.npz`` file per (kind, point) under ``<root>/<kind>/``, named by the sha256 of
everything that determines the value: the caller's key (lattice, loading, potential,
direction, method, accuracy settings, ...), the point's d/d0 and the surfwave version.
Writes go to a temporary file in the same directory and are renamed into place
(``os.replace``), so a reader never sees a partial entry, two jobs writing the same entry
both leave a valid one, and a killed job leaves at most a stray temporary file (ignored,
removed by :func:`clear`). An entry that cannot be read or does not match its key is
treated as missing and recomputed.

A store is marked as ours when it is created: the file ``SURFWAVE_CACHE`` at its root holds
the format tag (:data:`FORMAT`). :func:`clear` deletes only what it can prove is an entry of
ours (``<kind>/<64 hex>.npz``, ``.tmp-*`` files of our writer, the run statistics) and refuses
a directory without the marker or with any other file in it, naming a few; a store made by
older code (no marker) is accepted when every file in it matches those patterns.

Examples
--------
>>> import numpy as np, tempfile
>>> root = tempfile.mkdtemp()
>>> f = lambda d: {"y": d**2}
>>> cached_points("demo", {"a": 1}, np.array([1.0, 2.0]), f, root)["y"]
array([1., 4.])
>>> info(root)["entries"]
2
"""
from __future__ import annotations

import hashlib
import json
import os
import re
import time
import zipfile
from pathlib import Path
from typing import Any, Callable, Mapping, TextIO

import numpy as np
from numpy.typing import ArrayLike

from surfwave import __version__
from surfwave.data.atomic import atomic_write
from surfwave.data.progress import Progress, summary_line
from surfwave.data.provenance import module_closure
from surfwave.errors import InputError
from surfwave.validate import as_1d

#: Default location, relative to the working directory of the workflow.
DEFAULT_ROOT = Path("results") / "cache"
#: Points computed and stored at a time by the workflow's stages (a killed job keeps the
#: chunks it finished; at 3-20 ms per point a chunk is well under a second of work).
CHUNK = 32
_STATS = "stats"
_RUN_MARKER = "RUN"
#: The file at the root of every store, written when the store is created.
MARKER = "SURFWAVE_CACHE"
#: Format tag in the marker (JSON ``{"format": FORMAT, ...}``).
FORMAT = "surfwave-cache/1"
#: Names our writer gives: entries, temporary files of :func:`_atomic_write` and
#: :func:`_atomic_write_text` (``mkstemp`` with prefix ``.tmp-``), run statistics.
_ENTRY_RE = re.compile(r"[0-9a-f]{64}\.npz")
_TMP_RE = re.compile(r"\.tmp-[A-Za-z0-9_]+(\.npz)?")
_STATS_RE = re.compile(r"[0-9]+-[0-9]+-[A-Za-z0-9_.-]+\.json|" + _RUN_MARKER)
_KIND_RE = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]*")


def _canonical(obj):
    """JSON-able, deterministic form of a key (floats by repr, arrays as lists)."""
    if isinstance(obj, Mapping):
        return {str(k): _canonical(v) for k, v in sorted(obj.items(), key=lambda kv: str(kv[0]))}
    if isinstance(obj, np.ndarray):
        return _canonical(obj.tolist())
    if isinstance(obj, (list, tuple)):
        return [_canonical(v) for v in obj]
    if isinstance(obj, (bool, np.bool_)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        return repr(float(obj))
    if obj is None or isinstance(obj, str):
        return obj
    if hasattr(obj, "name"):  # e.g. a PairPotential: name plus parameters
        return {"name": obj.name, "params": _canonical(getattr(obj, "params", {}))}
    raise InputError(f"cache key value {obj!r} of type {type(obj).__name__} is not hashable")


def point_key(kind: str, key: Mapping, d_over_d0: float) -> tuple[str, str]:
    """(sha256 hex digest, canonical JSON) of one point: kind, key, d/d0, surfwave version."""
    full = {"kind": kind, "key": _canonical(dict(key)), "d_over_d0": repr(round(float(d_over_d0), 12)),
            "surfwave": __version__}
    text = json.dumps(full, sort_keys=True, separators=(",", ":"))
    return hashlib.sha256(text.encode()).hexdigest(), text


def _entry_path(root: Path, kind: str, digest: str) -> Path:
    return root / kind / f"{digest}.npz"


def _read(path: Path, text: str) -> dict[str, np.ndarray] | None:
    try:
        with np.load(path, allow_pickle=False) as z:
            if str(z["__key__"]) != text:
                return None
            return {k: z[k] for k in z.files if k != "__key__"}
    except (OSError, ValueError, KeyError, EOFError, zipfile.BadZipFile):
        return None


def _atomic_write(path: Path, arrays: Mapping[str, np.ndarray], text: str) -> None:
    """Store one entry (its key text beside the arrays) atomically and durably."""
    def savez(tmp: Path) -> None:
        with open(tmp, "wb") as fh:
            payload: dict[str, Any] = {"__key__": np.array(text), **arrays}
            np.savez(fh, **payload)

    atomic_write(path, savez, prefix=".tmp-", suffix=".npz", fsync=True)


def _record(root: Path, kind: str, hits: int, misses: int, label: str | None = None,
            seconds: float = 0.0) -> None:
    stats = root / _STATS
    stats.mkdir(parents=True, exist_ok=True)
    rec = {"time": time.time(), "kind": kind, "hits": hits, "misses": misses, "pid": os.getpid(),
           "label": label or kind, "seconds": seconds}
    _atomic_write_text(stats / f"{time.time_ns()}-{os.getpid()}-{kind}.json", json.dumps(rec))


def _atomic_write_text(path: Path, text: str) -> None:
    atomic_write(path, lambda tmp: tmp.write_text(text), prefix=".tmp-", suffix="")


def _as_store(a) -> np.ndarray:
    a = np.asarray(a)
    return a.astype(str) if a.dtype.kind in "OSU" else a


def cached_points(
    kind: str,
    key: Mapping,
    d_over_d0: ArrayLike,
    compute: Callable[[np.ndarray], Mapping[str, np.ndarray]],
    root: str | Path = DEFAULT_ROOT,
    chunk: int | None = None,
    label: str | None = None,
    log: TextIO | None = None,
) -> dict[str, np.ndarray]:
    """Per-point results for every d/d0, computing only the points not yet stored.

    Parameters
    ----------
    kind : str
        What is cached (a directory name), e.g. ``"bulk"``, ``"surface_mode"``, ``"entropy"``.
    key : mapping
        Everything besides d/d0 that determines the value (lattice, loading, potential,
        direction, method, accuracy settings, theta grid, ...); JSON-able values.
    d_over_d0 : array_like, shape (n,)
    compute : callable
        ``compute(d_missing) -> {name: array with leading axis len(d_missing)}``; called
        with the missing points only (in order, without duplicates): once, or once per
        ``chunk`` of them.
    root : path
        Directory of the store (default ``results/cache``).
    chunk : int, optional
        Compute and store the missing points this many at a time, so that a job killed
        mid-way keeps the points it finished (a rerun resumes there). None: all at once.
    label : str, optional
        What the points are for, e.g. ``"bulk, scene table1"``: the summary line
        (:func:`surfwave.data.progress.summary_line`) written to ``log`` and kept in the
        run's statistics (:func:`run_summary`). Progress is shown per chunk (a bar on a
        terminal, a line every 10 s in a log file).
    log : file, optional
        Where progress and the summary line go (default: ``sys.stderr``).

    Returns
    -------
    dict
        name -> array with leading axis n, in the order of ``d_over_d0``.
    """
    if not kind or "/" in kind or kind.startswith("."):
        raise InputError(f"cache kind must be a plain directory name, got {kind!r}")
    root = Path(root)
    d = as_1d(d_over_d0)
    _ensure_store(root)
    ids = [point_key(kind, key, x) for x in d]
    found: dict[str, dict] = {}
    for digest, text in ids:
        if digest not in found:
            entry = _read(_entry_path(root, kind, digest), text)
            if entry is not None:
                found[digest] = entry
    missing_idx, seen = [], set()
    for i, (digest, _) in enumerate(ids):
        if digest not in found and digest not in seen:
            missing_idx.append(i)
            seen.add(digest)
    step = len(missing_idx) if not chunk else int(chunk)
    name = label or kind
    detail = " ".join(str(key[k]) for k in ("potential", "direction") if k in key)
    bar = Progress(f"{name}, {detail}" if detail else name, len(missing_idx), stream=log)
    for start in range(0, len(missing_idx), max(step, 1)):
        part = missing_idx[start:start + step]
        result = compute(d[part])
        bar.update(len(part))
        for j, i in enumerate(part):
            arrays = {k: _as_store(v)[j] for k, v in result.items()}
            digest, text = ids[i]
            _atomic_write(_entry_path(root, kind, digest), arrays, text)
            found[digest] = {k: np.asarray(v) for k, v in arrays.items()}
    seconds = bar.close()
    hits = len(d) - len(missing_idx)
    _record(root, kind, hits=hits, misses=len(missing_idx), label=name, seconds=seconds)
    if label is not None:
        bar.write(summary_line(bar.label, len(d), hits, len(missing_idx), seconds) + "\n")
    names = list(found[ids[0][0]])
    return {k: np.stack([found[digest][k] for digest, _ in ids]) for k in names}


def code_version(*modules: str) -> str:
    """sha256 (16 hex) of the source of surfwave modules and everything they import.

    Put it in a key (``{"code": code_version("phonons"), ...}``) so that entries computed
    by older code are never reused, even while the package version stays the same.
    """
    h = hashlib.sha256()
    for path in module_closure(*modules):
        p = Path(path)
        h.update(p.name.encode())
        h.update(p.read_bytes() if p.exists() else b"<missing>")
    return h.hexdigest()[:16]


def job_key(job: Mapping, module: str, method: str, **point: Any) -> dict:
    """Cache key of a workflow job's points: the computing code, lattice, loading, method,
    plus ``point`` (potential, direction, accuracy knobs, ...); d/d0 is added per point.

    ``job`` is :func:`surfwave.pipeline.scenes.job_params` output; ``module`` the surfwave module that
    computes the values (its :func:`code_version` goes in the key, so entries of older code
    are never reused).
    """
    return {"code": code_version(module), "lattice": job["lattice"], "loading": job["loading"],
            "method": method, **point}


def start_run(root: str | Path = DEFAULT_ROOT) -> None:
    """Mark the start of a workflow run: :func:`info` counts hits and misses from here."""
    root = Path(root)
    _ensure_store(root)
    stats = root / _STATS
    stats.mkdir(parents=True, exist_ok=True)
    for old in stats.glob("*.json"):  # records of earlier runs: info() no longer counts them
        old.unlink(missing_ok=True)
    _atomic_write_text(stats / _RUN_MARKER, json.dumps({"time": time.time()}))


def info(root: str | Path = DEFAULT_ROOT) -> dict[str, Any]:
    """Summary of the store.

    Returns
    -------
    dict
        ``entries`` (int), ``size`` (bytes), ``kinds`` ({kind: entries}), ``hits`` and
        ``misses`` of the last run (since the last :func:`start_run`; the last call of
        :func:`cached_points` per kind if no run was marked), ``stale_temporary`` (files
        left by killed jobs), ``root``.
    """
    root = Path(root)
    out: dict[str, Any] = {"root": str(root), "entries": 0, "size": 0, "kinds": {}, "hits": 0, "misses": 0,
           "stale_temporary": 0}
    if not root.is_dir():
        return out
    for kind_dir in sorted(p for p in root.iterdir() if p.is_dir() and p.name != _STATS):
        n = 0
        for f in kind_dir.iterdir():
            if f.name.startswith(".tmp-"):
                out["stale_temporary"] += 1
            elif f.suffix == ".npz":
                n += 1
                out["size"] += f.stat().st_size
        out["kinds"][kind_dir.name] = n
        out["entries"] += n
    records = _run_records(root)
    marker = root / _STATS / _RUN_MARKER
    since = None
    if marker.exists():
        try:
            since = json.loads(marker.read_text())["time"]
        except (OSError, ValueError, KeyError):
            since = None
    if since is not None:
        chosen = [r for r in records if r["time"] >= since]
    else:
        last: dict[str, dict] = {}
        for r in records:  # oldest first: the newest record of each kind wins
            last[r["kind"]] = r
        chosen = list(last.values())
    out["hits"] = sum(r["hits"] for r in chosen)
    out["misses"] = sum(r["misses"] for r in chosen)
    return out


def _run_records(root: Path) -> list[dict]:
    stats = root / _STATS
    records = []
    if stats.is_dir():
        for f in stats.glob("*.json"):
            try:
                records.append(json.loads(f.read_text()))
            except (OSError, ValueError):
                continue
    return sorted(records, key=lambda r: r["time"])


def run_summary(root: str | Path = DEFAULT_ROOT) -> list[str]:
    """One line per labelled job of the current run (since :func:`start_run`):
    "bulk, scene x: 22 points, 14 from the cache, 8 computed in 3.1 s".

    The workflow prints these at the end of a run (``onsuccess``/``onerror``), since each
    job's own output goes to its log file.
    """
    totals: dict[str, list] = {}
    for r in _run_records(Path(root)):
        t = totals.setdefault(r.get("label", r["kind"]), [0, 0, 0.0])
        t[0] += r["hits"]
        t[1] += r["misses"]
        t[2] += r.get("seconds", 0.0)
    return [summary_line(label, h + m, h, m, s) for label, (h, m, s) in totals.items()]


def _ensure_store(root: Path) -> None:
    """Create the store (with its marker) if it does not exist yet.

    An existing directory gets the marker only if it is empty or an unmarked store of older
    code (every file matches our names); otherwise it is left unmarked, so :func:`clear`
    refuses it (the cache itself still works there).
    """
    if (root / MARKER).is_file():
        return
    root.mkdir(parents=True, exist_ok=True)
    if not _foreign_files(root):
        _atomic_write_text(root / MARKER, json.dumps({"format": FORMAT, "created": time.time(),
                                                      "surfwave": __version__}))


def _marker_ok(root: Path) -> bool:
    try:
        return json.loads((root / MARKER).read_text()).get("format") == FORMAT
    except (OSError, ValueError, AttributeError):
        return False


def _foreign_files(root: Path) -> list[Path]:
    """Every path below ``root`` that our writer would not have made (sorted)."""
    foreign = []
    for p in sorted(root.iterdir()):
        if p.name == MARKER and p.is_file():
            continue
        if p.is_file() and _TMP_RE.fullmatch(p.name):  # the marker's temporary file
            continue
        if not p.is_dir() or p.is_symlink() or not _KIND_RE.fullmatch(p.name):
            foreign.append(p)
            continue
        pattern = _STATS_RE if p.name == _STATS else _ENTRY_RE
        for f in sorted(p.iterdir()):
            if f.is_symlink() or not f.is_file() or not (pattern.fullmatch(f.name)
                                                         or _TMP_RE.fullmatch(f.name)):
                foreign.append(f)
    return foreign


def check_store(root: str | Path) -> tuple[bool, str]:
    """Whether ``root`` is a surfwave cache, and why (one line).

    Returns
    -------
    (bool, str)
        True for a marked store whose every file is ours, or an unmarked one of older code
        whose every file matches our names (the reason says which); False, naming the
        problem and a few foreign files, for anything else (a missing directory is a store
        with nothing in it: True).
    """
    root = Path(root)
    if not root.exists():
        return True, f"{root} does not exist (an empty cache)"
    if not root.is_dir():
        return False, f"{root} is not a directory"
    foreign = _foreign_files(root)
    if foreign:
        shown = ", ".join(str(f.relative_to(root)) for f in foreign[:5])
        more = f" and {len(foreign) - 5} more" if len(foreign) > 5 else ""
        why = "has files that are not cache entries" if _marker_ok(root) else \
            f"has no {MARKER} marker and holds files that are not cache entries"
        return False, f"{root} is not a surfwave cache: it {why}: {shown}{more}"
    if _marker_ok(root):
        return True, f"{root} is a surfwave cache ({FORMAT})"
    if (root / MARKER).exists():
        return False, f"{root} is not a surfwave cache: its {MARKER} file has no format {FORMAT!r}"
    if not any(root.iterdir()):
        return True, f"{root} is empty (no cache entries)"
    return True, (f"{root} has no {MARKER} marker (a cache of older surfwave): accepted, "
                  "every file in it has the name of a cache entry")


def clear(root: str | Path = DEFAULT_ROOT) -> int:
    """Delete every entry, the run statistics and stray temporary files of a store.

    Only files :func:`check_store` proves to be ours are touched, and a folder is removed
    only once it is empty; the marker stays (the store exists, empty).

    Returns
    -------
    int
        The entries removed.

    Raises
    ------
    InputError
        If ``root`` is not a surfwave cache (no marker, a foreign marker, or any file that is
        not ours: nothing is deleted then).
    """
    root = Path(root)
    ok, why = check_store(root)
    if not ok:
        raise InputError(f"refusing to clear: {why}")
    if not root.is_dir():
        return 0
    removed = 0
    for kind_dir in sorted(p for p in root.iterdir() if p.is_dir()):
        pattern = _STATS_RE if kind_dir.name == _STATS else _ENTRY_RE
        for f in kind_dir.iterdir():
            if pattern.fullmatch(f.name) or _TMP_RE.fullmatch(f.name):
                if kind_dir.name != _STATS and _ENTRY_RE.fullmatch(f.name):
                    removed += 1
                f.unlink(missing_ok=True)
        try:
            kind_dir.rmdir()  # only if empty: rmdir never removes a folder with anything in it
        except OSError:
            pass
    return removed
