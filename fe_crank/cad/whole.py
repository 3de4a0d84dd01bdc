"""The whole crankshaft as drawn: the recognised throws placed on their drawn bearings.

``cad_shaft_layout`` gives the ``fe_crank.geometry.shaft.ShaftLayout`` of a drawing of
several throws (its throw positions, journals and bearing centres as drawn, the engine's
throw angles, which ``fe_crank.cad.engine`` has checked against the drawing), and
``cad_shaft_mesh`` its mesh as the parametric whole shaft is meshed
(``fe_crank.mesh.shaft.mesh_shaft``): each throw's mesh turned and shifted to its place,
its end faces at the bearing centres split into equal sectors with rotated-copy meshes
(``fe_crank.mesh.interface``, the journal redrawn there as a round bar whose seam lies
on the throw frame's ``+y``: ``fe_crank.cad.model.redraw_ends``), so that neighbouring
throws meet node to node; the end journals' outer halves extruded from the end faces.

Throws that are the same solid share one mesh (as a parametric shaft's equal throws do):
each throw's recognised dimensions (oil bores and counterweights included) equal an
earlier throw's to ``SAME_TOL`` (relative to the crank radius) and its exact mass
properties (volume, centroid, inertia tensor of the throw between its bearing centres and
of each of its parts, in its throw frame) to ``SAME_TOL`` relative; the
others are meshed each on its own, with end faces that still meet node to node (the same
journal, the same sectors; checked when the shaft is joined).  The journals, pin length,
webs and bearing centres must be every throw's the same (``COMMON``: one geometry carries
them for the whole-shaft stage); a drawing whose throws differ there is refused, naming
the throw and the quantity, as is one whose throws are not evenly pitched (the bearing
centres of neighbours must meet).  Bodies bolted to the shaft (``[cad] bodies =
"bolted"``, ``CadFeatures.bolted``: kept out of the meshes) enter the layout as
``BoltedMass``es: each one's centrifugal force (its exact m r) on the journal beside its
web at its centroid's z, with the counterweights (``fe.shaft.whole_shaft``).

The ``ShaftLayout``'s ``geometry`` carries the drawing's recognised dimensions that the
whole-shaft stage reads (crank radius, journal and pin diameters, pin length, web
thickness, bearing centre to web, fillet radii; no counterweight specs: the web moments
take a drawn counterweight over its web's thickness, ``fe.shaft.cycle``); its web outline is the web's recognised side radius
(no parametric solid is built from it).  The bearings are the engine's, not the drawing's:
``[cad.shaft]`` states them as a geometry's ``[shaft]`` does (``bearing_spec``: widths, laws
with the oil film, per-bearing entries, the thrust bearing, the stiffness range, the power
take-off, flywheel and pulley; ``fe_crank.geometry.shaft.main_bearings`` places them on the
drawn journals), ``[cad] bearing_width`` their default width; where neither states them,
``ShaftSpec``'s defaults: one rigid main bearing per journal, named ``"1"``, ``"2"``, ...
from the front, as wide as the drawn journal's flat between its fillets (not stated: no
specific-load criterion).
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from fe_crank.cad.config import CadInput
from fe_crank.cad.features import CadFeatures, ThrowFeatures
from fe_crank.cad.throw import SLAB_FRACTION
from fe_crank.errors import InputError
from fe_crank.geometry.shaft import JournalSpan, PlacedThrow, ShaftLayout, main_bearings
from fe_crank.geometry.spec import (
    DEFAULT_STIFFNESS_RANGE,
    BoltedMass,
    CrankGeometry,
    ShaftSpec,
    ThrowSpec,
    WebOutline,
)
from fe_crank.mesh.interface import MAX_SECTORS, sectors_for
from fe_crank.mesh.shaft import ShaftMesh

#: relative agreement of two drawn throws that one mesh stands for
SAME_TOL = 1e-9
#: a drawn throw's end faces are split into two sectors at least: its rear face's mesh is
#: then a translated copy of its front face's (``mesh.interface``) even where every throw
#: has the same angle (a split into one sector is no split)
MIN_SECTORS = 2


def _dims(t: ThrowFeatures) -> dict[str, float]:
    out = {
        "crank radius": t.crank_radius,
        "crankpin diameter": t.crankpin.diameter,
        "crankpin bore diameter": t.crankpin.bore_diameter,
        "pin length": t.pin_length,
    }
    for k in (0, 1):
        out[f"journal_{k + 1} diameter"] = t.journals[k].diameter
        out[f"journal_{k + 1} bore diameter"] = t.journals[k].bore_diameter
        out[f"bearing centre {k + 1} (z)"] = t.bearings[k].z
        out[f"web_{k + 1} outer face (z)"] = t.webs[k].z_outer
        out[f"web_{k + 1} inner face (z)"] = t.webs[k].z_inner
    for f in t.fillets:
        out[f"{f.name} radius"] = f.radius
    out["oil bores"] = float(len(t.oil_bores))
    for i, b in enumerate(t.oil_bores):
        out[f"oil bore {i + 1} diameter"] = b.diameter
        out[f"oil bore {i + 1} angle (rad x crank radius)"] = b.angle * t.crank_radius
        for c, v in zip("xyz", b.point, strict=True):
            out[f"oil bore {i + 1} point {c}"] = v
    out["counterweights"] = float(len(t.counterweights))
    for cw in t.counterweights:
        out[f"counterweight_{cw.web} radius"] = cw.radius
        out[f"counterweight_{cw.web} fillet radius"] = cw.fillet_radius or 0.0
        out[f"counterweight_{cw.web} offset (rad x crank radius)"] = cw.offset * t.crank_radius
    return out


def _mass(t: ThrowFeatures) -> dict[str, float]:
    """The exact mass properties of the throw and of each of its parts (throw frame)."""
    out = {}
    for name, m in (("", t.mass.total), *((f"{k} ", v) for k, v in sorted(t.mass.parts.items()))):
        out[f"{name}volume"] = m.volume
        for i, c in enumerate(m.centroid):
            out[f"{name}centroid {'xyz'[i]}"] = c
        for i in range(3):
            for j in range(i, 3):
                out[f"{name}inertia {'xyz'[i]}{'xyz'[j]}"] = m.inertia[i][j]
    return out


#: the dimensions every throw of a whole shaft shares (its journals, pin length and webs:
#: one ``CrankGeometry`` carries them for the whole-shaft stage)
COMMON = (
    "crank radius",
    "crankpin diameter",
    "pin length",
    "journal_1 diameter",
    "journal_2 diameter",
    "bearing centre 1 (z)",
    "bearing centre 2 (z)",
    "web_1 outer face (z)",
    "web_2 outer face (z)",
    "web_1 inner face (z)",
    "web_2 inner face (z)",
)


def _differs(a: ThrowFeatures, b: ThrowFeatures, keys=None) -> tuple[str, float | None, float] | None:
    """The first quantity in which throw ``a`` differs from ``b`` (module doc), or None."""
    scale = b.crank_radius
    da, db, ma, mb = _dims(a), _dims(b), _mass(a), _mass(b)
    inertia = max(abs(v) for k, v in mb.items() if "inertia" in k)
    for k, v in db.items():
        if (keys is None or k in keys) and (k not in da or abs(da[k] - v) > SAME_TOL * scale):
            return k, da.get(k), v
    if keys is not None:
        return None
    if set(da) != set(db) or set(ma) != set(mb):
        return "features or parts", float(len(da) + len(ma)), float(len(db) + len(mb))
    for k, v in mb.items():
        tol = SAME_TOL * (mb["volume"] if "volume" in k else inertia if "inertia" in k else scale)
        if abs(ma[k] - v) > tol:
            return k, ma[k], v
    return None


def shared_meshes(features: CadFeatures) -> dict[str, str]:
    """Throw name -> the name of the first throw that is the same solid (itself where
    none before it is): the throws one mesh stands for."""
    out: dict[str, str] = {}
    for i, t in enumerate(features.throws):
        out[t.name] = next((u.name for u in features.throws[:i] if _differs(t, u) is None), t.name)
    return out


def require_common_dimensions(features: CadFeatures, cad: CadInput) -> None:
    """Every throw's journals, pin length, webs and bearing centres the first throw's
    (``COMMON``), else an ``InputError`` naming the throw and the quantity."""
    first = features.throws[0]
    for t in features.throws[1:]:
        bad = _differs(t, first, COMMON)
        if bad is not None:
            what, a, b = bad
            raise InputError(
                f"the whole-shaft model takes one set of journal, pin and web dimensions for every throw; throw "
                f"{t.name} of the CAD file differs from throw {first.name} in its {what} ({a} against {b} m, in the "
                "throw frame): a drawing whose throws differ there is checked throw by throw only; drop the "
                "main-bearing criteria",
                file=str(cad.file),
                key=cad.file_key,
            )


def require_round_journals(features: CadFeatures, cad: CadInput) -> None:
    """Each journal a plain round bar where ``cad.model.redraw_ends`` redraws it (the
    whole-shaft model's end faces are whole discs at the bearing centres): no axial bore
    through a journal, no oil bore opening on one within the redrawn length of its
    bearing centre (its mouth's extent along the axis, its diameter around the point where
    its axis leaves the journal); else an ``InputError`` naming the throw, the journal and
    the distances, before any meshing (``redraw_ends`` checks the solid itself too)."""
    for t in features.throws:
        for k, (j, b) in enumerate(zip(t.journals, t.bearings, strict=True)):
            name = f"journal_{k + 1}"
            if j.bore_diameter > 0:
                raise InputError(
                    f"throw {t.name}: its {name} is bored along the axis ({j.bore_diameter * 1e3:.6g} mm): the "
                    "whole-shaft model joins its throws on whole round end faces at the bearing centres; a hollow "
                    "journal is checked throw by throw only",
                    file=str(cad.file),
                    key=cad.file_key,
                )
            reach = SLAB_FRACTION * (j.z_max - b.z if k == 0 else b.z - j.z_min)
            for bore in t.oil_bores:
                if name not in bore.ends_on:
                    continue
                p, d = np.asarray(bore.point), np.asarray(bore.direction)
                # where the bore's axis leaves the journal's cylinder (radius r about z)
                a2 = d[0] ** 2 + d[1] ** 2
                r = j.diameter / 2
                b1 = p[0] * d[0] + p[1] * d[1]
                c = p[0] ** 2 + p[1] ** 2 - r * r
                disc = b1 * b1 - a2 * c
                if a2 <= 0 or disc < 0:
                    continue
                zs = [p[2] + d[2] * (-b1 + sgn * np.sqrt(disc)) / a2 for sgn in (1, -1)]
                near = min(abs(z - b.z) for z in zs) - bore.diameter / 2
                if near < reach:
                    raise InputError(
                        f"throw {t.name}: an oil bore ({bore.diameter * 1e3:.6g} mm) opens on its {name} "
                        f"{max(near, 0.0) * 1e3:.4g} mm from the bearing centre, within the {reach * 1e3:.4g} mm "
                        "where the whole-shaft model joins its throws on whole round end faces: such a drawing is "
                        "checked throw by throw only",
                        file=str(cad.file),
                        key=cad.file_key,
                    )


def _shaft_position(features: CadFeatures, t: ThrowFeatures) -> float:
    return sum((o - p) * e for o, p, e in zip(t.origin, features.axis.point, features.axis.direction, strict=True))


def _end_reach(features: CadFeatures, t: ThrowFeatures, side: int) -> float:
    """Throw-frame z of the end journal's far end (its cylinder's extent, or the free
    end face where the journal ends in one)."""
    j, b = t.journals[side], t.bearings[side]
    if b.free_end:
        return b.z
    return j.z_min if side == 0 else j.z_max


def recognised_geometry(features: CadFeatures, cad: CadInput, angles: dict[str, float]) -> CrankGeometry:
    """The dimensions of the drawing's first throw as the whole-shaft stage reads them
    (module doc); ``angles``: throw name -> the engine's angle."""
    t = features.throws[0]
    thick = t.webs[0].thickness
    radius = {f.name: f.radius for f in t.fillets}
    throws = tuple(ThrowSpec(ft.name, angles[ft.name]) for ft in features.throws)
    return CrankGeometry(
        name=cad.file.name,
        density=cad.density,
        crank_radius=t.crank_radius,
        journal_diameter=t.journals[0].diameter,
        journal_length=t.bearings[1].z - t.webs[1].z_outer,
        crankpin_diameter=t.crankpin.diameter,
        crankpin_length=t.pin_length,
        web_thickness=thick,
        web=WebOutline("stadium", t.webs[0].side_radius, t.webs[0].side_radius),
        crankpin_fillet=radius.get("crankpin_fillet_1", 0.0),
        journal_fillet=radius.get("journal_fillet_1", 0.0),
        throws=throws,
        file=str(cad.file),
    )


def bearing_spec(cad: CadInput) -> ShaftSpec:
    """The drawn shaft's main bearings as ``[cad.shaft]`` states them (a geometry's
    ``[shaft]`` without what the drawing gives), ``[cad] bearing_width`` their default width;
    ``ShaftSpec``'s defaults where neither is given (rigid, one per journal)."""
    spec = cad.shaft if cad.shaft is not None else ShaftSpec()
    if cad.bearing_width is not None:
        spec = dataclasses.replace(spec, bearing_width=cad.bearing_width)
    return spec


def cad_shaft_layout(features: CadFeatures, cad: CadInput, engine, *, engine_file: str) -> ShaftLayout:
    """The drawn shaft placed on its drawn bearings (module doc).  The engine check
    (``fe_crank.cad.engine.engine_keys``) has run: the throws are the engine's, in order."""
    if len(features.throws) < 2:
        raise InputError(
            "the whole-shaft model needs the whole shaft drawn: the CAD file holds one throw",
            file=str(cad.file),
            key=cad.file_key,
        )
    require_common_dimensions(features, cad)
    require_round_journals(features, cad)
    first = features.throws[0]
    e0 = engine.throw(first.name)
    sense = engine.shaft(e0.shaft).sense
    s = [_shaft_position(features, t) for t in features.throws]
    b1, b2 = first.bearings[0].z, first.bearings[1].z
    for k in range(len(s) - 1):
        a, b = features.throws[k], features.throws[k + 1]
        if abs((s[k + 1] - s[k]) - (b2 - b1)) > SAME_TOL * first.crank_radius:
            raise InputError(
                f"throws {a.name} and {b.name} of the CAD file are {(s[k + 1] - s[k]) * 1e3:.9g} mm apart, their bearing "
                f"centres {(b2 - b1) * 1e3:.9g} mm: the whole-shaft model joins the throws at shared bearing centres",
                file=str(cad.file),
                key=cad.file_key,
            )
    steps = [
        sense * (engine.throw(b.name).angle - engine.throw(a.name).angle)
        for a, b in zip(features.throws, features.throws[1:])
    ]
    if sectors_for(steps) == 0:
        raise InputError(
            f"the angles between adjacent throws ({', '.join(f'{math.degrees(a):g}' for a in steps)} deg) are not "
            f"multiples of 360/{MAX_SECTORS} deg: the whole-shaft model cannot join the drawn throws' meshes node to "
            "node; such a drawing is checked throw by throw only",
            file=str(cad.file),
            key="cad.throws",
        )
    z = [e0.axial_position + (v - s[0]) for v in s]
    angles = {t.name: engine.throw(t.name).angle for t in features.throws}
    g = recognised_geometry(features, cad, angles)
    throws = tuple(PlacedThrow(t.name, i, z[i], angles[t.name], g.throws[i]) for i, t in enumerate(features.throws))
    last = features.throws[-1]
    journals = [JournalSpan(0, z[0] + _end_reach(features, first, 0), z[0] + first.webs[0].z_outer, z[0] + b1)]
    for i in range(1, len(z)):
        journals.append(JournalSpan(i, z[i - 1] + first.webs[1].z_outer, z[i] + first.webs[0].z_outer, z[i - 1] + b2))
    journals.append(
        JournalSpan(len(z), z[-1] + last.webs[1].z_outer, z[-1] + _end_reach(features, last, 1), z[-1] + b2)
    )
    spec = bearing_spec(cad)
    gf, ef = str(cad.file), engine_file
    try:
        bearings = main_bearings(spec, journals, g, gf, ef)
    except InputError as e:  # the keys of [cad.shaft], in the file that states them
        raise InputError(e.reason, file=cad.toml or gf, key=f"cad.{e.key}" if e.key else "cad.shaft") from None
    bolted = tuple(
        BoltedMass(f"bolted_body_{i}", b.throw, b.web, b.mass.centroid[2], b.mass.unbalance_vector)
        for i, b in enumerate(features.bolted, start=1)
    )
    return ShaftLayout(
        geometry=g,
        throws=throws,
        journals=tuple(journals),
        bearings=bearings,
        stub=g.journal_length,
        pitch=float(np.mean(np.diff(z))),
        sense=int(sense),
        nose=None,
        flange=None,
        power_takeoff=spec.power_takeoff,
        geometry_file=gf,
        engine_file=ef,
        stiffness_range=spec.stiffness_range or DEFAULT_STIFFNESS_RANGE,
        end_loads=spec.end_loads,
        bolted=bolted,
    )


def cad_throw_masses(features: CadFeatures, layout: ShaftLayout) -> dict:
    """Throw name -> the exact mass properties of the drawn throw (its throw frame)."""
    return {t.name: features.throw(t.name).mass for t in layout.throws}


def cad_shaft_mesh(
    cad: CadInput, features: CadFeatures, layout: ShaftLayout, *, size, cache_dir, max_elements: int | None = None
) -> ShaftMesh:
    """The drawn shaft's ``ShaftMesh`` (module doc): each throw's mesh (one for the throws
    that are the same solid, ``shared_meshes``), its end faces split to join."""
    from fe_crank.cad.mesh import mesh_cad_throw
    from fe_crank.mesh.shaft import mesh_shaft

    shared = shared_meshes(features)
    done: dict = {}

    def throw_mesh(t: PlacedThrow, opt):
        name = shared[t.name]
        if name not in done:
            done[name] = mesh_cad_throw(cad, name, size=opt, cache_dir=cache_dir, max_elements=max_elements)
        return done[name].key, done[name]

    return mesh_shaft(
        layout,
        size=size,
        cache_dir=cache_dir,
        max_elements=max_elements,
        throw_mesh=throw_mesh,
        min_sectors=MIN_SECTORS,
    )


__all__ = [
    "MIN_SECTORS",
    "SAME_TOL",
    "bearing_spec",
    "cad_shaft_layout",
    "cad_shaft_mesh",
    "cad_throw_masses",
    "recognised_geometry",
    "require_common_dimensions",
    "require_round_journals",
    "shared_meshes",
]
