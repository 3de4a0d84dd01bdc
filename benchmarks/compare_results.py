"""Compare two report trees of ``fe-crank check`` numerically.

    python benchmarks/compare_results.py REPORTS_A REPORTS_B [--rtol 1e-9]

For every case folder (a folder holding ``results.json``) of either tree, the two
``results.json`` documents are walked together: numbers must agree to ``rtol``
relative (``|a - b| <= rtol * max(|a|, |b|)``; exact zeros must match exactly),
strings, booleans and nulls must be equal, lists must have the same length and
objects the same keys.  Times and file paths are ignored (keys ``source_file``,
``source``, ``folder``, anything ending in ``seconds``, ``time`` or ``path``).  The
verdict in ``case.json`` (``status``, ``exit_code``, ``worst``) must be equal too.

Exit 0 when the trees agree, 1 on any difference (each printed as
``case: key.path: a != b``), 2 on bad arguments.
"""

from __future__ import annotations

import argparse
import json
import math
import sys
from pathlib import Path

IGNORED = {"source_file", "source", "folder"}
IGNORED_SUFFIXES = ("seconds", "time", "path")
VERDICT = ("status", "exit_code", "worst")


def _ignored(key: str) -> bool:
    return key in IGNORED or key.endswith(IGNORED_SUFFIXES)


def diff(a, b, rtol: float, where: str = "") -> list[str]:
    """Differences between two JSON values, as ``where: a != b`` strings."""
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
            out += diff(x, y, rtol, f"{where}[{i}]")
        return out
    if isinstance(a, dict) and isinstance(b, dict):
        ka = {k for k in a if not _ignored(k)}
        kb = {k for k in b if not _ignored(k)}
        out = [f"{where}.{k}: only in the first tree" for k in sorted(ka - kb)]
        out += [f"{where}.{k}: only in the second tree" for k in sorted(kb - ka)]
        for k in sorted(ka & kb):
            out += diff(a[k], b[k], rtol, f"{where}.{k}" if where else k)
        return out
    return [f"{where}: {type(a).__name__} != {type(b).__name__}"]


def case_folders(root: Path) -> dict[str, Path]:
    """Case name -> folder, for the visible sub-folders of ``root`` (hidden ones are
    unfinished or stale temporary folders)."""
    return {p.name: p for p in sorted(root.iterdir()) if p.is_dir() and not p.name.startswith(".")}


def compare(root_a: Path, root_b: Path, rtol: float) -> list[str]:
    fa, fb = case_folders(root_a), case_folders(root_b)
    out = [f"{c}: only in {root_a}" for c in sorted(set(fa) - set(fb))]
    out += [f"{c}: only in {root_b}" for c in sorted(set(fb) - set(fa))]
    for case in sorted(set(fa) & set(fb)):
        ca, cb = fa[case] / "case.json", fb[case] / "case.json"
        if ca.exists() and cb.exists():
            va, vb = json.loads(ca.read_text()), json.loads(cb.read_text())
            out += [
                f"{case}: case.json {d}"
                for d in diff({k: va.get(k) for k in VERDICT}, {k: vb.get(k) for k in VERDICT}, rtol)
            ]
        ra, rb = fa[case] / "results.json", fb[case] / "results.json"
        if ra.exists() != rb.exists():
            out.append(f"{case}: results.json only in {'the first' if ra.exists() else 'the second'} tree")
            continue
        if not ra.exists():
            continue
        a, b = json.loads(ra.read_text()), json.loads(rb.read_text())
        out += [f"{case}: {d}" for d in diff(a, b, rtol)]
    return out


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("first", type=Path)
    p.add_argument("second", type=Path)
    p.add_argument("--rtol", type=float, default=1e-9, help="relative tolerance (default 1e-9)")
    args = p.parse_args(argv)
    for root in (args.first, args.second):
        if not root.is_dir():
            print(f"compare_results: no such folder: {root}", file=sys.stderr)
            return 2
    diffs = compare(args.first, args.second, args.rtol)
    n = len(case_folders(args.first))
    for d in diffs:
        print(d)
    print(
        f"{n} case(s) compared: {'no difference' if not diffs else f'{len(diffs)} difference(s)'} "
        f"beyond {args.rtol:g} relative"
    )
    return 1 if diffs else 0


if __name__ == "__main__":
    sys.exit(main())
