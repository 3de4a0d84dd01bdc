"""The governing overspeed state: what the overspeed picture and the ``_overspeed``
fields of the ``.vtu`` file show.

The overspeed criterion (``overspeed_safety``, ``fe_crank.assess.group.assess_group``)
is ``n = R_e / max sigma_v`` over the assessed groups and over the whole cycle
recomputed at the overspeed omega_os (``fe_crank.assess.overspeed``: rod and piston
inertia at omega_os, the crank's own body force at omega_os^2, the gas load of
``[operating] overspeed_gas``).  With one material for the throw, its governing value
is the group with the largest ``max_von_mises_overspeed``, at the crank angle theta*
where that maximum occurs.  The state drawn is the superposition of the unit cases at
theta* with the assessment's own coefficients (``assess.superpose.load_coefficients``)::

    u = omega_os^2 u_c + sum_k a_k(F_os(theta*)) u_pk - sense T_os(theta*) / M_z u_t

so the drawn von Mises at the governing node equals the table's value (linearity:
stress recovery and superposition commute).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.groups import COUNTERWEIGHTS
from fe_crank.assess.overspeed import overspeed_cycles
from fe_crank.fe.stress import stress_at_selected_nodes, von_mises
from fe_crank.report.superposed import field_at_angle
from fe_crank.throw_scope import throws_of


@dataclass(frozen=True)
class OverspeedState:
    """The overspeed state of one FE model and the facts its picture states."""

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
    counterweights: tuple = ()  # the throw's counterweight group results (marked in the picture)

    @property
    def rpm(self) -> float:
        return self.speed * 30.0 / math.pi


def throw_names(keys, dyn) -> list[str]:
    """The engine throws an FE model stands for, in the engine's order: its keys (throw
    names, or ``ALL_THROWS`` for every throw), read as ``assess_case`` reads them
    (``fe_crank.throw_scope.throws_of``)."""
    keys = [keys] if isinstance(keys, str) else list(keys)
    wanted = {n for k in keys for n in throws_of(k, dyn.throws)}
    return [n for n in dyn.throws if n in wanted]


def governing(assessment, names) -> tuple[object, object] | None:
    """(throw assessment, group result) of the largest overspeed von Mises over the throws
    ``names``: the lowest overspeed safety; ties go to the first throw, then the first
    group, in the assessment's order, as the criterion's location does."""
    best = None
    for t in assessment.throws:
        if t.name not in names:
            continue
        for g in t.groups:
            ext = g.max_von_mises_overspeed
            if ext is not None and (best is None or ext.value > best[1].max_von_mises_overspeed.value):
                best = (t, g)
    return best


def overspeed_state(units, assessment, dyn, lc, keys, dyn_os=None) -> OverspeedState | None:
    """The governing overspeed state of the FE model ``units`` (module docstring); None
    without an overspeed or an overspeed result.  ``dyn_os``: one overspeed cycle to draw;
    when not given, the governing one of ``assess.overspeed.overspeed_cycles(lc, dyn)``."""
    op = lc.operating
    if not op.overspeed:
        return None
    found = governing(assessment, throw_names(keys, dyn))
    if found is None:
        return None
    t, g = found
    ext = g.max_von_mises_overspeed
    if dyn_os is not None:
        cycles = [(getattr(op, "overspeed_gas", "motored"), dyn_os)]
    else:
        cycles = [(c.gas, c.dynamics) for c in overspeed_cycles(lc, dyn)]
    # The criterion takes the worst of the overspeed cycles (motored curve and zero gas):
    # draw the cycle whose state at theta* reaches the table's value at its node.
    best = None
    for gas, d in cycles:
        theta = np.asarray(d.theta)
        index = int(np.argmin(np.abs(theta - ext.angle))) if ext.angle is not None else 0
        u = field_at_angle(units, d, lc, t.name, index)
        at_node = _von_mises_at(units, u, int(ext.node)) if len(cycles) > 1 else 0.0
        if best is None or at_node > best[0]:
            best = (at_node, gas, d, index, u)
    _, gas, dyn_os, index, u = best
    theta = np.asarray(dyn_os.theta)
    return OverspeedState(
        t.name,
        g.group,
        float(ext.value),
        g.overspeed_safety,
        int(ext.node),
        tuple(float(c) for c in ext.point),
        index,
        float(np.degrees(theta[index])),
        float(dyn_os.speed),
        gas,
        np.asarray(u),
        tuple(g for g in t.groups if g.group in COUNTERWEIGHTS),
    )


def _von_mises_at(units, u: np.ndarray, node: int) -> float:
    """Averaged nodal von Mises of the field ``u`` at one mesh node, Pa."""
    s = stress_at_selected_nodes(
        units.mesh,
        [u],
        units.material.youngs_modulus,
        units.material.poisson_ratio,
        np.array([node]),
        dofs=units.system.basis.dofs,
    )
    return float(von_mises(s[0])[0])


def field_peak(values: np.ndarray, group) -> tuple[float, int]:
    """(largest value, node) of a drawn nodal field over a group's nodes (first of equals)."""
    ids = np.asarray((group.fields or {}).get("node_ids", ()), dtype=np.int64)
    if ids.size == 0:
        return float("nan"), -1
    j = int(ids[int(np.argmax(values[ids]))])
    return float(values[j]), j
