"""What the assessment takes from a throw recognised in a CAD file (``fe_crank.cad``).

* ``m53_geometry_of_cad(throw, cad)``: the UR M53 dimensions measured on the B-rep.
  Where the two sides of a throw differ, the value that gives the larger stress is
  taken: the smaller pin and journal diameters, web thickness, web width and fillet
  radii (the stress concentration factors of UR M53 3.2/3.3 grow as each falls), the
  longer lever from a bearing centre to its web's centre line.  B is the web's width
  measured across its mid-plane at the middle of the pin/journal overlap (UR M53 3.1),
  on the solid itself; a web with an opening across that section (a lightening hole)
  is outside the formulas' scope (``m53_scope``: no M53 dimensions, the FE route
  assesses it).  D_BH, D_BG: axial bores recognised in the pin and journals.
  The recesses T_H, T_G are not measured: a fillet that reaches into the web
  (``Fillet.undercut > 0``) needs ``[cad] pin_recess`` / ``journal_recess`` as UR M53
  defines them; without a recessed fillet they are 0 unless given.
* ``counterweights_of_cad(throw, axial_position, shaft, design, bolted)``: per balance
  plane, the built m r of the throw's counterweights and of the bodies bolted to it (the
  B-rep's exact mass properties) against the balance stage's required m r
  (``CounterweightDesign.nearest``).
"""

from __future__ import annotations

import math
from typing import Any

from fe_crank.assess.counterweight import CounterweightData, direction_error
from fe_crank.balance.counterweights import CounterweightDesign
from fe_crank.cad.config import CadInput
from fe_crank.cad.features import BoltedBody, ThrowFeatures
from fe_crank.errors import InputError
from fe_crank.rules.m53.calculation import M53Geometry


def _recess(cad: CadInput, throw: ThrowFeatures, kind: str, given: float | None) -> float:
    names = (f"{kind}_fillet_1", f"{kind}_fillet_2")
    deepest = max((f.undercut for f in throw.fillets if f.name in names), default=0.0)
    if given is not None:
        return given
    if deepest > 0.0:
        key = "cad.pin_recess" if kind == "crankpin" else "cad.journal_recess"
        raise InputError(
            f"throw {throw.name}: the {kind} fillet reaches {deepest * 1e3:.4g} mm into the web (a recessed "
            f"fillet); UR M53 needs its recess as UR M53 3.1 defines it: state it in {cad.where}",
            file=str(cad.file),
            key=key,
        )
    return 0.0


def m53_scope(throw: ThrowFeatures, tol: float = 1e-6) -> str | None:
    """Why UR M53's empirical formulas do not describe the throw, or None: a web with an
    opening across the section where B is measured (a lightening hole) is not the solid
    web the formulas were fitted to (the FE route still assesses it)."""
    for w in throw.webs:
        if w.solid_width < w.width - tol:
            return (
                f"web {w.side} has an opening across its section at the pin/journal overlap "
                f"({w.solid_width * 1e3:.4g} mm of material in a width of {w.width * 1e3:.4g} mm)"
            )
    return None


def m53_geometry_of_cad(throw: ThrowFeatures, cad: CadInput) -> M53Geometry | None:
    """UR M53 dimensions of a recognised throw (see the module docstring); None when the
    throw is outside the empirical formulas' scope (``m53_scope``)."""
    if m53_scope(throw) is not None:
        return None
    pin = [f.radius for f in throw.fillets if f.name.startswith("crankpin")]
    jou = [f.radius for f in throw.fillets if f.name.startswith("journal")]
    levers = [abs(b.z - 0.5 * (w.z_inner + w.z_outer)) for b, w in zip(throw.bearings, throw.webs)]
    bores = [b for b in throw.oil_bores if "crankpin" in b.ends_on]
    bore = max(bores, key=lambda b: b.diameter, default=None)
    return M53Geometry(
        pin_diameter=throw.crankpin.diameter,
        journal_diameter=min(j.diameter for j in throw.journals),
        crank_radius=throw.crank_radius,
        web_thickness=min(w.thickness for w in throw.webs),
        web_width=min(w.width for w in throw.webs),
        pin_fillet_radius=min(pin) if len(pin) == 2 else 0.0,
        journal_fillet_radius=min(jou) if len(jou) == 2 else 0.0,
        bearing_to_web=max(levers),
        pin_bore=throw.crankpin.bore_diameter,
        journal_bore=max(j.bore_diameter for j in throw.journals),
        pin_recess=_recess(cad, throw, "crankpin", cad.pin_recess),
        journal_recess=_recess(cad, throw, "journal", cad.journal_recess),
        pin_length=throw.pin_length,
        oil_bore_diameter=0.0 if bore is None else bore.diameter,
        oil_bore_angle=0.0 if bore is None else bore.angle,
    )


def counterweights_of_cad(
    throw: ThrowFeatures,
    axial_position: float,
    shaft: str,
    design: CounterweightDesign | None,
    bolted: tuple[tuple[int, BoltedBody], ...] = (),
    frame: tuple[float, int] | None = None,
) -> tuple[CounterweightData, ...]:
    """Counterweight data of a recognised throw, grouped by the balance plane they serve
    (as ``fe_crank.assess.adapters.counterweights_of``): its drawn counterweights and the
    bodies bolted to it (``bolted``: (number in ``CadFeatures.bolted`` from 1, body) of
    this throw; ``[cad] bodies = "bolted"``), whose m r adds to their plane's and whose
    centrifugal force is the bolts' load (no bolt data: no utilisation); ``frame`` as there."""
    parts = [(f"counterweight_{cw.web}", cw.mass, False, cw.web) for cw in throw.counterweights]
    parts += [(f"bolted_body_{i}", b.mass, True, b.web) for i, b in bolted]
    groups: dict[object, list[Any]] = {}
    for name, mass, is_bolted, web in parts:
        z = axial_position + mass.centroid[2]
        plane = design.nearest(shaft, z) if design is not None else None
        groups.setdefault(id(plane) if plane is not None else web, []).append((name, mass, is_bolted, plane))
    out = []
    for items in groups.values():
        mass = sum(m.mass for _, m, _, _ in items)
        ux = sum(m.unbalance_vector[0] for _, m, _, _ in items)
        uy = sum(m.unbalance_vector[1] for _, m, _, _ in items)
        mr = math.hypot(ux, uy)
        plane = items[0][3]
        out.append(
            CounterweightData(
                name="+".join(name for name, _, _, _ in items),
                mass=mass,
                centroid_radius=mr / mass if mass > 0 else 0.0,
                required_unbalance=None if plane is None else plane.unbalance,
                bolted=any(b for _, _, b, _ in items),
                direction_error=None if plane is None or frame is None else direction_error((ux, uy), plane, *frame),
            )
        )
    return tuple(out)
