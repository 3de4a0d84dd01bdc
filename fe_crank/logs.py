"""Logging of the command line (standard library ``logging``).

Library modules only log (``logging.getLogger(__name__)``, names under ``fe_crank``);
the command line configures the output for the time of one command with
``command_logging`` (``setup_logging``, then the logger as it was):

* on a terminal: a ``rich`` handler (time, level, message);
* otherwise (a pipe, a CI log): one plain line per record,
  ``HH:MM:SS LEVEL message``, written and flushed as it happens, so a CI log shows
  each finished stage and case while the batch runs;
* ``-q`` warnings and errors only, default: one line per finished stage and case,
  ``-v`` debug details as well.
"""

from __future__ import annotations

import logging
import sys
from collections.abc import Iterator
from contextlib import contextmanager

LOGGER = "fe_crank"
PLAIN_FORMAT = "%(asctime)s %(levelname)s %(message)s"


def level_for(verbosity: int) -> int:
    """-1 (``-q``) -> WARNING, 0 -> INFO, >= 1 (``-v``) -> DEBUG."""
    if verbosity < 0:
        return logging.WARNING
    return logging.INFO if verbosity == 0 else logging.DEBUG


def setup_logging(verbosity: int = 0, stream=None, *, rich: bool | None = None) -> logging.Logger:
    """Configure the ``fe_crank`` logger for a command-line run and return it.

    ``stream`` defaults to ``sys.stderr``; ``rich`` defaults to "the stream is a
    terminal".  Replaces the handlers an earlier call installed (idempotent)."""
    stream = sys.stderr if stream is None else stream
    log = logging.getLogger(LOGGER)
    for h in list(log.handlers):
        if getattr(h, "_fe_crank", False):
            log.removeHandler(h)
    use_rich = stream.isatty() if rich is None and hasattr(stream, "isatty") else bool(rich)
    if use_rich:
        from rich.console import Console
        from rich.logging import RichHandler

        handler: logging.Handler = RichHandler(console=Console(file=stream), show_path=False, markup=False)
        handler.setFormatter(logging.Formatter("%(message)s", datefmt="%H:%M:%S"))
    else:
        handler = logging.StreamHandler(stream)
        handler.setFormatter(logging.Formatter(PLAIN_FORMAT, datefmt="%H:%M:%S"))
    handler._fe_crank = True  # type: ignore[attr-defined]
    log.addHandler(handler)
    log.setLevel(level_for(verbosity))
    log.propagate = False
    return log


@contextmanager
def command_logging(verbosity: int = 0, stream=None, *, rich: bool | None = None) -> Iterator[logging.Logger]:
    """``setup_logging`` for the time of one command (``fe_crank.cli.main``).

    On exit the ``fe_crank`` logger gets back the handlers, level and propagation it had,
    so that no handler outlives the command bound to a stream its caller may close since
    (a test's captured stderr, a notebook's redirected output): a record logged later
    would otherwise go to a closed file."""
    log = logging.getLogger(LOGGER)
    handlers, level, propagate = list(log.handlers), log.level, log.propagate
    try:
        yield setup_logging(verbosity, stream, rich=rich)
    finally:
        for h in list(log.handlers):
            log.removeHandler(h)
            if h not in handlers:
                h.close()
        for h in handlers:
            log.addHandler(h)
        log.setLevel(level)
        log.propagate = propagate
