"""Command line: ``fe-crank SUBCOMMAND ...``.

``main(argv=None) -> int`` never calls ``sys.exit`` itself and never shows a
traceback for an expected error.  Exit codes: 0 pass, 1 a criterion failed,
2 bad input or a failed computation.

Each subcommand is a module in this package with ``add_arguments(parser)`` and
``run(args) -> int``; ``COMMANDS`` lists them (name -> (module, one-line help)).
The modules are imported statically: one that cannot be imported is an error.
"""

from __future__ import annotations

import argparse
import sys
from types import ModuleType

from fe_crank import __version__
from fe_crank.cli import balance, check, dynamics, mesh, validate
from fe_crank.errors import FeCrankError

EXIT_PASS, EXIT_FAIL, EXIT_ERROR = 0, 1, 2

COMMANDS: dict[str, tuple[ModuleType, str]] = {
    "validate": (validate, "check input files (load cases, engines, geometries); exit 0 or 2"),
    "dynamics": (dynamics, "kinematics and dynamics over the cycle: table, JSON, plots"),
    "balance": (balance, "free forces/moments by order, counterweights, balance shafts"),
    "mesh": (mesh, "build and mesh a crank geometry (cached); statistics and a picture"),
    "check": (check, "run load cases end to end and give verdicts (CI check)"),
}


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="fe-crank",
        description="Finite-element crankshaft and counterweight stress checker.",
    )
    p.add_argument("--version", action="version", version=f"fe-crank {__version__}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")
    for name, (module, help_text) in COMMANDS.items():
        sp = sub.add_parser(name, help=help_text, description=help_text)
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
    try:
        return int(args._module.run(args))
    except FeCrankError as exc:
        print(f"fe-crank {args.command}: error: {exc}", file=sys.stderr)
        return EXIT_ERROR
    except KeyboardInterrupt:
        print("fe-crank: interrupted", file=sys.stderr)
        return 130


def entry() -> None:  # console-script entry point
    sys.exit(main())
