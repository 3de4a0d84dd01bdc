"""One command-line convention across subcommands (fe_crank.cli): the same option
names for the same things, no abbreviations, -v/-q everywhere, logging lines in a pipe."""

from __future__ import annotations

import argparse
import io
import logging
import sys

import pytest

from fe_crank.cli import COMMANDS, _parser, main
from fe_crank.logs import command_logging, setup_logging

#: the one name of each shared option, and names that must not come back
CANONICAL = {"-o": "--output", "-v": "--verbose", "-q": "--quiet", "-j": "--jobs"}
SHARED = ("--output", "--mesh-size", "--cache-dir", "--no-render", "--no-plots", "--verbose", "--quiet")
FORBIDDEN = ("--out", "--size", "--outdir", "--output-dir", "--no-picture", "--mesh", "--cache")


def _subparsers() -> dict[str, argparse.ArgumentParser]:
    p = _parser()
    action = next(a for a in p._actions if isinstance(a, argparse._SubParsersAction))
    return dict(action.choices)


def _options(sp) -> dict[str, list[str]]:
    """dest -> option strings of a subcommand."""
    return {a.dest: list(a.option_strings) for a in sp._actions if a.option_strings}


def test_every_subcommand_is_there_and_refuses_abbreviations():
    subs = _subparsers()
    assert sorted(subs) == sorted(COMMANDS)
    assert _parser().allow_abbrev is False
    assert all(sp.allow_abbrev is False for sp in subs.values())


@pytest.mark.parametrize("name", sorted(COMMANDS))
def test_help_uses_the_same_option_names(name):
    sp = _subparsers()[name]
    strings = {s for ss in _options(sp).values() for s in ss}
    assert not strings & set(FORBIDDEN), f"{name}: a synonym of a shared option"
    for short, long in CANONICAL.items():  # a short flag always means the same long option
        for ss in _options(sp).values():
            if short in ss:
                assert long in ss, f"{name}: {short} is not {long}"
    assert {"-v", "--verbose", "-q", "--quiet"} <= strings
    help_text = sp.format_help()
    for opt in SHARED:
        if opt in strings:
            assert opt in help_text


def test_every_writing_subcommand_takes_output_with_the_same_default():
    for name, sp in _subparsers().items():
        acts = [a for a in sp._actions if "--output" in a.option_strings]
        if name in ("validate", "compare"):
            assert not acts  # writes nothing
            continue
        assert len(acts) == 1 and acts[0].option_strings == ["-o", "--output"], name
        assert str(acts[0].default) == "reports" and not acts[0].required, name


def test_mesh_options_are_named_alike_in_check_and_mesh():
    subs = _subparsers()
    for name in ("check", "mesh"):
        strings = {s for ss in _options(subs[name]).values() for s in ss}
        assert {"--mesh-size", "--cache-dir", "--no-render"} <= strings, name


def test_an_abbreviated_option_is_a_usage_error_not_a_guess(tmp_path, capsys):
    # "--job 2" was silently taken as "--jobs 2"
    assert main(["check", "--job", "2", str(tmp_path)]) == 2
    assert "unrecognized arguments: --job" in capsys.readouterr().err


def test_quiet_and_verbose_exclude_each_other(capsys):
    assert main(["validate", "-q", "-v", "x.toml"]) == 2


def test_plain_log_is_one_line_per_record_and_written_at_once():
    buf = io.StringIO()
    with command_logging(0, buf):
        logging.getLogger("fe_crank.pipeline.stages").info("%s: %s done in %.1f s", "case", "mesh", 1.25)
        assert buf.getvalue().count("\n") == 1  # already in the stream: no buffering until the batch ends
        line = buf.getvalue().strip()
        assert line.endswith("INFO case: mesh done in 1.2 s") and "\x1b[" not in line
        setup_logging(-1, buf)
        logging.getLogger("fe_crank.pipeline.stages").info("hidden")
        assert "hidden" not in buf.getvalue()


def test_ties_of_the_maximum_go_to_the_first_angle_whatever_the_last_digits():
    # two angles with the same peak up to 1e-13 relative (a solver's rounding): the
    # first is taken in both orders of magnitude of the difference, so serial and Dask
    # runs report the same angle; a real difference (1e-6) still wins
    import numpy as np

    from fe_crank.assess.group.assessment import first_extreme

    base = np.array([[1.0, 5.0], [3.0, 2.0], [3.0 * (1 + 1e-13), 2.0]])
    assert list(first_extreme(base, "max")) == [1, 0]
    base[1, 0] = 3.0 * (1 + 1e-13)
    base[2, 0] = 3.0
    assert list(first_extreme(base, "max")) == [1, 0]
    base[2, 0] = 3.0 * (1 + 1e-6)
    assert list(first_extreme(base, "max")) == [2, 0]
    assert first_extreme(np.array([2.0, 1.0, 1.0 + 1e-14]), "min") == 1


def test_the_top_level_api_survives_importing_the_check_package():
    import fe_crank
    import fe_crank.pipeline.batch
    import fe_crank.pipeline.case as case_module  # a submodule import still works

    assert callable(fe_crank.run_check) and case_module.run_case is fe_crank.pipeline.run_case
    assert callable(fe_crank.load_case)


def test_the_command_leaves_logging_as_it_found_it(monkeypatch):
    """``main`` sets logging up for its own run only: afterwards the ``fe_crank`` logger has
    the handlers, level and propagation it had, so no handler is left bound to a stream
    the caller has closed since (as pytest closes a test's captured stderr): a record
    logged later must not meet a closed file ("I/O operation on closed file")."""
    log = logging.getLogger("fe_crank")
    before = (list(log.handlers), log.level, log.propagate)
    err = io.StringIO()
    monkeypatch.setattr(sys, "stderr", err)
    assert main(["validate", "missing.toml"]) == 2
    assert "missing.toml: TOML file not found" in err.getvalue()
    err.close()
    assert (list(log.handlers), log.level, log.propagate) == before
    later = io.StringIO()
    monkeypatch.setattr(sys, "stderr", later)
    logging.getLogger("fe_crank.pipeline.stages").warning("a record after the command")
    assert "Logging error" not in later.getvalue()
