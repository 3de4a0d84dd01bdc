"""Report sections built from the stages' outputs: (heading, builder) in page order.

A builder takes ``(folder, outputs, options)`` (``fe_crank.outputs.CaseOutputs``),
writes its pictures into ``folder`` and returns HTML fragments, or an empty list when
the stage it shows did not run (the page header then carries the error that stopped
it).  Pictures the stages already draw for their own commands are drawn by those same
functions; the FE renders and the ``.vtu`` fields by ``fe_crank.report.fe_pictures``;
the assessment's tables by ``fe_crank.report.tables``.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from fe_crank.balance.analysis import forces_table
from fe_crank.files import write_atomic
from fe_crank.outputs import CaseOutputs
from fe_crank.report.fe_pictures import fe_section
from fe_crank.report.html import Page, esc, table
from fe_crank.report.shaft import shaft_section
from fe_crank.report.stage_plots import dynamics_plots, plot_hodographs
from fe_crank.report.sweep import sweep_section
from fe_crank.report.tables import assessment_section, counterweight_section, mesh_quality_section
from fe_crank.report.torsion import html_fragment, quasi_static_note, result_to_dict


def _num(x, fmt="{:.3g}") -> str:
    return "-" if x is None or not np.isfinite(x) else fmt.format(x)


def dynamics_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Piston motion, forces per cylinder, torque and the crankpin polar diagram
    (drawn by ``fe_crank.report.stage_plots``, as for ``fe-crank dynamics``), with the cycle's key numbers."""
    if so.cycles is None:
        return []
    res = so.cycles.operating
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


def balance_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """Free forces and moments by source and order, hodographs, counterweight design."""
    res = so.balance
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


def torsion_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """The torsional section with its PNGs and ``torsion.json`` in the case folder, or the
    note that the check is quasi-static."""
    lc = so.loadcase
    if lc is None:
        return []
    if so.torsion is None:
        if lc.torsion is not None:
            return ["<p>The case stopped before the torsional stage.</p>"]
        return [quasi_static_note()]
    res = so.torsion.result
    data = {"load_case": lc.name, "source_file": lc.source_file, **result_to_dict(res)}
    write_atomic(Path(folder) / "torsion.json", json.dumps(data, indent=1, allow_nan=False).encode())
    return [html_fragment(res, Path(folder))]


#: (heading, builder) in page order
BUILDERS = [
    ("Kinematics, forces and torque", dynamics_section),
    ("Torsional vibration of the crank train", torsion_section),
    ("Balance: free forces, hodographs, counterweights", balance_section),
    ("Counterweights: required vs built m*r", counterweight_section),
    ("The full-load curve: criteria against speed", sweep_section),
    ("Stresses and safety factors by location", assessment_section),
    ("The whole shaft on its main bearings", shaft_section),
    ("Stress field renders", fe_section),
    ("Mesh statistics and FE quality", mesh_quality_section),
]
