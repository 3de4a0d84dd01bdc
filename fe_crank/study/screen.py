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
cycle (the per-web patterns sum to ``centrifugal_cw``).  With a ``[torsion]`` section the
shaft also has the check's torque-flow cases (``study_shaft``'s ``torque_flow``): every
journal carries its own torque in every state, and a candidate's operating firing state
takes its own torsional journal torques (``with_operating_dynamics``), as the check's whole
shaft.

Web bending moments: the moment of every load in front of the web's mid-plane (as
``fe.shaft.cycle``): the shaft's without counterweights, plus the change of the bearing
forces, plus k_w times each counterweight's centrifugal force (a prism along z flush
with its web's outer face: the share of it in front of the mid-plane is its share of the
thickness).

Stresses (``candidate_stresses``): each throw's unit stresses at its assessed nodes
(``assess.shaft.piece_unit_stresses``, the per-web counterweight cases among them) are
taken once; a candidate's history in a state is sum_c W_c(theta) S_c with its weights W
(the per-web cases at k_w omega^2, the redundant bearings' forces solved again), each
node group's extremes by the check's own search (``assess.group.extremes``).  One
candidate of a placement is the reference in each state (the placement's middle balance
rate, ``seed_references``; else the first candidate screened there): bounds of its
stresses at every assessed node from its history computed in single precision
(``assess.group.reference.single_reference_path``, the rounding bounded) bound every other candidate's
of that placement and state, whose history differs by a constant (its
counterweights' centrifugal cases) and the change of the redundant bearings' forces
(``reference_shift``); the searches take those bounds and skip the groups that cannot
reach the state's extremes found so far: the same values, at a fraction of the cost.
A group's reference is built only when its turn comes and it can reach them: until then
it is bounded by another placement's reference of the same state where one is built (the
same argument for any two histories of the same angles), and a group skipped by that
bound is never built (``candidate_stresses``, ``candidate_overspeed``).

Screened on the drawn shape's mesh: a counterweight of another shape or thickness (the
sector the candidate writes) changes the web's stiffness and the load's spread over the
web, which the full check of the written geometry takes (docs/study.md).
"""

from __future__ import annotations

import dataclasses
import heapq
import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.factors import factors, location_of
from fe_crank.assess.fatigue import NODE_BLOCK, fatigue_limits
from fe_crank.assess.group.assessment import fatigue_assessed, of_counterweight, section_diameter, sigma_add_applies
from fe_crank.assess.group.bounds import window_peak_bound
from fe_crank.assess.group.extremes import Running, Wanted, group_extremes
from fe_crank.assess.group.peak import group_peak
from fe_crank.assess.group.reference import (
    PathBounds,
    ReferenceBalls,
    abs_sum,
    group_units,
    is_translation,
    reference_bounds,
    reference_shift,
    single_reference_path,
)
from fe_crank.assess.shaft import piece_unit_stresses
from fe_crank.assess.superpose import UnitStresses
from fe_crank.assess.workers import run_blocks
from fe_crank.cad.source import mesh_source_shaft
from fe_crank.fe.shaft.cases import ShaftCases, solve_cases
from fe_crank.fe.shaft.cycle import solve_cycle
from fe_crank.fe.shaft.model import ShaftFeOptions, build_shaft_model
from fe_crank.fe.shaft.whole_shaft import envelope_laws, shaft_cycle_of, throw_masses, torque_flow_cases
from fe_crank.fe.throw.node_groups import group_kind
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult, analyse
from fe_crank.mesh.shaft import rotation
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
    #: per throw (name, the unit stresses of every case at its assessed nodes:
    #: ``assess.shaft.piece_unit_stresses``, the check's own), for the stress screening
    stresses: tuple[tuple[str, UnitStresses], ...] = ()
    #: per screened state (label, speed, the weights' shape) and (throw, group): the first
    #: screened candidate's stresses there (``assess.group.reference.single_reference_path``), what
    #: the later candidates' searches are bounded by (``candidate_stresses``)
    references: dict = dataclasses.field(default_factory=dict)
    #: per throw, sum_c |U_c| at its assessed nodes (``assess.group.reference.abs_sum``)
    abs_sums: dict = dataclasses.field(default_factory=dict)
    #: per (throw, group), its unit stresses in single precision
    #: (``assess.group.reference.group_units``), taken by its first reference for the others
    group_units: dict = dataclasses.field(default_factory=dict)
    #: per (reference weights, throw, group), the reference's Goodman balls
    #: (``assess.group.reference.ReferenceBalls``), kept for the candidates that are it
    #: translated (``_Bounds.translated``)
    balls: dict = dataclasses.field(default_factory=dict)


@dataclass(frozen=True)
class StateLoads:
    """One candidate in one engine state: per bearing (n, 2) N on the bearing, engine
    frame; per web (n, 2) N m."""

    state: EngineState
    bearings: np.ndarray  # (n, nb, 2), the stated bearing law
    webs: np.ndarray  # (n, n_webs, 2), the stated bearing law
    #: (sets, n, nb, 2): every law set of ``StudyShaft.law_sets`` (the stated one first)
    bearing_sets: np.ndarray | None = None
    #: (n, n_cases) the shaft's case weights of the stated law, the redundant bearings'
    #: forces filled in (``fe.shaft.cycle.solve_cycle``): the stresses by superposition
    weights: np.ndarray | None = None


def web_case(web: Web) -> str:
    return f"cw_{web[1]}@{web[0]}"


def study_shaft(
    layout: ShaftLayout,
    material,
    fe,
    *,
    size,
    cache_dir,
    max_elements=None,
    stresses: bool = True,
    torque_flow: bool = False,
) -> StudyShaft:
    """Mesh, condense and solve the unit cases once (module doc); ``fe``: the load case's
    ``[fe]`` options (solver, pin half-angle, symmetry); ``stresses``: keep each throw's
    unit stresses for the stress screening; ``torque_flow``: with the check's torque-flow
    cases (``fe.shaft.whole_shaft.torque_flow_cases``, as its whole shaft with [torsion]):
    every journal carries its own torque in every state (``shaft_cycle_of`` forms their
    weights from each state's journal torques).  Those cases are the drawn mesh's unit
    angular accelerations and front-face torque, loads of the mesh alone: the same for
    every candidate, whose counterweights enter only through the weights."""
    sm = mesh_source_shaft(layout.geometry, layout, size=size, cache_dir=cache_dir, max_elements=max_elements)
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
    if torque_flow:
        extra |= torque_flow_cases(model)
    cases = solve_cases(model, extra)
    units = tuple(
        (str(pp.throw), piece_unit_stresses(cases, k, material))
        for k, pp in enumerate(model.pieces)
        if pp.kind == "throw" and stresses
    )
    model.release_recovery()  # the unit stresses taken: the largest arrays go
    laws = [b.law for b in layout.bearings]
    return StudyShaft(layout, cases, throw_masses(layout), laws, sm.n_dof, envelope_laws(layout, laws), stresses=units)


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


def with_operating_dynamics(
    shaft: StudyShaft, bases: list[StateBase], operating: DynamicsResult, dynamics: DynamicsResult
) -> list[StateBase]:
    """``bases`` with the operating speed's firing state (the state whose dynamics is the
    dynamics stage's ``operating`` cycle) on ``dynamics`` instead: the operating cycle with
    a candidate's torsional journal torques (``torsion.stage.operating_dynamics``), as the
    check's whole shaft with [torsion] takes its operating cycle (``outputs.CaseOutputs
    .assessed_dynamics``)."""
    own = next(i for i, b in enumerate(bases) if b.state.dynamics is operating)
    out = list(bases)
    s = bases[own].state
    out[own] = state_base(shaft, EngineState(s.label, s.speed, dynamics))
    return out


def candidate_loads(
    shaft: StudyShaft,
    base: StateBase,
    factors: dict[Web, float],
    drawn: dict[Web, DrawnWeb],
    *,
    envelope: bool = True,
) -> StateLoads:
    """Bearing loads and web moments of one candidate in one state (module doc);
    ``envelope`` False: the stated law's alone (``bearing_sets`` that one)."""
    cases, layout = shaft.cases, shaft.layout
    w2 = base.state.speed**2
    W = base.W.copy()
    for web, k in factors.items():
        W[:, cases.index(web_case(web))] = k * w2
    f, _, W_full = solve_cycle(cases, W, shaft.laws)
    bearings = _to_engine(-f, base.psi[:, None])
    others = shaft.law_sets[1:] if envelope else ()
    sets = [bearings] + [_to_engine(-solve_cycle(cases, W, laws)[0], base.psi[:, None]) for laws in others]
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
    return StateLoads(base.state, bearings, webs, np.stack(sets), W_full)


def _placement(shaft: StudyShaft, weights: np.ndarray) -> tuple[int, ...]:
    """The per-web counterweight cases a history loads: candidates of one placement share
    a reference (``candidate_stresses``), the closest."""
    cols = [i for i, n in enumerate(shaft.cases.names) if n.startswith("cw_")]
    return tuple(i for i in cols if weights[0, i] != 0.0)


def _reference_key(shaft: StudyShaft, sl: StateLoads) -> tuple:
    assert sl.weights is not None
    return (sl.state.label, sl.state.speed, sl.weights.shape, _placement(shaft, sl.weights))


#: nodes per block of the fatigue search where a reference bounds it (tight bounds: few
#: nodes to evaluate)
REFERENCE_BLOCK = 32

#: the node groups of the shaft's own surfaces (their stress: the fillets' static and
#: fatigue safeties) and of the counterweight's transition to its web
SHAFT_KINDS = ("crankpin_fillet", "journal_fillet", "oil_bore", "crankpin")
COUNTERWEIGHT_KINDS = ("counterweight_fillet", "junction")


@dataclass(frozen=True)
class StressScreen:
    """One candidate's stresses over every screened state (Pa; safeties against the
    check's criteria, ``assess.group.extremes.group_extremes``): the shaft's surfaces
    (fillets, oil bore, crankpin) and the counterweights' fillets and junctions with
    their webs; ``*_where``: the throw, group, state and speed of the extreme."""

    shaft_peak: float  # largest von Mises over the cycle
    shaft_peak_where: str
    static_safety: float  # least yield / peak of the shaft's surfaces
    fatigue_safety: float | None  # least Goodman safety (None: no fatigue data)
    fatigue_where: str
    counterweight_peak: float  # largest von Mises at a counterweight's fillet or junction
    counterweight_where: str


def seed_references(shaft: StudyShaft, loads: list[StateLoads], overspeed: list[StateLoads] | None = None) -> None:
    """Take the history of ``loads`` (one candidate in every state; ``overspeed``: its
    overspeed cycles) as the reference of its placement in each state where none is set
    yet, in place of the first candidate screened there (``candidate_stresses``,
    ``candidate_overspeed``).  Any history of the same angles bounds any other
    (``assess.group.reference``), so the screened values are the same whichever history
    is the reference; the bounds are the tighter, and the searches the cheaper, the
    closer the reference lies to each candidate: the study takes the middle one of a
    placement's balance rates (``study.run``)."""
    for sl in loads:
        assert sl.weights is not None
        shaft.references.setdefault(_reference_key(shaft, sl), {}).setdefault("weights", sl.weights)
    if overspeed and shaft.stresses:
        W = np.vstack([sl.weights for sl in overspeed if sl.weights is not None])
        key = ("overspeed", W.shape, _placement(shaft, W))
        shaft.references.setdefault(key, {}).setdefault("weights", W)


def _other_references(shaft: StudyShaft, key: tuple) -> list[dict]:
    """The references of the same state (or overspeed cycles) and weights' shape as
    ``key`` but of another placement: what bounds a group whose own reference is not built
    (``candidate_stresses``)."""
    return [r for k, r in shaft.references.items() if k != key and k[:-1] == key[:-1]]


class _Bounds:
    """A history's bounds at one group's nodes from its own placement's reference, built
    when first needed (``candidate_stresses``): until then from another placement's
    reference of the same state where one holds the group (``cheap``), each as rigorous
    as the other (``assess.group.reference``'s argument holds for any two histories of
    the same angles)."""

    def __init__(self, shaft, refs, others, name, unit, weights, nodes, group, fatigue_values, shifts):
        self.shaft, self.refs, self.others, self.name, self.unit = shaft, refs, others, name, unit
        self.weights, self.nodes, self.group, self.fatigue_values, self.shifts = (
            weights,
            nodes,
            group,
            fatigue_values,
            shifts,
        )

    def _shift(self, ref_w: np.ndarray):
        k = (self.name, id(ref_w))
        if k not in self.shifts:
            # a translation's M takes every case that departs (``small`` 0): its exact shift
            small = 0.0 if self._translation(ref_w) else 1e-9
            shifted = reference_shift(ref_w, self.unit, self.weights, self.shaft.abs_sums[self.name], small)
            self.shifts[k] = (ref_w, shifted)
        return self.shifts[k][1]

    def _translation(self, ref_w: np.ndarray) -> bool:
        """``is_translation`` of this history against ``ref_w``, once per state (every
        group and throw of the state shares both)."""
        k = ("translation", id(ref_w))
        if k not in self.shifts:
            self.shifts[k] = (ref_w, is_translation(ref_w, self.weights))
        return bool(self.shifts[k][1])

    def translated(self) -> tuple[ReferenceBalls, np.ndarray] | None:
        """(the own reference's Goodman balls at the group's nodes, kept for the later
        candidates; M at the nodes) where this history is the reference's translated by a
        constant (``assess.group.reference.is_translation``), else None."""
        ref_w = self.refs["weights"]
        if not self.fatigue_values or not self._translation(ref_w):
            return None
        shifted = self._shift(ref_w)
        if shifted is None:
            return None
        key = (id(ref_w), self.name, self.group)  # ref_w: kept by ``shaft.references``
        if key not in self.shaft.balls:
            self.shaft.balls[key] = ReferenceBalls(self.unit, ref_w, self.nodes)
        return self.shaft.balls[key], shifted[0][:, self.nodes]

    def cheap(self):
        """Bounds from another placement's reference of the group, None without one."""
        for r in self.others:
            if (self.name, self.group) in r:
                shifted = self._shift(r["weights"])
                if shifted is not None:
                    return reference_bounds(r[(self.name, self.group)], *(a[:, self.nodes] for a in shifted))
        return None

    def own(self):
        """Bounds from the group's own reference (built now if not yet: ``shaft.references``
        keeps it for the later candidates); None where the histories' angles differ."""
        key = (self.name, self.group)
        ref_w = self.refs["weights"]
        if key not in self.refs:
            units = self.shaft.group_units.get(key)
            if units is None:
                units = self.shaft.group_units[key] = group_units(self.unit, self.nodes)
            self.refs[key] = single_reference_path(
                self.unit, ref_w, self.nodes, fatigue_values=self.fatigue_values, units=units
            )
        shifted = self._shift(ref_w)
        return None if shifted is None else reference_bounds(self.refs[key], *(a[:, self.nodes] for a in shifted))


def candidate_stresses(
    shaft: StudyShaft,
    loads: list[StateLoads],
    material,
    *,
    additional_bending: float = 0.0,
    diameters: tuple[float | None, float | None] = (None, None),
    fatigue: bool = True,
) -> StressScreen:
    """The candidate's stresses in every state (``loads``, their ``weights``):
    sigma(theta) = sum_c W_c(theta) S_c at each throw's assessed nodes, each group's
    extremes by the check's own search (``group_extremes``: the static peak, the least
    Goodman safety with the size and surface factors of ``diameters`` (pin, journal) and
    UR M53's sigma_add on the shaft fillets, as ``assess.shaft.assess_shaft_throws``;
    ``fatigue`` False: the static peaks alone, ``fatigue_safety`` None).

    Groups searched lazily: in each state the groups go in increasing lower bound of the
    least Goodman safety, then in decreasing upper bound of the peak, each by the best
    bounds at hand -- its own placement's reference (``single_reference_path``, built
    only when needed and kept), else another placement's reference of the same state --
    and a group whose bounds cannot reach the state's extremes found so far (its peak
    bound below the largest peak found, its safety bound above the least safety found:
    both strictly; its peak bound alone where its search finds no safety: a counterweight's
    group, a group not assessed for fatigue, or ``fatigue`` False) is neither built nor
    searched.  A group holding a reported value, or
    tying with it exactly, has bounds that reach it, so it is searched: each reported value
    and its place (the first of the throws and groups in their order holding it) are those
    of a search of every group: a group searched has its own placement's bounds, the
    search it has without the skipping, and the order of the groups changes only which
    of its nodes the search evaluates, not their values nor the group's own extremes
    (``assess.group.extremes``)."""
    crank_radius = shaft.layout.geometry.crank_radius
    limits = fatigue_limits(material) if fatigue else None
    best = {"shaft": (0.0, ""), "cw": (0.0, "")}
    static = math.inf
    fat: tuple[float, str] | None = None

    def screen_state(sl: StateLoads) -> tuple[str, list[tuple[str, str]], dict]:
        """One state's searched groups: (its place text, the groups in the throws' and
        groups' order, their extremes)."""
        assert sl.weights is not None
        theta = np.asarray(sl.state.dynamics.theta, float)
        running = Running()
        at = f"{sl.state.label} at {sl.state.speed * 30 / math.pi:.0f} rpm"
        key_ = _reference_key(shaft, sl)
        refs = shaft.references.setdefault(key_, {})
        refs.setdefault("weights", sl.weights)
        others = _other_references(shaft, key_)
        best_peak = {"shaft": -math.inf, "cw": -math.inf}
        items = []
        shifts: dict = {}
        for name, unit in shaft.stresses:
            if name not in shaft.abs_sums:
                shaft.abs_sums[name] = abs_sum(unit)
            for g in sorted(unit.groups):
                kind = group_kind(g)
                if not len(unit.groups[g]) or kind not in SHAFT_KINDS + COUNTERWEIGHT_KINDS:
                    continue
                nodes = np.asarray(unit.groups[g])
                fat_values = limits is not None and kind in SHAFT_KINDS and fatigue_assessed(g)
                add = additional_bending if sigma_add_applies(g) else 0.0
                kf = (
                    factors(material, section_diameter(g, *diameters), location_of(g)).product
                    if fat_values and fatigue
                    else 1.0
                )
                items.append(
                    (
                        name,
                        unit,
                        g,
                        add,
                        kf,
                        _Bounds(shaft, refs, others, name, unit, sl.weights, nodes, g, fat_values, shifts),
                    )
                )

        def reach(b: PathBounds | None, kf: float, add: float) -> tuple[float, float]:
            """(least lower bound of the Goodman safety, largest upper bound of the peak)."""
            lower = math.inf
            if fatigue and b is not None and b.amplitude is not None:
                assert limits is not None
                lower = float(b.goodman_lower(kf * limits.bending, limits.tensile, add).min())
            return lower, (math.inf if b is None else float(b.peak.max()))

        # best first: a group with only another placement's bounds is built when its turn
        # comes and those bounds can still reach the extremes, then queued again by its own
        heap = []
        for i, (name, _unit, g, add, kf, bd) in enumerate(items):
            own = (name, g) in refs
            b = bd.own() if own else bd.cheap()
            if b is None and not own:
                b, own = bd.own(), True
            lower, top = reach(b, kf, add)
            heap.append((lower, -top, i, own, b))
        heapq.heapify(heap)
        found = {}
        while heap:
            lower, top_, i, own, b = heapq.heappop(heap)
            name, unit, g, add, kf, bd = items[i]
            key = "shaft" if group_kind(g) in SHAFT_KINDS else "cw"
            if -top_ < best_peak[key] and (not bd.fatigue_values or lower > running.fatigue):
                continue  # cannot reach the state's extremes found so far (docstring)
            if not own:
                b = bd.own()
                lo2, top2 = reach(b, kf, add)
                heapq.heappush(heap, (max(lower, lo2), -min(-top_, top2), i, True, b))
                continue
            r = group_extremes(
                unit,
                g,
                sl.weights,
                theta,
                material,
                crank_radius=crank_radius,
                diameter=section_diameter(g, *diameters),
                wanted=Wanted(fatigue=fatigue and key == "shaft", gough_pollard=False),
                running=running,
                additional_bending=add,
                reference=b,
                block=NODE_BLOCK if b is None else REFERENCE_BLOCK,
                translated=bd.translated(),
            )
            best_peak[key] = max(best_peak[key], r.max_von_mises.value)
            found[(name, g)] = r
        return at, [(name, g) for name, _unit, g, *_ in items], found

    # the states on the assessment's threads (``assess.workers``): each its own references,
    # bounds and searches; reported in their order, as one after the other
    per_state: list = [None] * len(loads)

    def one(i: int, _scratch) -> None:
        per_state[i] = screen_state(loads[i])

    run_blocks(one, range(len(loads)))
    for at, order, found in per_state:
        for name, g in order:  # reported in the throws' and groups' order
            if (name, g) not in found:
                continue
            r = found[(name, g)]
            shaft_group = group_kind(g) in SHAFT_KINDS
            key = "shaft" if shaft_group else "cw"
            v = r.max_von_mises.value
            if v > best[key][0]:
                best[key] = (v, f"throw {name} {g}, {at}")
            if shaft_group:
                static = min(static, r.static_safety)
                if r.fatigue_safety is not None and (fat is None or r.fatigue_safety.value < fat[0]):
                    fat = (r.fatigue_safety.value, f"throw {name} {g}, {at}")
    return StressScreen(
        best["shaft"][0],
        best["shaft"][1],
        static,
        None if fat is None else fat[0],
        "" if fat is None else fat[1],
        best["cw"][0],
        best["cw"][1],
    )


#: more nodes than this in a group: its overspeed peak is searched in decreasing
#: ``window_peak_bound`` (``group_peak``'s default block of 128, four blocks)
OVERSPEED_WINDOW_MIN = 512


@dataclass(frozen=True)
class OverspeedScreen:
    """One candidate at the overspeed (Pa): the largest von Mises stress over the
    overspeed cycles of every assessed group of the shaft's throws, the least overspeed
    safety (yield over it, the check's ``overspeed_safety``; inf without a yield
    strength), the counterweights' fillets and junctions' largest (the check's
    ``counterweight_overspeed_stress``), and where each is."""

    peak: float
    peak_where: str
    safety: float
    counterweight_peak: float
    counterweight_where: str


def candidate_overspeed(shaft: StudyShaft, loads: list[StateLoads], material) -> OverspeedScreen | None:
    """The candidate's overspeed stresses (module doc) from its ``loads`` in each overspeed
    cycle (``candidate_loads`` of the overspeed states: their ``weights``); None without
    any.  Each group's peak is the check's (``group_peak`` over the cycles' weights stacked,
    ``assess_group``'s overspeed; its nodes searched in decreasing ``window_peak_bound``,
    the same peak), the safety the yield strength over it.  The groups go in decreasing
    upper bound of their peak (the best at hand: their own placement's reference, else
    another placement's, as ``candidate_stresses``); a group whose bound lies strictly
    below the largest peak found (and, for a counterweight's group, below the largest of
    the counterweights' groups found) can hold neither value nor tie with it and is
    neither built nor searched: the values and places are those of every group's peak."""
    if not loads or not shaft.stresses:
        return None
    W = np.vstack([sl.weights for sl in loads if sl.weights is not None])
    key_ = ("overspeed", W.shape, _placement(shaft, W))
    refs = shaft.references.setdefault(key_, {})
    refs.setdefault("weights", W)
    others = _other_references(shaft, key_)
    items = []
    shifts: dict = {}
    for name, unit in shaft.stresses:
        if name not in shaft.abs_sums:
            shaft.abs_sums[name] = abs_sum(unit)
        for g in sorted(unit.groups):
            nodes = np.asarray(unit.groups[g])
            if nodes.size:
                items.append(
                    (name, unit, g, nodes, _Bounds(shaft, refs, others, name, unit, W, nodes, g, False, shifts))
                )
    heap = []
    for i, (name, _unit, g, _nodes, bd) in enumerate(items):
        own = (name, g) in refs
        b = bd.own() if own else bd.cheap()
        if b is None and not own:
            b, own = bd.own(), True
        heap.append((-math.inf if b is None else -float(b.peak.max()), i, own, b))
    heapq.heapify(heap)
    peaks: dict = {}
    top_all = top_cw = -math.inf
    while heap:
        top_, i, own, b = heapq.heappop(heap)
        name, unit, g, nodes, bd = items[i]
        cw = of_counterweight(g)
        if -top_ < top_all and (not cw or -top_ < top_cw):
            continue  # cannot reach the largest peak found (docstring)
        if not own:
            b = bd.own()
            heapq.heappush(heap, (max(top_, -math.inf if b is None else -float(b.peak.max())), i, True, b))
            continue
        tight = None if b is None else b.peak
        if tight is None and nodes.size > OVERSPEED_WINDOW_MIN:
            tight = window_peak_bound(unit, W, nodes)
        _, vm, _ = group_peak(unit, W, nodes, bound=tight)
        v = float(vm.max())
        peaks[(name, g)] = v
        top_all = max(top_all, v)
        if cw:
            top_cw = max(top_cw, v)
    best = {"all": (0.0, ""), "cw": (0.0, "")}
    for name, _unit, g, _nodes, _bd in items:  # reported in the throws' and groups' order
        if (name, g) not in peaks:
            continue
        v = peaks[(name, g)]
        for key in ("all", "cw") if of_counterweight(g) else ("all",):
            if v > best[key][0]:
                best[key] = (v, f"throw {name} {g}")
    ys = material.yield_strength
    peak = best["all"][0]
    safety = ys / peak if (ys is not None and peak > 0) else math.inf
    return OverspeedScreen(peak, best["all"][1], safety, best["cw"][0], best["cw"][1])
