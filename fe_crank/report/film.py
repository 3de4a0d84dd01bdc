"""The main bearings' oil film in the report (formatting only: the numbers are
``assess.oil_film``'s): the bearings' data, a table per bearing of its thinnest film and
peak pressure with and without counterweights, the minimum film thickness against speed
per bearing, and each bearing's orbit in the state of its thinnest film with the
clearance circle drawn."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fe_crank.assess.oil_film import FILM_MODEL, FilmState, governing_state
from fe_crank.outputs import WholeShaftOutput
from fe_crank.report.html import Page, esc, table
from fe_crank.report.plots import figure, save

RPM = 30.0 / math.pi


def plot_film_vs_speed(path: Path, states: tuple[FilmState, ...]) -> Path:
    """h_min (um) against speed per bearing (all cylinders firing; the worst load state
    at each speed), counterweights as built (solid) and without (dashed)."""
    fig = figure((7.5, 4.2))
    ax = fig.add_subplot(1, 1, 1)
    names = [b.name for b in states[0].bearings]
    speeds = sorted({s.speed for s in states})
    for k, name in enumerate(names):
        for which, style in (("with_counterweights", "-o"), ("without_counterweights", "--x")):
            h = [
                min(getattr(s.bearings[k], which).judged_min_film_m for s in states if s.speed == w) * 1e6
                for w in speeds
            ]
            label = f"bearing {name}" + ("" if which == "with_counterweights" else ", without cw")
            ax.plot(np.array(speeds) * RPM, h, style, ms=3, lw=1.1, label=label, color=f"C{k}")
    ax.set_xlabel("speed [rpm]")
    ax.set_ylabel("minimum oil film thickness [um]")
    ax.set_title("minimum oil film thickness per main bearing (worst load state at each speed)", fontsize=9)
    ax.grid(True, alpha=0.35)
    ax.legend(fontsize=6, ncol=2)
    fig.tight_layout()
    return save(fig, path)


def plot_orbits(path: Path, states: tuple[FilmState, ...]) -> Path:
    """Each bearing's journal orbit (um, engine frame) in the state of its thinnest film,
    with and without counterweights, inside its clearance circle."""
    n = len(states[0].bearings)
    cols = min(n, 4)
    rows = math.ceil(n / cols)
    fig = figure((3.2 * cols, 3.3 * rows))
    t = np.linspace(0, 2 * np.pi, 361)
    for k in range(n):
        st = governing_state(states, k)
        b = st.bearings[k]
        c = b.bearing.clearance * 1e6
        ax = fig.add_subplot(rows, cols, k + 1)
        ax.plot(c * np.cos(t), c * np.sin(t), "k-", lw=0.8, label="clearance")
        for o, label, style in ((b.with_counterweights, "with cw", "-"), (b.without_counterweights, "without", "--")):
            e = o.eps * c
            ax.plot(np.append(e[:, 0], e[0, 0]), np.append(e[:, 1], e[0, 1]), style, lw=1.1, label=label)
        ax.plot([0], [0], "k+")
        ax.set_aspect("equal")
        ax.set_title(f"bearing {b.name}, {st.speed * RPM:.0f} rpm, {st.case}", fontsize=8)
        ax.set_xlabel("x [um]", fontsize=8)
        ax.set_ylabel("y [um]", fontsize=8)
        ax.tick_params(labelsize=7)
        ax.grid(True, alpha=0.3)
        if k == 0:
            ax.legend(fontsize=6, loc="lower left")
    fig.tight_layout()
    return save(fig, path)


def _um(x: float | None) -> str:
    return "-" if x is None else f"{x * 1e6:.3g}"


def film_section(folder: Path, ws: WholeShaftOutput, render: bool) -> list[str]:
    """The report's oil-film part of the whole-shaft section (module doc); empty without
    a hydrodynamic bearing."""
    states = ws.film
    if not states:
        return []
    first = states[0].bearings
    data = [
        [
            esc(b.name),
            f"{b.bearing.diameter * 1e3:.4g}",
            f"{b.bearing.width * 1e3:.4g}",
            f"{b.bearing.clearance * 1e6:.4g}",
            esc(b.oil),
            esc(b.bearing.groove) + ("" if b.bearing.groove == "none" else f" ({b.bearing.groove_width * 1e3:.3g} mm)"),
            f"{b.bearing.land_width / b.bearing.diameter:.3g}",
        ]
        for b in first
    ]
    rows = []
    for k, b0 in enumerate(first):
        st = governing_state(states, k)
        b = st.bearings[k]
        a, o = b.with_counterweights, b.without_counterweights
        rows.append(
            [
                esc(b0.name),
                f"{st.speed * RPM:.0f} {esc(st.case)}",
                _um(a.min_film_m) + ("" if a.converged else " (not periodic)"),
                f"{a.min_film_angle_deg:.0f}",
                f"{a.max_eccentricity:.3f}",
                f"{max(s.bearings[k].with_counterweights.peak_pressure_pa for s in states) / 1e6:.3g}",
                _um(o.min_film_m) + ("" if o.converged else " (not periodic)"),
                f"{max(s.bearings[k].without_counterweights.peak_pressure_pa for s in states) / 1e6:.3g}",
                "-" if a.max_slope is None else f"{a.max_slope * 1e3:.3g}",
                _um(a.edge_misalignment_m),
                _um(a.min_edge_film_m),
            ]
        )
    parts = [
        "<h3>main bearings' oil film</h3>",
        f"<p>{esc(FILM_MODEL)}. The loads are the whole shaft's on its structural bearing law; the film's "
        "stiffness is not fed back. The journal's slope comes from the whole shaft's deflection; the edge film is "
        "the clearance less the tilted rigid journal's reach at the bearing's edges (docs/shaft.md). The limits are "
        "the load case's own, none is assumed: a minimum film is commonly set at the sum of the journal's and the "
        "lining's peak roughness after running in (the criterion of Trans. ASME 79 (1957) 1235, 'Predominant peak "
        "surface roughness: a criterion for minimum oil film thickness'), of the order of a micrometre for ground "
        "journals; a peak film pressure by the lining's fatigue strength from its supplier's data.</p>",
        table(["bearing", "d [mm]", "B [mm]", "c [um]", "oil", "groove", "land B/D"], data, num_cols={1, 2, 3, 6}),
        table(
            [
                "bearing",
                "thinnest film at [rpm, state]",
                "h_min [um]",
                "at [deg]",
                "eps_max",
                "peak pressure, all speeds [MPa]",
                "h_min without cw [um]",
                "peak pressure without cw [MPa]",
                "max slope [mrad]",
                "edge misalignment [um]",
                "edge film [um]",
            ],
            rows,
            num_cols=set(range(2, 11)),
        ),
    ]
    if render:
        plot_film_vs_speed(Path(folder) / "shaft_film_speed.png", states)
        plot_orbits(Path(folder) / "shaft_film_orbits.png", states)
        parts += [
            Page.figure(
                "shaft_film_speed.png",
                "Minimum oil film thickness of every hydrodynamic main bearing against speed, with the "
                "counterweights as built and without them",
            ),
            Page.figure(
                "shaft_film_orbits.png",
                "Journal orbits in the clearance circle, each bearing at the speed and load state of its thinnest film",
            ),
        ]
    return parts
