"""The assessment's tables in the case report: counterweights, stresses and safety
factors by location, mesh statistics and FE quality."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fe_crank.assess.case import shared_models
from fe_crank.assess.counterweight import balance_rate
from fe_crank.mesh.types import MeshStats
from fe_crank.outputs import CaseOutputs
from fe_crank.report.html import Page, esc, table
from fe_crank.report.joints import joint_table
from fe_crank.report.plots import plot_bars

#: mesh statistics shown, with how each is written
_STATS = (
    ("nodes", "nodes (linear mesh)", "{}"),
    ("elements", "elements", "{}"),
    ("p2_dofs", "P2 degrees of freedom", "{}"),
    ("min_quality", "min element quality (gmsh minSICN, 1 ideal)", "{:.3g}"),
    ("straightened", "curved elements made straight-sided", "{}"),
    ("min_jacobian_ratio", "min Jacobian ratio of the quadratic elements", "{:.3g}"),
    ("build_seconds", "meshing time [s]", "{:.1f}"),
)


def _mpa(x) -> str:
    return "-" if x is None or not np.isfinite(x) else f"{x / 1e6:.1f}"


def _num(x, fmt="{:.3g}") -> str:
    return "-" if x is None or not np.isfinite(x) else fmt.format(x)


def _at(ext) -> str:
    """An extreme stress in MPa with the crank angle where it occurs."""
    if ext is None:
        return "-"
    return _mpa(ext.value) + ("" if ext.angle is None else f" at {math.degrees(ext.angle):.0f} deg")


def mesh_stats_rows(stats: MeshStats) -> list[list[object]]:
    """The mesh statistics as rows, each with its unit (no Python reprs)."""
    rows: list[list[object]] = [[f"mesh: {label}", fmt.format(getattr(stats, name))] for name, label, fmt in _STATS]
    rows.append(["mesh: from the cache", "yes" if stats.from_cache else "no"])
    planes = {0: "x = 0", 1: "y = 0", 2: "z = 0"}
    rows.append(
        ["mesh: mirrored across", ", ".join(planes.get(a, str(a)) for a in stats.symmetry) or "- (meshed whole)"]
    )
    rows += [[f"mesh: longest edge on {g}", f"{h * 1e3:.2f} mm"] for g, h in stats.fillet_max_edge.items()]
    return rows


def counterweight_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Required vs built counterweight m*r (bars) and the counterweight checks."""
    a = so.assessment
    checks = [(t.name, c) for t in (a.throws if a is not None else ()) for c in t.counterweights]
    if not checks:
        return []
    labels = [f"throw {t}: {c.name.replace('counterweight_', 'cw ')}" for t, c in checks]
    built = [c.built_unbalance for _, c in checks]
    req = [c.required_unbalance if c.required_unbalance is not None else np.nan for _, c in checks]
    plot_bars(
        Path(folder) / "counterweight_mr.png",
        labels,
        {"required": req, "built": built},
        ylabel="m r [kg m]",
        title="Counterweight unbalance: required vs built",
    )
    rows = [
        [
            lab,
            _num(c.required_unbalance, "{:.4g}"),
            f"{c.built_unbalance:.4g}",
            "-"
            if c.unbalance_error is None
            else f"{100 * c.unbalance_error:.1f} %"
            + (" (!) more than 10 % off" if abs(c.unbalance_error) > 0.10 else ""),
            _num(c.bolt_load, "{:.4g}"),
            _num(c.bolt_utilisation),
        ]
        for lab, (_, c) in zip(labels, checks)
    ]
    rates = [(f"throw {t.name}", balance_rate(t.counterweights)) for t in a.throws] if a is not None else []
    rates.append(("shaft", balance_rate(c for _, c in checks)))
    return [
        table(
            ["counterweight", "required m r [kg m]", "built m r [kg m]", "error", "bolt load [N]", "bolt utilisation"],
            rows,
            num_cols={1, 2, 3, 4, 5},
        ),
        table(
            ["balance rate (built m r / required m r)", "rate"],
            [[name, _num(rate, "{:.3f}")] for name, rate in rates],
            num_cols={1},
        ),
        Page.figure("counterweight_mr.png", "Counterweight m*r: required by the balance strategy vs built geometry"),
    ] + ([joint_table(a.throws)] if a is not None and any(t.joints for t in a.throws) else [])


def assessment_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Per throw and group: peak stresses, static, overspeed and fatigue safety factors."""
    a = so.assessment
    if a is None:
        return []
    out = []
    for t in a.throws:
        rows = []
        for g in t.groups:
            rows.append(
                [
                    g.group,
                    g.n_nodes,
                    _at(g.max_von_mises),
                    _at(g.max_von_mises_overspeed),
                    _num(g.static_safety),
                    _num(g.overspeed_safety),
                    _num(g.fatigue_safety.value) if g.fatigue_safety else "-",
                    _num(g.gough_pollard_safety.value) if g.gough_pollard_safety else "-",
                    _mpa(g.amplitude_at_critical),
                    _mpa(g.additional_bending) if g.additional_bending else "-",
                    _mpa(g.mean_at_critical),
                ]
            )
        out.append(
            f"<h3>Throw {esc(t.name)} ({t.n_angles} crank angles)</h3>"
            + table(
                [
                    "group",
                    "nodes",
                    "max von Mises [MPa]",
                    "at overspeed [MPa]",
                    "static S",
                    "overspeed S",
                    "fatigue S (Goodman)",
                    "Gough-Pollard S",
                    "amplitude [MPa]",
                    "+ UR M53 sigma_add [MPa]",
                    "mean [MPa]",
                ],
                rows,
                num_cols=set(range(1, 11)),
            )
        )
        m53 = t.m53
        if m53:
            mrows = [
                [
                    f.fillet,
                    f.scf_source,
                    _num(f.scf_bending),
                    _num(f.scf_torsion),
                    _mpa(f.equivalent),
                    _mpa(f.fatigue_strength),
                    _num(f.acceptability),
                ]
                for f in m53
            ]
            out.append(
                "<h4>IACS UR M53</h4>"
                + table(
                    ["fillet", "SCF source", "alpha_B", "alpha_T", "sigma_V [MPa]", "sigma_DW [MPa]", "Q"],
                    mrows,
                    num_cols={2, 3, 4, 5, 6},
                )
            )
    if a.notes:
        out.append(
            "<h3>Assumptions of the assessment</h3><ul>"
            + "".join(f"<li>{esc(n.display)}</li>" for n in a.notes)
            + "</ul>"
        )
    return out


def mesh_quality_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Mesh statistics and FE quality indicators: DOF, solver, equilibrium error of
    every unit case, averaged vs unaveraged fillet stress (UR M53: within 5 %)."""
    units_by_key, meshes = so.unit_solutions, so.meshes.throws if so.meshes is not None else {}
    if not units_by_key:
        return []
    averaging = {st.keys[0]: st.averaging for st in (so.assessment.states if so.assessment is not None else ())}
    out = []
    for keys, unit_solutions in shared_models(units_by_key):
        throw = keys[0]
        m = unit_solutions.mesh
        rows: list[list[object]] = [
            ["elements (quadratic tetrahedra)", m.t.shape[1]],
            ["nodes", unit_solutions.points.shape[1]],
            ["degrees of freedom", unit_solutions.n_dof],
            ["solver", unit_solutions.solver_description],
            ["support model", unit_solutions.support_model],
        ]
        tm = meshes.get(throw)
        if tm is not None:
            rows += mesh_stats_rows(tm.stats)
            rows += [[f"fillet radius {k}", f"{v * 1e3:.2f} mm"] for k, v in tm.fillet_radii.items()]
        for name, c in unit_solutions.cases.items():
            rows.append([f"equilibrium error, case {name}", f"{c.equilibrium_error:.2e}"])
        for k, v in (unit_solutions.timings or {}).items():
            rows.append([f"time: {k}", f"{v:.2f} s"])
        for g, v in averaging.get(throw, {}).items():
            rows.append(
                [
                    f"unaveraged vs averaged von Mises at the {g} peak",
                    f"{100 * v:+.1f} %" + ("" if abs(v) <= 0.05 else " (above the 5 % of UR M53: refine the fillet)"),
                ]
            )
        out.append(
            f"<h3>{'Throws' if len(keys) > 1 else 'Throw'} {esc(', '.join(keys))}</h3>"
            + table(["quantity", "value"], rows)
        )
    return out
