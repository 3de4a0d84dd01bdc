"""Refuse impossible crank geometries before gmsh runs (``GeometryError``).

Each rule names the key of the geometry file it concerns.  The rules are plain
geometry of the throw frame (``fe_crank.geometry.spec``):

* every length positive, fillets non-negative, angles in (0, 360) deg, a counterweight's
  ``offset`` (its turn from opposite the pin) within (-180, 180) deg;
* a fillet must land on the web face around its pin or journal and fit the pin /
  journal length: ``r_f < r_end - d/2`` and ``r_f < L/2`` (pin), ``r_f < L`` (journal);
* the web outline must contain the crankpin and journal sections
  (``r_end >= d/2``);
* a counterweight must clear the crankpin and its fillet
  (distance from the pin centre to the sector, turned by its offset, ``>= d_p/2 + r_f``), touch the web
  (``r_inner < journal_end_radius``), not reach the crankpin's mid-plane and add
  material: a sector no thicker than the web that lies wholly inside the web outline
  is refused (its m r would be web material counted again);
* an undercut must be shallower than its fillet radius and the web, and its groove
  (outer radius ``r + r_f + sqrt(r_f^2 - (r_f - u)^2)``) must stay inside the web;
* with ``require_overlap`` the pin and journal sections must overlap:
  ``(d_j + d_p)/2 > R``.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from fe_crank.errors import GeometryError
from fe_crank.geometry.spec import CounterweightSpec, CrankGeometry


def _fail(g: CrankGeometry, key: str, reason: str) -> GeometryError:
    return GeometryError(reason, file=g.file or None, key=key)


def distance_to_sector(point: tuple[float, float], cw: CounterweightSpec) -> float:
    """Distance (m) from a point of the xy plane to the counterweight's annular sector.

    The sector is ``inner_radius <= r <= outer_radius`` within ``angle/2`` of its
    mid-line, ``-y`` turned by ``offset`` towards ``+x``.  Zero when the point lies inside it.
    """
    x, y = sector_frame(point, cw.offset)
    rho = math.hypot(x, y)
    # polar angle from -y, positive towards +x is irrelevant by symmetry: use |.|
    theta = abs(math.atan2(x, -y))
    half = cw.angle / 2.0
    r1, r2 = cw.outer_radius, cw.inner_radius
    if theta <= half:
        return max(r2 - rho, rho - r1, 0.0)
    # nearest of the two straight edges (segments from r2 to r1 along +-half)
    best = math.inf
    for s in (-1.0, 1.0):
        d = np.array([s * math.sin(half), -math.cos(half)])
        t = float(np.clip(np.dot([x, y], d), r2, r1))
        best = min(best, math.hypot(x - t * d[0], y - t * d[1]))
    return best


def sector_frame(point: tuple[float, float], offset: float) -> tuple[float, float]:
    """The point in the frame of a sector turned by ``offset`` (rad, from ``-y`` towards
    ``+x``): the frame turned with it, so that the sector's mid-line is its ``-y``;
    the point itself for ``offset = 0``."""
    if offset == 0.0:
        return point
    x, y = point
    c, s = math.cos(offset), math.sin(offset)
    return (c * x + s * y, -s * x + c * y)


def inside_web_outline(points: np.ndarray, g: CrankGeometry, tol: float = 1e-9) -> np.ndarray:
    """Which points (2, n) of the xy plane lie in the web outline, the convex hull of
    the circle ``journal_end_radius`` about the axis and ``pin_end_radius`` about the
    crankpin centre (0, R).  That hull is the union of the circles interpolated
    between the two, ``c(t) = (0, t R)``, ``r(t) = a + t (b - a)``, t in [0, 1], and
    ``|p - c(t)| - r(t)`` is convex in t: its minimum over a fine grid decides."""
    a, b, R = g.web.journal_end_radius, g.web.pin_end_radius, g.crank_radius
    t = np.linspace(0.0, 1.0, 401)[:, None]
    x, y = points
    d = np.hypot(x[None, :], y[None, :] - t * R) - (a + t * (b - a))
    return d.min(axis=0) <= tol * max(R, a, b)


def sector_inside_web(g: CrankGeometry, cw: CounterweightSpec, n: int = 181) -> bool:
    """True when the counterweight's annular sector lies wholly inside the web outline
    (a set lies in a convex region when its boundary does: both arcs and both
    radial edges are sampled; angles from ``-y`` towards ``+x``, the sector turned by its
    ``offset``)."""
    half = cw.angle / 2.0
    phi = np.linspace(-half, half, n) + cw.offset
    s = np.linspace(cw.inner_radius, cw.outer_radius, n)
    pts = [np.stack([r * np.sin(phi), -r * np.cos(phi)]) for r in (cw.inner_radius, cw.outer_radius)]
    pts += [np.stack([s * np.sin(e), -s * np.cos(e)]) for e in (cw.offset - half, cw.offset + half)]
    return bool(np.all(inside_web_outline(np.concatenate(pts, axis=1), g)))


def check_geometry(g: CrankGeometry) -> None:
    """Raise ``GeometryError`` (file, key, reason) for the first impossible input.

    A (frozen) geometry once found possible is not checked again in the same process
    (``_checked``): its loading, meshing and solid building each ask."""
    try:
        hash(g)
    except TypeError:  # a field that cannot be hashed: checked every time
        _check(g)
    else:
        _checked(g)


@functools.lru_cache(maxsize=256)
def _checked(g: CrankGeometry) -> None:
    """``_check`` of a hashable geometry; a refusal raises and is not kept."""
    _check(g)


def _check(g: CrankGeometry) -> None:
    """``check_geometry``'s checks."""
    positive = {
        "density": g.density,
        "crank_radius": g.crank_radius,
        "journal.diameter": g.journal_diameter,
        "journal.length": g.journal_length,
        "crankpin.diameter": g.crankpin_diameter,
        "crankpin.length": g.crankpin_length,
        "web.thickness": g.web_thickness,
        "web.journal_end_radius": g.web.journal_end_radius,
        "web.pin_end_radius": g.web.pin_end_radius,
    }
    for key, v in positive.items():
        if not (math.isfinite(v) and v > 0.0):
            raise _fail(g, key, f"must be positive (got {v:g} in SI units)")
    for key, v in (("crankpin.fillet_radius", g.crankpin_fillet), ("journal.fillet_radius", g.journal_fillet)):
        if not (math.isfinite(v) and v >= 0.0):
            raise _fail(g, key, f"cannot be negative (got {v * 1e3:g} mm)")
    rp, rj = g.crankpin_diameter / 2, g.journal_diameter / 2
    if g.web.pin_end_radius < rp:
        raise _fail(
            g,
            "web",
            f"the web's pin end (radius {g.web.pin_end_radius * 1e3:g} mm) does not cover the crankpin (radius {rp * 1e3:g} mm)",
        )
    if g.web.journal_end_radius < rj:
        raise _fail(
            g,
            "web",
            f"the web's journal end (radius {g.web.journal_end_radius * 1e3:g} mm) does not cover the journal (radius {rj * 1e3:g} mm)",
        )
    # fillets
    rf = g.crankpin_fillet
    room = g.web.pin_end_radius - rp
    if rf >= room and rf > 0:
        raise _fail(
            g,
            "crankpin.fillet_radius",
            f"fillet radius {rf * 1e3:g} mm is larger than the web allows around the pin ({room * 1e3:g} mm between pin and web edge)",
        )
    if rf >= g.crankpin_length / 2 and rf > 0:
        raise _fail(
            g,
            "crankpin.fillet_radius",
            f"two fillets of {rf * 1e3:g} mm do not fit on a crankpin {g.crankpin_length * 1e3:g} mm long",
        )
    rf = g.journal_fillet
    room = g.web.journal_end_radius - rj
    if rf >= room and rf > 0:
        raise _fail(
            g,
            "journal.fillet_radius",
            f"fillet radius {rf * 1e3:g} mm is larger than the web allows around the journal ({room * 1e3:g} mm between journal and web edge)",
        )
    if rf >= g.journal_length and rf > 0:
        raise _fail(
            g,
            "journal.fillet_radius",
            f"fillet {rf * 1e3:g} mm does not fit on a journal {g.journal_length * 1e3:g} mm long",
        )
    for part, rf, u, r0, r_end in (
        ("crankpin", g.crankpin_fillet, g.crankpin_undercut, rp, g.web.pin_end_radius),
        ("journal", g.journal_fillet, g.journal_undercut, rj, g.web.journal_end_radius),
    ):
        if not (math.isfinite(u) and u >= 0.0):
            raise _fail(g, f"{part}.undercut", f"cannot be negative (got {u * 1e3:g} mm)")
        if u > 0.0:
            if not u < rf:
                raise _fail(
                    g,
                    f"{part}.undercut",
                    f"undercut {u * 1e3:g} mm must be smaller than the fillet radius {rf * 1e3:g} mm",
                )
            if u >= g.web_thickness:
                raise _fail(
                    g,
                    f"{part}.undercut",
                    f"undercut {u * 1e3:g} mm is deeper than the web ({g.web_thickness * 1e3:g} mm)",
                )
            outer = r0 + rf + math.sqrt(rf**2 - (rf - u) ** 2)
            if outer >= r_end:
                raise _fail(
                    g,
                    f"{part}.undercut",
                    f"the undercut groove reaches radius {outer * 1e3:.3g} mm, beyond the web edge ({r_end * 1e3:g} mm)",
                )
    if g.require_overlap and g.pin_overlap <= 0.0:
        raise _fail(
            g,
            "require_overlap",
            f"crankpin and journal do not overlap: (d_j + d_p)/2 - R = {g.pin_overlap * 1e3:.3g} mm <= 0",
        )
    if g.oil_bore is not None:
        if not (g.oil_bore.diameter > 0.0):
            raise _fail(g, "crankpin.oil_bore.diameter", "must be positive")
        if g.oil_bore.diameter >= rp:
            raise _fail(
                g,
                "crankpin.oil_bore.diameter",
                f"oil bore {g.oil_bore.diameter * 1e3:g} mm too large for a crankpin of radius {rp * 1e3:g} mm",
            )
    if not g.throws:
        raise _fail(g, "throws", "a crankshaft needs at least one throw")
    names = [t.name for t in g.throws]
    if len(set(names)) != len(names):
        raise _fail(g, "throws", f"throw names must be unique (got {names})")
    for i, t in enumerate(g.throws):
        webs = [c.web for c in t.counterweights]
        if len(set(webs)) != len(webs):
            raise _fail(g, f"throws[{i}].counterweight", "at most one counterweight per web")
        for cw in t.counterweights:
            _check_counterweight(g, cw, f"throws[{i}].counterweight" if len(g.throws) > 1 else "counterweight")


def _check_counterweight(g: CrankGeometry, cw: CounterweightSpec, key: str) -> None:
    if cw.web not in (1, 2):
        raise _fail(g, f"{key}.webs", f"web must be 1 or 2 (got {cw.web})")
    for name in ("outer_radius", "inner_radius", "thickness"):
        v = getattr(cw, name)
        if not (math.isfinite(v) and v > 0.0):
            raise _fail(g, f"{key}.{name}", f"must be positive (got {v:g} in SI units)")
    if not 0.0 < cw.angle < 2 * math.pi:
        raise _fail(
            g, f"{key}.angle", f"included angle must be between 0 and 360 deg (got {math.degrees(cw.angle):g} deg)"
        )
    if not (math.isfinite(cw.offset) and abs(cw.offset) < math.pi):
        raise _fail(
            g,
            f"{key}.offset",
            f"the turn from opposite the pin must lie between -180 and 180 deg (got {math.degrees(cw.offset):g} deg)",
        )
    if cw.inner_radius >= cw.outer_radius:
        raise _fail(
            g,
            f"{key}.inner_radius",
            f"inner radius {cw.inner_radius * 1e3:g} mm must be smaller than the outer radius {cw.outer_radius * 1e3:g} mm",
        )
    if cw.inner_radius >= g.web.journal_end_radius:
        raise _fail(
            g,
            f"{key}.inner_radius",
            f"counterweight (inner radius {cw.inner_radius * 1e3:g} mm) does not touch the web (journal end radius {g.web.journal_end_radius * 1e3:g} mm): it would float",
        )
    if cw.thickness > g.web_thickness + g.crankpin_length / 2:
        raise _fail(
            g, f"{key}.thickness", f"counterweight {cw.thickness * 1e3:g} mm thick reaches past the crankpin mid-plane"
        )
    if cw.thickness <= g.web_thickness and sector_inside_web(g, cw):
        raise _fail(
            g,
            key,
            "counterweight lies wholly inside the web outline: it adds no material "
            "(its m r would be web material counted twice); make its outer radius reach beyond the web",
        )
    clearance = distance_to_sector((0.0, g.crank_radius), cw) - (g.crankpin_diameter / 2 + g.crankpin_fillet)
    if clearance <= 0.0:
        raise _fail(
            g,
            key,
            f"counterweight overlaps the crankpin or its fillet by {-clearance * 1e3:.3g} mm (reduce its angle, "
            "outer radius or offset)",
        )
    rc = cw.fillet_radius
    if rc is not None:
        room = min(cw.thickness, cw.outer_radius - g.web.journal_end_radius, clearance)
        if not (math.isfinite(rc) and rc > 0.0):
            raise _fail(g, f"{key}.fillet_radius", f"must be positive (got {rc:g} in SI units)")
        if rc >= room:
            raise _fail(
                g,
                f"{key}.fillet_radius",
                f"{rc * 1e3:g} mm does not fit: it must be smaller than the "
                f"counterweight's thickness, its overhang beyond the web and its clearance to the "
                f"crankpin fillet ({room * 1e3:.3g} mm here)",
            )
        step = abs(cw.thickness - g.web_thickness)
        if 0.0 < step <= rc:
            raise _fail(
                g,
                f"{key}.fillet_radius",
                f"{rc * 1e3:g} mm does not fit on the {step * 1e3:.3g} mm step "
                "between the counterweight's and the web's faces: make the counterweight as thick as the "
                "web or the step larger than the fillet radius",
            )
