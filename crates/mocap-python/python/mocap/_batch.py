"""Whole-dataset jobs from Python: `mocap batch`'s engine (the same manifest
lines, files done in parallel with the GIL released, resumable)."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Iterable, Optional, Union

from ._mocap import _batch, _run_one, motion_files

PathLike = Union[str, os.PathLike]


def summarise(path: PathLike, *, to: Optional[str] = "json", out: Optional[PathLike] = None) -> dict:
    """One file's manifest line (`to`: None to only validate, "json" for the
    figures, "bvh"/"glb" to convert into `out`): file, sha256, status, and the
    error with its location or the figures. Never raises for a bad file; the
    unit of work for Dask, Ray or a process pool."""
    return json.loads(_run_one(Path(path), to=to, out=None if out is None else Path(out)))


def batch(
    source: Union[PathLike, Iterable[PathLike]],
    *,
    to: Optional[str] = "json",
    out: Optional[PathLike] = None,
    manifest: Optional[PathLike] = None,
    jobs: Optional[int] = None,
) -> list[dict]:
    """Every motion file of `source` (a folder, walked recursively, or a list of
    files) validated (`to=None`), summarised (`"json"`) or converted (`"bvh"`,
    `"glb"` into `out`) on `jobs` threads; the manifest lines in file order,
    appended to the JSON-lines `manifest` when given, where files already
    listed with the same sha256 are not done again."""
    if isinstance(source, (str, os.PathLike)):
        root = Path(source)
        files = motion_files(root)
        root = root if root.is_dir() else root.parent
    else:
        files = [Path(p) for p in source]
        root = Path(os.path.commonpath([str(p.parent) for p in files])) if files else Path(".")
    lines = _batch(files, root, to=to, out=None if out is None else Path(out), manifest=None if manifest is None else Path(manifest), jobs=jobs)
    return [json.loads(line) for line in lines]
