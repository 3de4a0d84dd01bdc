"""Shared pieces of the input layer: strict pydantic base, TOML reading, error text.

Every input model forbids unknown keys: a misspelt key is an error, not ignored.
Validation errors become one ``InputError`` naming the file, the key path and the
reason (a number may be shown, never a string or table read from a file).  File
reading is bounded (``MAX_FILE_BYTES``, ``MAX_DEPTH``; docs/limits.md); the rules of
include paths are in ``io.includes``.
"""

from __future__ import annotations

import errno
import hashlib
import math
import os
import re
import tomllib
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from dataclasses import dataclass
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError
from pydantic_core import ErrorDetails

from fe_crank.errors import InputError

M = TypeVar("M", bound=BaseModel)


class Strict(BaseModel):
    """Base of every input model: unknown keys forbidden, instances frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True, str_strip_whitespace=True, allow_inf_nan=False)


def key_path(loc: tuple[Any, ...]) -> str:
    """('cylinders', 1, 'bore') -> 'cylinders[1].bore'."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def _reason(err: ErrorDetails) -> str:
    msg = err.get("msg", "invalid")
    kind = err.get("type", "")
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, ") :]
    if kind == "missing":
        return "required key is missing"
    if kind == "extra_forbidden":  # the value is never shown: it may come from any file
        return "unknown key; check the spelling against the documented keys"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        got = err.get("input")
        return f"{msg} (got {got!r})" if isinstance(got, (int, float)) and not isinstance(got, bool) else msg
    return msg


#: the tags pydantic puts into an error's location for a member of a union (``str``,
#: ``literal[False]``, ``list[constrained-str]``, ``function-after[...]``): never keys of a file
_UNION_TAG = re.compile(
    r"^(str|int|float|bool|none|bytes|decimal|date|datetime|any|"
    r"(literal|list|tuple|dict|set|frozenset|union|nullable|tagged-union|chain|lax-or-strict|"
    r"json-or-python|is-instance|function-(after|before|wrap|plain))\[.*\]|constrained-\w+)$"
)


def _model_names() -> set[str]:
    """Names of every pydantic model class loaded: pydantic tags a union member that is a
    model with its class name."""
    names, stack = set(), [BaseModel]
    while stack:
        cls = stack.pop()
        for sub in cls.__subclasses__():
            if sub.__name__ not in names:
                names.add(sub.__name__)
                stack.append(sub)
    return names


def _is_tag(part: Any, models: set[str]) -> bool:
    return isinstance(part, str) and (part in models or bool(_UNION_TAG.match(part)))


_INSTANCE = re.compile(r"(a valid dictionary) or instance of \w+")


def _plain(text: str) -> str:
    """A pydantic message without its internals: "a valid dictionary or instance of
    CounterweightInput" is a table."""
    return _INSTANCE.sub("a table", text).replace("a valid dictionary", "a table")


@dataclass(frozen=True)
class _Err:
    loc: tuple[Any, ...]  # the key path, union tags removed
    site: tuple[Any, ...] | None  # the path of the union the error came through (None: no union)
    member: str  # the union member's tag
    reason: str


def _clean(errors: list[ErrorDetails]) -> list[_Err]:
    """The errors pydantic reports, one per fault of the file (module doc of ``validate``).

    A value that matches no member of a union gets one error per member; the members
    that failed only at the union's own key (wrong type) are dropped when another member
    failed further inside (that member was meant: its errors are the file's), and when
    every member failed at the key the alternatives become one message.  A model
    validator's message that starts with a key of the table names that key."""
    models = _model_names()
    out: list[_Err] = []
    for err in errors:
        loc: list[Any] = []
        site: tuple[Any, ...] | None = None
        member = ""
        for part in err.get("loc", ()):
            if _is_tag(part, models):
                if site is None:
                    site, member = tuple(loc), str(part)
                continue
            loc.append(part)
        reason = _plain(_reason(err))
        data = err.get("input")
        if err.get("type") == "value_error" and isinstance(data, dict):
            word, _, rest = reason.partition(" ")
            if word in data and rest.startswith(("must ", "cannot ")):  # "damping must not be negative"
                loc.append(word)
        out.append(_Err(tuple(loc), site, member, reason))
    keep: list[_Err] = []
    sites: dict[tuple[Any, ...], list[_Err]] = {}
    for e in out:
        if e.site is None:
            keep.append(e)
        else:
            sites.setdefault(e.site, []).append(e)
    for site, errs in sites.items():
        deep = [e for e in errs if len(e.loc) > len(site)]
        if deep:
            keep.extend(deep)
            continue
        reasons = list(dict.fromkeys(e.reason for e in errs))
        if len(reasons) == 1:
            text = reasons[0]
        elif all(r.startswith("Input should be ") for r in reasons):  # the alternatives in one message
            text = "should be " + " or ".join(r.removeprefix("Input should be ") for r in reasons)
        else:
            text = "; or ".join(reasons)
        keep.append(_Err(site, None, "", text))
    unique: dict[tuple[str, str], _Err] = {}
    for e in keep:
        unique.setdefault((key_path(e.loc), e.reason), e)
    return list(unique.values())


def validation_to_input_error(exc: ValidationError, file: str | Path, prefix: str = "") -> InputError:
    """One ``InputError`` for a pydantic validation error: one line per fault of the
    file, each naming the file, the key path and the reason, without pydantic's union
    members or class names (``_clean``)."""
    lines = []
    first_key = None
    for err in _clean(exc.errors()):
        key = key_path(err.loc)
        if prefix:
            key = f"{prefix}.{key}" if key else prefix
        first_key = first_key or key
        lines.append((key, err.reason))
    if len(lines) == 1:
        key, reason = lines[0]
        return InputError(reason, file=str(file), key=key or None)
    e = InputError("\n".join(f"{file}: {key or '(top level)'}: {reason}" for key, reason in lines))
    e.file, e.key = str(file), first_key
    return e


#: largest accepted input file (TOML or CSV), bytes; FE_CRANK_MAX_FILE_BYTES raises it
MAX_FILE_BYTES = 4_000_000
#: deepest accepted nesting of tables and arrays in an input file
MAX_DEPTH = 12
_BOM = b"\xef\xbb\xbf"


def _limit(name: str, default: int) -> int:
    raw = os.environ.get(name, "")
    try:
        return int(raw) if raw.strip() else default
    except ValueError:
        raise InputError(f"must be a whole number of bytes (got {raw[:20]!r})", key=name) from None


@dataclass(frozen=True)
class InputFile:
    """One input file as it was read: its resolved path and the SHA-256 of its bytes."""

    path: Path
    sha256: str


#: the input files read within ``recording_inputs`` (None: not recording)
_READ: ContextVar[list[InputFile] | None] = ContextVar("fe_crank_inputs_read", default=None)


@contextmanager
def recording_inputs() -> Iterator[list[InputFile]]:
    """Within the block, every input file ``read_text`` opens is appended (once) to the
    list yielded, even when its contents are then refused: the files a load case was
    read from, for the provenance of its results."""
    read: list[InputFile] = []
    token = _READ.set(read)
    try:
        yield read
    finally:
        _READ.reset(token)


def _record(p: Path) -> None:
    read = _READ.get()
    if read is None:
        return
    try:
        path = p.resolve()
    except (OSError, RuntimeError):  # a symbolic-link loop
        path = Path(os.path.abspath(p))
    if any(f.path == path for f in read):
        return
    digest = hashlib.sha256()
    with p.open("rb") as fh:  # in blocks: an input of any size is hashed in bounded memory
        for block in iter(lambda: fh.read(1 << 20), b""):
            digest.update(block)
    read.append(InputFile(path, digest.hexdigest()))


def record_file(path: str | Path) -> None:
    """Record an input file that is not read as text (a CAD file, read by OpenCASCADE)
    for the provenance, as ``read_text`` records the files it reads (``recording_inputs``)."""
    _record(Path(path))


def read_text(path: str | Path, what: str = "file", *, record: bool = True) -> str:
    """Read a UTF-8 text input file (a leading byte-order mark is dropped).

    Refused with an ``InputError`` naming the file: missing, a folder, unreadable
    (permissions, a symbolic-link loop), larger than ``MAX_FILE_BYTES``, binary or
    not UTF-8.  The file's contents never appear in the message.  A file that could be
    opened is recorded for the provenance (``recording_inputs``) unless ``record`` is
    false (the package's own data files).
    """
    p = Path(path)
    limit = _limit("FE_CRANK_MAX_FILE_BYTES", MAX_FILE_BYTES)
    try:
        if p.is_dir():
            raise InputError(f"is a folder, expected a {what}", file=str(p))
        with p.open("rb") as fh:
            raw = fh.read(limit + 1)
        if record:
            _record(p)
    except InputError:
        raise
    except FileNotFoundError:
        raise InputError(f"{what} not found", file=str(p)) from None
    except PermissionError:
        raise InputError(f"{what} cannot be read: permission denied", file=str(p)) from None
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise InputError(f"{what} cannot be read: symbolic-link loop", file=str(p)) from None
        raise InputError(f"{what} cannot be read: {exc.strerror or type(exc).__name__}", file=str(p)) from None
    if len(raw) > limit:
        raise InputError(
            f"{what} larger than {limit} bytes (the limit; FE_CRANK_MAX_FILE_BYTES raises it, docs/limits.md)",
            file=str(p),
        )
    if raw.startswith(_BOM):
        raw = raw[len(_BOM) :]
    if b"\x00" in raw:
        raise InputError(f"is a binary file, expected a {what}", file=str(p))
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError as exc:
        raise InputError(f"not a UTF-8 text file (invalid byte at offset {exc.start})", file=str(p)) from None


def check_tree(data: Any, file: str | Path, prefix: str = "") -> None:
    """Refuse nesting deeper than ``MAX_DEPTH`` and non-finite numbers (TOML's
    ``inf``/``nan``: no input of fe-crank means them), naming the key.  Iterative:
    any depth is inspected without recursion."""
    stack = [(data, prefix, 0)]
    while stack:
        node, key, depth = stack.pop()
        if isinstance(node, float) and not math.isfinite(node):
            raise InputError("must be a finite number (inf and nan are not accepted)", file=str(file), key=key or None)
        if isinstance(node, (dict, list)):
            if depth >= MAX_DEPTH:
                raise InputError(
                    f"tables and arrays nested deeper than {MAX_DEPTH} levels", file=str(file), key=key or None
                )
            items = node.items() if isinstance(node, dict) else enumerate(node)
            for k, v in items:
                sub = f"{key}[{k}]" if isinstance(k, int) else (f"{key}.{k}" if key else str(k))
                stack.append((v, sub, depth + 1))


def read_toml(path: str | Path, *, record: bool = True) -> dict[str, Any]:
    """Read a TOML input file: ``read_text`` refusals, malformed TOML, nesting deeper
    than ``MAX_DEPTH`` and non-finite numbers are an InputError naming the file."""
    p = Path(path)
    text = read_text(p, "TOML file", record=record)
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"malformed TOML: {exc}", file=str(p)) from None
    except RecursionError:
        raise InputError(f"malformed TOML: nested deeper than {MAX_DEPTH} levels", file=str(p)) from None
    check_tree(data, p)
    return data


def validate(model: type[M], data: Any, file: str | Path, prefix: str = "") -> M:
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        raise validation_to_input_error(exc, file, prefix) from None
