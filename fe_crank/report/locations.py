"""The words of a ``results.Location``: where a criterion's value occurs, as the verdict
line, results.json, the JUnit case and case.json print it (the one place they are made).

    throw 2, journal_fillet_2, node 31 at (31.0, 0.0, 2.0) mm, 30 deg   an FE group's node
    throw 1, journal fillet (empirical (UR M53 3.2/3.3))                 a UR M53 fillet
    throw 2, counterweight_1                                            a counterweight
    throw 1, counterweight_1 (per bolt)                                 a bolted joint
    main bearing 2, 30 deg                                              a main bearing's peak
    main bearing 2 (peak / (d w), w = 29 mm), 30 deg                    ... over d w
    main bearing 2, 30 deg, bearing law spring 3e+08 N/m                ... the envelope's governing law
    throw 1, journal_fillet_2, peak pin force, r/4 (assessed) -> r/8 (finest)   a hot spot

then, each after "; ", the load state of a misfire case and the speed (when the criterion
spans several); with two models the model's name in front ("whole-shaft model: ...").
A criterion's verdict line adds its remarks (``CriterionResult.remarks``).
"""

from __future__ import annotations

import dataclasses

from fe_crank.results import CriterionResult, Location
from fe_crank.rules.m53.oil_bore import where as m53_where


def _base(loc: Location) -> str:
    k = loc.kind
    if k == "group":
        s = f"throw {loc.throw}, {loc.group}"
        if loc.point is not None:
            p = ", ".join(f"{c * 1e3:.1f}" for c in loc.point)
            s += f", node {loc.node} at ({p}) mm"
        if loc.angle_deg is not None:
            s += f", {loc.angle_deg:.0f} deg"
        return s
    if k == "m53":
        return f"throw {loc.throw}, {m53_where(loc.group)} ({loc.detail})"
    if k == "counterweight":
        return f"throw {loc.throw}, {loc.group}"
    if k == "joint":
        return f"throw {loc.throw}, {loc.group} (per bolt)"
    if k in ("bearing", "bearing_specific"):
        s = f"main bearing {loc.group}"
        if k == "bearing_specific" and loc.width is not None:
            s += f" (peak / (d w), w = {loc.width * 1e3:.4g} mm)"
        s = s if loc.angle_deg is None else f"{s}, {loc.angle_deg:.0f} deg"
        return f"{s}, {loc.detail}" if loc.detail else s
    if k == "hot_spot":
        s = f"throw {loc.throw}, {loc.group}, {loc.detail}"
        if loc.levels is not None:
            s += f", r/{loc.levels[0]:g} (assessed) -> r/{loc.levels[1]:g} (finest)"
        return s
    raise ValueError(f"unknown location kind {k!r}")


def location_text(loc: Location | None) -> str:
    """The words of ``loc`` (module doc; "" for None)."""
    if loc is None:
        return ""
    s = _base(loc)
    if loc.case:
        s = f"{s}; {loc.case}" if s else loc.case
    if loc.speed_rpm is not None and s:
        s = f"{s}; {loc.speed_rpm:.0f} rpm"
    if loc.model:
        s = f"{loc.model}: {s}" if s else loc.model
    return s


def criterion_location(c: CriterionResult) -> str:
    """A criterion's verdict-line words: its location, then its remarks, "; " between."""
    return "; ".join(x for x in (location_text(c.where), *c.remarks) if x)


def with_words(c: CriterionResult) -> CriterionResult:
    """``c`` with its ``location`` and its speeds' locations in words (from ``where``; a
    criterion without ``where`` keeps the words it has)."""
    if c.where is None and not c.remarks:
        return c
    per = tuple(p if p.where is None else dataclasses.replace(p, location=location_text(p.where)) for p in c.per_speed)
    return dataclasses.replace(c, location=criterion_location(c), per_speed=per)


__all__ = ["criterion_location", "location_text", "with_words"]
