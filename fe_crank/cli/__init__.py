"""Command line: ``fe-crank SUBCOMMAND ...``.

``main(argv=None) -> int`` never calls ``sys.exit`` itself and never shows a
traceback for an expected error.  Exit codes: 0 pass, 1 a criterion failed,
2 bad input or a failed computation.

Each subcommand is a module in this package with ``add_arguments(parser)`` and
``run(args) -> int``; ``COMMANDS`` lists them (name -> (module, one-line help)).
The modules are imported statically: one that cannot be imported is an error.

One convention for every subcommand: no abbreviated options (``allow_abbrev=False``),
``-o/--output DIR`` (default ``reports/``) where files are written, ``--mesh-size`` and
``--cache-dir`` where meshes are made, ``-v/--verbose`` and ``-q/--quiet`` everywhere
(standard-library logging, ``fe_crank.logs``).
"""

from __future__ import annotations

import argparse
import sys
from types import ModuleType

from fe_crank.cli import balance, check, compare, dynamics, mesh, study, torsion, validate
from fe_crank.errors import FeCrankError
from fe_crank.logs import command_logging
from fe_crank.version import __version__

EXIT_PASS, EXIT_FAIL, EXIT_ERROR = 0, 1, 2

COMMANDS: dict[str, tuple[ModuleType, str]] = {
    "validate": (validate, "check input files (load cases, engines, geometries); exit 0 or 2"),
    "dynamics": (dynamics, "kinematics and dynamics over the cycle: table, JSON, plots"),
    "balance": (balance, "free forces/moments by order, counterweights, balance shafts"),
    "mesh": (mesh, "build and mesh a crank geometry (cached); statistics and a picture"),
    "torsion": (torsion, "torsional vibration of the crank train: modes, Campbell, forced response"),
    "check": (check, "run load cases end to end and give verdicts (CI check)"),
    "study": (study, "counterweight candidates (balance rate, placement) screened on the whole shaft"),
    "compare": (compare, "compare the numbers of two report folders of check; exit 0 equal, 1 different"),
}


def common_options() -> argparse.ArgumentParser:
    """The options every subcommand takes (an argparse parent parser)."""
    c = argparse.ArgumentParser(add_help=False, allow_abbrev=False)
    g = c.add_mutually_exclusive_group()
    g.add_argument(
        "-v", "--verbose", action="count", default=0, help="more log lines (-v: debug details); logs go to stderr"
    )
    g.add_argument("-q", "--quiet", action="store_true", help="log warnings and errors only")
    return c


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="fe-crank",
        description="Finite-element crankshaft and counterweight stress checker.",
        allow_abbrev=False,
    )
    p.add_argument("--version", action="version", version=f"fe-crank {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    for name, (module, help_text) in COMMANDS.items():
        sp = sub.add_parser(name, help=help_text, description=help_text, allow_abbrev=False, parents=[common_options()])
        module.add_arguments(sp)
        sp.set_defaults(_module=module)
    return p


def main(argv: list[str] | None = None) -> int:
    parser = _parser()
    try:
        args = parser.parse_args(argv)
    except SystemExit as exc:  # argparse exits on --help / usage errors
        return EXIT_PASS if exc.code in (0, None) else EXIT_ERROR
    if not getattr(args, "command", None):
        parser.print_help(sys.stderr)
        return EXIT_ERROR
    # logging set up for this command only: the caller's logging is as it was afterwards
    with command_logging(-1 if getattr(args, "quiet", False) else getattr(args, "verbose", 0)):
        _setup_process()
        try:
            return int(args._module.run(args))
        except FeCrankError as exc:
            print(f"fe-crank {args.command}: error: {exc}", file=sys.stderr)
            return EXIT_ERROR
        except KeyboardInterrupt:
            print("fe-crank: interrupted", file=sys.stderr)
            return 130


def _setup_process() -> None:
    """Process-wide settings belong to the application, not the library: VTK's own log
    kept to errors (no "bad X server connection" noise offscreen)."""
    try:
        from vtkmodules.vtkCommonCore import vtkLogger

        vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_ERROR)
    except ImportError:  # pragma: no cover - VTK comes with pyvista
        pass


def entry() -> None:  # console-script entry point
    sys.exit(main())
