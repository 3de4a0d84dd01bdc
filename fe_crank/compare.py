"""Numerical comparison of two report trees of ``fe-crank check`` (``fe-crank compare``).

For every case folder (a visible sub-folder of the tree) present in both trees, the two
``results.json`` documents are walked together: numbers must agree to ``rtol`` relative,
``|a - b| <= rtol * max(|a|, |b|)`` (so ``rtol = 0`` asks for equal numbers; two NaN
are equal), strings, booleans and nulls must be equal, lists must have the same length
and objects the same keys.  Times and file paths are not compared (keys ``source_file``,
``source``, ``folder``, and any key ending in ``seconds``, ``time`` or ``path``).  The
verdict in ``case.json`` (``status``, ``exit_code``, ``worst``) must be equal too.  A case
folder in one tree only, or a ``results.json`` in one tree only, is a difference.

Each difference is one line, ``case: key.path: a != b``.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.io.base import read_text

IGNORED = frozenset({"source_file", "source", "folder"})
IGNORED_SUFFIXES = ("seconds", "time", "path")
VERDICT = ("status", "exit_code", "worst")
#: deepest nesting of lists and objects compared (a results.json nests about 6 levels)
MAX_DEPTH = 64


@dataclass(frozen=True)
class Comparison:
    """The outcome of comparing two report trees: the number of case folders of the
    first tree and every difference found (empty when the trees agree)."""

    cases: int
    differences: tuple[str, ...]


def _ignored(key: str) -> bool:
    return key in IGNORED or key.endswith(IGNORED_SUFFIXES)


def diff(a, b, rtol: float, where: str = "", depth: int = 0) -> list[str]:
    """Differences between two JSON values, as ``where: a != b`` strings."""
    if depth > MAX_DEPTH:
        raise InputError(f"nested deeper than {MAX_DEPTH} levels", key=where or None)
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None or isinstance(a, str) or isinstance(b, str):
        return [] if a == b and type(a) is type(b) else [f"{where}: {a!r} != {b!r}"]
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if math.isnan(a) and math.isnan(b):
            return []
        if a == b or abs(a - b) <= rtol * max(abs(a), abs(b)):
            return []
        return [f"{where}: {a!r} != {b!r} (relative {abs(a - b) / max(abs(a), abs(b)):.3g})"]
    if isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            return [f"{where}: {len(a)} items != {len(b)} items"]
        out = []
        for i, (x, y) in enumerate(zip(a, b)):
            out += diff(x, y, rtol, f"{where}[{i}]", depth + 1)
        return out
    if isinstance(a, dict) and isinstance(b, dict):
        ka = {k for k in a if not _ignored(k)}
        kb = {k for k in b if not _ignored(k)}
        out = [f"{where}.{k}: only in the first tree" for k in sorted(ka - kb)]
        out += [f"{where}.{k}: only in the second tree" for k in sorted(kb - ka)]
        for k in sorted(ka & kb):
            out += diff(a[k], b[k], rtol, f"{where}.{k}" if where else k, depth + 1)
        return out
    return [f"{where}: {type(a).__name__} != {type(b).__name__}"]


def case_folders(root: Path) -> dict[str, Path]:
    """Case name -> folder, for the visible sub-folders of ``root`` (hidden ones are
    unfinished or stale temporary folders)."""
    if not root.is_dir():
        raise InputError("no such folder (a report tree of fe-crank check)", file=str(root))
    return {p.name: p for p in sorted(root.iterdir()) if p.is_dir() and not p.name.startswith(".")}


def _read_json(path: Path):
    try:
        return json.loads(read_text(path, "JSON file"))
    except json.JSONDecodeError as exc:
        raise InputError(f"not a JSON document (line {exc.lineno}, column {exc.colno})", file=str(path)) from None
    except RecursionError:
        raise InputError("not a JSON document fe-crank wrote: nested too deeply", file=str(path)) from None


def compare_trees(root_a: Path, root_b: Path, rtol: float) -> Comparison:
    """Compare the report trees ``root_a`` and ``root_b`` (module docstring).  A missing
    tree, an unreadable or malformed JSON file and a negative or non-finite ``rtol`` are
    an ``InputError``."""
    if not (math.isfinite(rtol) and rtol >= 0):
        raise InputError(f"must be a finite number >= 0, got {rtol!r}", key="--rtol")
    fa, fb = case_folders(root_a), case_folders(root_b)
    out = [f"{c}: only in {root_a}" for c in sorted(set(fa) - set(fb))]
    out += [f"{c}: only in {root_b}" for c in sorted(set(fb) - set(fa))]
    for case in sorted(set(fa) & set(fb)):
        ca, cb = fa[case] / "case.json", fb[case] / "case.json"
        if ca.exists() and cb.exists():
            va, vb = _read_json(ca), _read_json(cb)
            if not (isinstance(va, dict) and isinstance(vb, dict)):
                raise InputError("not a case record (a JSON object)", file=str(ca if not isinstance(va, dict) else cb))
            verdict_a, verdict_b = ({k: v.get(k) for k in VERDICT} for v in (va, vb))
            out += [f"{case}: case.json {d}" for d in diff(verdict_a, verdict_b, rtol)]
        ra, rb = fa[case] / "results.json", fb[case] / "results.json"
        if ra.exists() != rb.exists():
            out.append(f"{case}: results.json only in {'the first' if ra.exists() else 'the second'} tree")
            continue
        if not ra.exists():
            continue
        out += [f"{case}: {d}" for d in diff(_read_json(ra), _read_json(rb), rtol)]
    return Comparison(cases=len(fa), differences=tuple(out))
