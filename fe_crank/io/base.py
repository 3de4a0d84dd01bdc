"""Shared pieces of the input layer: strict pydantic base, TOML reading, error text.

Every input model forbids unknown keys: a misspelt key is an error, not ignored.
Validation errors become one ``InputError`` naming the file, the key path, the
offending value and the reason.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any, TypeVar

from pydantic import BaseModel, ConfigDict, ValidationError

from fe_crank.errors import InputError

M = TypeVar("M", bound=BaseModel)


class Strict(BaseModel):
    """Base of every input model: unknown keys forbidden, instances frozen."""

    model_config = ConfigDict(extra="forbid", frozen=True, str_strip_whitespace=True)


def key_path(loc: tuple[Any, ...]) -> str:
    """('cylinders', 1, 'bore') -> 'cylinders[1].bore'."""
    out = ""
    for part in loc:
        if isinstance(part, int):
            out += f"[{part}]"
        else:
            out += ("." if out else "") + str(part)
    return out


def _reason(err: dict) -> str:
    msg = err.get("msg", "invalid")
    kind = err.get("type", "")
    if msg.startswith("Value error, "):
        msg = msg[len("Value error, "):]
    if kind == "missing":
        return "required key is missing"
    if kind == "extra_forbidden":
        return f"unknown key (value {err.get('input')!r}); check the spelling against the documented keys"
    if kind in ("greater_than", "greater_than_equal", "less_than", "less_than_equal"):
        return f"{msg} (got {err.get('input')!r})"
    return msg


def validation_to_input_error(exc: ValidationError, file: str | Path, prefix: str = "") -> InputError:
    lines = []
    first_key = None
    for err in exc.errors():
        # pydantic appends the tag of union members to the location; drop internal parts
        loc = tuple(p for p in err.get("loc", ()) if not (isinstance(p, str) and p.startswith("function-")))
        key = key_path(loc)
        if prefix:
            key = f"{prefix}.{key}" if key else prefix
        first_key = first_key or key
        lines.append(f"{file}: {key or '(top level)'}: {_reason(err)}")
    if len(lines) == 1:
        e = InputError(lines[0].split(": ", 2)[-1], file=str(file), key=first_key or None)
        return e
    e = InputError("\n".join(lines))
    e.file, e.key = str(file), first_key
    return e


def read_toml(path: str | Path) -> dict:
    """Read a TOML file; a missing or malformed file is an InputError naming it."""
    p = Path(path)
    try:
        with p.open("rb") as fh:
            return tomllib.load(fh)
    except FileNotFoundError:
        raise InputError("file not found", file=str(p)) from None
    except IsADirectoryError:
        raise InputError("is a folder, expected a .toml file", file=str(p)) from None
    except tomllib.TOMLDecodeError as exc:
        raise InputError(f"malformed TOML: {exc}", file=str(p)) from None
    except UnicodeDecodeError as exc:
        raise InputError(f"not a UTF-8 text file: {exc}", file=str(p)) from None


def validate(model: type[M], data: Any, file: str | Path, prefix: str = "") -> M:
    try:
        return model.model_validate(data)
    except ValidationError as exc:
        raise validation_to_input_error(exc, file, prefix) from None


def resolve_reference(value: str, relative_to: str | Path) -> Path:
    """A path in a file is relative to that file's folder."""
    p = Path(value)
    if not p.is_absolute():
        p = Path(relative_to).parent / p
    return p
