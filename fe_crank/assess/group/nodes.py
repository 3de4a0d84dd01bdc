"""The node groups the assessment evaluates (fillets, oil bore, counterweights and their
junctions with the webs, ``fe.throw.node_groups``) and the unit-case stresses at their nodes."""

from __future__ import annotations

import numpy as np

from fe_crank.assess.superpose import UnitStresses, unit_nodal_stress
from fe_crank.assess.workers import Scratch, run_blocks, thread_count
from fe_crank.errors import InputError
from fe_crank.fe.core.loads import CENTRIFUGAL_PARTS
from fe_crank.fe.throw.node_groups import ASSESSED_BOUNDARIES, COUNTERWEIGHTS, node_groups
from fe_crank.fe.throw.pin_directions import patch_case, pin_direction
from fe_crank.fe.throw.unit_cases import UnitSolutions

#: the unit cases besides the pin cases that the superposition takes (``superpose.load_coefficients``)
SUPERPOSED = ("centrifugal", *CENTRIFUGAL_PARTS, "torque", "angular_acceleration")

__all__ = ["ASSESSED_BOUNDARIES", "COUNTERWEIGHTS", "SUPERPOSED", "assessed_groups", "unit_stresses"]


def assessed_groups(unit_solutions: UnitSolutions) -> dict[str, np.ndarray]:
    """Mesh node numbers of every assessed group present in the mesh
    (``fe.throw.node_groups.node_groups``): the fillet and oil-bore boundaries, each
    counterweight subdomain and its junction with the web."""
    return node_groups(unit_solutions.mesh, unit_solutions.system.basis)


def _recover(unit_solutions: UnitSolutions, cases: tuple[str, ...], ids: np.ndarray) -> np.ndarray:
    """``unit_nodal_stress(unit_solutions, cases, ids)``, the cases split into as many sets as the
    context has threads (``workers.thread_count``)."""
    threads = thread_count()
    sets = [s for s in np.array_split(np.arange(len(cases)), max(1, min(int(threads), len(cases)))) if s.size]
    if len(sets) == 1:
        return unit_nodal_stress(unit_solutions, cases, ids)
    out = np.empty((len(cases), 6, ids.size))

    def one(sel: np.ndarray, _scratch: Scratch) -> None:
        out[sel] = unit_nodal_stress(unit_solutions, tuple(cases[j] for j in sel), ids)

    run_blocks(one, sets, len(sets))
    return out


def unit_stresses(unit_solutions: UnitSolutions, groups: dict[str, np.ndarray] | None = None) -> UnitStresses:
    """Nodal stresses of every solved unit case at the assessed nodes (FE stage's
    ``UnitSolutions``).  Stress recovery is linear in u, so these are exact unit fields.

    With several threads (``workers.threads``) the unit cases are split into that many
    sets, each recovered on its own thread (``workers.run_blocks``).  Each case's averages are computed by the same
    operations on the same operands whichever set it is in (the recovery treats every
    displacement field on its own), so the result is the one-thread result bit for bit;
    each thread rebuilds the node gradients of the assessed elements (their cost is
    spent once more per extra thread)."""
    groups = assessed_groups(unit_solutions) if groups is None else groups
    if not groups:
        raise InputError(
            f"the mesh has none of the assessed groups ({', '.join(ASSESSED_BOUNDARIES + COUNTERWEIGHTS)})",
            key="geometry",
        )
    ids = np.unique(np.concatenate(list(groups.values())))
    local = {k: np.searchsorted(ids, v) for k, v in groups.items()}
    cases = tuple(
        c for c in unit_solutions.cases if c in SUPERPOSED or pin_direction(c) is not None or patch_case(c) is not None
    )
    stress = _recover(unit_solutions, cases, ids)  # = stress_at_nodes(u_c)[:, ids], assessed elements only
    mz = float(unit_solutions.cases["torque"].applied[5]) if "torque" in unit_solutions.cases else -1.0
    return UnitStresses(
        stress=stress,
        points=np.asarray(unit_solutions.points)[:, ids],
        groups=local,
        node_ids=ids,
        cases=cases,
        torque_mz=mz,
        pin_patches=tuple(unit_solutions.options.pin_patches),
    )
