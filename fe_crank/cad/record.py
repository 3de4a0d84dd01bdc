"""The CAD source and its recognised features for the outputs: a JSON-ready record
(``cad_record``, for the provenance) and lines for an engineer (``feature_lines``:
every feature with its face numbers and dimensions, mm and kg)."""

from __future__ import annotations

import dataclasses
import math

from fe_crank.cad.features import CadFeatures


def cad_record(features: CadFeatures) -> dict:
    """Plain data (SI) of the source and everything recognised, for ``results.json``."""
    return dataclasses.asdict(features)


def _mm(v: float) -> str:
    return f"{v * 1e3:.4g} mm"


def _deg(a: float, period: float = 360.0) -> str:
    """An angle (rad) in degrees as printed, in [0, period): one that prints as the
    period is printed as 0."""
    text = f"{math.degrees(a) % period:.6g}"
    return "0" if float(text) >= period else text


def _faces(tags) -> str:
    return "faces " + ", ".join(str(t) for t in tags) if tags else "no face"


def feature_lines(features: CadFeatures) -> list[str]:
    """What was recognised, one line per feature (units on every number)."""
    s = features.source
    u = s.unit
    stated = (
        "stated by the file"
        if u.stated_by == "file"
        else f"from length_unit (the file states {u.file_states or 'none'})"
    )
    out = [
        f"{s.format} file {s.file} (SHA-256 {s.sha256[:16]}...), unit {u.name} = {u.metres:g} m {stated}; "
        f"{s.solids} solid(s), bodies = {s.bodies}; density {s.density:g} kg/m^3"
        + (f" ({s.material})" if s.material else ""),
        f"crank axis: {_faces(features.axis.faces)}, direction ({', '.join(f'{c:.4g}' for c in features.axis.direction)})",
    ]
    for t in features.throws:
        out.append(
            f"throw {t.name}: angle {_deg(t.angle)} deg, crank radius {_mm(t.crank_radius)} "
            f"(stroke {_mm(2 * t.crank_radius)}), mass {t.mass.total.mass:.5g} kg, m r "
            f"{t.mass.total.unbalance * 1e3:.5g} kg mm"
        )
        for c in (t.journals[0], t.crankpin, t.journals[1]):
            bore = f", axial bore {_mm(c.bore_diameter)}" if c.bore_diameter else ""
            out.append(
                f"  {c.name}: {_faces(c.faces)}, diameter {_mm(c.diameter)}, z {_mm(c.z_min)} to {_mm(c.z_max)}{bore}"
            )
        for f in t.fillets:
            under = f", reaches {_mm(f.undercut)} into the web" if f.undercut > 0 else ""
            kind = f"{len(f.arcs)} torus arc(s)" if len(f.arcs) == len(f.faces) else "blend"
            out.append(f"  {f.name}: {_faces(f.faces)}, radius {_mm(f.radius)} ({kind}){under}")
        for w in t.webs:
            out.append(
                f"  web_{w.side}: inner {_faces(w.inner_faces)} at z {_mm(w.z_inner)}, outer {_faces(w.outer_faces)} "
                f"at z {_mm(w.z_outer)}; thickness {_mm(w.thickness)}, width B {_mm(w.width)}"
                + (f" ({_mm(w.solid_width)} of it material)" if w.solid_width < w.width - 1e-9 else "")
                + f", side radius {_mm(w.side_radius)}"
            )
        for b in t.oil_bores:
            out.append(
                f"  oil_bore: {_faces(b.faces)}, diameter {_mm(b.diameter)}, angle {_deg(b.angle, 180.0)} deg, "
                f"opens on {', '.join(b.ends_on) or 'nothing recognised'}"
            )
        for bearing in t.bearings:
            how = "free end face of the shaft" if bearing.free_end else "middle of the journal"
            out.append(f"  bearing centre {bearing.side}: z {_mm(bearing.z)} ({how})")
        found = {cw.web: cw for cw in t.counterweights}
        for web in (1, 2):
            cw = found.get(web)
            if cw is None:
                out.append(
                    f"  counterweight_{web}: none recognised (no material on the far side of the axis beyond r = "
                    f"{_mm(t.webs[web - 1].side_radius)}; counterweight_radius in [cad] says where one begins)"
                )
                continue
            m = cw.mass
            fr = f", fillets {_faces(cw.fillet_faces)} radius {_mm(cw.fillet_radius)}" if cw.fillet_radius else ""
            turned = (
                f", turned {math.degrees(cw.offset):.4g} deg from opposite its pin (-y towards +x)" if cw.offset else ""
            )
            out.append(
                f"  counterweight_{cw.web}: beyond r = {_mm(cw.radius)}, mass {m.mass:.5g} kg at r "
                f"{_mm(math.hypot(*m.centroid[:2]))}, m r {m.unbalance * 1e3:.5g} kg mm, J about the axis "
                f"{m.inertia_axis * 1e6:.5g} kg mm^2{turned}{fr}"
            )
    for end in features.ends:
        m = end.mass
        out.append(
            f"{end.name}: {_faces(end.faces)}, beyond throw {end.throw}'s end journal, z {_mm(end.z_min)} to "
            f"{_mm(end.z_max)} (length {_mm(end.length)}), largest diameter {_mm(end.diameter)}, mass {m.mass:.5g} kg"
        )
    for i, body in enumerate(features.bolted, start=1):
        m = body.mass
        out.append(
            f"bolted body {i} (not in the FE model): throw {body.throw}, web {body.web}, mass {m.mass:.5g} kg at "
            f"r {_mm(math.hypot(*m.centroid[:2]))}, m r {m.unbalance * 1e3:.5g} kg mm"
            + "".join(
                f"; bolt hole {_faces(h.faces)}, diameter {_mm(h.diameter)} at r {_mm(h.pitch_radius)}, axis "
                f"({', '.join(f'{c:.3g}' for c in h.direction)})"
                for h in body.holes
            )
        )
    return out
