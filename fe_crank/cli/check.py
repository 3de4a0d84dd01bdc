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
from fe_crank.notes import verdict_remarks


def add_arguments(p) -> None:
    p.add_argument(
        "paths",
        nargs="+",
        type=Path,
        metavar="PATH",
        help="load-case files, or folders searched for *.toml files with an [operating] table",
    )
    p.add_argument(
        "-o",
        "--output",
        type=Path,
        default=Path("reports"),
        metavar="DIR",
        help="folder for the per-case reports (default: reports/)",
    )
    p.add_argument("--junit", type=Path, metavar="FILE", help="also write JUnit XML (one test per criterion)")
    p.add_argument(
        "-j",
        "--jobs",
        type=int,
        default=1,
        metavar="N",
        help="run cases in N local processes (default 1: in this process)",
    )
    p.add_argument(
        "--dask-scheduler",
        metavar="ADDRESS",
        help="run the cases on an existing Dask distributed cluster, e.g. tcp://10.0.0.5:8786",
    )
    p.add_argument(
        "--mesh-size",
        choices=tuple(PRESETS),
        default=None,
        help="mesh preset (default coarse: fillet elements <= r/4, IACS UR M53 guidance; "
        "test is for quick trials only)",
    )
    p.add_argument(
        "--cache-dir",
        default=str(DEFAULT_CACHE_DIR),
        metavar="DIR",
        help=f"mesh cache folder shared by every case and worker (default: {DEFAULT_CACHE_DIR}, relative "
        "to the working directory; resolved before cases are sent to processes or Dask workers)",
    )
    p.add_argument("--no-render", action="store_true", help="skip the pyvista pictures (faster)")
    p.add_argument("--no-vtu", action="store_true", help="do not write the .vtu result fields")
    p.add_argument(
        "--allow-outside-paths",
        action="store_true",
        help="let engine/geometry/CSV paths leave the load case's folder tree (refused by default)",
    )
    p.add_argument(
        "--max-elements",
        type=int,
        metavar="N",
        help="raise the limit on the estimated element count of a mesh (docs/limits.md)",
    )
    p.add_argument(
        "--convergence",
        action=argparse.BooleanOptionalAction,
        default=None,
        help="hot-spot convergence study: fillets meshed at r/4, r/6, r/8 (from the preset), "
        "peak change <= 5 %% (default: the load case's [mesh] convergence, on unless the mesh is test)",
    )


def _options(args):
    from fe_crank.pipeline import CheckOptions

    return CheckOptions(
        mesh_size=args.mesh_size,
        cache_dir=str(args.cache_dir),
        render=not args.no_render,
        write_vtu=not args.no_vtu,
        allow_outside_paths=args.allow_outside_paths,
        max_elements=args.max_elements,
        convergence=args.convergence,
    )


def _row(r) -> list[str]:
    w = r.worst
    case = Path(r.folder).name if r.folder else Path(r.source).stem
    if r.status == "error":
        first = r.message.splitlines()[0] if r.message else ""
        return [case, "-", "-", "ERROR", f"{r.seconds:.1f} s", first]
    return [
        case,
        w.name.removeprefix("criteria.") if w else "-",
        f"{100 * w.margin:+.1f} %" if w else "-",
        r.status.upper(),
        f"{r.seconds:.1f} s",
        verdict_remarks(r.warnings),
    ]


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
    for r in results:  # the verdict lines' remarks (not a sign-off, which criteria a warning concerns)
        row = _row(r)
        if r.status != "error" and row[-1]:
            console.print(f"{row[0]}: {row[-1]}", markup=False, highlight=False)


def run(args) -> int:
    from fe_crank.pipeline import batch_exit_code, find_loadcases, run_cases

    if args.jobs < 1:
        raise InputError("must be at least 1", key="--jobs")
    if args.max_elements is not None and args.max_elements < 1:
        raise InputError("must be at least 1", key="--max-elements")
    check_output_paths(args.output, args.junit)
    options = _options(args)
    paths = find_loadcases(args.paths)
    if not paths:
        raise InputError(
            "no load-case files (*.toml with an [operating] table) found in " + ", ".join(map(str, args.paths))
        )
    tty = sys.stdout.isatty()
    t0 = time.perf_counter()
    try:
        if tty:
            results = _run_with_progress(paths, args, options)
        else:
            results = run_cases(paths, args.output, options, jobs=args.jobs, scheduler=args.dask_scheduler)
    except OSError as exc:  # the output folder went away or became read-only during the run
        raise InputError(
            f"cannot write the reports: {exc.strerror or type(exc).__name__}", file=str(args.output), key="--output"
        ) from None
    if args.junit:
        from fe_crank.report.junit import write_junit

        try:
            write_junit(args.junit, results)
        except OSError as exc:
            raise InputError(
                f"cannot write the JUnit XML: {exc.strerror or type(exc).__name__}", file=str(args.junit), key="--junit"
            ) from None
    if tty:
        from rich.console import Console

        _print_rich(results, Console())
    else:
        print(format_plain(results))
    code = batch_exit_code(results)
    n = {s: sum(r.status == s for r in results) for s in ("pass", "fail", "error")}
    print(
        f"{len(results)} case(s): {n['pass']} pass, {n['fail']} fail, {n['error']} error "
        f"in {time.perf_counter() - t0:.1f} s; reports in {args.output}/"
        + (f"; JUnit XML in {args.junit}" if args.junit else "")
    )
    for r in results:
        if r.status == "error":
            where = "" if r.source in r.message else f"{r.source}: "
            print(f"error: {where}{r.message}", file=sys.stderr)
    return code


def check_output_paths(output: Path, junit: Path | None) -> None:
    """Refuse unusable output paths before any work starts: ``-o`` must be a folder
    that can be created and written (probed with a temporary file), ``--junit`` a
    file (not a folder) in a writable folder.  Raises InputError naming the option."""
    import os
    import tempfile

    def probe(folder: Path, key: str) -> None:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            fd, tmp = tempfile.mkstemp(prefix=".fe-crank-probe-", dir=folder)
            os.close(fd)
            os.unlink(tmp)
        except FileExistsError:
            raise InputError("is an existing file, expected a folder", file=str(folder), key=key) from None
        except NotADirectoryError:
            raise InputError("a part of the path is a file, expected folders", file=str(folder), key=key) from None
        except PermissionError:
            raise InputError("cannot write there: permission denied", file=str(folder), key=key) from None
        except OSError as exc:
            raise InputError(
                f"cannot write there: {exc.strerror or type(exc).__name__}", file=str(folder), key=key
            ) from None

    if output.exists() and not output.is_dir():
        raise InputError("is an existing file, expected a folder", file=str(output), key="--output")
    probe(output, "--output")
    if junit is not None:
        if junit.is_dir():
            raise InputError("is a folder, expected a file name", file=str(junit), key="--junit")
        probe(junit.parent if str(junit.parent) else Path("."), "--junit")
        if junit.exists() and not os.access(junit, os.W_OK):
            raise InputError("cannot write there: permission denied", file=str(junit), key="--junit")


def _run_with_progress(paths, args, options):
    """Run with a rich progress display (terminal only): one bar for the batch and,
    in a serial run, the stage each case is in."""
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, SpinnerColumn, TextColumn, TimeElapsedColumn

    from fe_crank.pipeline import run_cases

    with Progress(
        SpinnerColumn(),
        TextColumn("{task.description}"),
        BarColumn(),
        MofNCompleteColumn(),
        TimeElapsedColumn(),
        transient=True,
    ) as progress:
        task = progress.add_task("checking", total=len(paths))

        def on_stage(path: str, stage: str) -> None:
            progress.update(task, description=f"{Path(path).stem}: {stage}")

        def on_result(r) -> None:
            progress.advance(task)

        return run_cases(
            paths,
            args.output,
            options,
            jobs=args.jobs,
            scheduler=args.dask_scheduler,
            on_result=on_result,
            on_stage=on_stage,
        )
