"""Publishing a finished case folder atomically, and cleaning up after killed runs.

A case folder is built under a hidden temporary name in ``out_dir`` and renamed into
place only when it is complete, so an interrupted run never leaves a report that
looks finished.
"""

from __future__ import annotations

import os
import re
import shutil
import time
from pathlib import Path

PARTIAL_MARK = ".partial-"


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:  # pragma: no cover - someone else's process
        return True
    return True


def clean_stale_partials(out_dir: str | Path) -> list[Path]:
    """Remove temporary case folders left by runs that were killed (their process is
    gone).  Returns what was removed."""
    out = Path(out_dir)
    removed: list[Path] = []
    if not out.is_dir():
        return removed
    for p in out.iterdir():
        m = re.match(r"^\..+\.partial-(\d+)-", p.name)
        if m and p.is_dir() and not _pid_alive(int(m.group(1))):
            shutil.rmtree(p, ignore_errors=True)
            removed.append(p)
    return removed


def publish_folder(tmp_dir: Path, final: Path) -> Path:
    """Rename the finished ``tmp_dir`` to ``final``, replacing an older report.

    A folder cannot be renamed over a non-empty one, so the old folder is first
    renamed aside and deleted after the new one is in place; at every instant
    ``final`` is either absent, the old complete report or the new complete one.
    """
    old = None
    if final.exists():
        old = final.with_name(f".{final.name}.old-{os.getpid()}-{time.monotonic_ns()}")
        os.replace(final, old)
    os.replace(tmp_dir, final)
    if old is not None:
        shutil.rmtree(old, ignore_errors=True)
    return final


def case_slug(path: str | Path) -> str:
    """Folder name of a case's report: the file stem, made filesystem-safe."""
    stem = Path(path).stem
    return re.sub(r"[^A-Za-z0-9_.-]+", "_", stem) or "case"
