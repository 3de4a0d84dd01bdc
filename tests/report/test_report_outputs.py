"""What a check writes, read back as a user's tools read it: the VTU in meshio, the
provenance in results.json (against the schema) and JUnit, a self-contained HTML,
log lines while the batch runs.  One real batch (gmsh, scikit-fem, pyvista offscreen)."""

from __future__ import annotations

import hashlib
import io
import json
import re
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

import fe_crank
from fe_crank.logs import command_logging

pytestmark = pytest.mark.heavy

DATA = Path(__file__).resolve().parents[1] / "data"


@pytest.fixture(scope="module")
def run(tmp_path_factory, mesh_cache):
    tmp = tmp_path_factory.mktemp("outputs")
    # a case that stops after loading (no geometry) but has criteria: JUnit must still list them
    text = (DATA / "early_stop_no_geometry.toml").read_text()
    stop = tmp / "stops_with_criteria.toml"
    stop.write_text(
        text + '\n[material]\nname = "42CrMo4"\n\n[criteria]\nmin_static_safety = 1.5\nmin_fatigue_safety = 1.3\n'
    )
    log = io.StringIO()
    with command_logging(0, log):
        results = fe_crank.run_check(
            [DATA / "small_pass.toml", stop],
            tmp / "reports",
            mesh_size="test",
            cache_dir=mesh_cache,
            junit=tmp / "junit.xml",
        )
    return tmp, {Path(r.source).stem: r for r in results}, log.getvalue()


def _results(tmp):
    return json.loads((tmp / "reports" / "small_pass" / "results.json").read_text())


def test_vtu_has_quadratic_cells_and_the_criterion_peak(run):
    import meshio

    tmp, res, _ = run
    doc = _results(tmp)
    m = meshio.read(tmp / "reports" / "small_pass" / "throw1.vtu")
    assert [c.type for c in m.cells] == ["tetra10"]
    # every point is a node of a cell (linear cells from corners left 84 % of them unused)
    assert np.unique(m.cells[0].data).size == len(m.points)
    # static safety S = R_e / max von Mises over the cycle (docs/assessment.md): the
    # file's cycle maximum must give back the criterion's value
    crit = {c["name"]: c for c in doc["criteria"]}
    s = crit["criteria.min_static_safety"]["value"]
    ys = doc["material"]["yield_strength"]
    vm_cycle = m.point_data["max_von_mises_cycle_Pa"]
    assert np.nanmax(vm_cycle) == pytest.approx(ys / s, rel=1e-12)
    # the governing-angle field: its maximum over the drawn group is that group's peak
    groups = {g["max_von_mises"]["group"]: g for t in doc["throws"] for g in t["groups"]}
    angle = float(m.field_data["crank_angle_deg"][0])
    gid = {k.split(":", 1)[1]: int(v[0]) for k, v in m.field_data.items() if k.startswith("assessed_group:")}
    drawn = [
        g
        for g in groups.values()
        if g["max_von_mises"]["angle_deg"] is not None and abs(g["max_von_mises"]["angle_deg"] - angle) < 1e-9
    ]
    assert drawn
    for g in drawn:
        name = g["max_von_mises"]["group"]
        # superposition of the same unit fields in another order: equal to rounding
        # (1e-9 would catch a 1-degree angle slip, worth ~1e-3 here)
        got = m.point_data["von_mises_Pa"][m.point_data["assessed_group"] == gid[name]].max()
        assert got == pytest.approx(g["max_von_mises"]["value"], rel=1e-9)
    # overspeed field: the governing state of the overspeed check (tests/report/test_report_overspeed.py),
    # so over the assessed nodes it gives back the criterion's S = R_e / max sigma_v, to rounding
    s_os = crit["criteria.min_overspeed_safety"]["value"]
    vm_os = m.point_data["von_mises_overspeed_Pa"][m.point_data["assessed_group"] >= 0]
    assert np.nanmax(vm_os) == pytest.approx(ys / s_os, rel=1e-9)
    for name in (
        "displacement_m",
        "stress_Pa",
        "principal_1_Pa",
        "principal_3_Pa",
        "fatigue_amplitude_Pa",
        "fatigue_mean_Pa",
        "fatigue_safety",
        "boundary",
    ):
        assert name in m.point_data
    assert m.point_data["stress_Pa"].shape == (len(m.points), 6)
    assert "subdomain" in m.cell_data and any(k.startswith("subdomain:") for k in m.field_data)


def test_provenance_in_results_json_validates_and_hashes_the_inputs(run):
    import jsonschema

    from fe_crank.assess.results import load_schema

    tmp, _, _ = run
    doc = _results(tmp)
    jsonschema.validate(doc, load_schema())
    prov = doc["provenance"]
    assert prov["version"] == fe_crank.__version__ and prov["package"] == "fe-crank"
    assert prov["mesh"]["preset"] == "test" and prov["mesh"]["sign_off"] is False
    assert prov["solver"]["used"] and prov["support"][0]["support"] == "determinate"
    assert re.fullmatch(r"\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d\+00:00", prov["started"])
    # independent hash: sha256 over "<relative path>\0<bytes>" of the case and its geometry, sorted
    h = hashlib.sha256()
    for name in sorted(["geometry_small.toml", "small_pass.toml"]):
        h.update(name.encode() + b"\0" + (DATA / name).read_bytes())
    assert prov["input"]["sha256"] == h.hexdigest()
    texts = [w["text"] for w in doc["warnings"]]
    assert any(t.startswith("NOT A SIGN-OFF") for t in texts)


def test_html_is_self_contained_and_says_not_a_sign_off(run):
    tmp, _, _ = run
    html = (tmp / "reports" / "small_pass" / "report.html").read_text()
    srcs = re.findall(r'<img[^>]*\ssrc="([^"]*)"', html)
    assert len(srcs) >= 8 and all(s.startswith("data:image/png;base64,") for s in srcs)
    assert not re.search(r'(src|href)="(?!data:)[^"#]+"', html)  # nothing outside the file
    assert "NOT A SIGN-OFF (test mesh)" in html
    assert "input SHA-256" in html and fe_crank.__version__ in html


def _junit_problems(root) -> list[str]:
    """Rules of the common JUnit schema (the Jenkins/Ant XSD that CI reporters accept)."""
    bad = []
    num = re.compile(r"^\d+(\.\d+)?$")
    ts = re.compile(r"^\d{4}-\d\d-\d\dT\d\d:\d\d:\d\d$")  # xs:dateTime without zone
    if root.tag != "testsuites":
        bad.append("root")
    for s in root.findall("testsuite"):
        for a in ("name", "tests", "failures", "errors", "time", "timestamp", "hostname"):
            if not s.get(a):
                bad.append(f"testsuite {a}")
        if not ts.match(s.get("timestamp", "")):
            bad.append("timestamp")
        cases = s.findall("testcase")
        if int(s.get("tests")) != len(cases):
            bad.append("tests count")
        if int(s.get("failures")) != sum(len(c.findall("failure")) for c in cases):
            bad.append("failures count")
        if int(s.get("errors")) != sum(len(c.findall("error")) for c in cases):
            bad.append("errors count")
        for c in cases:
            if not (c.get("name") and c.get("classname") and num.match(c.get("time", ""))):
                bad.append("testcase attrs")
            if {ch.tag for ch in c} - {"failure", "error", "skipped", "system-out", "system-err"}:
                bad.append("testcase child")
    return bad


def test_junit_validates_with_times_classnames_and_errored_criteria(run):
    tmp, res, _ = run
    root = ET.parse(tmp / "junit.xml").getroot()
    assert _junit_problems(root) == []
    suites = {s.get("name"): s for s in root.findall("testsuite")}
    ok = suites["small_pass"]
    cases = ok.findall("testcase")
    assert all(float(c.get("time")) > 0 for c in cases)
    assert sum(float(c.get("time")) for c in cases) == pytest.approx(float(ok.get("time")), abs=0.002 * len(cases))
    assert {c.get("classname") for c in cases} == {"fe-crank.small_pass"}
    props = {p.get("name"): p.get("value") for p in ok.iter("property")}
    assert props["version"] == fe_crank.__version__ and props["mesh_preset"] == "test"
    assert props["input_sha256"] == _results(tmp)["provenance"]["input"]["sha256"]
    # the case that stopped: its two criteria are there, errored, plus the pipeline error
    stop = suites["stops_with_criteria"]
    names = {c.get("name"): c for c in stop.findall("testcase")}
    assert set(names) == {"criteria.min_static_safety", "criteria.min_fatigue_safety", "pipeline"}
    assert all(c.find("error") is not None for c in names.values())
    assert res["stops_with_criteria"].status == "error"


def test_log_has_a_line_per_finished_stage_and_case(run):
    _, _, log = run
    lines = log.splitlines()
    for stage in ("load", "dynamics", "balance", "mesh", "fe", "assess", "report"):
        assert any(re.search(rf"INFO small_pass: {stage} done in \d+\.\d s$", ln) for ln in lines), stage
    assert any(
        # the verdict line carries its remarks: a test mesh is not a sign-off
        re.search(
            r"INFO small_pass: PASS \(worst criteria\.\w+, margin [+-]\d+\.\d %\) in \d+\.\d s "
            r"\[not a sign-off: test mesh \(preset 'test'\).*\]$",
            ln,
        )
        for ln in lines
    )
    assert any("WARNING stops_with_criteria: ERROR" in ln for ln in lines)
