"""JUnit XML for CI systems: one ``<testcase>`` per criterion of each load case.

Layout (the de-facto schema GitLab, Jenkins and GitHub reporters read)::

    <testsuites name="fe-crank" tests=.. failures=.. errors=.. time=..>
      <testsuite name="<case>" tests=.. failures=.. errors=.. time=..>
        <testcase classname="fe-crank.<case>" name="<criterion>" time="0">
          <failure message="margin -12.0 %: ...">...</failure>   (failed criterion)
        </testcase>
        <testcase classname="fe-crank.<case>" name="pipeline">
          <error message="...">...</error>                          (case that errored)
        </testcase>
      </testsuite>
    </testsuites>
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path
from typing import Sequence

from fe_crank.files import write_atomic
from fe_crank.results import STATUS_ERROR, CaseResult


def _criterion_text(c) -> str:
    from fe_crank.report.html import display

    (v, unit), (lim, _) = display(c.value, c.unit), display(c.limit, c.unit)
    unit = f" {unit}" if unit else ""
    loc = f" at {c.location}" if c.location else ""
    return f"{c.name}{loc}: value {v}{unit}, limit {lim}{unit}, margin {100 * c.margin:+.1f} %"


def junit_xml(results: Sequence[CaseResult]) -> str:
    """The JUnit XML document for a batch, as text."""
    root = ET.Element("testsuites", name="fe-crank")
    tot = {"tests": 0, "failures": 0, "errors": 0, "time": 0.0}
    for r in results:
        suite = ET.SubElement(root, "testsuite", name=r.name)
        n = f = e = 0
        ET.SubElement(ET.SubElement(suite, "properties"), "property", name="source", value=r.source)
        for c in r.criteria:
            tc = ET.SubElement(suite, "testcase", classname=f"fe-crank.{r.name}", name=c.name, time="0")
            n += 1
            if not c.passed:
                f += 1
                fail = ET.SubElement(tc, "failure", message=_criterion_text(c), type="criterion")
                fail.text = _criterion_text(c) + (f"\n{c.description}" if c.description else "")
            else:
                ET.SubElement(tc, "system-out").text = _criterion_text(c)
        if r.status == STATUS_ERROR:
            tc = ET.SubElement(
                suite, "testcase", classname=f"fe-crank.{r.name}", name="pipeline", time=f"{r.seconds:.3f}"
            )
            n += 1
            e += 1
            stage = f" (stage {r.error_stage})" if r.error_stage else ""
            err = ET.SubElement(tc, "error", message=r.message.splitlines()[0] if r.message else "error",
                                type=f"error{stage}")
            err.text = r.message
        suite.set("tests", str(n))
        suite.set("failures", str(f))
        suite.set("errors", str(e))
        suite.set("time", f"{r.seconds:.3f}")
        tot["tests"] += n
        tot["failures"] += f
        tot["errors"] += e
        tot["time"] += r.seconds
    for k, v in tot.items():
        root.set(k, f"{v:.3f}" if k == "time" else str(v))
    ET.indent(root)
    return '<?xml version="1.0" encoding="UTF-8"?>\n' + ET.tostring(root, encoding="unicode") + "\n"


def write_junit(path: str | Path, results: Sequence[CaseResult]) -> Path:
    """Write the JUnit XML atomically."""
    return write_atomic(path, junit_xml(results))
