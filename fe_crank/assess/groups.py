"""The node groups the assessment evaluates (fillets, oil bore, counterweights and their
junctions with the webs) and the unit-case stresses at their nodes."""

from __future__ import annotations

import numpy as np

from fe_crank.assess.superpose import UnitStresses, unit_nodal_stress
from fe_crank.assess.workers import run_blocks, thread_count
from fe_crank.errors import InputError
from fe_crank.fe.pin_directions import patch_case, pin_direction
from fe_crank.fe.unit_cases import UnitSolutions

#: boundary groups assessed at their nodes; subdomains assessed with all their nodes
ASSESSED_BOUNDARIES = (
    "crankpin_fillet_1",
    "crankpin_fillet_2",
    "journal_fillet_1",
    "journal_fillet_2",
    "oil_bore",
    "counterweight_fillet_1",  # the counterweight-to-web transition fillets (geometry/cw_fillet.py)
    "counterweight_fillet_2",
)
COUNTERWEIGHTS = ("counterweight_1", "counterweight_2")


def _element_nodes(unit_solutions: UnitSolutions, elements) -> np.ndarray:
    return np.unique(np.asarray(unit_solutions.system.basis.element_dofs)[:, elements])


def assessed_groups(unit_solutions: UnitSolutions) -> dict[str, np.ndarray]:
    """Mesh node numbers of every assessed group present in the mesh: the fillet and
    oil-bore boundaries (all P2 nodes of their facets), each counterweight subdomain and
    its junction with the web (nodes shared by the counterweight's and the web's
    elements)."""
    mesh, basis = unit_solutions.mesh, unit_solutions.system.basis
    groups = {}
    for name in ASSESSED_BOUNDARIES:
        if name in (mesh.boundaries or {}):
            groups[name] = np.unique(basis.get_dofs(facets=mesh.boundaries[name]).all())
    subs = mesh.subdomains or {}
    for i, cw in enumerate(COUNTERWEIGHTS, start=1):
        if cw in subs:
            cw_nodes = _element_nodes(unit_solutions, subs[cw])
            groups[cw] = cw_nodes
            web = f"web_{i}"
            if web in subs:
                junction = np.intersect1d(cw_nodes, _element_nodes(unit_solutions, subs[web]))
                if junction.size:
                    groups[f"junction_{i}"] = junction
    return groups


def _recover(unit_solutions: UnitSolutions, cases: tuple[str, ...], ids: np.ndarray) -> np.ndarray:
    """``unit_nodal_stress(unit_solutions, cases, ids)``, the cases split into as many sets as the
    context has threads (``workers.thread_count``)."""
    threads = thread_count()
    sets = [s for s in np.array_split(np.arange(len(cases)), max(1, min(int(threads), len(cases)))) if s.size]
    if len(sets) == 1:
        return unit_nodal_stress(unit_solutions, cases, ids)
    out = np.empty((len(cases), 6, ids.size))

    def one(sel, _scratch):
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
        c
        for c in unit_solutions.cases
        if c in ("centrifugal", "torque", "angular_acceleration")
        or pin_direction(c) is not None
        or patch_case(c) is not None
    )
    stress = _recover(unit_solutions, cases, ids)  # = stress_at_nodes(u_c)[:, ids], assessed elements only
    mz = float(unit_solutions.cases["torque"].applied[5]) if "torque" in unit_solutions.cases else -1.0
    jz = (
        float(unit_solutions.cases["angular_acceleration"].applied[5])
        if "angular_acceleration" in unit_solutions.cases
        else 0.0
    )
    return UnitStresses(
        stress=stress,
        points=np.asarray(unit_solutions.points)[:, ids],
        groups=local,
        node_ids=ids,
        cases=cases,
        torque_mz=mz,
        inertia_mz=jz,
        pin_patches=tuple(unit_solutions.options.pin_patches),
    )
