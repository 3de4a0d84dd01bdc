"""The full-load curve in the report: every criterion that depends on speed against
speed with its limit (one picture each), the per-speed values in a table, and with
misfire cases which case and speed govern each shaft segment's torsional vibration."""

from __future__ import annotations

import math
from pathlib import Path

from fe_crank.mechanism.misfire import READING
from fe_crank.outputs import CaseOutputs
from fe_crank.report.html import Page, esc, table
from fe_crank.report.locations import location_text
from fe_crank.report.plots import plot_against_speed

RPM = 30.0 / math.pi


def _scale(unit: str) -> tuple[float, str]:
    if unit == "m":  # an oil film's thickness
        return 1e6, "um"
    return (1e-6, "MPa") if unit == "Pa" else (1.0, unit)


def sweep_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Empty unless the case has a full-load curve or misfire cases."""
    a = so.assessment
    if a is None:
        return []
    swept = [c for c in a.criteria if len(c.per_speed) > 1]
    out = []
    if swept:
        speeds = [p.speed_rpm for p in swept[0].per_speed]
        out.append(
            f"<p>Every criterion that depends on speed is evaluated at the {len(speeds)} speeds of the full-load "
            f"curve, {speeds[0]:.0f}-{speeds[-1]:.0f} rpm, on the same unit stresses (one FE solve); its verdict "
            "is its worst speed.  The tables by location below show the operating speed "
            f"({a.speed * RPM:.0f} rpm).</p>"
        )
        header = ["speed [rpm]"]
        columns, panels, captions = [], [], []
        for c in swept:
            k, unit = _scale(c.unit)
            short = c.name.split(".")[-1]
            values = [k * p.value for p in c.per_speed]
            raw = [p.value for p in c.per_speed]
            worst = raw.index(min(raw) if c.sense == "min" else max(raw))
            label = f"{short} [{unit}]" if unit else short
            panels.append((label, values, k * c.limit, worst))
            captions.append(
                f"{c.name} ({c.description}): limit {k * c.limit:.4g} {unit}, worst "
                f"{values[worst]:.4g} at {c.per_speed[worst].speed_rpm:.0f} rpm ({location_text(c.per_speed[worst].where)})"
            )
            header.append(label)
            columns.append(values)
        plot_against_speed(Path(folder) / "speed_criteria.png", speeds, panels)
        out.append(Page.figure("speed_criteria.png", "; ".join(captions)))
        rows = [[f"{w:.0f}"] + [f"{col[i]:.4g}" for col in columns] for i, w in enumerate(speeds)]
        out.append(table(header, rows, num_cols=set(range(len(header)))))
    if so.torsion is not None and so.torsion.misfire is not None:
        mis = so.torsion.misfire
        rows = []
        for seg in mis.firing.model.segment_names:
            g = mis.governing(seg)
            rows.append([seg, f"{g.m_tn:.4g}", f"{g.speed * RPM:.0f}", g.case])
        out.append(
            "<h3>Torsional vibration with misfire</h3>"
            f"<p>Misfire cases: {esc(', '.join(c.cylinder for c in mis.cases))} ({esc(READING)}; "
            f"motored: {esc(mis.cases[0].gas)}).  Per shaft segment the largest M_TN of all cases over the speed "
            "range, with the case and the speed that give it:</p>"
            + table(["segment", "M_TN [N m]", "speed [rpm]", "case"], rows, num_cols={1, 2})
        )
    return out
