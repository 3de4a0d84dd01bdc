"""JUnit XML for CI systems: one ``<testcase>`` per criterion of each load case.

Layout (the common JUnit schema that Jenkins, GitLab and GitHub reporters read)::

    <testsuites name="fe-crank" tests=.. failures=.. errors=.. time=.. timestamp=..>
      <testsuite name="<case file stem>" tests=.. failures=.. errors=.. skipped="0"
                 time=.. timestamp=.. hostname=..>
        <properties> source, version, input_sha256, mesh_preset, sign_off, solver </properties>
        <testcase classname="fe-crank.<case file stem>" name="<criterion>" time="..">
          <failure message="..." type="criterion">...</failure>    (failed criterion)
          <error message="..." type="...">...</error>               (case that errored)
          <system-out>value, limit, margin; the warnings of this criterion</system-out>
        </testcase>
        <system-out>the warnings that concern the whole case</system-out>
      </testsuite>
    </testsuites>

``classname`` is the case file stem (letters, digits, ``_.-``), stable across runs
so CI keeps each criterion's history.  A case that errored lists every criterion of
its load case as an ``<error>`` test (plus ``pipeline`` carrying the message; only
``pipeline`` when the load case could not be read).  Times: the case's wall time
shared equally among its tests (the criteria come out of one computation), so the
tests add up to the suite time.
"""

from __future__ import annotations

import re
import socket
import xml.etree.ElementTree as ET
from collections.abc import Sequence
from pathlib import Path

from fe_crank.files import write_atomic
from fe_crank.records import CaseResult, now_utc
from fe_crank.results import STATUS_ERROR


def _criterion_text(c) -> str:
    from fe_crank.report.html import display

    (v, unit), (lim, _) = display(c.value, c.unit), display(c.limit, c.unit)
    unit = f" {unit}" if unit else ""
    loc = f" at {c.location}" if c.location else ""
    return f"{c.name}{loc}: value {v}{unit}, limit {lim}{unit}, margin {100 * c.margin:+.1f} %"


def classname(r: CaseResult) -> str:
    """``fe-crank.<file stem>``: no spaces or commas, the same whatever the case's title."""
    stem = Path(r.folder).name if r.folder else Path(r.source).stem
    return "fe-crank." + (re.sub(r"[^A-Za-z0-9_.-]+", "_", stem) or "case")


def _properties(suite, r: CaseResult) -> None:
    props = ET.SubElement(suite, "properties")
    prov = r.provenance
    items: list[tuple[str, str | None]] = [("source", r.source), ("started", r.started)]
    if prov is not None:
        items += [
            ("version", prov.version),
            ("input_sha256", prov.input.sha256),
            ("mesh_preset", prov.mesh.preset),
            ("sign_off", str(bool(prov.mesh.sign_off)).lower()),
            ("solver", ",".join(prov.solver.used) if prov.solver is not None else None),
        ]
    for name, value in items:
        if value not in (None, ""):
            ET.SubElement(props, "property", name=name, value=str(value))


def junit_xml(results: Sequence[CaseResult], *, hostname: str | None = None) -> str:
    """The JUnit XML document for a batch, as text."""
    host = hostname or socket.gethostname()
    root = ET.Element("testsuites", name="fe-crank")
    tot = {"tests": 0, "failures": 0, "errors": 0, "time": 0.0}
    for r in results:
        cls = classname(r)
        suite = ET.SubElement(root, "testsuite", name=cls.removeprefix("fe-crank."))
        _properties(suite, r)
        case_wide = "\n".join(f"warning: {w.display}" for w in r.warnings if not w.criteria)
        errored = r.status == STATUS_ERROR
        names = [c.name for c in r.criteria] if not errored or r.criteria else list(r.planned_criteria)
        n_tests = len(names) + (1 if errored else 0)
        each = f"{r.seconds / max(n_tests, 1):.3f}"
        n = f = e = 0
        by_name = {c.name: c for c in r.criteria}
        stage = f" (stage {r.error_stage})" if r.error_stage else ""
        first = r.message.splitlines()[0] if r.message else "error"
        for name in names:
            tc = ET.SubElement(suite, "testcase", classname=cls, name=name, time=each)
            n += 1
            c = by_name.get(name)
            if errored:
                e += 1
                err = ET.SubElement(tc, "error", message=f"not evaluated: {first}", type=f"error{stage}")
                err.text = r.message
            elif c is None:
                raise ValueError(f"criterion {name!r} is missing from the case's results")
            elif not c.passed:
                f += 1
                fail = ET.SubElement(tc, "failure", message=_criterion_text(c), type="criterion")
                fail.text = _criterion_text(c) + (f"\n{c.description}" if c.description else "")
            if c is not None:
                mine = "".join(f"\nwarning: {w.display}" for w in r.warnings if w.criteria and w.concerns(c.name))
                ET.SubElement(tc, "system-out").text = _criterion_text(c) + mine
        if errored:
            tc = ET.SubElement(suite, "testcase", classname=cls, name="pipeline", time=each)
            n += 1
            e += 1
            err = ET.SubElement(tc, "error", message=first, type=f"error{stage}")
            err.text = r.message
        if case_wide:  # the warnings of the whole case once, after its test cases (JUnit's order)
            ET.SubElement(suite, "system-out").text = case_wide
        suite.set("tests", str(n))
        suite.set("failures", str(f))
        suite.set("errors", str(e))
        suite.set("skipped", "0")
        suite.set("time", f"{r.seconds:.3f}")
        suite.set("timestamp", (r.started or "")[:19] or _now())
        suite.set("hostname", host)
        tot["tests"] += n
        tot["failures"] += f
        tot["errors"] += e
        tot["time"] += r.seconds
    for k, v in tot.items():
        root.set(k, f"{v:.3f}" if k == "time" else str(v))
    root.set("timestamp", min((r.started for r in results if r.started), default=_now())[:19])
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def _now() -> str:
    return now_utc()[:19]


def write_junit(path: str | Path, results: Sequence[CaseResult]) -> Path:
    """Write the JUnit XML atomically."""
    return write_atomic(path, junit_xml(results))
