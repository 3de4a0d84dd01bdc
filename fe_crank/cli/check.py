"""``fe-crank check PATH...``: run load cases end to end and give verdicts.

Exit code: 0 every criterion of every case passes, 1 a criterion failed,
2 a case could not be read or computed (the other cases still run).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.mesh.options import DEFAULT_CACHE_DIR, PRESETS


def add_arguments(p) -> None:
    p.add_argument("paths", nargs="+", type=Path, metavar="PATH",
                   help="load-case files, or folders searched for *.toml files with an [operating] table")
    p.add_argument("-o", "--output", type=Path, default=Path("reports"), metavar="DIR",
                   help="folder for the per-case reports (default: reports/)")
    p.add_argument("--junit", type=Path, metavar="FILE", help="also write JUnit XML (one test per criterion)")
    p.add_argument("-j", "--jobs", type=int, default=1, metavar="N",
                   help="run cases in N local processes (default 1: in this process)")
    p.add_argument("--dask-scheduler", metavar="ADDRESS",
                   help="run the cases on an existing Dask distributed cluster, e.g. tcp://10.0.0.5:8786")
    p.add_argument("--mesh-size", choices=tuple(PRESETS), default=None,
                   help="mesh preset (default coarse: fillet elements <= r/4, IACS UR M53 guidance; "
                        "test is for quick trials only)")
    p.add_argument("--cache-dir", default=str(DEFAULT_CACHE_DIR), metavar="DIR",
                   help=f"mesh cache folder shared by every case and worker (default: {DEFAULT_CACHE_DIR}, relative "
                        "to the working directory; resolved before cases are sent to processes or Dask workers)")
    p.add_argument("--no-render", action="store_true", help="skip the pyvista pictures (faster)")
    p.add_argument("--no-vtu", action="store_true", help="do not write the .vtu result fields")
    p.add_argument("--convergence", action=argparse.BooleanOptionalAction, default=None,
                   help="hot-spot convergence study: fillets meshed at r/4, r/6, r/8 (from the preset), "
                        "peak change <= 5 %% (default: the load case's [mesh] convergence, on unless the mesh is test)")


def _options(args):
    from fe_crank.check import CheckOptions

    return CheckOptions(mesh_size=args.mesh_size, cache_dir=str(args.cache_dir), render=not args.no_render,
                        write_vtu=not args.no_vtu, convergence=args.convergence)


def _row(r) -> list[str]:
    w = r.worst
    case = Path(r.folder).name if r.folder else Path(r.source).stem
    if r.status == "error":
        first = r.message.splitlines()[0] if r.message else ""
        return [case, "-", "-", "ERROR", f"{r.seconds:.1f} s", first]
    return [case, w.name.removeprefix("criteria.") if w else "-", f"{100 * w.margin:+.1f} %" if w else "-", r.status.upper(),
            f"{r.seconds:.1f} s", ""]


HEADER = ["case", "worst criterion", "margin", "verdict", "time", "note"]


def format_plain(results) -> str:
    """Summary table as plain text (CI logs)."""
    rows = [HEADER] + [_row(r) for r in results]
    widths = [max(len(row[j]) for row in rows) for j in range(len(HEADER) - 1)]
    lines = []
    for row in rows:
        cells = [row[j].ljust(widths[j]) for j in range(len(widths))] + [row[-1]]
        lines.append("  ".join(cells).rstrip())
    return "\n".join(lines)


def _print_rich(results, console) -> None:
    from rich.table import Table

    t = Table(title="fe-crank check")
    for h in HEADER[:-1]:  # the error messages follow the table in full
        t.add_column(h, justify="right" if h in ("margin", "time") else "left", no_wrap=h != "case")
    style = {"pass": "green", "fail": "red", "error": "magenta"}
    for r in results:
        row = _row(r)[:-1]
        row[3] = f"[{style[r.status]}]{row[3]}[/]"
        t.add_row(*row)
    console.print(t)


def run(args) -> int:
    from fe_crank.check import batch_exit_code, find_loadcases, run_cases

    if args.jobs < 1:
        raise InputError("must be at least 1", key="--jobs")
    options = _options(args)
    paths = find_loadcases(args.paths)
    if not paths:
        raise InputError("no load-case files (*.toml with an [operating] table) found in "
                         + ", ".join(map(str, args.paths)))
    tty = sys.stdout.isatty()
    t0 = time.perf_counter()
    if tty:
        results = _run_with_progress(paths, args, options)
    else:
        results = run_cases(paths, args.output, options, jobs=args.jobs, scheduler=args.dask_scheduler)
    if args.junit:
        from fe_crank.report.junit import write_junit

        write_junit(args.junit, results)
    if tty:
        from rich.console import Console

        _print_rich(results, Console())
    else:
        print(format_plain(results))
    code = batch_exit_code(results)
    n = {s: sum(r.status == s for r in results) for s in ("pass", "fail", "error")}
    print(f"{len(results)} case(s): {n['pass']} pass, {n['fail']} fail, {n['error']} error "
          f"in {time.perf_counter() - t0:.1f} s; reports in {args.output}/"
          + (f"; JUnit XML in {args.junit}" if args.junit else ""))
    for r in results:
        if r.status == "error":
            where = "" if r.source in r.message else f"{r.source}: "
            print(f"error: {where}{r.message}", file=sys.stderr)
    return code


def _run_with_progress(paths, args, options):
    """Run with a rich progress display (terminal only): one bar for the batch and,
    in a serial run, the stage each case is in."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    from fe_crank.check import run_cases

    with Progress(SpinnerColumn(), TextColumn("{task.description}"), BarColumn(), MofNCompleteColumn(),
                  TimeElapsedColumn(), transient=True) as progress:
        task = progress.add_task("checking", total=len(paths))

        def on_stage(path: str, stage: str) -> None:
            progress.update(task, description=f"{Path(path).stem}: {stage}")

        def on_result(r) -> None:
            progress.advance(task)

        return run_cases(paths, args.output, options, jobs=args.jobs, scheduler=args.dask_scheduler,
                         on_result=on_result, on_stage=on_stage)
