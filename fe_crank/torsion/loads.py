"""The loads handed to the assessment at every speed of the full-load curve: the torque
flow through each throw (``flow.torque_flow``) of every load state, with the torsional
vibration when the torsional stage ran (``flow.fe_loads``).

Per speed ``omega`` of the sweep (``EngineCycles.sweep``) and per state (all cylinders
firing, each misfire case): the dynamics stage's cycle at ``omega`` gives the pin force
and the throws' own torques; the torque flow gives the torque entering at the FE torque
face and leaving at its reaction face for the load case's power take-off end
(``[fe] torque_reaction``); with the torsional stage, the vibratory journal torques,
the throw's angular acceleration and its inertia and damping torque of the same
synthesis at the same ``omega`` (the misfire case's own forced response for a misfire
state).  The overspeed cycles take the rigid-shaft flow.  UR M53 2.2.2 takes the
nominal torsional stress from the largest alternating torque over the torsional speed
range: each throw also receives the hand-over histories of its journals
(``handover.journal_torques``, or the worst case of ``misfire.MisfireTorsion``).

Where the FE model loads the pin per rod place (``fe.throw.pin_patches``), the vibratory
tangential force ``fe_pin_force - pin_force`` (the inertia and damping torque of the
throw's mass in the chain, ``flow.fe_loads``) is shared among the throw's rods in
proportion to their cylinders' inertias in the chain (``build.reciprocating_inertia``:
the rod's rotating share and the mean reciprocating inertia), each rod's share at its
place (``ThrowCycle.fe_rods``): exact for the cylinders' part of the inertia torque, which
each rod carries for its own cylinder; the throw's own (CAD-vs-mesh) part and the
damping follow the same shares, a model choice (identical cylinders share equally).
"""

from __future__ import annotations

from fe_crank import model
from fe_crank.assess.loads import FIRING, AssessedLoads, LoadState, ThrowCycle, misfire_label
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult, RodLoad
from fe_crank.throw_scope import throws_of
from fe_crank.torsion.analysis import TorsionResult
from fe_crank.torsion.build import reciprocating_inertia
from fe_crank.torsion.flow import fe_loads, torque_flow
from fe_crank.torsion.handover import JournalTorque


def load_state(
    dynamics: DynamicsResult,
    engine: model.Engine,
    case: str,
    *,
    reaction: str = "end_2",
    torsion: TorsionResult | None = None,
    fe_inertia: dict[str, float] | None = None,
) -> LoadState:
    """The loads of every throw in the cycle ``dynamics`` (module docstring);
    ``fe_inertia``: throw name -> the moment about the axis of its FE mesh's
    ``angular_acceleration`` unit case (needed with ``torsion``)."""
    flows = torque_flow(dynamics, engine, reaction=reaction, torsion=torsion)
    throws = {}
    for name in dynamics.throws:  # the engine's order
        f = flows[name]
        pin = dynamics.throws[name].pin_force
        rods = dynamics.throws[name].rods
        if torsion is None:
            throws[name] = ThrowCycle(pin, f.torque_in, f.torque_out, rods=rods)
            continue
        if fe_inertia is None or name not in fe_inertia:
            raise ValueError(f"throw {name}: the torsional loads need the FE angular-acceleration unit case")
        t = engine.throw(name)
        fl = fe_loads(
            f, pin, fe_inertia=fe_inertia[name], crank_radius=t.crank_radius, sense=engine.shaft(t.shaft).sense
        )
        shared = vibratory_shares(engine, name, rods, fl.pin_force - pin)
        throws[name] = ThrowCycle(pin, f.torque_in, f.torque_out, fl.angular_acceleration, fl.pin_force, rods, shared)
    return LoadState(dynamics.speed, case, dynamics.theta, throws)


def vibratory_shares(engine: model.Engine, throw: str, rods: tuple[RodLoad, ...], extra) -> tuple[RodLoad, ...]:
    """Each rod's force plus its share ``J_i / sum J`` of the vibratory tangential force
    ``extra`` (n, 2) (module docstring), ``J_i`` its cylinder's inertia in the chain."""
    if not rods:
        return ()
    radius = engine.throw(throw).crank_radius
    cyl = {c.name: c for c in engine.cylinders}
    j = [reciprocating_inertia(cyl[r.cylinder], radius) for r in rods]
    total = sum(j)
    return tuple(
        RodLoad(r.cylinder, r.pin_force + (ji / total if total > 0 else 1.0 / len(rods)) * extra, r.pin_position)
        for r, ji in zip(rods, j)
    )


def fe_inertias(unit_solutions: dict[str, UnitSolutions], throws) -> dict[str, float]:
    """Throw name -> the moment about the axis of its FE model's ``angular_acceleration``
    unit case (the meshed throw's J_z, kg m^2); ``throws``: the engine's throw names
    (``fe_crank.throw_scope.throws_of`` resolves a model key standing for all)."""
    out = {}
    for key, u in unit_solutions.items():
        if "angular_acceleration" in u.cases:
            for name in throws_of(key, throws):
                out[name] = float(u.cases["angular_acceleration"].applied[5])
    return out


def m53_journal_torques(torsion: TorsionResult, handed: dict[str, JournalTorque]) -> dict[str, tuple]:
    """Throw name -> the hand-over histories of the journals in front of and behind it
    (a journal at a free end has none)."""
    names = torsion.model.segment_names
    out = {}
    for throw in torsion.model.throw_mass:
        front, rear = torsion.journal_segments(throw)
        out[throw] = tuple(handed[names[i]].history for i in (front, rear) if 0 <= i < len(names))
    return out


def assessed_loads(
    engine: model.Engine,
    cycles: EngineCycles,
    *,
    reaction: str = "end_2",
    torsion: TorsionResult | None = None,
    misfire_torsion: dict[str, TorsionResult] | None = None,
    fe_inertia: dict[str, float] | None = None,
    handed: dict[str, JournalTorque] | None = None,
) -> AssessedLoads:
    """``AssessedLoads`` of every speed and state (module docstring).  ``torsion``: the
    forced response with every cylinder firing, ``misfire_torsion``: misfiring cylinder
    -> its forced response (both None: rigid shaft); ``handed``: segment name -> the
    torque handed to UR M53 (``handover.journal_torques``)."""
    if misfire_torsion is None:
        misfire_torsion = {}
    speeds = []
    for sc in cycles.sweep:
        states = [load_state(sc.firing, engine, FIRING, reaction=reaction, torsion=torsion, fe_inertia=fe_inertia)]
        for m in sc.misfire:
            res = misfire_torsion.get(m.cylinder) if torsion is not None else None
            if torsion is not None and res is None:
                raise ValueError(f"no torsional response with cylinder {m.cylinder} misfiring")
            states.append(
                load_state(
                    m.dynamics, engine, misfire_label(m.cylinder), reaction=reaction, torsion=res, fe_inertia=fe_inertia
                )
            )
        speeds.append(tuple(states))
    overspeed = tuple(load_state(c.dynamics, engine, c.gas, reaction=reaction) for c in cycles.overspeed)
    m53 = m53_journal_torques(torsion, handed) if torsion is not None and handed is not None else {}
    return AssessedLoads(tuple(speeds), cycles.operating_index, overspeed, m53, torsion is not None)


__all__ = ["load_state", "vibratory_shares", "assessed_loads", "m53_journal_torques", "fe_inertias"]
