"""The candidates on the whole shaft: bearing loads and web moments by superposition.

The shaft of the load case is meshed and condensed once (``fe.shaft.model``) with every
web's counterweight as a centrifugal pattern of its own, and its unit cases solved once
on the determinate base (``fe.shaft.cases``) with a case ``cw_<web>@<throw>`` per web.
A candidate's counterweight on a web is the drawn one scaled in mass by k_w, so its
centrifugal load is k_w omega^2 times that case: per state of the engine (a speed of the
full-load curve, all cylinders firing or a misfire case; no load where the engine has a
gas table) the applied weights are those of the shaft without counterweights
(``fe.shaft.whole_shaft.shaft_cycle_of``, ``counterweights=False``) with the per-web cases
added, and the bearings' laws are solved again (``fe.shaft.cycle.solve_cycle``).  With
k_w = 1 on every drawn web this is the whole-shaft model's own "with counterweights"
cycle (the per-web patterns sum to ``centrifugal_cw``).

Web bending moments: the moment of every load in front of the web's mid-plane (as
``fe.shaft.cycle``): the shaft's without counterweights, plus the change of the bearing
forces, plus k_w times each counterweight's centrifugal force (a prism along z flush
with its web's outer face: the share of it in front of the mid-plane is its share of the
thickness).

Screened on the drawn shape's mesh: a counterweight of another shape or thickness (the
sector the candidate writes) changes the web's stiffness and the load's spread over the
web, which the full check of the written geometry takes (docs/study.md).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from fe_crank.fe.shaft.cases import ShaftCases, solve_cases
from fe_crank.fe.shaft.cycle import solve_cycle
from fe_crank.fe.shaft.model import ShaftFeOptions, build_shaft_model
from fe_crank.fe.shaft.whole_shaft import envelope_laws, shaft_cycle_of, throw_masses
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult, analyse
from fe_crank.mesh.shaft import mesh_shaft, rotation
from fe_crank.model import OperatingPoint
from fe_crank.study.candidates import DrawnWeb, Web


@dataclass(frozen=True)
class EngineState:
    label: str  # "full load", "misfire cyl. 2", "no load"
    speed: float  # rad/s
    dynamics: DynamicsResult


@dataclass
class StudyShaft:
    layout: ShaftLayout
    cases: ShaftCases
    mass: dict
    laws: list
    n_dof: int
    #: the law sets the main-bearing loads are enveloped over, the stated one first
    #: (``fe.shaft.whole_shaft.envelope_laws``: the check's main-bearing criteria take the same)
    law_sets: tuple = ()


@dataclass(frozen=True)
class StateLoads:
    """One candidate in one engine state: per bearing (n, 2) N on the bearing, engine
    frame; per web (n, 2) N m."""

    state: EngineState
    bearings: np.ndarray  # (n, nb, 2), the stated bearing law
    webs: np.ndarray  # (n, n_webs, 2), the stated bearing law
    #: (sets, n, nb, 2): every law set of ``StudyShaft.law_sets`` (the stated one first)
    bearing_sets: np.ndarray | None = None


def web_case(web: Web) -> str:
    return f"cw_{web[1]}@{web[0]}"


def study_shaft(layout: ShaftLayout, material, fe, *, size, cache_dir, max_elements=None) -> StudyShaft:
    """Mesh, condense and solve the unit cases once (module doc); ``fe``: the load case's
    ``[fe]`` options (solver, pin half-angle, symmetry)."""
    sm = mesh_shaft(layout, size=size, cache_dir=cache_dir, max_elements=max_elements)
    opt = ShaftFeOptions(
        solver=fe.solver, pin_half_angle=fe.pin_half_angle, symmetry=fe.symmetry, counterweight_webs=True
    )
    model = build_shaft_model(sm, material, opt)
    extra = {
        web_case((pp.throw, w)): {(pp.index, f"centrifugal_cw_{w}"): 1.0}
        for pp in model.pieces
        if pp.kind == "throw" and pp.throw is not None
        for w in (1, 2)
    }
    cases = solve_cases(model, extra)
    model.release_recovery()  # the study takes no stresses: the largest arrays go
    laws = [b.law for b in layout.bearings]
    return StudyShaft(layout, cases, throw_masses(layout), laws, sm.n_dof, envelope_laws(layout, laws))


def engine_states(engine, operating, cycles: EngineCycles) -> tuple[EngineState, ...]:
    """Every speed of the full-load curve, all cylinders firing and each misfire case, and
    the same speeds without gas load (inertia only) where the engine has a gas table."""
    out = []
    for sc in cycles.sweep:
        out.append(EngineState("full load", sc.speed, sc.firing))
        out.extend(EngineState(f"misfire cyl. {m.cylinder}", sc.speed, m.dynamics) for m in sc.misfire)
    if engine.gas is not None:
        step = cycles.operating.cycle / cycles.operating.theta.size
        bare = dataclasses.replace(engine, gas=None)
        out.extend(
            EngineState("no load", sc.speed, analyse(bare, OperatingPoint(sc.speed), step=step)) for sc in cycles.sweep
        )
    return tuple(out)


def _to_engine(v: np.ndarray, psi: np.ndarray) -> np.ndarray:
    """Shaft frame -> engine frame, the shaft turned by psi (from +y towards +x)."""
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([c * v[..., 0] + s * v[..., 1], -s * v[..., 0] + c * v[..., 1]], axis=-1)


def _moment(lever: float, F: np.ndarray) -> np.ndarray:
    return lever * np.stack([-F[..., 1], F[..., 0]], axis=-1)


@dataclass
class StateBase:
    """The shaft without counterweights in one state, kept for every candidate."""

    state: EngineState
    W: np.ndarray  # applied weights
    psi: np.ndarray
    bearings_off: np.ndarray  # (n, nb, 2) engine frame, on the bearing
    webs_off: np.ndarray  # (n, n_webs, 2)
    web_planes: tuple[float, ...]


def state_base(shaft: StudyShaft, state: EngineState) -> StateBase:
    layout = shaft.layout
    off = shaft_cycle_of(shaft.cases, layout, shaft.mass, state.dynamics, counterweights=False, laws=shaft.laws)
    first = layout.throws[0]
    psi = np.asarray(state.dynamics.throws[first.name].angle_global) - layout.sense * first.angle
    return StateBase(
        state,
        off.weights,
        psi,
        np.stack([b.load_n for b in off.bearings], axis=1),
        np.stack([w.bending_moment_nm for w in off.webs], axis=1),
        tuple(w.z for w in off.webs),
    )


def candidate_loads(
    shaft: StudyShaft, base: StateBase, factors: dict[Web, float], drawn: dict[Web, DrawnWeb]
) -> StateLoads:
    """Bearing loads and web moments of one candidate in one state (module doc)."""
    cases, layout = shaft.cases, shaft.layout
    w2 = base.state.speed**2
    W = base.W.copy()
    for web, k in factors.items():
        W[:, cases.index(web_case(web))] = k * w2
    f, _, _ = solve_cycle(cases, W, shaft.laws)
    bearings = _to_engine(-f, base.psi[:, None])
    sets = [bearings] + [_to_engine(-solve_cycle(cases, W, laws)[0], base.psi[:, None]) for laws in shaft.law_sets[1:]]
    # web moments: the change of the bearing forces and the counterweights' forces
    dF = -(bearings - base.bearings_off)  # forces on the shaft, engine frame
    g = layout.geometry
    zp, t = g.crankpin_length / 2, g.web_thickness
    cw_items = []
    for th in layout.throws:
        R = rotation(layout.sense * th.angle)[:2, :2]
        for cw in th.spec.counterweights:
            k = factors.get((th.name, cw.web), 0.0)
            if k == 0.0:
                continue
            u = np.asarray(drawn[(th.name, cw.web)].unbalance_vector)
            F = _to_engine(np.broadcast_to(k * w2 * (R @ u), base.psi.shape + (2,)), base.psi)
            z0, z1 = (
                (th.z - zp - t, th.z - zp - t + cw.thickness)
                if cw.web == 1
                else (th.z + zp + t - cw.thickness, th.z + zp + t)
            )
            cw_items.append((z0, z1, F))
    webs = base.webs_off.copy()
    zb = [b.z for b in layout.bearings]
    for i, zc in enumerate(base.web_planes):
        M = np.zeros_like(webs[:, i])
        for j, z in enumerate(zb):
            if z < zc:
                M += _moment(z - zc, dF[:, j])
        for z0, z1, F in cw_items:
            b_ = min(z1, zc)
            if b_ <= z0:
                continue
            M += _moment(0.5 * (z0 + b_) - zc, (b_ - z0) / (z1 - z0) * F)
        webs[:, i] += M
    return StateLoads(base.state, bearings, webs, np.stack(sets))
