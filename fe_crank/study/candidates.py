"""Counterweight candidates: per-web mass factors, the sector that builds each, the balance residual.

A candidate is a placement (the webs that carry a counterweight), a rotating balance rate
f_rot and a reciprocating share f_rec.  Each throw's target unbalance, as the balance
stage sizes it per throw (``balance.counterweights``)::

    U_t = (f_rot m_rot + f_rec sum_j m_j) R

is split equally over the throw's placed webs.  Each placed web's counterweight is the
shape drawn on that web scaled in mass by k_w = (U_t / n_t) / U_w (U_w: the drawn
counterweight's m r from the solid's exact mass properties, ``geometry.mass``), its
centre of mass where the drawn one's is (opposite the pin, or turned by the offset,
below); a web left out has k_w = 0.  Mass, m r and polar
inertia scale with k_w exactly.

The parametric shape that reaches k_w U_w: an annular sector (``balance.sector``) with
the drawn radii, angle and thickness, one dimension solved for, trying the study's
``free`` dimensions in order.  The solid's m r differs from the closed-form sector's
where the counterweight overlaps the web; the sector is solved for
k_w U_sector(drawn), which builds k_w U_w exactly when the thickness is solved for (the
counterweight and the part of it the web hides are prisms of that thickness) and to
within that overlap's change otherwise.  A shape is refused (the candidate reported as
not buildable, with the reason) when it needs a thickness beyond the web's, an outer
radius beyond the envelope, more than a half ring, an inner radius inside the journal,
or a sector that reaches the crankpin (with its fillet).

The offset (``study.offset``): a candidate's counterweights are the drawn ones turned
rigidly to the offset from opposite the pin (``CounterweightSpec.offset``; the drawn
offset when the study states none).  A turned counterweight is another solid: its
centrifugal load is spread over other elements and its m r points elsewhere, so the
drawn counterweights turned to each offset (``turned_view``) are a shaft of their own,
with their exact mass properties, their own mesh and unit cases (``study.run``); the
mass factors k_w are taken on that shaft's drawn webs.

The balance residual: the free forces of the engine (``balance.forces.free_forces``:
rotating and reciprocating) with the candidate's counterweights added as rotating
masses k_w U_w at their planes (the parts' centroids) and in the direction of the drawn
(turned) counterweight's m r, first order.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from fe_crank.balance.forces import FreeForces, free_forces
from fe_crank.balance.mechanism import reciprocating_mass, rotating_mass
from fe_crank.balance.sector import SectorProperties, annular_sector, solve_sector
from fe_crank.balance.terms import point_term, rotating_force
from fe_crank.errors import GeometryError, InputError
from fe_crank.geometry.checks import check_geometry
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry, ThrowSpec
from fe_crank.io.geometry import bolt_misfit
from fe_crank.model import Engine
from fe_crank.study.spec import StudySpec

Web = tuple[str, int]  # (throw name, web 1 front / 2 rear)


@dataclass(frozen=True)
class DrawnWeb:
    """The counterweight drawn on one web: its spec and its solid's exact properties."""

    web: Web
    spec: CounterweightSpec
    mass: float  # kg
    unbalance: float  # kg m
    unbalance_vector: tuple[float, float]  # kg m, throw frame
    polar_inertia: float  # kg m^2 about the crank axis
    z: float  # m, the part's centroid on the shaft (engine frame)
    sector_unbalance: float  # kg m, the closed-form sector of the drawn dimensions


@dataclass(frozen=True)
class WebShape:
    web: Web
    factor: float  # k_w
    sector: SectorProperties | None  # None: no counterweight, or not buildable
    free: str | None  # the dimension solved for
    refused: str | None  # why it cannot be built


@dataclass(frozen=True)
class Candidate:
    index: int
    placement: str
    rotating: float  # fraction
    reciprocating: float  # fraction
    offset: float  # rad
    factors: dict[Web, float]  # every drawn web: k_w (0 where left out)
    shapes: tuple[WebShape, ...]  # the placed webs

    @property
    def buildable(self) -> bool:
        return all(s.refused is None for s in self.shapes)

    @property
    def refusals(self) -> tuple[str, ...]:
        """Why it cannot be built, webs of one reason together."""
        by: dict[str, list[str]] = {}
        for s in self.shapes:
            if s.refused:
                by.setdefault(s.refused, []).append(f"{s.web[0]}.{s.web[1]}")
        return tuple(f"web{'s' if len(w) > 1 else ''} {', '.join(w)}: {why}" for why, w in by.items())

    @property
    def label(self) -> str:
        rec = f" + {round(self.reciprocating * 100, 9):g} % recip." if self.reciprocating else ""
        off = f", turned {round(math.degrees(self.offset), 9):g} deg" if self.offset else ""
        return f"{self.placement}, {round(self.rotating * 100, 9):g} %{rec}{off}"


def drawn_webs(layout: ShaftLayout, mass: dict) -> dict[Web, DrawnWeb]:
    """Every web drawn with a counterweight, in axial order (``mass``: throw name ->
    ``geometry.mass.MassProperties``, ``fe.shaft.whole_shaft.throw_masses``)."""
    out = {}
    for th in layout.throws:
        for cw in sorted(th.spec.counterweights, key=lambda c: c.web):
            p = mass[th.name].parts[f"counterweight_{cw.web}"]
            sec = annular_sector(cw.outer_radius, cw.inner_radius, cw.thickness, cw.angle, mass[th.name].density)
            out[(th.name, cw.web)] = DrawnWeb(
                (th.name, cw.web),
                cw,
                p.mass,
                p.unbalance,
                p.unbalance_vector,
                p.inertia_axis,
                th.z + p.centroid[2],
                sec.unbalance,
            )
    return out


def throw_targets(engine: Engine, f_rot: float, f_rec: float) -> dict[str, float]:
    """U_t (kg m) per throw (module doc)."""
    out = {}
    for t in engine.throws:
        mj = sum(reciprocating_mass(c) for c in engine.cylinders if c.throw == t.name)
        out[t.name] = (f_rot * rotating_mass(engine, t.name) + f_rec * mj) * t.crank_radius
    return out


def placed_webs(spec: StudySpec, drawn: dict[Web, DrawnWeb], layout: ShaftLayout) -> dict[str, tuple[Web, ...]]:
    """Placement name -> its webs, checked against the drawn ones (``InputError`` with the key)."""
    out = {}
    any_rate = any(f > 0.0 for f in spec.rotating) or any(f > 0.0 for f in spec.reciprocating)
    for i, p in enumerate(spec.placements):
        key = f"study.placements[{i}].webs"
        webs = tuple(drawn) if p.webs is None else p.webs
        for j, w in enumerate(webs):
            if w not in drawn:
                raise InputError(
                    f"web {w[0]}.{w[1]} has no counterweight in the geometry ({layout.geometry_file}): "
                    "the study scales the counterweight drawn on a web, so draw one there",
                    file=spec.file,
                    key=key if p.webs is None else f"{key}[{j}]",
                )
        if any_rate:
            for th in layout.throws:
                if not any(w[0] == th.name for w in webs):
                    raise InputError(
                        f"throw {th.name} has no web in this placement: its counterweight share has nowhere to go",
                        file=spec.file,
                        key=key,
                    )
        out[p.name] = webs
    return out


def check_buildable_as_drawn(spec: StudySpec, drawn: dict[Web, DrawnWeb], layout: ShaftLayout) -> None:
    """The drawn counterweights are the family's base shape: one beyond the envelope or
    through the crankpin is bad input."""
    for w, d in drawn.items():
        why = _clash(d.spec.outer_radius, d.spec.inner_radius, d.spec.angle, layout, spec.envelope, d.spec.offset)
        if why:
            raise InputError(
                f"the counterweight drawn on web {w[0]}.{w[1]} {why}",
                file=spec.file,
                key="study.envelope" if "envelope" in why else "study.placements",
            )


def _clash(
    r1: float, r2: float, angle: float, layout: ShaftLayout, envelope: float | None, offset: float = 0.0
) -> str | None:
    """Beyond the envelope, or reaching the crankpin's direction: the sector's edge nearer
    the pin lies ``pi - |offset| - angle/2`` from it (the exact clearance is the
    geometry's own check, ``_geometry_refuses``)."""
    g = layout.geometry
    if envelope is not None and r1 > envelope * (1 + 1e-12):
        return f"reaches {r1 * 1e3:.4g} mm, beyond the envelope of {envelope * 1e3:.4g} mm"
    R, rp = g.crank_radius, g.crankpin_diameter / 2 + g.crankpin_fillet
    half = math.asin(min(1.0, rp / R)) if R > 0 else math.pi
    if math.pi - abs(offset) - angle / 2 < half and r2 < R + rp and r1 > R - rp:
        turned = f" turned {math.degrees(offset):.4g} deg" if offset else ""
        return (
            f"reaches the crankpin: a {math.degrees(angle):.4g} deg sector{turned} from {r2 * 1e3:.4g} to {r1 * 1e3:.4g} mm "
            f"overlaps the pin (radius with fillet {rp * 1e3:.4g} mm at {R * 1e3:.4g} mm)"
        )
    return None


def _geometry_refuses(layout: ShaftLayout, web: Web, cw: CounterweightSpec, s: SectorProperties) -> str | None:
    """The geometry's own rules (``geometry.checks``: clear of the pin and its fillet,
    the fillet fits the step to the web's face, ...; ``io.geometry.bolt_misfit``: a bolted
    counterweight's bolts pass through it) on the throw with this sector."""
    new = dataclasses.replace(cw, outer_radius=s.r_outer, inner_radius=s.r_inner, angle=s.angle, thickness=s.thickness)
    th = next(t for t in layout.throws if t.name == web[0])
    g = dataclasses.replace(layout.geometry, throws=(dataclasses.replace(th.spec, counterweights=(new,)),))
    try:
        check_geometry(g)
    except GeometryError as exc:
        return exc.reason
    return bolt_misfit(g, new)  # the bolts as drawn must still pass through it (the geometry file's rule)


def web_shape(web: Web, k: float, d: DrawnWeb, layout: ShaftLayout, spec: StudySpec, density: float) -> WebShape:
    """The sector that builds k U_w on this web (module doc)."""
    if k == 0.0:
        return WebShape(web, 0.0, None, None, None)
    cw = d.spec
    if k == 1.0:
        return WebShape(
            web, 1.0, annular_sector(cw.outer_radius, cw.inner_radius, cw.thickness, cw.angle, density), None, None
        )
    target = k * d.sector_unbalance
    t_web = layout.geometry.web_thickness
    reasons = []
    for free in spec.free:
        given: dict[str, float | None] = {
            "r_outer": cw.outer_radius,
            "r_inner": cw.inner_radius,
            "thickness": cw.thickness,
            "angle": cw.angle,
        }
        given[free] = None
        try:
            s = solve_sector(
                target,
                free=free,
                r_outer=given["r_outer"],
                r_inner=given["r_inner"],
                thickness=given["thickness"],
                angle=given["angle"],
                density=density,
                envelope=spec.envelope,
                # the drawn inner radius stands (a counterweight may reach over the journal's
                # root as drawn); a solved one may not reach inside the journal
                journal_radius=layout.geometry.journal_diameter / 2 if free == "r_inner" else None,
            )
        except InputError as exc:
            reasons.append(f"{free}: {exc.reason}")
            continue
        if s.thickness > t_web * (1 + 1e-12):
            reasons.append(f"thickness: {s.thickness * 1e3:.4g} mm, thicker than the web ({t_web * 1e3:.4g} mm)")
            continue
        why = _clash(s.r_outer, s.r_inner, s.angle, layout, spec.envelope, cw.offset) or _geometry_refuses(
            layout, web, cw, s
        )
        if why:
            reasons.append(f"{free}: {why}")
            continue
        return WebShape(web, k, s, free, None)
    return WebShape(web, k, None, None, "; ".join(reasons))


def drawn_offset(drawn: dict[Web, DrawnWeb], spec: StudySpec) -> float:
    """The offset every drawn counterweight is turned by (rad): the study's offsets when it
    states none; drawn counterweights turned differently need the study's (``InputError``)."""
    offs = sorted({d.spec.offset for d in drawn.values()})
    if len(offs) > 1:
        raise InputError(
            "the drawn counterweights are turned by different offsets ("
            + ", ".join(f"{math.degrees(o):.6g} deg" for o in offs)
            + "): state the offsets to screen",
            file=spec.file,
            key="study.offset",
        )
    return offs[0] if offs else 0.0


def study_offsets(spec: StudySpec, drawn: dict[Web, DrawnWeb]) -> tuple[float, ...]:
    """The offsets the study screens (rad): its stated ones, else the drawn one."""
    return spec.offsets if spec.offsets is not None else (drawn_offset(drawn, spec),)


def turned_geometry(g: CrankGeometry, offset: float) -> CrankGeometry:
    """The geometry with every counterweight turned to ``offset`` (rad, from opposite the
    pin towards +x): the same sectors, rigidly turned."""
    throws = tuple(
        dataclasses.replace(t, counterweights=tuple(dataclasses.replace(cw, offset=offset) for cw in t.counterweights))
        for t in g.throws
    )
    return dataclasses.replace(g, throws=throws)


def turned_view(
    layout: ShaftLayout, drawn: dict[Web, DrawnWeb], offset: float, mass: dict | None = None
) -> tuple[ShaftLayout, dict[Web, DrawnWeb], dict]:
    """The shaft with its drawn counterweights turned to ``offset`` (``turned_geometry``),
    its drawn webs (their exact mass properties) and its throws' mass properties
    (``mass``: the drawn shaft's, returned as they are when nothing turns)."""
    from fe_crank.fe.shaft.whole_shaft import throw_masses

    if all(d.spec.offset == offset for d in drawn.values()):
        return layout, drawn, mass if mass is not None else throw_masses(layout)
    g = turned_geometry(layout.geometry, offset)
    placed = tuple(dataclasses.replace(th, spec=g.throw(th.spec.name)) for th in layout.throws)
    turned = dataclasses.replace(layout, geometry=g, throws=placed)
    m = throw_masses(turned)
    return turned, drawn_webs(turned, m), m


def candidates(
    spec: StudySpec, drawn: dict[Web, DrawnWeb], layout: ShaftLayout, engine: Engine
) -> tuple[Candidate, ...]:
    """Every placement x rotating rate x reciprocating share x offset, in that order; the
    shapes of an offset on the drawn counterweights turned to it (``turned_view``)."""
    webs_of = placed_webs(spec, drawn, layout)
    check_buildable_as_drawn(spec, drawn, layout)
    density = layout.geometry.density
    views = {}
    for i, off in enumerate(study_offsets(spec, drawn)):
        if off not in views:
            try:  # the geometry's own rules on the turned counterweights, before any solid is built
                check_geometry(turned_geometry(layout.geometry, off))
            except GeometryError as exc:
                raise InputError(
                    f"the drawn counterweights turned to {math.degrees(off):.6g} deg: {exc.reason}",
                    file=spec.file,
                    key=f"study.offset[{i}]",
                ) from None
            lay, dr, _ = turned_view(layout, drawn, off, mass={})
            try:
                check_buildable_as_drawn(spec, dr, lay)
            except InputError as exc:
                raise InputError(
                    f"turned to {math.degrees(off):.6g} deg, {exc.reason}", file=spec.file, key=f"study.offset[{i}]"
                ) from None
            views[off] = (lay, dr)
    out: list[Candidate] = []
    for p in spec.placements:
        webs = webs_of[p.name]
        for f_rot in spec.rotating:
            for f_rec in spec.reciprocating:
                target = throw_targets(engine, f_rot, f_rec)
                for off in study_offsets(spec, drawn):
                    lay, dr = views[off]
                    factors = dict.fromkeys(dr, 0.0)
                    shapes = []
                    for w in webs:
                        n_t = sum(1 for x in webs if x[0] == w[0])
                        k = (target[w[0]] / n_t) / dr[w].unbalance
                        factors[w] = k
                        shapes.append(web_shape(w, k, dr[w], lay, spec, density))
                    out.append(Candidate(len(out), p.name, f_rot, f_rec, off, factors, tuple(shapes)))
    return tuple(out)


def residual(
    engine: Engine,
    speed: float,
    drawn: dict[Web, DrawnWeb],
    factors: dict[Web, float],
    planes: dict[Web, float] | None = None,
) -> FreeForces:
    """The free forces with the candidate's counterweights (module doc; reference z = 0):
    each web's k_w U_w at ``planes`` (default the drawn part's centroid), in the direction
    of the drawn counterweight's m r: opposite its pin for one centred there, else the
    direction of its solid's m r vector (throw frame, from +y towards +x)."""
    before = free_forces(engine, speed)
    terms = []
    for w, k in factors.items():
        if k == 0.0:
            continue
        d = drawn[w]
        z = d.z if planes is None else planes[w]
        t = engine.throw(w[0])
        sh = engine.shaft(t.shaft)
        # a sector centred on -y: exactly opposite the pin; a turned one: its m r's direction
        a = math.atan2(*d.unbalance_vector) if d.spec.offset != 0.0 else math.pi
        psi = sh.phase + sh.sense * t.angle + a
        force = rotating_force(k * d.unbalance * (sh.speed_ratio * speed) ** 2, psi, sh.sense)
        terms.append(point_term("counterweights", sh.speed_ratio, force, (sh.centre[0], sh.centre[1], z)))
    return before.with_terms(terms)


def first_order(ff: FreeForces) -> tuple[float, float]:
    """Largest first-order free force (N) and couple (N m) over a revolution."""
    t = ff.total(1.0, None)
    return float(t.force_hodograph().major), float(t.moment_hodograph().major)


def unbalance_total(factors: dict[Web, float], drawn: dict[Web, DrawnWeb]) -> float:
    return float(np.sum([k * drawn[w].unbalance for w, k in factors.items()]))


def achieved_unbalance(
    layout: ShaftLayout, cand: Candidate, drawn: dict[Web, DrawnWeb]
) -> dict[Web, tuple[float, float]]:
    """Per placed web: (target k_w U_w, the m r of the written sector's solid) in kg m,
    from the solid's exact mass properties (``geometry.mass``): the check of the sector
    synthesis where the counterweight overlaps the web."""
    from fe_crank.geometry.mass import mass_properties

    out = {}
    for s in cand.shapes:
        if s.sector is None or s.factor == 0.0:
            continue
        cw = drawn[s.web].spec
        new = dataclasses.replace(
            cw,
            outer_radius=s.sector.r_outer,
            inner_radius=s.sector.r_inner,
            angle=s.sector.angle,
            thickness=s.sector.thickness,
        )
        th = next(t for t in layout.throws if t.name == s.web[0])
        mp = mass_properties(layout.geometry, dataclasses.replace(th.spec, counterweights=(new,)))
        out[s.web] = (s.factor * drawn[s.web].unbalance, mp.counterweight_unbalance(s.web[1]))
    return out


def written_throw(th_spec: ThrowSpec, cand: Candidate) -> ThrowSpec:
    """The throw the candidate writes (``study.outputs.write_candidate``): each placed
    web's counterweight the solved sector, a drawn web left out without one."""
    shapes = {s.web: s for s in cand.shapes}
    cws = []
    for cw in th_spec.counterweights:
        s = shapes.get((th_spec.name, cw.web))
        if s is None or s.factor == 0.0 or s.sector is None:
            continue
        cws.append(
            dataclasses.replace(
                cw,
                outer_radius=s.sector.r_outer,
                inner_radius=s.sector.r_inner,
                angle=s.sector.angle,
                thickness=s.sector.thickness,
            )
        )
    return dataclasses.replace(th_spec, counterweights=tuple(cws))


@dataclass(frozen=True)
class WrittenMass:
    """The shaft a candidate writes, from its solids' exact mass properties
    (``geometry.mass``; docs/study.md, "The shape that reaches each mass").

    ``load_factors``: per drawn web, the factor on the drawn counterweight's centrifugal
    case whose m r equals the written shaft's change on that web: the written
    counterweight's m r plus the web material the drawn prism took and the written one
    leaves to the web (the web part's m r, written minus drawn), projected on the drawn
    counterweight's direction; ``planes``: the axial position (m, shaft) of that m r's
    first moment."""

    exact: bool  # False: a shape could not be built, the drawn one scaled stands in
    counterweight_mass: float  # kg, the written counterweights together
    mass_change: float  # kg, the written shaft against the drawn one
    polar_inertia_change: float  # kg m^2
    unbalance: float  # kg m, the written counterweights' m r together
    load_factors: dict[Web, float]
    planes: dict[Web, float]


class ThrowSolidCache:
    """``mass_properties`` of throw solids, each distinct solid (its counterweights'
    dimensions; name, angle and bolts do not change it) built once."""

    def __init__(self, layout: ShaftLayout):
        self.geometry = layout.geometry
        self._by: dict = {}

    def of(self, spec: ThrowSpec):
        from fe_crank.geometry.mass import mass_properties

        key = tuple(dataclasses.replace(cw, bolted=None) for cw in spec.counterweights)
        if key not in self._by:
            self._by[key] = mass_properties(self.geometry, spec)
        return self._by[key]


def written_mass(
    layout: ShaftLayout, cand: Candidate, drawn: dict[Web, DrawnWeb], mass: dict, solids: ThrowSolidCache
) -> WrittenMass:
    """The candidate's written shaft (class doc); ``mass``: the drawn throws' properties."""
    if not cand.buildable:
        return WrittenMass(
            False,
            sum(k * drawn[w].mass for w, k in cand.factors.items()),
            sum((k - 1.0) * drawn[w].mass for w, k in cand.factors.items()),
            sum((k - 1.0) * drawn[w].polar_inertia for w, k in cand.factors.items()),
            sum(k * drawn[w].unbalance for w, k in cand.factors.items()),
            dict(cand.factors),
            {w: d.z for w, d in drawn.items()},
        )
    cw_mass = d_mass = d_j = u_sum = 0.0
    factors: dict[Web, float] = {}
    planes: dict[Web, float] = {}
    for th in layout.throws:
        old = mass[th.name]
        new = solids.of(written_throw(th.spec, cand))
        d_mass += new.total.mass - old.total.mass
        d_j += new.total.inertia_axis - old.total.inertia_axis
        for w in (1, 2):
            part = new.parts.get(f"counterweight_{w}")
            if part is not None:
                cw_mass += part.mass
                u_sum += part.unbalance
            d = drawn.get((th.name, w))
            if d is None:
                continue
            uw = np.asarray(d.unbalance_vector)
            web_new, web_old = new.parts[f"web_{w}"], old.parts[f"web_{w}"]
            items = [(web_new, 1.0), (web_old, -1.0)] + ([(part, 1.0)] if part is not None else [])
            u = sum(s * np.asarray(p.unbalance_vector) for p, s in items)
            first = sum(s * np.asarray(p.unbalance_vector) * p.centroid[2] for p, s in items)
            proj = float(u @ uw)
            factors[(th.name, w)] = proj / float(uw @ uw)
            planes[(th.name, w)] = th.z + (float(first @ uw) / proj if proj != 0.0 else d.z - th.z)
    return WrittenMass(True, cw_mass, d_mass, d_j, u_sum, factors, planes)
