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
    level_meshes,
)
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.shaft.fields import piece_states
from fe_crank.fe.throw.options import FeOptions, Material
from fe_crank.fe.throw.pin_directions import pin_cases, unit_force
from fe_crank.mesh.zone import ZoneSolid, parametric_solid

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


def surface_peaks(mesh, basis, material: Material, fields: dict[str, np.ndarray]):
    """{entry: (peak von Mises, Pa, surface, node)} of each load set on each hot-spot family
    of a throw mesh (entries as ``levels.level_peaks``'s: the family's prefix + load set),
    and per load set and family {surface: (peak, node)} (the hot spots' candidates)."""
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
    best: dict[str, tuple[float, str]] = {}
    per: dict[tuple[str, str], dict[str, tuple[float, int]]] = {}
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
                best[prefix + key] = (peaks[top][0], top)
    return best, per


def hot_spots_of(
    per: dict[tuple[str, str], dict[str, tuple[float, int]]],
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
    cases: ShaftCases,
    material: Material,
    throw: str,
    states: dict[str, np.ndarray],
    *,
    solid: ZoneSolid | None = None,
    factors=FACTORS,
    tolerance: float = TOLERANCE,
    zone_radius: float = ZONE_RADIUS,
    solver: str = "auto",
    displacements: dict[str, np.ndarray] | None = None,
) -> ConvergenceStudy:
    """The study (module doc) of throw ``throw`` of the whole shaft under its load sets
    ``states`` ({name: case weights (n_cases,)}); ``solid``: the throw's solid the zones are
    cut from (default: the layout's parametric throw); ``displacements``: the piece's
    displacement of each load set (interleaved, its own frame) where already known
    (default: ``piece_states``)."""
    if len(factors) < 2 or factors[0] != 1.0:
        raise ValueError("a zone study starts from the assessed mesh (factor 1) and has at least two levels")
    t0 = time.perf_counter()
    k = piece_of(cases, throw)
    pp = cases.model.pieces[k]
    sm = cases.model.mesh
    tm = sm.throw_meshes[sm.pieces[k].mesh]
    c = pp.cond
    names = list(states)
    W = np.column_stack([np.asarray(states[n], float) for n in names])
    if displacements is None:
        U = piece_states(cases, {k: W}, material, solver)[k]
        displacements = {n: U[:, j] for j, n in enumerate(names)}
    fields = {n: displacements[n] for n in names}
    coef = cases.coef[k] @ W
    loads = {n: zone_loads(c.names, coef[:, j]) for j, n in enumerate(names)}
    half_angle = cases.model.options.pin_half_angle
    pins = piece_pins(cases, k, half_angle)
    first, per = surface_peaks(c.mesh, c.basis, material, fields)
    base = tm.options
    levels = [
        ConvergenceLevel(
            fillet_divisions=base.fillet_divisions,
            n_dof=int(3 * c.basis.N),
            fillet_max_edge=dict(tm.stats.fillet_max_edge),
            peaks={e: v[0] for e, v in first.items()},
            where={e: v[1] for e, v in first.items()},
            seconds=time.perf_counter() - t0,
            reused=True,
            bore_divisions=base.bore_divisions,
        )
    ]
    if solid is None:
        spec = next(t.spec for t in sm.layout.throws if t.name == throw)
        solid = parametric_solid(sm.layout.geometry, spec)

    def radius_of(surface: str) -> float:
        return tm.fillet_radii[surface] if surface in tm.fillet_radii else solid.lengths[surface]

    spots = hot_spots_of(per, np.asarray(c.basis.doflocs), radius_of, zone_radius)
    interp = Interpolator(c.mesh, c.basis.dofs, np.asarray(c.basis.doflocs))
    options = FeOptions(pin_half_angle=half_angle)
    every = [n for _, ns in FAMILIES for n in ns]
    t0 = time.perf_counter()
    mopts = [
        dataclasses.replace(base, fillet_divisions=base.fillet_divisions * f, bore_divisions=base.bore_divisions * f)
        for f in factors[1:]
    ]
    meshes = level_meshes(solid, mopts, spots, boundary_samples(c.mesh), GROUP_FRACTION * c.basis.N)
    meshing = (time.perf_counter() - t0) / len(mopts)
    for mopt, zones in zip(mopts, meshes):
        t0 = time.perf_counter() - meshing
        best: dict[str, tuple[float, str]] = {}
        n_dof, edges = 0, dict[str, float]()
        for zm in zones:
            Uz, zb = solve_zone(zm, material, options, pins, loads, fields, interp)
            n_dof += int(3 * zb.N)
            for s, v in zm.fillet_max_edge.items():
                edges[s] = max(edges.get(s, 0.0), v)
            got = zone_peaks(zm, zb, material, Uz, every, REACH)
            for name, found in got.items():
                for prefix, surfaces in FAMILIES:
                    for s in surfaces:
                        if s in found and found[s] > best.get(prefix + name, (-np.inf, ""))[0]:
                            best[prefix + name] = (found[s], s)
        missing = sorted(set(first) - set(best))
        if missing:
            raise RuntimeError(f"the whole shaft's hot-spot zones of throw {throw} hold no node of {missing}")
        levels.append(
            ConvergenceLevel(
                fillet_divisions=mopt.fillet_divisions,
                n_dof=n_dof,
                fillet_max_edge=edges,
                peaks={e: best[e][0] for e in first},
                where={e: best[e][1] for e in first},
                seconds=time.perf_counter() - t0,
                bore_divisions=mopt.bore_divisions,
                zones=len(spots),
            )
        )
        log.info("whole shaft, throw %s, level r/%g: %d zones, %d DOF", throw, mopt.fillet_divisions, len(spots), n_dof)
    changes = {
        e: [abs(b.peaks[e] - a.peaks[e]) / b.peaks[e] for a, b in zip(levels, levels[1:])] for e in levels[0].peaks
    }
    return ConvergenceStudy(
        levels=tuple(levels),
        loads={n: dict(loads[n]) for n in names},
        tolerance=tolerance,
        changes=changes,
        method="zones",
        zone_radius=zone_radius,
    )


__all__ = ["hot_spots_of", "piece_of", "piece_pins", "shaft_throw_study", "surface_peaks", "zone_loads"]
