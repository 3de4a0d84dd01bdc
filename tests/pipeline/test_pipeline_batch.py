"""Batch machinery of ``fe-crank check``: exit codes, JUnit XML, atomic case folders,
process-pool and Dask runs giving the same results as a serial run.

These tests use cases that stop early (bad input, missing geometry) so they run in
a fraction of a second; the end-to-end tests through the FE stack are in
``test_pipeline_e2e.py``.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.files import write_atomic
from fe_crank.pipeline import batch_exit_code, find_loadcases, run_case, run_cases
from fe_crank.records import CaseResult
from fe_crank.report.junit import junit_xml
from fe_crank.results import CriterionResult

DATA = Path(__file__).resolve().parents[1] / "data"
BROKEN = [DATA / "broken_units.toml", DATA / "broken_syntax.toml"]


def _comparable(r: CaseResult) -> tuple:
    """What must not depend on how a case ran (timings and folders may)."""
    return (r.name, Path(r.source).name, r.status, r.message, r.criteria, r.error_stage)


def test_broken_cases_exit_2_with_messages_naming_file_and_key(tmp_path, capsys):
    code = main(["check", *map(str, BROKEN), "-o", str(tmp_path / "r")])
    assert code == 2
    out, err = capsys.readouterr()
    assert "broken_units.toml: operating.speed" in err and "without a unit" in err
    assert "broken_syntax.toml: malformed TOML" in err
    assert "Traceback" not in out + err
    # one line per case in the summary, verdict ERROR; no progress bar or colour codes in a
    # log (stdout is not a terminal here)
    assert out.count("ERROR") == 2
    assert "\x1b[" not in out + err
    assert len(out.strip().splitlines()) == 1 + 2 + 1  # header, two cases, totals line
    for name in ("broken_units", "broken_syntax"):
        folder = tmp_path / "r" / name
        doc = json.loads((folder / "case.json").read_text())
        assert doc["status"] == "error" and doc["exit_code"] == 2 and doc["error_stage"] == "load"
        assert (folder / "report.html").read_text().count("ERROR") >= 1


def test_folder_discovery_takes_only_load_cases(tmp_path):
    (tmp_path / "engine.toml").write_text('name = "e"\nstrokes = 4\n')
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "case.toml").write_text('name = "c"\n[operating]\nspeed = "1 rpm"\n')
    (tmp_path / "bad.toml").write_text("name = [\n")  # unreadable: reported, not skipped
    found = [p.relative_to(tmp_path).as_posix() for p in find_loadcases([tmp_path])]
    assert found == ["bad.toml", "sub/case.toml"]


def test_missing_path_is_an_input_error(tmp_path, capsys):
    assert main(["check", str(tmp_path / "nope.toml")]) == 2
    assert "nope.toml: no such file or folder" in capsys.readouterr().err


def test_case_without_geometry_reports_the_stage_that_stopped_it(tmp_path):
    r = run_case(DATA / "early_stop_no_geometry.toml", tmp_path)
    assert r.status == "error" and r.exit_code == 2
    # either the stage is not built in this installation, or the geometry is missing
    assert ("not available" in r.message) or ("geometry" in r.message)
    assert r.error_stage == "geometry"  # the stage that needs the geometry file
    assert [t.stage for t in r.timings][0] == "load"


def _crit(name, margin):
    return CriterionResult(name=name, passed=margin >= 0, value=1.0 + margin, limit=1.0, margin=margin)


def test_junit_counts_criteria_failures_and_errors():
    ok = CaseResult("a", "a.toml", "pass", criteria=(_crit("fatigue pin fillet", 0.2), _crit("static", 0.5)))
    bad = CaseResult("b", "b.toml", "fail", criteria=(_crit("fatigue pin fillet", -0.1), _crit("static", 0.3)))
    err = CaseResult("c", "c.toml", "error", message="c.toml: operating.speed: no unit", error_stage="load")
    root = ET.fromstring(junit_xml([ok, bad, err]))
    assert root.tag == "testsuites"
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("5", "1", "1")
    suites = root.findall("testsuite")
    assert [s.get("name") for s in suites] == ["a", "b", "c"]
    failed = suites[1].findall("testcase/failure")
    assert len(failed) == 1 and "margin -10.0 %" in failed[0].get("message")
    assert suites[2].find("testcase/error").get("message") == "c.toml: operating.speed: no unit"
    assert batch_exit_code([ok]) == 0 and batch_exit_code([ok, bad]) == 1 and batch_exit_code([ok, bad, err]) == 2
    assert bad.worst.name == "fatigue pin fillet"


def test_junit_file_from_cli_parses(tmp_path):
    junit = tmp_path / "ci" / "junit.xml"
    assert main(["check", *map(str, BROKEN), "-o", str(tmp_path / "r"), "--junit", str(junit)]) == 2
    root = ET.parse(junit).getroot()
    assert root.get("errors") == "2" and len(root.findall("testsuite")) == 2


def test_write_atomic_leaves_old_file_when_writing_fails(tmp_path):
    target = tmp_path / "results.json"
    write_atomic(target, "old")

    class Boom:
        def __str__(self):  # pragma: no cover - never reached
            return "x"

    with pytest.raises(TypeError):
        write_atomic(target, Boom())  # not str/bytes: refused, the old file kept
    assert target.read_text() == "old"
    assert [p.name for p in tmp_path.iterdir()] == ["results.json"]


def test_rerun_replaces_a_case_folder_whole(tmp_path):
    run_case(BROKEN[0], tmp_path)
    (tmp_path / "broken_units" / "stale.png").write_bytes(b"old")
    run_case(BROKEN[0], tmp_path)
    assert not (tmp_path / "broken_units" / "stale.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["broken_units"]


def test_process_pool_gives_the_same_results_as_serial(tmp_path):
    cases = BROKEN + [DATA / "early_stop_no_geometry.toml"]
    serial = run_cases(cases, tmp_path / "s")
    pooled = run_cases(cases, tmp_path / "p", jobs=2)
    assert [_comparable(r) for r in serial] == [_comparable(r) for r in pooled]


def test_dask_local_cluster_gives_the_same_results_as_serial(tmp_path):
    import distributed  # dask[distributed] is a declared dependency

    cases = [BROKEN[0], DATA / "early_stop_no_geometry.toml"]
    serial = run_cases(cases, tmp_path / "s")
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        on_dask = run_cases(cases, tmp_path / "d", scheduler=cluster.scheduler_address)
    assert [_comparable(r) for r in serial] == [_comparable(r) for r in on_dask]
    assert (tmp_path / "d" / "broken_units" / "case.json").exists()


KILL_SCRIPT = textwrap.dedent(
    """
    import sys, time
    import fe_crank.report as rep
    real = rep.write_case_report

    def slow(folder, *a, **k):
        real(folder, *a, **k)          # every file of the report is written ...
        print("WRITTEN", flush=True)
        time.sleep(60)                 # ... but the case is not finished yet

    rep.write_case_report = slow
    from fe_crank.pipeline import run_cases
    run_cases(sys.argv[2:], sys.argv[1])
    """
)


def test_killed_run_leaves_no_partial_report(tmp_path):
    """SIGKILL while the second case is writing its report: the first case's folder
    is complete, the second case has no folder, only a hidden partial one that the
    next run removes."""
    out = tmp_path / "reports"
    script = tmp_path / "slow.py"
    script.write_text(KILL_SCRIPT)
    env = {**os.environ, "PYTHONUNBUFFERED": "1"}
    # first case runs normally (its own process, no slow hook), second one is slowed
    assert main(["check", str(BROKEN[0]), "-o", str(out)]) == 2
    proc = subprocess.Popen(
        [sys.executable, str(script), str(out), str(BROKEN[1])], stdout=subprocess.PIPE, text=True, env=env
    )
    try:
        line = proc.stdout.readline()
        assert line.strip() == "WRITTEN"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=20)
    finally:
        if proc.poll() is None:  # pragma: no cover
            proc.kill()
    visible = sorted(p.name for p in out.iterdir() if not p.name.startswith("."))
    assert visible == ["broken_units"]  # the killed case did not publish a folder
    hidden = [p for p in out.iterdir() if p.name.startswith(".broken_syntax.partial-")]
    assert len(hidden) == 1 and (hidden[0] / "report.html").exists()  # files were there, unpublished
    assert (out / "broken_units" / "case.json").exists()
    # the next run removes the dead run's partial folder and publishes the case
    run_cases([BROKEN[1]], out)
    assert sorted(p.name for p in out.iterdir()) == ["broken_syntax", "broken_units"]
