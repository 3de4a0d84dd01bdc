"""The displacement states the report shows and the UR M53 averaging check reads, by
superposition of the FE unit cases with the assessment's own coefficients
(``fe_crank.assess.superpose``)::

    u(theta) = omega^2 u_c + sum_k a_k(F(theta)) u_pk - sense T(theta) / M_z u_t

Stress recovery is linear in u, so the stress of a state equals the assessment's
superposed unit stresses at every node: pictures, fields and tables agree.  The
displacement is kept in the frame of the supports (``fe.core.support_frame``: the main-bearing
centres at rest, the torque face not turning), the rigid motion of the determinate solve
removed: the report's VTU fields and deformed pictures show the deformation only.

Per FE model (one model may stand for several throws, ``fe_crank.throw_scope``):

* the hot spot (``critical``): the node with the lowest fatigue safety (static safety
  when there is no fatigue result) over the throws the model stands for, drawn at the
  crank angle of its group's largest von Mises;
* the governing overspeed state (``overspeed_state``): the group with the largest von
  Mises over the overspeed cycles, at the crank angle of that maximum, in the overspeed
  cycle (motored curve or zero gas) whose state reaches the table's value at its node;
* the UR M53 averaging indicator of each shaft fillet at the hot spot's angle
  (Appendix III 2.3: unaveraged vs averaged von Mises at the fillet's peak within 5 %).
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

import numpy as np

from fe_crank.assess.group.assessment import GroupResult
from fe_crank.assess.group.nodes import COUNTERWEIGHTS
from fe_crank.assess.loads import LoadState
from fe_crank.assess.superpose import UnitStresses, cycle_coefficients
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
from fe_crank.fe.core.support_frame import field_in_support_frame
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.throw_scope import throws_of

#: the shaft fillets whose averaging indicator is checked (UR M53 App. III 2.3)
FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2")


@dataclass(frozen=True)
class HotSpot:
    """Where and when the pictures look: the critical point of the assessment."""

    throw: str  # engine throw name
    group: str
    node: int
    point: tuple[float, float, float]
    angle: float | None  # rad: the crank angle drawn (None: no angle-bound result)
    what: str  # "fatigue" or "static"


@dataclass(frozen=True)
class OverspeedState:
    """The governing overspeed state of one FE model and the facts its picture states."""

    throw: str  # the throw whose overspeed cycle governs (of those the model stands for)
    group: str  # the governing group
    value: float  # Pa, the group's max von Mises over the overspeed cycle (the table's value)
    safety: float | None  # the group's overspeed safety R_e / value (the table's value)
    node: int  # mesh node of that maximum
    point: tuple[float, float, float]
    index: int  # cycle-angle index of theta*
    angle_deg: float  # theta*, degrees of the cycle
    speed: float  # omega_os, rad/s
    gas: str  # the gas load of the governing overspeed cycle, in words
    displacement: np.ndarray  # superposed displacement at theta*, flat DOF vector
    counterweights: tuple[GroupResult, ...] = ()  # the throw's counterweight group results (marked in the picture)
    stress: np.ndarray | None = None  # (6, n_nodes) averaged nodal stress of the state, Pa (when fields are kept)

    @property
    def rpm(self) -> float:
        return self.speed * 30.0 / math.pi


@dataclass(frozen=True)
class ModelStates:
    """The states of one FE model: the hot spot's, the overspeed state, the averaging check."""

    keys: tuple[str, ...]  # the model keys sharing this FE model
    throws: tuple[str, ...]  # the engine throws it stands for, in the engine's order
    hotspot: HotSpot
    index: int  # cycle-angle index drawn (the hot spot's angle)
    angle_deg: float | None
    displacement: np.ndarray  # flat DOF vector at the hot spot's angle
    averaging: dict[str, float]  # fillet -> UR M53 averaging indicator at that state
    overspeed: OverspeedState | None = None
    stress: np.ndarray | None = None  # (6, n_nodes) averaged nodal stress at the hot spot's angle (fields kept)


def throw_names(keys: Iterable[str], throws: dict[str, Any]) -> list[str]:
    """The engine throws an FE model stands for, in the engine's order: its keys (throw
    names, or ``ALL_THROWS`` for every throw, ``fe_crank.throw_scope.throws_of``)."""
    keys = [keys] if isinstance(keys, str) else list(keys)
    wanted = {n for k in keys for n in throws_of(k, throws)}
    return [n for n in throws if n in wanted]


def angle_index(state: LoadState, angle: float | None) -> int:
    """Index of the cycle angle nearest ``angle`` (the first of equals)."""
    if angle is None:
        return 0
    return int(np.argmin(np.abs(np.asarray(state.theta) - angle)))


def field_at_angle(
    unit_solutions: UnitSolutions,
    state: LoadState,
    throw: str,
    index: int,
    sense: int,
    places: dict[str, float] | None = None,
) -> np.ndarray:
    """Displacement of the throw at cycle-angle index ``index`` of the load state
    ``state`` (the operating cycle, or an overspeed cycle: ``state.speed`` is the omega
    of its centrifugal term), with the assessment's loads (``assess.loads.ThrowCycle``)
    and coefficients (``superpose.cycle_coefficients``).  ``places``: each rod's place on
    the pin (``fe.throw.pin_patches.rod_positions``): with the FE model's patch cases, each rod's
    force goes to its band, as in the assessment.  The displacement is in the frame of the
    supports (``fe.core.support_frame``: the rigid motion the determinate solve leaves in
    removed, the main-bearing centres at rest), as the report writes and draws it; its
    stresses are the solve's (a rigid motion has none)."""
    tc = state.throws[throw]
    cases = tuple(unit_solutions.cases)
    mz = float(unit_solutions.cases["torque"].applied[5]) if "torque" in unit_solutions.cases else -1.0
    one = slice(index, index + 1)
    alpha = tc.angular_acceleration
    rods = tc.fe_rod_loads(places or {})
    unit = UnitStresses(
        np.zeros((len(cases), 6, 0)),
        np.zeros((3, 0)),
        cases=cases,
        torque_mz=mz,
        pin_patches=tuple(unit_solutions.options.pin_patches),
    )
    c = cycle_coefficients(
        unit,
        tc.fe_pin[one],
        tc.torque_in[one],
        state.speed,
        sense=sense,
        rod_loads=None if rods is None else tuple((np.asarray(f)[one], e) for f, e in rods),
        angular_acceleration=None if alpha is None else alpha[one],
        vibration=tc.fe_pin_force is not None and not tc.fe_rods,
    )[0]
    return field_in_support_frame(unit_solutions, unit_solutions.combine(dict(zip(cases, c))))


def _finite_key(v: float) -> float:
    return v if np.isfinite(v) else np.inf


def critical(throws: tuple[ThrowAssessment, ...], names: list[str]) -> HotSpot | None:
    """The hot spot over the throws ``names`` (module docstring).  Ties go to the first
    throw, then the first group, in the assessment's order (deterministic whichever way
    the case ran).  Fatigue works on the whole cycle, so the angle drawn is that of the
    group's largest von Mises."""
    wanted = set(names)
    cands = []
    for ti, t in enumerate(throws):
        if t.name not in wanted:
            continue
        fat = [
            (_finite_key(g.fatigue_safety.value), ti, gi, t.name, g, g.fatigue_safety, "fatigue")
            for gi, g in enumerate(t.groups)
            if g.fatigue_safety is not None and g.fatigue_safety.value is not None
        ]
        cands += fat or [
            (_finite_key(g.static_safety), ti, gi, t.name, g, g.max_von_mises, "static")
            for gi, g in enumerate(t.groups)
            if g.max_von_mises is not None
        ]
    if not cands:
        return None
    _, _, _, throw, g, ext, what = min(cands, key=lambda c: c[:3])
    angle = g.max_von_mises.angle if g.max_von_mises is not None else ext.angle
    x, y, z = (float(c) for c in ext.point)
    return HotSpot(throw, g.group, int(ext.node), (x, y, z), angle, what)


def governing(throws: tuple[ThrowAssessment, ...], names: list[str]) -> tuple[ThrowAssessment, GroupResult] | None:
    """(throw assessment, group result) of the largest overspeed von Mises over the throws
    ``names``: the lowest overspeed safety; ties go to the first throw, then the first
    group, in the assessment's order, as the criterion's location does."""
    best: tuple[ThrowAssessment, GroupResult] | None = None
    for t in throws:
        if t.name not in names:
            continue
        for g in t.groups:
            ext = g.max_von_mises_overspeed
            if ext is None:
                continue
            if best is None or ext.value > best[1].max_von_mises_overspeed.value:  # type: ignore[union-attr]
                best = (t, g)
    return best


def von_mises_at(unit_solutions: UnitSolutions, u: np.ndarray, node: int) -> float:
    """Averaged nodal von Mises of the field ``u`` at one mesh node, Pa."""
    m = unit_solutions.material
    s = stress_at_selected_nodes(
        unit_solutions.mesh,
        [u],
        m.youngs_modulus,
        m.poisson_ratio,
        np.array([node]),
        dofs=unit_solutions.system.basis.dofs,
    )
    return float(von_mises(s[0])[0])


def overspeed_state(
    unit_solutions: UnitSolutions,
    throws: tuple[ThrowAssessment, ...],
    names: list[str],
    cycles: tuple[LoadState, ...],
    senses: dict[str, int],
    places: dict[str, dict[str, float]] | None = None,
) -> OverspeedState | None:
    """The governing overspeed state of one FE model (module docstring); None without an
    overspeed cycle or an overspeed result.  ``senses``: each throw's shaft sense;
    ``places``: throw -> its rods' places on the pin (``field_at_angle``)."""
    if not cycles:
        return None
    found = governing(throws, names)
    if found is None:
        return None
    t, g = found
    ext = g.max_von_mises_overspeed
    assert ext is not None  # governing() picks groups with an overspeed result
    # The criterion takes the worst of the overspeed cycles (motored curve and zero gas):
    # take the cycle whose state at theta* reaches the table's value at its node.
    best = None
    for c in cycles:
        theta = np.asarray(c.theta)
        index = int(np.argmin(np.abs(theta - ext.angle))) if ext.angle is not None else 0
        u = field_at_angle(unit_solutions, c, t.name, index, senses[t.name], (places or {}).get(t.name))
        at_node = von_mises_at(unit_solutions, u, int(ext.node)) if len(cycles) > 1 else 0.0
        if best is None or at_node > best[0]:
            best = (at_node, c, index, u)
    assert best is not None
    _, cycle, index, u = best
    theta = np.asarray(cycle.theta)
    return OverspeedState(
        t.name,
        g.group,
        float(ext.value),
        g.overspeed_safety,
        int(ext.node),
        (float(ext.point[0]), float(ext.point[1]), float(ext.point[2])),
        index,
        float(np.degrees(theta[index])),
        float(cycle.speed),
        cycle.case,
        np.asarray(u),
        tuple(gr for gr in t.groups if gr.group in COUNTERWEIGHTS),
    )


def model_states(
    keys: tuple[str, ...],
    unit_solutions: UnitSolutions,
    throws: tuple[ThrowAssessment, ...],
    dyn: LoadState,
    overspeed: tuple[LoadState, ...],
    senses: dict[str, int],
    *,
    fields: bool,
    places: dict[str, dict[str, float]] | None = None,
) -> ModelStates | None:
    """The states of the FE model ``unit_solutions`` standing for the throws of ``keys``
    (module docstring) in the load state ``dyn`` (the operating speed, all cylinders
    firing) and the overspeed cycles; None when the assessment has no hot spot for it.
    ``fields``: also recover the averaged nodal stress of both states on the whole mesh
    (for the report's ``.vtu`` fields and pictures).  ``places``: throw -> its rods' places
    on the pin (``fe.throw.pin_patches.rod_positions``), for a model loaded per rod place."""
    names = throw_names(keys, dyn.throws)
    crit = critical(throws, names)
    if crit is None:
        return None
    index = angle_index(dyn, crit.angle)
    u = field_at_angle(unit_solutions, dyn, crit.throw, index, senses[crit.throw], (places or {}).get(crit.throw))
    boundaries = unit_solutions.mesh.boundaries or {}
    fillets = [g for g in FILLETS if g in boundaries]
    averaging = {g: float(v) for g, v in unit_solutions.averaging_indicator(u, fillets).items()} if fillets else {}
    os_state = overspeed_state(unit_solutions, throws, names, overspeed, senses, places)
    stress = None
    if fields:
        stress = unit_solutions.stress_at_nodes(u)
        if os_state is not None:
            from dataclasses import replace

            os_state = replace(os_state, stress=unit_solutions.stress_at_nodes(os_state.displacement))
    angle_deg = None if crit.angle is None else float(np.degrees(dyn.theta[index]))
    return ModelStates(tuple(keys), tuple(names), crit, index, angle_deg, u, averaging, os_state, stress)
