"""Include paths: a path in an input file names another file (an engine, a geometry, a gas
table), relative to the file that names it.

It must resolve into the folder tree of the load case being read (``input_root``) unless
paths outside it are allowed (``--allow-outside-paths``, ``FE_CRANK_ALLOW_OUTSIDE_PATHS``;
docs/limits.md); a refusal names the referencing file and key, an error inside the
included file names that file and its own keys.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path
from typing import Any

from fe_crank.errors import InputError
from fe_crank.io.base import read_toml

#: the folder tree include paths must stay in, and whether paths outside it are allowed
_ROOT: ContextVar[Path | None] = ContextVar("fe_crank_input_root", default=None)
_ALLOW_OUTSIDE: ContextVar[bool | None] = ContextVar("fe_crank_allow_outside", default=None)
ALLOW_OUTSIDE_ENV = "FE_CRANK_ALLOW_OUTSIDE_PATHS"


def folder_tree(path: str | Path) -> Path:
    """The folder tree of an input file: the parent of its folder, so that the usual
    layout (``loadcases/``, ``engines/``, ``geometry/`` side by side) is inside it.
    The folder as named (a load case that is a link counts where the link is)."""
    return Path(os.path.abspath(path)).parent.resolve().parent


def outside_allowed() -> bool:
    v = _ALLOW_OUTSIDE.get()
    if v is None:
        return os.environ.get(ALLOW_OUTSIDE_ENV, "").strip().lower() in ("1", "true", "yes")
    return v


@contextmanager
def input_root(path: str | Path, allow_outside: bool | None = None) -> Iterator[None]:
    """Within the block, include paths must resolve into ``folder_tree(path)``
    unless ``allow_outside`` (default: the ``FE_CRANK_ALLOW_OUTSIDE_PATHS`` variable)."""
    t1 = _ROOT.set(folder_tree(path))
    t2 = _ALLOW_OUTSIDE.set(allow_outside)
    try:
        yield
    finally:
        _ROOT.reset(t1)
        _ALLOW_OUTSIDE.reset(t2)


def resolve_reference(value: str, relative_to: str | Path, *, key: str = "") -> Path:
    """A path in a file is relative to that file's folder.

    It must resolve (symbolic links followed) into the folder tree of the load case
    being read (``input_root``; without one, of ``relative_to``), or the option
    ``--allow-outside-paths`` must be given.  The refusal is the same whether the
    target exists or not, and nothing is read from it.
    """
    p = Path(value)
    if not p.is_absolute():
        p = Path(relative_to).parent / p
    if outside_allowed():
        return p
    root = _ROOT.get() or folder_tree(relative_to)
    try:
        inside = p.resolve().is_relative_to(root)
    except (OSError, RuntimeError):  # a symbolic-link loop
        inside = False
    if not inside:
        raise InputError(
            f"the path {value!r} leads outside the load case's folder tree ({root}); such paths are refused "
            f"unless --allow-outside-paths (or {ALLOW_OUTSIDE_ENV}=1) is given",
            file=str(relative_to),
            key=key or None,
        )
    return p


def with_include_context(exc: InputError, file: str | Path, key: str) -> InputError:
    """``exc`` (raised for an included file) with "(included by FILE: KEY)" added, so
    that the message also names the reference that brought the file in."""
    suffix = f"(included by {file}: {key})"
    if "\n" in exc.reason:
        new = type(exc)(f"{exc.reason}\n{suffix}")
        new.file, new.key = exc.file, exc.key
        return new
    return type(exc)(f"{exc.reason} {suffix}", file=exc.file, key=exc.key)


def read_included(value: str, relative_to: str | Path, key: str, what: str) -> tuple[Path, dict[str, Any]]:
    """Resolve an include (``engine = "..."``), read it as TOML.  A file that cannot
    be read is reported against the referencing file and key; errors inside the
    included file name that file and its own keys."""
    p = resolve_reference(value, relative_to, key=key)
    if not p.is_file():
        state = "is a folder" if p.is_dir() else "not found"
        raise InputError(f"the {what} {value!r} {state}", file=str(relative_to), key=key)
    try:
        return p, read_toml(p)
    except InputError as exc:
        if exc.key is None:  # the file as a whole: say who referenced it
            raise InputError(f"the {what} {value!r}: {exc.reason}", file=str(relative_to), key=key) from None
        raise
