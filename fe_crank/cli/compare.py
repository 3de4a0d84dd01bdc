"""``fe-crank compare REPORTS_A REPORTS_B [--rtol X]``: compare the numbers of two report
trees of ``fe-crank check`` (``fe_crank.compare``), e.g. before and after a change that
must leave every result as it was (``--rtol 0``).

Prints each difference on its own line (``case: key.path: a != b``) and a summary.
Exit 0 when the trees agree, 1 on any difference, 2 on a missing tree, an unreadable
results file or a bad ``--rtol``.
"""

from __future__ import annotations

from pathlib import Path

from fe_crank.compare import compare_trees


def add_arguments(p) -> None:
    p.add_argument("first", type=Path, metavar="REPORTS_A", help="a report folder written by fe-crank check")
    p.add_argument("second", type=Path, metavar="REPORTS_B", help="another report folder, compared case by case")
    p.add_argument(
        "--rtol",
        type=float,
        default=1e-9,
        help="relative tolerance of numbers, |a - b| <= rtol max(|a|, |b|) (default 1e-9; 0: equal numbers)",
    )


def run(args) -> int:
    result = compare_trees(args.first, args.second, args.rtol)
    for line in result.differences:
        print(line)
    n = len(result.differences)
    print(
        f"{result.cases} case(s) compared: {'no difference' if not n else f'{n} difference(s)'} "
        f"beyond {args.rtol:g} relative"
    )
    return 1 if n else 0
