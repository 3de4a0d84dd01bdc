"""`fe-crank check` end to end through the real stack (gmsh, scikit-fem, pyvista
offscreen) on a small throw: a passing, a failing and a broken case in one batch."""

from __future__ import annotations

import json
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from helpers.images import image_statistics

from fe_crank.cli import main
from fe_crank.pipeline import CheckOptions, run_cases

pytestmark = pytest.mark.heavy  # two meshes' worth of FE solves and renders

DATA = Path(__file__).resolve().parents[1] / "data"
CASES = [DATA / "small_pass.toml", DATA / "failing_overspeed.toml", DATA / "broken_units.toml"]


@pytest.fixture(scope="module")
def batch(tmp_path_factory, mesh_cache):
    """The batch run once; its meshes go to the run's cache (the small throws' test meshes
    are the other tests' too) and serve the later runs here."""
    tmp = tmp_path_factory.mktemp("e2e")
    out, junit, cache = tmp / "reports", tmp / "junit.xml", mesh_cache
    code = main(
        [
            "check",
            *map(str, CASES),
            "-o",
            str(out),
            "--junit",
            str(junit),
            "--mesh-size",
            "test",
            "--cache-dir",
            str(cache),
        ]
    )
    return code, out, junit, cache


def test_exit_code_2_when_one_case_is_broken(batch):
    code, out, _, _ = batch
    assert code == 2
    status = {p.name: json.loads((p / "case.json").read_text())["status"] for p in out.iterdir()}
    assert status == {"small_pass": "pass", "failing_overspeed": "fail", "broken_units": "error"}


def test_exit_codes_0_and_1_without_the_broken_case(batch, tmp_path):
    _, _, _, cache = batch  # meshes cached by the batch
    common = ["--mesh-size", "test", "--cache-dir", str(cache), "--no-render", "--no-vtu"]
    assert main(["check", str(CASES[0]), "-o", str(tmp_path / "a"), *common]) == 0
    assert main(["check", str(CASES[0]), str(CASES[1]), "-o", str(tmp_path / "b"), *common]) == 1


def test_files_of_a_computed_case(batch):
    _, out, _, _ = batch
    folder = out / "small_pass"
    for name in (
        "results.json",
        "case.json",
        "report.html",
        "throw1.vtu",
        "throw1_von_mises.png",
        "throw1_hotspot.png",
        "throw1_overspeed.png",
        "crankpin_polar.png",
        "torque.png",
    ):
        assert (folder / name).is_file(), name
    assert not (out / "broken_units" / "results.json").exists()  # no assessment, no results document
    assert not [p for p in out.iterdir() if p.name.startswith(".")]  # no temporary left behind


def test_results_json_validates_against_the_schema(batch):
    import jsonschema  # a declared dependency: a failed import must fail the test

    from fe_crank.assess.results import load_schema

    _, out, _, _ = batch
    schema = load_schema()
    for case, passed in (("small_pass", True), ("failing_overspeed", False)):
        doc = json.loads((out / case / "results.json").read_text())
        jsonschema.validate(doc, schema)
        assert doc["passed"] is passed
        case_doc = json.loads((out / case / "case.json").read_text())
        assert [c["name"] for c in doc["criteria"]] == [c["name"] for c in case_doc["criteria"]]


def test_junit_counts_the_criteria(batch):
    _, out, junit, _ = batch
    root = ET.parse(junit).getroot()
    n_pass = len(json.loads((out / "small_pass" / "results.json").read_text())["criteria"])
    fail_doc = json.loads((out / "failing_overspeed" / "results.json").read_text())
    n_fail = len(fail_doc["criteria"])
    n_failed = sum(not c["passed"] for c in fail_doc["criteria"])
    assert n_pass == 3 and n_fail == 2 and n_failed >= 1
    assert int(root.get("tests")) == n_pass + n_fail + 1  # + the broken case's <error>
    assert int(root.get("failures")) == n_failed
    assert int(root.get("errors")) == 1
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    assert len(suites["small_pass"].findall("testcase")) == 3  # suite named after the file stem


def test_rendered_pictures_are_not_blank(batch):
    _, out, _, _ = batch
    for name in ("throw1_von_mises.png", "throw1_hotspot.png", "throw1_overspeed.png"):
        st = image_statistics(out / "small_pass" / name)
        assert st["coverage"] > 0.05 and st["std"] > 0.02 and st["colours"] > 100, name


def test_dask_local_cluster_gives_the_serial_results(batch, tmp_path):
    import distributed  # dask[distributed] is a declared dependency

    _, out, _, cache = batch
    opts = CheckOptions(mesh_size="test", cache_dir=str(cache), render=False, write_vtu=False)
    with distributed.LocalCluster(
        n_workers=1, threads_per_worker=1, processes=False, dashboard_address=None
    ) as cluster:
        on_dask = run_cases(CASES[:2], tmp_path / "d", opts, scheduler=cluster.scheduler_address)
    for r in on_dask:
        serial = json.loads((out / Path(r.source).stem / "case.json").read_text())
        assert r.status == serial["status"]
        assert [c.name for c in r.criteria] == [c["name"] for c in serial["criteria"]]
        assert [c.location for c in r.criteria] == [c["location"] for c in serial["criteria"]]
        for c, s in zip(r.criteria, serial["criteria"]):
            assert c.value == pytest.approx(s["value"], rel=1e-9)


def test_sigkill_during_the_computation_leaves_no_report(tmp_path):
    """Kill `fe-crank check` while it meshes or solves the real stack: the case has no
    published folder, only a hidden partial one without case.json."""
    import os
    import signal
    import subprocess
    import sys
    import time

    out = tmp_path / "reports"
    cmd = [
        sys.executable,
        "-c",
        "from fe_crank.cli import entry; entry()",
        "check",
        str(CASES[0]),
        "-o",
        str(out),
        "--mesh-size",
        "test",
        "--cache-dir",
        str(tmp_path / "cache"),
    ]
    proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env={**os.environ})
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and not (out.is_dir() and any(out.iterdir())):
            time.sleep(0.05)
        time.sleep(0.5)  # inside load/dynamics/mesh: the case takes several seconds
        assert proc.poll() is None, "the case finished before it could be interrupted"
        proc.send_signal(signal.SIGKILL)
        proc.wait(timeout=20)
    finally:
        if proc.poll() is None:  # pragma: no cover
            proc.kill()
    entries = list(out.iterdir())
    assert entries and all(p.name.startswith(".small_pass.partial-") for p in entries)
    assert not any((p / "case.json").exists() for p in entries)
