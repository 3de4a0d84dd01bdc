"""Report sections built from stage outputs: (heading, builder) in page order.

A builder takes ``(folder, stage_out, options)``, writes its pictures into
``folder`` and returns HTML fragments, or an empty list when the stage it shows did
not run (the page header then carries the error that stopped it).  Pictures the
stages already draw for their own commands are drawn by those same functions; the
FE renders and the ``.vtu`` fields by ``fe_crank.report.fe_pictures``.
"""

from __future__ import annotations

import math
from dataclasses import fields as dc_fields
from dataclasses import is_dataclass
from pathlib import Path

import numpy as np

from fe_crank.balance.analysis import forces_table
from fe_crank.report.fe_pictures import fe_section
from fe_crank.report.fields import shared_models
from fe_crank.report.html import Page, esc, table
from fe_crank.report.plots import plot_bars
from fe_crank.report.quality import averaging
from fe_crank.report.stage_plots import dynamics_plots, plot_hodographs
from fe_crank.torsion.report import report_section as torsion_section


def _mpa(x) -> str:
    return "-" if x is None or not np.isfinite(x) else f"{x / 1e6:.1f}"


def _num(x, fmt="{:.3g}") -> str:
    return "-" if x is None or not np.isfinite(x) else fmt.format(x)


def _at(ext) -> str:
    """An extreme stress in MPa with the crank angle where it occurs."""
    if ext is None:
        return "-"
    return _mpa(ext.value) + ("" if ext.angle is None else f" at {math.degrees(ext.angle):.0f} deg")


def dynamics_section(folder: Path, so: dict, options) -> list[str]:
    """Piston motion, forces per cylinder, torque and the crankpin polar diagram
    (drawn by ``fe_crank.report.stage_plots``, as for ``fe-crank dynamics``), with the cycle's key numbers."""
    res = so.get("dynamics")
    if res is None:
        return []
    dynamics_plots(res, Path(folder))
    rows = [
        ["speed", f"{res.speed * 30 / math.pi:.0f} rpm"],
        ["mean indicated torque", f"{res.mean_torque:.1f} N m"],
        ["indicated power", f"{res.power / 1e3:.2f} kW"],
        ["torque non-uniformity (max - min) / mean", _num(res.torque_nonuniformity)],
    ]
    for name, t in res.throws.items():
        f = np.hypot(t.pin_force[:, 0], t.pin_force[:, 1])
        i = int(np.argmax(f))
        rows.append(
            [f"throw {name}: largest crankpin force", f"{f[i] / 1e3:.2f} kN at {math.degrees(res.theta[i]):.0f} deg"]
        )
    return [
        table(["quantity", "value"], rows),
        Page.figure("piston_motion.png", "Piston displacement, velocity and acceleration over the cycle"),
        Page.figure(
            "forces.png", "Gas, reciprocating inertia, tangential and radial force per cylinder" + gas_steps(res)
        ),
        Page.figure("torque.png", "Indicated torque and its mean"),
        Page.figure(
            "crankpin_polar.png",
            "Crankpin polar diagram: rod force on the pin in the throw frame (x tangential, y radial outward)",
        ),
    ]


def gas_steps(res, share: float = 0.1) -> str:
    """Caption text explaining a step in a cylinder's gas force (a change between two
    neighbouring angles above ``share`` of its peak): the pressure model drops there at
    once, e.g. the exhaust blow-down of the Wiebe cycle at bottom dead centre after
    firing (the exhaust valve is taken to open instantaneously)."""
    out = []
    for name, c in res.cylinders.items():
        g = np.asarray(c.gas, float)
        if g.size < 3 or not np.any(g):
            continue
        d = np.abs(np.diff(g))
        i = int(np.argmax(d))
        if d[i] > share * np.max(np.abs(g)):
            out.append(
                f"cylinder {name}: the gas force steps by {d[i] / 1e3:.3g} kN at "
                f"{math.degrees(res.theta[i + 1]):.0f} deg"
            )
    if not out:
        return ""
    return (
        "; " + ", ".join(out) + " (the cylinder pressure of the gas model changes there at once; in the Wiebe "
        "cycle this is the exhaust blow-down at bottom dead centre, the valve taken to open instantaneously)"
    )


def balance_section(folder: Path, so: dict, options) -> list[str]:
    """Free forces and moments by source and order, hodographs, counterweight design."""
    res = so.get("balance")
    if res is None:
        return []
    out = [
        f"<p>Free forces and couples at {res.speed * 30 / math.pi:.0f} rpm, by source and order "
        "(amplitudes of the hodograph ellipse: major / minor semi-axis).</p>"
    ]
    rows = [
        [
            r["source"],
            f"{r['order']:g}",
            _num(r["force_max"], "{:.4g}"),
            _num(r["force_min"], "{:.4g}"),
            r["force_kind"],
            _num(r["moment_max"], "{:.4g}"),
            _num(r["moment_min"], "{:.4g}"),
            r["moment_kind"],
        ]
        for r in forces_table(res.forces)
    ]
    out.append(
        table(
            ["source", "order", "F major [N]", "F minor [N]", "force", "M major [N m]", "M minor [N m]", "couple"],
            rows,
            num_cols={1, 2, 3, 5, 6},
        )
    )
    res_rows = [
        [f"{r['order']:g}", _num(r["force_max"], "{:.4g}"), _num(r["moment_max"], "{:.4g}")]
        for r in forces_table(res.residual)
        if r["source"] == "total"
    ]
    out.append(
        "<h3>Residual after counterweights and balance shafts</h3>"
        + table(["order", "F major [N]", "M major [N m]"], res_rows, num_cols={0, 1, 2})
    )
    st = res.design.strategy
    cw_rows = []
    for cw, sec in zip(res.design.counterweights, res.sectors):
        s = (
            "-"
            if sec is None
            else (
                f"r1 {sec.r_outer * 1e3:.1f}, r2 {sec.r_inner * 1e3:.1f}, b {sec.thickness * 1e3:.1f} mm, "
                f"{math.degrees(sec.angle):.0f} deg: {sec.mass:.3f} kg at {sec.centroid_radius * 1e3:.1f} mm"
            )
        )
        cw_rows.append(
            [cw.shaft, f"{cw.z * 1e3:.1f}", f"{cw.unbalance:.4g}", f"{math.degrees(cw.angle_on_shaft):.1f}", s]
        )
    out.append(
        f"<h3>Counterweights required</h3><p>strategy: rotating masses x {st.rotating_fraction:g}, "
        f"first-order reciprocating x {st.reciprocating_fraction:g}, couple {esc(st.couple)}</p>"
        + table(["shaft", "z [mm]", "m r [kg m]", "angle [deg]", "annular sector"], cw_rows, num_cols={1, 2, 3})
    )
    for p in plot_hodographs(res, Path(folder)):
        out.append(Page.figure(p.name, f"Hodographs of the free force and couple, {p.stem.replace('_', ' ')}"))
    return out


def counterweight_section(folder: Path, so: dict, options) -> list[str]:
    """Required vs built counterweight m*r (bars) and the counterweight checks."""
    a = so.get("assessment")
    checks = [(t.name, c) for t in getattr(a, "throws", ()) for c in t.counterweights]
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
    return [
        table(
            ["counterweight", "required m r [kg m]", "built m r [kg m]", "error", "bolt load [N]", "bolt utilisation"],
            rows,
            num_cols={1, 2, 3, 4, 5},
        ),
        Page.figure("counterweight_mr.png", "Counterweight m*r: required by the balance strategy vs built geometry"),
    ]


def assessment_section(folder: Path, so: dict, options) -> list[str]:
    """Per throw and group: peak stresses, static, overspeed and fatigue safety factors."""
    a = so.get("assessment")
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
                    "mean [MPa]",
                ],
                rows,
                num_cols=set(range(1, 10)),
            )
        )
        m53 = getattr(t, "m53", ())
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
            "<h3>Assumptions of the assessment</h3><ul>" + "".join(f"<li>{esc(n)}</li>" for n in a.notes) + "</ul>"
        )
    return out


#: (heading, builder) in page order; the FE pictures come from ``fe_section``.
BUILDERS: list = [
    ("Kinematics, forces and torque", dynamics_section),
    ("Balance: free forces, hodographs, counterweights", balance_section),
    ("Counterweights: required vs built m*r", counterweight_section),
    ("Stresses and safety factors by location", assessment_section),
]
BUILDERS.insert(1, ("Torsional vibration of the crank train", torsion_section))  # torsion stage


def mesh_quality_section(folder: Path, so: dict, options) -> list[str]:
    """Mesh statistics and FE quality indicators: DOF, solver, equilibrium error of
    every unit case, averaged vs unaveraged fillet stress (UR M53: within 5 %)."""
    units_by_key, meshes = so.get("units"), so.get("meshes") or {}
    if not units_by_key:
        return []
    out = []
    for keys, units in shared_models(units_by_key):
        throw = keys[0]
        m = units.mesh
        rows = [
            ["elements (quadratic tetrahedra)", m.t.shape[1]],
            ["nodes", units.points.shape[1]],
            ["degrees of freedom", units.n_dof],
            ["solver", getattr(units, "solver_description", units.solver)],
            ["support model", units.support_model],
        ]
        tm = meshes.get(throw)
        stats = getattr(tm, "stats", None)
        if stats is not None:
            items = (
                [(f.name, getattr(stats, f.name)) for f in dc_fields(stats)]
                if is_dataclass(stats)
                else list(dict(stats).items())
                if isinstance(stats, dict)
                else []
            )
            rows += [[f"mesh: {k}", v if not isinstance(v, float) else f"{v:.4g}"] for k, v in items]
        radii = getattr(tm, "fillet_radii", None) or {}
        rows += [[f"fillet radius {k}", f"{v * 1e3:.2f} mm"] for k, v in radii.items()]
        for name, c in units.cases.items():
            rows.append([f"equilibrium error, case {name}", f"{c.equilibrium_error:.2e}"])
        for k, v in (units.timings or {}).items():
            rows.append([f"time: {k}", f"{v:.2f} s"])
        for g, v in averaging(so).get(throw, {}).items():
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


BUILDERS += [
    ("Stress field renders", fe_section),
    ("Mesh statistics and FE quality", mesh_quality_section),
]
