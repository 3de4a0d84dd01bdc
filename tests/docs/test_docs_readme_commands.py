"""Every command the README shows, run as a new user would from a clone (or listed
below, with the reason, as the README says)."""

from __future__ import annotations

import re
import shlex
from pathlib import Path

import pytest

from fe_crank.cli import main

ROOT = Path(__file__).resolve().parents[2]

#: README commands this test does not run, and why (README, "Verification" says so too)
NOT_RUN = {
    "make demo": "runs fe-crank check loadcases/ itself (minutes); CI runs it",
    "make test": "runs this test suite",
    "pip install": "installation",
    "fe-crank check loadcases/": "the shipped cases (the batch: make demo; the worked example fails by design, exit 1)",
}


def readme_commands() -> list[str]:
    """Command lines of the README's code blocks (prompts, list markers, comments removed)."""
    text = (ROOT / "README.md").read_text()
    out = []
    for block in re.findall(r"```[a-z]*\n(.*?)```", text, flags=re.S):
        for line in block.splitlines():
            line = line.strip()
            line = re.sub(r"^(\$ |- run: |- )", "", line)
            line = line.split("  #")[0].split(" # ")[0].strip()
            line = line.replace(".venv/bin/fe-crank", "fe-crank")
            if line.startswith(("fe-crank ", "make ", "pip install")):
                out.append(line)
    return out


def _skipped(cmd: str) -> str | None:
    return next((why for prefix, why in NOT_RUN.items() if cmd.startswith(prefix)), None)


def test_the_readme_shows_commands_and_each_is_run_or_listed():
    cmds = readme_commands()
    assert len(cmds) >= 8
    run = [c for c in cmds if _skipped(c) is None]
    assert {c.split()[1] for c in run} >= {"validate", "dynamics", "balance", "mesh"}


@pytest.mark.parametrize("cmd", [c for c in readme_commands() if _skipped(c) is None])
def test_readme_command_runs(cmd, tmp_path, monkeypatch, mesh_cache):
    monkeypatch.chdir(ROOT)  # the README's paths are relative to a clone
    argv = shlex.split(cmd)[1:]
    if argv[0] != "validate" and "-o" not in argv:
        argv += ["-o", str(tmp_path / "out")]  # the default reports/ would land in the clone
    if argv[0] in ("mesh", "check"):
        argv += ["--cache-dir", str(mesh_cache)]  # the run's: its meshes are those of the other tests
    assert main(argv) == 0
