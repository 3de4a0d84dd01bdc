"""A check of the nodal stresses the assessment relies on.

Nodal stresses are element values extrapolated to the nodes and averaged.  On badly
shaped curved quadratic tetrahedra (small Jacobian ratios at fillets) the extrapolation
can overshoot by a large factor.  For each assessed boundary group and the unit cases
``pin_y`` and ``torque``, the peak nodal von Mises is compared with the peak at the
quadrature points of the elements touching the group (values the FE solution
interpolates, not extrapolates).  A ratio well above 1 marks nodal peaks that are not
to be trusted; ``assess_case`` writes it into the assessment's notes.
"""

from __future__ import annotations

import numpy as np

from fe_crank.assess.stress import von_mises
from fe_crank.assess.superpose import UnitStresses
from fe_crank.fe.core.stress import stress_at_quadrature, stress_at_selected_nodes
from fe_crank.fe.throw.unit_cases import UnitSolutions

#: ratios above this are reported
RATIO_LIMIT = 1.25


def recovery_ratios(
    unit_solutions: UnitSolutions,
    groups: dict[str, np.ndarray],
    cases: tuple[str, ...] = ("pin_y", "torque"),
    *,
    unit: UnitStresses | None = None,
) -> dict[str, float]:
    """Group -> max over ``cases`` of (peak nodal vM / peak quadrature-point vM).

    Both stresses are recovered only where they are compared: the nodal averages at the
    groups' nodes (``stress_at_selected_nodes``, equal to the whole-mesh average there) and
    the quadrature-point stress of the elements touching each group's facets.  ``unit``:
    the assessment's unit stresses (``groups.unit_stresses``) when they hold these groups
    under the same names and the cases: their nodal averages are read there instead of
    being recovered a second time (the same averages; only the grouping of each
    average's additions may differ in the last bit, far below the two decimals the
    notes print).
    """
    mesh = unit_solutions.mesh
    basis = unit_solutions.system.basis
    mat = unit_solutions.material
    bounds = mesh.boundaries or {}
    present = {
        name: (np.asarray(nodes), bounds[name]) for name, nodes in groups.items() if len(bounds.get(name, ())) > 0
    }
    out: dict[str, float] = {}
    if not present:
        return out
    # a model loaded per rod place (patch cases pin_y@k) is checked on each place's pin_y
    checked = [c for c in cases if c in unit_solutions.cases] + [
        k for c in cases for k in unit_solutions.cases if c not in unit_solutions.cases and k.startswith(c + "@")
    ]
    if not checked:
        return out
    if (
        unit is not None
        and unit.node_ids is not None
        and all(c in unit.cases for c in checked)
        and all(
            name in unit.groups and np.array_equal(unit.node_ids[unit.groups[name]], nodes)
            for name, (nodes, _) in present.items()
        )
    ):
        nodal = {
            (case, name): unit.stress[unit.cases.index(case)][:, unit.groups[name]]
            for case in checked
            for name in present
        }
    else:
        ids = np.unique(np.concatenate([nodes for nodes, _ in present.values()]))
        nodal_all = stress_at_selected_nodes(
            mesh,
            [unit_solutions.displacement(c) for c in checked],
            mat.youngs_modulus,
            mat.poisson_ratio,
            ids,
            dofs=basis.dofs,
        )
        nodal = {
            (case, name): nodal_all[j][:, np.searchsorted(ids, nodes)]
            for j, case in enumerate(checked)
            for name, (nodes, _) in present.items()
        }
    for case in checked:
        u = unit_solutions.displacement(case)
        for name, (_nodes, facets) in present.items():
            els = np.unique(mesh.f2t[0, facets])
            quad = stress_at_quadrature(basis, u, mat.youngs_modulus, mat.poisson_ratio, elements=els)
            q = float(von_mises(quad.reshape(6, -1)[None])[0].max())
            n = float(von_mises(nodal[case, name][None])[0].max())
            if q > 0:
                out[name] = max(out.get(name, 0.0), n / q)
    return out


def recovery_notes(ratios: dict[str, float], limit: float = RATIO_LIMIT) -> list[str]:
    return [
        f"stress recovery: peak nodal stress at {g} is {r:.2f} x the peak at the quadrature points of "
        f"its elements (unit cases); nodal peaks there are extrapolation artefacts of the mesh, treat its "
        f"safety factors as unreliable (finer or better-shaped fillet elements)"
        for g, r in sorted(ratios.items())
        if r > limit
    ]
