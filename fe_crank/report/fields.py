"""The result fields of one FE model: what the ``.vtu`` file holds and the pictures show.

One ``meshio.Mesh`` of quadratic tetrahedra (``fe_crank.fe.vtu``) per meshed throw,
built once and both written and drawn, so file, pictures and tables agree:

* at the governing crank angle (the angle of the largest von Mises stress of the
  hot-spot group, by superposition of the unit cases with the assessment's own
  coefficients): ``displacement_m``, ``stress_Pa`` (Voigt xx yy zz xy yz zx),
  ``von_mises_Pa``, ``principal_1..3_Pa``, ``max_shear_Pa``;
* at overspeed: the governing state of the overspeed criterion (the cycle recomputed
  at omega_os with rod and piston inertia, at the crank angle of the governing
  group's maximum; ``fe_crank.report.overspeed_state``): the same names with
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

import numpy as np

from fe_crank.fe.vtu import boundary_point_ids, quadratic_tet_mesh, region_ids, stress_fields
from fe_crank.report.overspeed_state import OverspeedState, overspeed_state, throw_names
from fe_crank.report.superposed import angle_index, field_at_angle

#: assessment per-node arrays -> VTU names, and how nodes in two groups combine
_ASSESSED = (
    ("max_von_mises", "max_von_mises_cycle_Pa", np.fmax),
    ("amplitude", "fatigue_amplitude_Pa", np.fmax),
    ("mean", "fatigue_mean_Pa", np.fmax),
    ("fatigue_safety", "fatigue_safety", np.fmin),
    ("gough_pollard_safety", "gough_pollard_safety", np.fmin),
)


@dataclass(frozen=True)
class HotSpot:
    """Where and when the pictures look: the critical point of the assessment."""

    throw: str  # engine throw name
    group: str
    node: int
    point: tuple[float, float, float]
    angle: float | None  # rad: the crank angle drawn (None: no angle-bound result)
    what: str  # "fatigue" or "static"


def _finite_key(v: float) -> float:
    return v if np.isfinite(v) else np.inf


def critical(assessment, keys, dyn) -> HotSpot | None:
    """The hot spot the pictures show: the node with the lowest fatigue safety (static
    safety when there is no fatigue result) over the throws the FE model stands for
    (``keys``: throw names, or ``ALL_THROWS`` standing for every throw, as
    ``assess_case`` reads them, ``fe_crank.throw_scope``).  Ties go to the first throw, then the first group, in the
    assessment's order (deterministic whichever way the case ran).  Fatigue works on
    the whole cycle, so the angle drawn is that of the group's largest von Mises."""
    names = set(throw_names(keys, dyn))
    cands = []
    for ti, t in enumerate(assessment.throws):
        if t.name not in names:
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
    return HotSpot(throw, g.group, int(ext.node), tuple(float(c) for c in ext.point), angle, what)


def assessed_fields(throw_assessment, n_points: int) -> tuple[dict[str, np.ndarray], dict]:
    """Per-node assessment arrays of one throw spread over all mesh nodes (NaN where
    not assessed; infinite safeties, i.e. unloaded or not computed, also NaN)."""
    out = {name: np.full(n_points, np.nan) for _, name, _ in _ASSESSED}
    gid = np.full(n_points, -1, np.int32)
    field = {}
    for i, g in enumerate(getattr(throw_assessment, "groups", ())):
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

    mesh: object  # meshio.Mesh
    hotspot: HotSpot
    angle_deg: float | None
    overspeed: OverspeedState | None = None  # the state of the ``_overspeed`` fields


def throw_fields(units, assessment, dyn, lc, keys, dyn_os=None) -> ThrowFields | None:
    """The fields of the FE model ``units`` standing for the throws ``keys`` (see the
    module docstring); None when the assessment has no hot spot for it.  ``dyn``: the
    dynamics the assessment used; ``dyn_os``: its overspeed cycle (computed when not given)."""
    crit = critical(assessment, keys, dyn)
    if crit is None:
        return None
    index = angle_index(dyn, crit.angle)
    u = field_at_angle(units, dyn, lc, crit.throw, index)
    basis = units.system.basis
    n = basis.doflocs.shape[1]
    data = {"displacement_m": np.asarray(u).reshape(-1, 3), **stress_fields(units.stress_at_nodes(u))}
    os_state = overspeed_state(units, assessment, dyn, lc, keys, dyn_os)
    if os_state is not None:
        data["displacement_overspeed_m"] = os_state.displacement.reshape(-1, 3)
        data.update(stress_fields(units.stress_at_nodes(os_state.displacement), "_overspeed"))
    t = next((t for t in assessment.throws if t.name == crit.throw), None)
    extra, field = assessed_fields(t, n)
    data.update(extra)
    cdata, fsub = region_ids(units.mesh)
    field.update(fsub)
    if getattr(units.mesh, "boundaries", None):
        data["boundary"], fb = boundary_point_ids(units.mesh, basis)
        field.update(fb)
    angle_deg = None if crit.angle is None else float(np.degrees(dyn.theta[index]))
    if angle_deg is not None:
        field["crank_angle_deg"] = np.array([angle_deg])
    if os_state is not None:
        field["overspeed_crank_angle_deg"] = np.array([os_state.angle_deg])
        field["overspeed_rpm"] = np.array([os_state.rpm])
    mesh = quadratic_tet_mesh(basis.doflocs, basis.element_dofs, point_data=data, cell_data=cdata, field_data=field)
    return ThrowFields(mesh, crit, angle_deg, os_state)


def shared_models(units_by_key: dict) -> list[tuple[list[str], object]]:
    """[(keys, units)] grouping the keys that share one FE solution, in order."""
    groups: dict[int, tuple[list[str], object]] = {}
    for k, u in units_by_key.items():
        groups.setdefault(id(u), ([], u))[0].append(k)
    return list(groups.values())
