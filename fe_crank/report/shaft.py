"""The whole-shaft model in the report and in results.json (formatting only: every number
comes from the whole-shaft stage, ``fe_crank.pipeline.shaft_stage``, and the assessment,
``assess.shaft.ShaftAssessment``).

* ``shaft_results``: the ``whole_shaft`` object of results.json (per main bearing its load
  over the cycle with and without counterweights, per web its bending moment, the throws'
  group results, the governing state, the stage's timings);
* ``shaft_section``: the report's section: the model in words, the bearings' table, the
  criteria in both models, the polar diagram of every bearing with and without
  counterweights, the bars of peak and mean bearing load, the webs' bending moment over
  the cycle, the whole shaft drawn with its von Mises stress at the governing angle and
  its ``.vtu`` (quadratic cells).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fe_crank.assess.oil_film import film_json
from fe_crank.assess.results import group_json
from fe_crank.assess.shaft import ShaftAssessment
from fe_crank.outputs import CaseOutputs, WholeShaftOutput
from fe_crank.report.film import film_section
from fe_crank.report.html import Page, esc, table
from fe_crank.report.locations import location_text
from fe_crank.report.plots import figure, plot_bars, save


def shaft_results(ws: WholeShaftOutput, assessed: ShaftAssessment, fields_seconds: float | None = None) -> dict:
    """The ``whole_shaft`` object of results.json (schema ``$defs`` in results.schema.json):
    the stage's shaft ``ws``, its assessment ``assessed``; ``fields_seconds``: the time of
    the whole fields (None: not computed)."""
    doc = ws.result.to_dict()
    doc.pop("n_dof")
    doc = {"support_model": ws.result.support_model, "n_dof": ws.result.n_dof, **doc}
    doc["throws"] = [
        {"name": t.name, "n_angles": t.n_angles, "groups": [group_json(g) for g in t.groups]} for t in assessed.throws
    ]
    if assessed.sweep:  # the main-bearing criteria's speeds and load states
        doc["main_bearings_per_speed"] = [
            {
                "speed_rpm": st.speed * 30.0 / math.pi,
                "case": st.case,
                "bearings": [
                    {
                        "name": b.name,
                        "peak_n": b.with_counterweights.peak_n,
                        "peak_angle_deg": b.with_counterweights.peak_angle_deg,
                        "specific_load_pa": b.with_counterweights.specific_load_pa,
                        "peak_without_counterweights_n": b.without_counterweights.peak_n,
                    }
                    for b in st.bearings
                ],
            }
            for st in assessed.sweep
        ]
    if ws.film:  # the hydrodynamic bearings' oil film (assess.oil_film)
        doc["oil_film"] = film_json(ws.film)
    h = assessed.governing
    doc["governing"] = None if h is None else {"throw": h.throw, "group": h.group, "crank_angle_deg": h.angle_deg}
    timings = {**ws.result.timings, "assessment": assessed.seconds}
    if fields_seconds is not None:
        timings["fields"] = fields_seconds
    doc["timings_s"] = {k: float(v) for k, v in timings.items()}
    return doc


def _kn(x: float) -> str:
    return f"{x / 1e3:.3g}"


def _bearing_rows(ws: WholeShaftOutput) -> list[list[str]]:
    rows = []
    for b in ws.result.bearings:
        a, o = b.with_counterweights, b.without_counterweights
        rows.append(
            [
                esc(b.name),
                f"{a.z * 1e3:.1f}",
                _kn(a.peak_n),
                f"{a.peak_angle_deg:.0f}",
                _kn(a.mean_n),
                f"{a.specific_load_pa / 1e6:.3g}",
                _kn(o.peak_n),
                _kn(o.mean_n),
                f"{o.specific_load_pa / 1e6:.3g}",
                f"{(a.peak_n / o.peak_n - 1) * 100:+.0f} %" if o.peak_n > 0 else "-",
            ]
        )
    return rows


def _by_model_rows(so: CaseOutputs) -> list[list[str]]:
    a = so.assessment
    if a is None or not a.by_model:
        return []
    return [
        [esc(v.criterion), esc(v.model), f"{v.value:.4g}", esc(location_text(v.where)), "governs" if v.governs else ""]
        for v in a.by_model
    ]


def plot_bearing_polars(path: Path, ws: WholeShaftOutput) -> Path:
    """One polar diagram per main bearing (load on the bearing, engine frame, kN), with and
    without counterweights on the same axes."""
    bs = ws.result.bearings
    cols = min(len(bs), 4)
    rows = math.ceil(len(bs) / cols)
    fig = figure((3.1 * cols, 3.1 * rows))
    for k, b in enumerate(bs):
        ax = fig.add_subplot(rows, cols, k + 1)
        for loads, label, style in (
            (b.with_counterweights, "with counterweights", "-"),
            (b.without_counterweights, "without", "--"),
        ):
            f = loads.load_n / 1e3
            ax.plot(np.append(f[:, 0], f[0, 0]), np.append(f[:, 1], f[0, 1]), style, lw=1.2, label=label)
        ax.plot([0], [0], "k+")
        ax.set_aspect("equal", adjustable="datalim")
        ax.set_title(f"main bearing {b.name}", fontsize=9)
        ax.set_xlabel("F_x [kN]", fontsize=8)
        ax.set_ylabel("F_y [kN]", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, alpha=0.35)
        if k == 0:
            ax.legend(fontsize=7, loc="best")
    fig.tight_layout()
    return save(fig, path)


def plot_web_moments(path: Path, ws: WholeShaftOutput) -> Path:
    """|M| at every web's mid-plane over the cycle, with and without counterweights."""
    deg = ws.result.crank_angle_deg
    fig = figure((9.0, 3.6))
    axes = [fig.add_subplot(1, 2, i + 1) for i in range(2)]
    for ax, which, title in (
        (axes[0], "with_counterweights", "with counterweights"),
        (axes[1], "without_counterweights", "without counterweights"),
    ):
        for w in ws.result.webs:
            m = getattr(w, which).bending_moment_nm
            ax.plot(
                deg,
                np.hypot(m[:, 0], m[:, 1]),
                lw=1.0,
                label=f"throw {w.with_counterweights.throw} web {w.with_counterweights.web}",
            )
        ax.set_title(f"bending moment at the web centres, {title}", fontsize=9)
        ax.set_xlabel("crank angle [deg]")
        ax.set_ylabel("|M| [N m]")
        ax.grid(True, alpha=0.35)
    axes[0].legend(fontsize=6, ncol=2)
    fig.tight_layout()
    return save(fig, path)


def _picture(folder: Path, so: CaseOutputs, render: bool, vtu: bool) -> list[str]:
    from fe_crank.mesh.shaft import tet10
    from fe_crank.vtu_writer import quadratic_tet_mesh, write_vtu

    f = so.shaft_fields
    h = so.assessment.shaft.governing if so.assessment is not None and so.assessment.shaft is not None else None
    if f is None or h is None:
        return []
    mesh = quadratic_tet_mesh(
        f.mesh.doflocs,
        tet10(f.mesh),
        point_data={"displacement_m": f.displacement.T, "von_mises_Pa": f.von_mises},
    )
    out = []
    what = f"throw {h.throw}, {h.group}, crank angle {h.angle_deg:.0f} deg"
    if vtu:
        write_vtu(folder / "whole_shaft.vtu", mesh)
        out.append(
            "<p>Fields for ParaView: <code>whole_shaft.vtu</code> (the whole shaft's quadratic tetrahedra, shaft "
            f"frame; displacement and von Mises stress at the governing angle: {esc(what)}).</p>"
        )
    if render:
        from fe_crank.report import render as rd

        grid = rd.grid_of(mesh, {"von_mises_MPa": f.von_mises / 1e6})
        size = float(np.linalg.norm(np.ptp(f.mesh.doflocs, axis=1)))
        umax = float(np.max(np.linalg.norm(f.displacement, axis=0)))
        scale = rd.exaggeration_factor(umax, size, fraction=0.02)
        rd.render_field(
            folder / "whole_shaft_von_mises.png",
            grid,
            "von_mises_MPa",
            title="von Mises [MPa]",
            displacement="displacement_m",
            scale=scale,
            hotspot=f.mesh.doflocs[:, f.hotspot_node] + scale * f.displacement[:, f.hotspot_node],
            hotspot_label=f"largest {h.von_mises / 1e6:.4g} MPa",
            text=f"whole shaft at the governing angle: {what}; deformation x {scale:g}",
            window_size=(1400, 700),
        )
        out.append(
            Page.figure(
                "whole_shaft_von_mises.png",
                f"The whole shaft on its main bearings, von Mises stress at the angle of its largest value ({what})",
            )
        )
    return out


def shaft_section(folder: Path, so: CaseOutputs, options) -> list[str]:
    """The report's whole-shaft section (module doc); empty when the stage did not run."""
    ws = so.whole_shaft
    if ws is None:
        return []
    folder = Path(folder)
    render = options is None or options.render
    vtu = options is None or options.write_vtu
    lay = ws.layout
    parts = [
        f"<p>{esc(ws.result.support_model)}. {len(lay.throws)} throw(s) at their engine positions, "
        f"journal stubs of {lay.stub * 1e3:.4g} mm from the webs to the bearing centres"
        + ("" if lay.pitch is None else f" (pitch {lay.pitch * 1e3:.4g} mm)")
        + f"; {ws.result.n_dof:,} unknowns, condensed exactly onto the bearing-centre planes (docs/shaft.md). "
        "The per-throw model (UR M53's, statically determinate) is assessed beside it; each criterion takes "
        "the worse of the two.</p>",
        "<h3>main-bearing loads over the cycle</h3>",
        table(
            [
                "bearing",
                "z [mm]",
                "peak [kN]",
                "at [deg]",
                "mean [kN]",
                "specific [MPa]",
                "peak without cw [kN]",
                "mean without cw [kN]",
                "specific without cw [MPa]",
                "counterweights change the peak",
            ],
            _bearing_rows(ws),
            num_cols=set(range(1, 10)),
        ),
    ]
    rows = _by_model_rows(so)
    if rows:
        parts.append("<h3>criteria in both models</h3>")
        parts.append(table(["criterion", "model", "value", "where", ""], rows))
    if render:
        plot_bearing_polars(folder / "shaft_bearing_polar.png", ws)
        labels = [f"bearing {b.name}" for b in ws.result.bearings]
        plot_bars(
            folder / "shaft_bearing_loads.png",
            labels,
            {
                "peak, with cw": [b.with_counterweights.peak_n / 1e3 for b in ws.result.bearings],
                "peak, without": [b.without_counterweights.peak_n / 1e3 for b in ws.result.bearings],
                "mean, with cw": [b.with_counterweights.mean_n / 1e3 for b in ws.result.bearings],
                "mean, without": [b.without_counterweights.mean_n / 1e3 for b in ws.result.bearings],
            },
            ylabel="load [kN]",
            title="main-bearing load: peak and mean over the cycle",
        )
        plot_web_moments(folder / "shaft_web_moments.png", ws)
        parts += [
            Page.figure(
                "shaft_bearing_polar.png",
                "Polar diagrams of the main-bearing loads (force of the journal on the bearing, engine frame) "
                "with the counterweights as built and without them",
            ),
            Page.figure(
                "shaft_bearing_loads.png", "Peak and mean load of every main bearing, with and without counterweights"
            ),
            Page.figure("shaft_web_moments.png", "The shaft's bending moment at every web centre over the cycle"),
        ]
    return parts + film_section(folder, ws, render) + _picture(folder, so, render, vtu)
