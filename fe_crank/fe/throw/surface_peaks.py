"""Peak von Mises stress on named surfaces of a throw mesh (the hot spots the convergence
study follows): the shaft fillets, the counterweights' transition fillets, the oil-bore
outlet.  Averaged nodal stress, the value the assessment reads, recovered at those
surfaces' nodes only (``stress.stress_at_selected_nodes``)."""

from __future__ import annotations

import numpy as np

from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
from fe_crank.fe.core.supports import boundary_facets
from fe_crank.fe.throw.unit_cases import UnitSolutions

FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2", "journal_fillet_1", "journal_fillet_2")
COUNTERWEIGHT_FILLETS = ("counterweight_fillet_1", "counterweight_fillet_2")
OIL_BORE = ("oil_bore",)


def peak_fillet_stress(unit_solutions: UnitSolutions, u: np.ndarray, fillets=FILLETS) -> tuple[float, str]:
    """Largest averaged nodal von Mises stress on the fillet surfaces present, and where."""
    return peak_fillet_stresses(unit_solutions, {"u": u}, fillets)["u"]


def peak_fillet_stresses(
    unit_solutions: UnitSolutions, fields: dict[str, np.ndarray], fillets=FILLETS
) -> dict[str, tuple[float, str]]:
    """``peak_fillet_stress`` of several displacement fields on one mesh: name -> (peak, fillet).

    The averaged nodal stress is recovered at the fillet nodes only, on the elements that
    share them (``stress.stress_at_selected_nodes``: the whole-mesh average at those nodes
    to the last bits of the summation order), with one node basis for all fields.
    """
    mesh, basis = unit_solutions.mesh, unit_solutions.system.basis
    groups = {
        name: basis.get_dofs(boundary_facets(mesh, name, "the convergence study")).all()
        for name in fillets
        if name in (mesh.boundaries or {})
    }
    if not groups:
        raise ValueError(f"the mesh has none of the surfaces {fillets}")
    ids = np.unique(np.concatenate(list(groups.values())))
    mat = unit_solutions.material
    s = stress_at_selected_nodes(
        mesh, list(fields.values()), mat.youngs_modulus, mat.poisson_ratio, ids, dofs=basis.dofs
    )
    out = {}
    for j, key in enumerate(fields):
        vm = von_mises(s[j])
        best, where = -np.inf, ""
        for name, nodes in groups.items():
            v = float(vm[np.searchsorted(ids, nodes)].max())
            if v > best:
                best, where = v, name
        out[key] = (best, where)
    return out


__all__ = ["FILLETS", "COUNTERWEIGHT_FILLETS", "OIL_BORE", "peak_fillet_stress", "peak_fillet_stresses"]
