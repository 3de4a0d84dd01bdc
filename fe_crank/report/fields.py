"""The result fields of one FE model: what the ``.vtu`` file holds and the pictures show.

One ``meshio.Mesh`` of quadratic tetrahedra (``fe_crank.fe.core.result_fields``) per FE model,
built once from the assessment's states (``fe_crank.assess.states``) and both written and
drawn, so file, pictures and tables agree:

* at the governing crank angle (the angle of the largest von Mises stress of the
  hot-spot group): ``displacement_m``, ``stress_Pa`` (Voigt xx yy zz xy yz zx),
  ``von_mises_Pa``, ``principal_1..3_Pa``, ``max_shear_Pa``;
* at overspeed: the governing state of the overspeed criterion: the same names with
  ``_overspeed``;
* over the cycle, at the assessed nodes (NaN elsewhere): ``max_von_mises_cycle_Pa``,
  ``fatigue_amplitude_Pa`` and ``fatigue_mean_Pa`` (equivalent sigma_a', sigma_m'),
  ``fatigue_safety`` (Goodman), ``gough_pollard_safety``; ``assessed_group`` (id);
* regions: cell data ``subdomain``, point data ``boundary``; field data maps
  ``subdomain:<name>``, ``boundary:<name>``, ``assessed_group:<name>`` to ids and
  ``crank_angle_deg`` to the governing angle, ``overspeed_crank_angle_deg`` and
  ``overspeed_rpm`` to the overspeed state's angle and speed.
"""

from __future__ import annotations

from dataclasses import dataclass

import meshio
import numpy as np

from fe_crank.assess.group.assessment import GroupResult
from fe_crank.assess.states import HotSpot, ModelStates, OverspeedState
from fe_crank.assess.throw import ThrowAssessment
from fe_crank.fe.core.result_fields import boundary_point_ids, quadratic_tet_mesh, region_ids, stress_fields
from fe_crank.fe.throw.unit_cases import UnitSolutions

#: assessment per-node arrays -> VTU names, and how nodes in two groups combine
_ASSESSED = (
    ("max_von_mises", "max_von_mises_cycle_Pa", np.fmax),
    ("amplitude", "fatigue_amplitude_Pa", np.fmax),
    ("mean", "fatigue_mean_Pa", np.fmax),
    ("fatigue_safety", "fatigue_safety", np.fmin),
    ("gough_pollard_safety", "gough_pollard_safety", np.fmin),
)


def assessed_fields(throw_assessment: ThrowAssessment | None, n_points: int) -> tuple[dict[str, np.ndarray], dict]:
    """Per-node assessment arrays of one throw spread over all mesh nodes (NaN where
    not assessed; infinite safeties, i.e. unloaded or not computed, also NaN)."""
    out = {name: np.full(n_points, np.nan) for _, name, _ in _ASSESSED}
    gid = np.full(n_points, -1, np.int32)
    field = {}
    for i, g in enumerate(throw_assessment.groups if throw_assessment is not None else ()):
        f = g.fields or {}
        ids = np.asarray(f.get("node_ids", ()), dtype=np.int64)
        if ids.size == 0:
            continue
        field[f"assessed_group:{g.group}"] = np.array([i, 0])
        gid[ids] = np.where(gid[ids] < 0, i, gid[ids])
        for key, name, combine in _ASSESSED:
            if key in f:
                v = np.asarray(f[key], float)
                v = np.where(np.isfinite(v), v, np.nan)
                out[name][ids] = combine(out[name][ids], v)
    out["assessed_group"] = gid
    return out, field


@dataclass(frozen=True)
class ThrowFields:
    """The fields of one FE model and the facts its pictures state."""

    mesh: meshio.Mesh
    hotspot: HotSpot
    angle_deg: float | None
    overspeed: OverspeedState | None = None  # the state of the ``_overspeed`` fields


def throw_fields(
    unit_solutions: UnitSolutions, states: ModelStates, throws: tuple[ThrowAssessment, ...]
) -> ThrowFields:
    """The fields of one FE model from its states (module docstring); the states must carry
    their stress (the assessment recovers it when fields are asked for)."""
    if states.stress is None:
        raise ValueError("the states carry no stress field: assess with fields=True")
    basis = unit_solutions.system.basis
    n = basis.doflocs.shape[1]
    data = {"displacement_m": np.asarray(states.displacement).reshape(-1, 3), **stress_fields(states.stress)}
    os_state = states.overspeed
    if os_state is not None and os_state.stress is not None:
        data["displacement_overspeed_m"] = os_state.displacement.reshape(-1, 3)
        data.update(stress_fields(os_state.stress, "_overspeed"))
    t = next((t for t in throws if t.name == states.hotspot.throw), None)
    extra, field = assessed_fields(t, n)
    data.update(extra)
    cdata, fsub = region_ids(unit_solutions.mesh)
    field.update(fsub)
    if unit_solutions.mesh.boundaries:
        data["boundary"], fb = boundary_point_ids(unit_solutions.mesh, basis)
        field.update(fb)
    if states.angle_deg is not None:
        field["crank_angle_deg"] = np.array([states.angle_deg])
    if os_state is not None:
        field["overspeed_crank_angle_deg"] = np.array([os_state.angle_deg])
        field["overspeed_rpm"] = np.array([os_state.rpm])
    mesh = quadratic_tet_mesh(basis.doflocs, basis.element_dofs, point_data=data, cell_data=cdata, field_data=field)
    return ThrowFields(mesh, states.hotspot, states.angle_deg, os_state)


def field_peak(values: np.ndarray, group: GroupResult) -> tuple[float, int]:
    """(largest value, node) of a drawn nodal field over a group's nodes (first of equals)."""
    ids = np.asarray((group.fields or {}).get("node_ids", ()), dtype=np.int64)
    if ids.size == 0:
        return float("nan"), -1
    j = int(ids[int(np.argmax(values[ids]))])
    return float(values[j]), j
