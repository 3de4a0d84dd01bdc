"""What the assessment takes from the geometry and balance stages.

* ``m53_geometry_of(geometry)``: UR M53 dimensions of a ``CrankGeometry``.  The web
  width B is taken at the middle of the pin/journal overlap (UR M53 3.1 figure), on the
  web outline (convex hull of a circle of ``journal_end_radius`` about the crank axis
  and one of ``pin_end_radius`` about the pin: its width varies linearly between the
  two centres).  The journal of a throw is half a main bearing (docs/geometry.md), so the
  main-bearing centre is the journal's end face and the distance to the web centre line
  is a = L_journal + W/2 (the same lever as the FE supports and SCF mode).  No axial bores, no recesses.
* ``counterweights_of(...)``: per balance plane, the built m r of the throw's
  counterweights (exact B-rep mass properties of the geometry stage, ``fe_crank.geometry.mass``) against the
  balance stage's required m r (``CounterweightDesign.nearest``), and for bolted ones
  each counterweight's joint with its own mass and radius (``joints``, VDI 2230:
  ``assess.cw_joint``) and the bolt capacity n A_s R_e,bolt (A_s: ISO 898-1 tensile stress area of the coarse
  thread for M8-M36, else pi/4 (0.88 d)^2, within 6 % of the table over M8-M30).
"""

from __future__ import annotations

import math
from typing import Any

from fe_crank.assess.counterweight import BoltedCounterweight, CounterweightData, JointGeometry, direction_error
from fe_crank.assess.cw_joint import yield_point
from fe_crank.balance.counterweights import CounterweightDesign
from fe_crank.geometry.mass import MassProperties
from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry, ThrowSpec
from fe_crank.rules.m53.calculation import M53Geometry

#: ISO 898-1 tensile stress area (mm^2) of coarse-pitch metric threads by nominal d (mm)
STRESS_AREA_MM2 = {
    8: 36.6,
    10: 58.0,
    12: 84.3,
    14: 115.0,
    16: 157.0,
    18: 192.0,
    20: 245.0,
    22: 303.0,
    24: 353.0,
    27: 459.0,
    30: 561.0,
    33: 694.0,
    36: 817.0,
}


def m53_geometry_of(geometry: CrankGeometry | None) -> M53Geometry | None:
    """UR M53 dimensions of a ``fe_crank.geometry.spec.CrankGeometry`` (None without one)."""
    g = geometry
    if g is None:
        return None
    d, dg, r = g.crankpin_diameter, g.journal_diameter, g.crank_radius
    y_mid = 0.5 * ((r - 0.5 * d) + 0.5 * dg)  # middle of the overlap (or of the gap)
    rj, rp = g.web.journal_end_radius, g.web.pin_end_radius
    width = 2.0 * (rj + (rp - rj) * min(max(y_mid / r, 0.0), 1.0))
    bore = g.oil_bore
    return M53Geometry(
        pin_diameter=d,
        journal_diameter=dg,
        crank_radius=r,
        web_thickness=g.web_thickness,
        web_width=width,
        pin_fillet_radius=g.crankpin_fillet,
        journal_fillet_radius=g.journal_fillet,
        bearing_to_web=g.journal_length + 0.5 * g.web_thickness,
        pin_length=g.crankpin_length,
        oil_bore_diameter=0.0 if bore is None else bore.diameter,
        oil_bore_angle=0.0 if bore is None else bore.angle,
    )


def stress_area(diameter: float) -> float:
    """Tensile stress area (m^2) of a metric coarse thread of nominal ``diameter`` (m)."""
    d_mm = diameter * 1e3
    for nominal, area in STRESS_AREA_MM2.items():
        if abs(d_mm - nominal) < 0.05:
            return area * 1e-6
    return math.pi / 4.0 * (0.88 * diameter) ** 2


def joint_geometry(g: CrankGeometry, cw: CounterweightSpec) -> JointGeometry:
    """Where the bolted counterweight ``cw`` (``CounterweightSpec``) of ``g`` bears on its web
    (``assess.cw_joint``: the joint's eccentric model)."""
    t = g.web_thickness
    return JointGeometry(
        seat_radius=g.web.journal_end_radius,
        web_thickness=t,
        thickness=cw.thickness,
        inner_radius=cw.inner_radius,
        outer_radius=cw.outer_radius,
        angle=cw.angle,
        bearing_lever=g.journal_length + 0.5 * t,
        bearing_span=g.crankpin_length + 2.0 * (t + g.journal_length),
        web=cw.web,
        offset=cw.offset,
    )


def counterweights_of(
    spec: ThrowSpec,
    props: MassProperties,
    axial_position: float,
    shaft: str,
    design: CounterweightDesign | None,
    geometry: CrankGeometry | None = None,
    frame: tuple[float, int] | None = None,
) -> tuple[CounterweightData, ...]:
    """Counterweight data of one throw (its geometry ``spec`` and its CAD mass properties
    ``props``, from the geometry stage), grouped by the balance plane they serve.

    Counterweights of the throw that are nearest to the same balance counterweight of
    ``design`` are summed (their m r vectors add, each at its counterweight's real angle); ``required_unbalance`` is that
    plane's requirement, or None without a balance design; ``frame``: the engine throw's
    angle and its shaft's sense, to compare the built m r vector's direction with the
    requirement's (``assess.counterweight.direction_error``; None: magnitudes only).
    """
    if not spec.counterweights:
        return ()
    groups: dict[object, list[Any]] = {}
    for cw in spec.counterweights:
        part = props.parts.get(f"counterweight_{cw.web}")
        if part is None:
            continue
        z = axial_position + part.centroid[2]
        plane = design.nearest(shaft, z) if design is not None else None
        groups.setdefault(id(plane) if plane is not None else cw.web, []).append((cw, part, plane))
    out = []
    for items in groups.values():
        mass = sum(p.mass for _, p, _ in items)
        ux = sum(p.unbalance_vector[0] for _, p, _ in items)
        uy = sum(p.unbalance_vector[1] for _, p, _ in items)
        mr = math.hypot(ux, uy)
        plane = items[0][2]
        bolted = [cw.bolted for cw, _, _ in items if cw.bolted is not None]
        capacity = None
        if bolted and all(b.yield_strength is not None or b.property_class is not None for b in bolted):
            capacity = sum(b.count * stress_area(b.diameter) * yield_point(b) for b in bolted)
        joints = tuple(
            BoltedCounterweight(
                f"counterweight_{cw.web}",
                cw.bolted,
                p.mass,
                math.hypot(*p.unbalance_vector[:2]) / p.mass,
                None if geometry is None else joint_geometry(geometry, cw),
            )
            for cw, p, _ in items
            if cw.bolted is not None and p.mass > 0
        )
        out.append(
            CounterweightData(
                name="+".join(f"counterweight_{cw.web}" for cw, _, _ in items),
                mass=mass,
                centroid_radius=mr / mass if mass > 0 else 0.0,
                required_unbalance=None if plane is None else plane.unbalance,
                bolted=bool(bolted),
                bolt_capacity=capacity,
                joints=joints,
                direction_error=None if plane is None or frame is None else direction_error((ux, uy), plane, *frame),
            )
        )
    return tuple(out)
