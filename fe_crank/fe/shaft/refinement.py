"""The whole shaft's own hot-spot convergence study: its throws' hot spots refined in zones
driven by the whole-shaft solution.

The per-throw study (``fe.refinement.zone_study``) refines the hot spots of the per-throw
model under its two load sets.  The whole shaft carries its throws on all its bearings,
so its stresses, their peaks and where they sit are its own.  For each throw of the shaft
and each of the shaft's governing states of that throw (``load sets``: the case weights of
the whole-shaft unit cases, ``ShaftCases.names``, chosen by the assessment), this study

* recovers the throw piece's displacement on its whole mesh in that state, exactly as the
  condensation defines it (``piece_states``: u = sum_p a_p L_p + X v, ``fe.shaft.fields``),
  and its nodal von Mises stress on the hot-spot surfaces (the assessed mesh's peaks: the
  study's first level);
* finds the hot spots there by the per-throw study's rule (``hot_spots_of``: for each
  surface family and load set, the peak node of every surface whose peak is at least
  ``CANDIDATE`` x the family's; balls of ``ZONE_RADIUS`` x the fillet radius, the oil
  bore's diameter; centres closer than half a radius merged);
* meshes the balls from the throw's own solid at the finer levels
  (``zone_study.level_meshes``: the per-throw study's mesher) and solves each zone once per
  level for all load sets (``zone.solve_zone``: one factorisation, one right-hand side a
  load set), driven on its cut, journals and end faces by the piece's displacement and
  loaded inside by that state's own loads (``zone_loads``: the pin's cosine pressure of
  each pin pattern with the shaft model's arc, the body forces);
* reads the zone's peaks within ``REACH`` x its radius (``zone.zone_peaks``).

The result is a ``ConvergenceStudy`` per throw (method ``"zones"``), the same record as
the per-throw study's: the assessment takes its factors for the whole shaft's criteria
(``assess.refinement``).  Its assumption is the per-throw zones': the driven displacement
on the cut is the coarse (assessed) solution, whose error decays away from the hot spot
(docs/fe.md, "Only the hot spots refined").
"""

from __future__ import annotations

import dataclasses
import logging
import time

import numpy as np

from fe_crank.fe.core.loads import COUNTERWEIGHT_BODIES, pin_pressure_load, pin_surface
from fe_crank.fe.core.stress import stress_at_selected_nodes, von_mises
from fe_crank.fe.refinement.levels import (
    FACTORS,
    TOLERANCE,
    ConvergenceLevel,
    ConvergenceStudy,
)
from fe_crank.fe.refinement.zone import Interpolator, boundary_samples, solve_zone, zone_peaks
from fe_crank.fe.refinement.zone_study import (
    CANDIDATE,
    FAMILIES,
    GROUP_FRACTION,
    REACH,
    ZONE_RADIUS,
    HotSpot,
    held_level_meshes,
)
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.shaft.fields import piece_states
from fe_crank.fe.throw.options import FeOptions, Material
from fe_crank.fe.throw.pin_directions import pin_cases, unit_force
from fe_crank.mesh.zone import parametric_solid

log = logging.getLogger(__name__)

#: the whole shaft's body patterns (``fe.shaft.patterns``) -> the zone's body unit cases
#: (``fe.core.loads.BODY_CASES``): the same body force on the same elements
BODY_PATTERNS = {"centrifugal": "centrifugal_throw", "spin_up": "angular_acceleration"}
#: relative difference under which the throw's and its counterweights' centrifugal
#: coefficients are taken as one (the whole throw's ``centrifugal``: no subdomain needed)
SAME_SPEED = 1e-12


def piece_of(cases: ShaftCases, throw: str) -> int:
    """The index of the piece of throw ``throw`` in the shaft model."""
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind == "throw" and str(pp.throw) == throw:
            return k
    raise ValueError(f"the whole shaft has no throw {throw!r}")


def zone_loads(names: tuple[str, ...], coef: np.ndarray) -> dict[str, float]:
    """The loads inside a zone of a throw piece with local pattern coefficients ``coef``
    (n_pat,) of its patterns ``names`` (``fe.shaft.patterns``), as the zone's unit cases
    with their weights: the pin patterns as themselves (their pressure: ``piece_pins``), the
    body patterns as the per-throw model's body cases, the throw's and its counterweights'
    centrifugal force as the whole throw's when their coefficients agree (else the parts).
    The bearing surfaces' and end faces' patterns act on faces the zone drives (its
    journals and end faces, ``zone.driven_boundaries``): they are left out."""
    a = dict(zip(names, (float(x) for x in coef)))
    out: dict[str, float] = {}
    pins = set(pin_cases())
    for name, w in a.items():
        if name in pins and w != 0.0:
            out[name] = w
        elif name == "spin_up" and w != 0.0:
            out[BODY_PATTERNS[name]] = w
    own, cw = a.get("centrifugal", 0.0), a.get("centrifugal_cw", 0.0)
    webs = {f"centrifugal_cw_{b[-1]}": a.get(f"centrifugal_cw_{b[-1]}", 0.0) for b in COUNTERWEIGHT_BODIES}
    if abs(own - cw) <= SAME_SPEED * max(abs(own), abs(cw)) and not any(webs.values()):
        if own != 0.0:
            out["centrifugal"] = own
        return out
    if own != 0.0:
        out[BODY_PATTERNS["centrifugal"]] = own
    for name, w in webs.items():
        if w + cw != 0.0:
            out[name] = w + cw
    return out


def piece_pins(cases: ShaftCases, piece: int, half_angle: float) -> dict:
    """Each pin pattern's pressure (``fe.core.loads.PinPressure``) on the throw piece's crankpin,
    as the shaft model applied it (``fe.shaft.patterns.throw_patterns``)."""
    basis = cases.model.pieces[piece].cond.basis
    surface = pin_surface(basis, "crankpin")
    return {
        name: pin_pressure_load(basis, unit_force(name), half_angle=half_angle, surface=surface)[1]
        for name in pin_cases()
    }


def surface_peaks(mesh, basis, material: Material, fields: dict[tuple[str, str], np.ndarray]):
    """{(throw, entry): (peak von Mises, Pa, surface)} of each load set (``fields``' keys:
    (throw, load set)) on each hot-spot family of a throw mesh (entries as
    ``levels.level_peaks``'s: the family's prefix + load set), and per load set and family
    {surface: (peak, node)} (the hot spots' candidates)."""
    groups = {
        name: basis.get_dofs(mesh.boundaries[name]).all()
        for _, names in FAMILIES
        for name in names
        if name in (mesh.boundaries or {})
    }
    ids = np.unique(np.concatenate(list(groups.values())))
    s = stress_at_selected_nodes(
        mesh, list(fields.values()), material.youngs_modulus, material.poisson_ratio, ids, dofs=basis.dofs
    )
    best: dict[tuple[str, str], tuple[float, str]] = {}
    per: dict[tuple[tuple[str, str], str], dict[str, tuple[float, int]]] = {}
    for j, key in enumerate(fields):
        vm = von_mises(s[j])
        for prefix, names in FAMILIES:
            peaks = {}
            for name in names:
                if name in groups:
                    v = vm[np.searchsorted(ids, groups[name])]
                    peaks[name] = (float(v.max()), int(groups[name][int(np.argmax(v))]))
            if peaks:
                per[key, prefix] = peaks
                top = max(peaks, key=lambda n: peaks[n][0])
                best[key[0], prefix + key[1]] = (peaks[top][0], top)
    return best, per


def hot_spots_of(
    per: dict,
    points: np.ndarray,
    radius_of,
    zone_radius: float = ZONE_RADIUS,
) -> list[HotSpot]:
    """The zones (``zone_study.hot_spots``'s rule, module doc) from ``surface_peaks``'s
    candidates; ``radius_of(surface)``: the length a zone radius is measured in."""
    found: list[tuple[float, HotSpot]] = []
    for peaks in per.values():
        top = max(v for v, _ in peaks.values())
        for name, (v, node) in peaks.items():
            if v >= CANDIDATE * top:
                x = points[:, node]
                found.append((v, HotSpot((float(x[0]), float(x[1]), float(x[2])), zone_radius * radius_of(name), name)))
    found.sort(key=lambda t: -t[0])
    out: list[HotSpot] = []
    for _, h in found:
        if all(np.linalg.norm(np.subtract(h.centre, o.centre)) > 0.5 * min(h.radius, o.radius) for o in out):
            out.append(h)
    return out


def shaft_throw_study(
    cases: ShaftCases, material: Material, throw: str, states: dict[str, np.ndarray], **kwargs
) -> ConvergenceStudy:
    """The study of the one throw ``throw`` (``shaft_zone_studies``'s keywords)."""
    return shaft_zone_studies(cases, material, {throw: states}, **kwargs)[throw]


def shaft_zone_studies(
    cases: ShaftCases,
    material: Material,
    states: dict[str, dict[str, np.ndarray]],
    *,
    factors=FACTORS,
    tolerance: float = TOLERANCE,
    zone_radius: float = ZONE_RADIUS,
    solver: str = "auto",
) -> dict[str, ConvergenceStudy]:
    """The study (module doc) of each throw of ``states`` ({throw: {load set: case weights
    (n_cases,)}}), {throw: its study}.  Throws of one mesh (``ShaftMesh.pieces[k].mesh``:
    the same throw geometry) share their zones: the union of their hot spots (merged as
    one throw's, within half a zone radius) cut from the one solid and meshed once per
    level, each zone factorised once for the load sets of all of them (one right-hand side
    each), a throw's peaks read over every zone (a level's unknowns and time are the
    group's, in each throw's record)."""
    if len(factors) < 2 or factors[0] != 1.0:
        raise ValueError("a zone study starts from the assessed mesh (factor 1) and has at least two levels")
    sm = cases.model.mesh
    pieces = {throw: piece_of(cases, throw) for throw in states}
    W = {t: np.column_stack([np.asarray(w, float) for w in states[t].values()]) for t in states}
    t0 = time.perf_counter()
    U = piece_states(cases, {pieces[t]: W[t] for t in states}, material, solver)
    recovered = (time.perf_counter() - t0) / max(1, len(states))
    by_mesh: dict[str, list[str]] = {}
    for t in states:
        by_mesh.setdefault(sm.pieces[pieces[t]].mesh, []).append(t)
    half_angle = cases.model.options.pin_half_angle
    out: dict[str, ConvergenceStudy] = {}
    for key, throws in by_mesh.items():
        t0 = time.perf_counter()
        k0 = pieces[throws[0]]
        c, tm = cases.model.pieces[k0].cond, sm.throw_meshes[key]
        fields: dict[tuple[str, str], np.ndarray] = {}
        loads: dict[tuple[str, str], dict[str, float]] = {}
        for t in throws:
            coef = cases.coef[pieces[t]] @ W[t]
            for j, name in enumerate(states[t]):
                fields[t, name] = U[pieces[t]][:, j]
                loads[t, name] = zone_loads(c.names, coef[:, j])
        first, per = surface_peaks(c.mesh, c.basis, material, fields)
        base = tm.options
        assessed = time.perf_counter() - t0 + recovered
        spec = next(p.spec for p in sm.layout.throws if p.name == throws[0])
        solid = parametric_solid(sm.layout.geometry, spec)

        def radius_of(surface: str, tm=tm, solid=solid) -> float:
            return tm.fillet_radii[surface] if surface in tm.fillet_radii else solid.lengths[surface]

        spots = hot_spots_of(per, np.asarray(c.basis.doflocs), radius_of, zone_radius)
        pins = piece_pins(cases, k0, half_angle)
        interp = Interpolator(c.mesh, c.basis.dofs, np.asarray(c.basis.doflocs))
        options = FeOptions(pin_half_angle=half_angle)
        every = [n for _, ns in FAMILIES for n in ns]
        t0 = time.perf_counter()
        mopts = [
            dataclasses.replace(
                base, fillet_divisions=base.fillet_divisions * f, bore_divisions=base.bore_divisions * f
            )
            for f in factors[1:]
        ]
        meshes = held_level_meshes(solid, mopts, spots, boundary_samples(c.mesh), GROUP_FRACTION * c.basis.N)
        meshing = (time.perf_counter() - t0) / len(mopts)
        levels: dict[str, list[ConvergenceLevel]] = {
            t: [
                ConvergenceLevel(
                    fillet_divisions=base.fillet_divisions,
                    n_dof=int(3 * c.basis.N),
                    fillet_max_edge=dict(tm.stats.fillet_max_edge),
                    peaks={e[1]: v[0] for e, v in first.items() if e[0] == t},
                    where={e[1]: v[1] for e, v in first.items() if e[0] == t},
                    seconds=assessed,
                    reused=True,
                    bore_divisions=base.bore_divisions,
                )
            ]
            for t in throws
        }
        # the zone solver's load sets by name: one per (throw, load set)
        label = {e: f"{j}" for j, e in enumerate(loads)}
        named_loads = {label[e]: v for e, v in loads.items()}
        named_fields = {label[e]: v for e, v in fields.items()}
        of_label = {v: e for e, v in label.items()}
        for mopt, zones in zip(mopts, meshes):
            t0 = time.perf_counter() - meshing
            best: dict[tuple[str, str], tuple[float, str]] = {}
            n_dof, edges = 0, dict[str, float]()
            for zm in zones:
                Uz, zb = solve_zone(zm, material, options, pins, named_loads, named_fields, interp)
                n_dof += int(3 * zb.N)
                for s, v in zm.fillet_max_edge.items():
                    edges[s] = max(edges.get(s, 0.0), v)
                got = zone_peaks(zm, zb, material, Uz, every, REACH)
                for lab, found in got.items():
                    t, name = of_label[lab]
                    for prefix, surfaces in FAMILIES:
                        for s in surfaces:
                            e = (t, prefix + name)
                            if s in found and found[s] > best.get(e, (-np.inf, ""))[0]:
                                best[e] = (found[s], s)
            missing = sorted(set(first) - set(best))
            if missing:
                raise RuntimeError(f"the whole shaft's hot-spot zones hold no node of {missing}")
            seconds = time.perf_counter() - t0
            for t in throws:
                lv0 = levels[t][0]
                levels[t].append(
                    ConvergenceLevel(
                        fillet_divisions=mopt.fillet_divisions,
                        n_dof=n_dof,
                        fillet_max_edge=edges,
                        peaks={e: best[t, e][0] for e in lv0.peaks},
                        where={e: best[t, e][1] for e in lv0.peaks},
                        seconds=seconds,
                        bore_divisions=mopt.bore_divisions,
                        zones=len(spots),
                    )
                )
            log.info(
                "whole shaft, throws %s, level r/%g: %d zones, %d DOF, %.1f s",
                ", ".join(throws),
                mopt.fillet_divisions,
                len(spots),
                n_dof,
                seconds,
            )
        for t in throws:
            lv = levels[t]
            out[t] = ConvergenceStudy(
                levels=tuple(lv),
                loads={name: dict(loads[t, name]) for name in states[t]},
                tolerance=tolerance,
                changes={
                    e: [abs(b.peaks[e] - a.peaks[e]) / b.peaks[e] for a, b in zip(lv, lv[1:])] for e in lv[0].peaks
                },
                method="zones",
                zone_radius=zone_radius,
            )
    return out


__all__ = [
    "hot_spots_of",
    "piece_of",
    "piece_pins",
    "shaft_throw_study",
    "shaft_zone_studies",
    "surface_peaks",
    "zone_loads",
]
