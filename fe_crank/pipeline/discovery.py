"""Which files of the command line are load cases, and the report folder of each."""

from __future__ import annotations

import hashlib
import os
from collections.abc import Iterable, Sequence
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.pipeline.publish import case_slug


def is_loadcase_file(path: Path) -> bool:
    """A ``.toml`` with an ``[operating]`` table.  An unreadable TOML counts too, so
    that a broken load case in a folder is reported instead of silently skipped."""
    from fe_crank.io.base import read_toml

    try:
        data = read_toml(path)  # bounded: size, nesting depth; never a traceback
    except InputError:
        return True
    return isinstance(data.get("operating"), dict)


def find_loadcases(paths: Iterable[str | Path]) -> list[Path]:
    """Expand files and folders into load-case files.

    A file is taken as given (a wrong one becomes an error result); a folder
    contributes its ``*.toml`` files (recursively, sorted) that have an
    ``[operating]`` table.  A path that does not exist raises ``InputError``.
    """
    out: list[Path] = []
    for p in map(Path, paths):
        if p.is_dir():
            out.extend(f for f in sorted(p.rglob("*.toml")) if is_loadcase_file(f))
        elif p.exists():
            out.append(p)
        else:
            raise InputError("no such file or folder", file=str(p))
    seen, unique = set(), []
    for p in out:
        try:
            key = p.resolve()
        except (OSError, RuntimeError):  # a symbolic-link loop: reported when the case is read
            key = p.absolute()
        if key not in seen:
            seen.add(key)
            unique.append(p)
    return unique


def unique_slugs(paths: Sequence[Path]) -> list[str]:
    """Folder names for a batch: the stem, with a short hash of the path where two
    files share a stem."""
    stems = [case_slug(p) for p in paths]
    out = []
    for p, s in zip(paths, stems):
        if stems.count(s) > 1:
            s = f"{s}-{hashlib.sha1(os.path.abspath(p).encode()).hexdigest()[:6]}"
        out.append(s)
    return out
