"""A small throw whose counterweight corners are right angles between planes, as a geometry dict."""

from __future__ import annotations


def square_cornered_throw(fillet: str | None = "3 mm", **cw_over) -> dict:
    """A small throw whose counterweight corners are right angles between planes: stadium
    web 36 mm wide (straight sides x = +-18 mm for y >= 0), 180-deg sector (radial faces in
    the plane y = 0), as thick as the web, so each corner at (+-18, 0) is the re-entrant
    right angle of the plane y = 0 (sector) and the plane x = +-18 mm (web side)."""
    cw = {"outer_radius": "40 mm", "inner_radius": "14 mm", "angle": "180 deg", "webs": [1, 2], **cw_over}
    if fillet is not None:
        cw["fillet_radius"] = fillet
    return {
        "name": "small counterweighted throw",
        "density": "7800 kg/m^3",
        "crank_radius": "20 mm",
        "journal": {"diameter": "24 mm", "length": "10 mm", "fillet_radius": "2 mm"},
        "crankpin": {"diameter": "20 mm", "length": "16 mm", "fillet_radius": "2 mm"},
        "web": {"thickness": "10 mm", "outline": "stadium", "width": "36 mm"},
        "counterweight": cw,
    }
