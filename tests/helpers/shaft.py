"""Round shafts of extruded pieces for the whole-shaft model's closed-form tests."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.fe.shaft.cases import solve_cases
from fe_crank.fe.shaft.cycle import solve_cycle
from fe_crank.fe.shaft.model import build_shaft_model
from fe_crank.geometry.shaft import MainBearing, ShaftLayout
from fe_crank.geometry.spec import BearingLaw
from fe_crank.mesh.extrude import extrude, round_disc
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.shaft import Piece, ShaftMesh


@dataclass(frozen=True)
class Steel:
    youngs_modulus: float = 210e9
    poisson_ratio: float = 0.3
    density: float = 7850.0


def round_shaft(spans: int, span: float, radius: float, *, layers: int = 40, size: float | None = None):
    """A uniform round shaft of ``spans`` equal spans on spans + 1 bearings (at the span
    ends), each span one extruded piece with bands ``front``/``rear`` (half a bearing's
    journal: one layer) and ``load`` (two layers round mid-span).  Returns the model."""
    disc = round_disc(radius, size or radius / 1.2)
    h = span / layers
    levels = np.linspace(0.0, span, layers + 1)
    bands = {"front": (0.0, h), "rear": (span - h, span), "load": (span / 2 - h, span / 2 + h)}
    mesh = extrude(disc, levels, bands)
    bearings = tuple(MainBearing(str(j + 1), j, j * span, h, BearingLaw(), thrust=j == spans) for j in range(spans + 1))
    layout = ShaftLayout(
        geometry=None,
        throws=(),
        journals=(),
        bearings=bearings,
        stub=h,
        pitch=span,
        sense=1,
        nose=None,
        flange=None,
        power_takeoff="rear",
        geometry_file="<test>",
        engine_file="<test>",
    )
    pieces = tuple(
        Piece(f"span {i + 1}", "end", "span", 0.0, i * span, None, (("front", i), ("rear", i + 1)))
        for i in range(spans)
    )
    sm = ShaftMesh(layout, {"span": mesh}, {}, pieces, 1, MeshOptions())
    return build_shaft_model(sm, Steel(), extra_surfaces={"span": ("load",)})


def point_loads(model, loads: dict[int, float]):
    """Cases for a force -P y (downwards) at mid-span of each span in ``loads`` (span -> P)."""
    span = model.mesh.layout.pitch
    extra = {}
    for i, P in loads.items():
        c = model.coupling(f"P{i}", (i + 0.5) * span, [(i, "load")])
        extra[f"P{i}"] = {k: -P * v for k, v in c.terms[1].items()}
    return solve_cases(model, extra)


def reactions(cases, laws=None):
    """Forces of the bearings on the shaft (n_bearings, 2) under all the extra loads at once."""
    W = np.zeros((1, len(cases.names)))
    for i, n in enumerate(cases.names):
        if n.startswith("P"):
            W[0, i] = 1.0
    laws = laws or [b.law for b in cases.model.mesh.layout.bearings]
    f, d, _ = solve_cycle(cases, W, laws)
    return f[0], d[0]


def three_moment(spans: int, span: float, loads: dict[int, float]) -> np.ndarray:
    """Support reactions (upwards) of a continuous beam of equal spans, EI constant, with
    point loads P_i (downwards) at mid-span, simply supported ends: Clapeyron's three-moment
    equation M_(i-1) + 4 M_i + M_(i+1) = -(3/8) L (P_i + P_(i+1)) for equal spans and
    mid-span loads (Timoshenko, Strength of Materials I, art. 58), then the reactions
    from the span's statics."""
    n = spans
    P = np.array([loads.get(i, 0.0) for i in range(n)])
    M = np.zeros(n + 1)
    if n > 1:
        A = np.zeros((n - 1, n - 1))
        b = np.zeros(n - 1)
        for i in range(1, n):
            A[i - 1, i - 1] = 4.0
            if i > 1:
                A[i - 1, i - 2] = 1.0
            if i < n - 1:
                A[i - 1, i] = 1.0
            b[i - 1] = -(3.0 / 8.0) * span * (P[i - 1] + P[i])
        M[1:n] = np.linalg.solve(A, b)
    R = np.zeros(n + 1)
    for i in range(n):  # span i between supports i and i+1; M sagging positive (hogging < 0)
        R[i] += P[i] / 2 + (M[i + 1] - M[i]) / span
        R[i + 1] += P[i] / 2 + (M[i] - M[i + 1]) / span
    return R


def small_engine(angles, pitch: float = 0.06, crank_radius: float = 0.02, names=None, sense: int = 1):
    """An inline engine with one cylinder per throw at ``angles`` (rad), ``pitch`` apart
    and centred on z = 0, four-stroke, even firing: the throws' inertia loads only;
    ``sense``: the shaft's direction of rotation."""
    from fe_crank import model

    n = len(angles)
    names = names or [str(i + 1) for i in range(n)]
    z0 = -0.5 * pitch * (n - 1)
    throws = tuple(model.Throw(names[i], "main", a, crank_radius, z0 + i * pitch, 0.2) for i, a in enumerate(angles))
    rod = model.Rod(0.08, 0.15, 0.02)
    cylinders = tuple(
        model.Cylinder(names[i], names[i], 0.04, rod, 0.12, 0.0, 0.0, 4 * np.pi * i / n) for i in range(n)
    )
    return model.Engine("small test engine", 4, (model.Shaft("main", sense=sense),), throws, cylinders)


def small_geometry(angles, counterweights: bool = True):
    """tests/data/geometry_small_shaft.toml with throws at ``angles`` (rad)."""
    import dataclasses
    from pathlib import Path

    from fe_crank.io.geometry import load_geometry

    g = load_geometry(Path(__file__).resolve().parents[1] / "data" / "geometry_small_shaft.toml")
    spec = g.throws[0]
    cws = spec.counterweights if counterweights else ()
    throws = tuple(
        dataclasses.replace(spec, name=str(i + 1), angle=a, counterweights=cws) for i, a in enumerate(angles)
    )
    return dataclasses.replace(g, throws=throws)
