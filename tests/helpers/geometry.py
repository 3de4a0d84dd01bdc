"""A plain throw's geometry input, as a dict to vary key by key."""

from __future__ import annotations


def base_throw(**over) -> dict:
    """A fillet-less stadium throw's geometry dict; ``over`` replaces keys (a dict merges into its section)."""
    d = {
        "name": "test throw",
        "density": "7800 kg/m^3",
        "crank_radius": "40 mm",
        "journal": {"diameter": "50 mm", "length": "20 mm", "fillet_radius": "0 mm"},
        "crankpin": {"diameter": "40 mm", "length": "30 mm", "fillet_radius": "0 mm"},
        "web": {"thickness": "15 mm", "outline": "stadium", "width": "60 mm"},
    }
    for k, v in over.items():
        if isinstance(v, dict) and isinstance(d.get(k), dict):
            d[k] = {**d[k], **v}
        else:
            d[k] = v
    return d
