"""Small builders shared by the balance tests (not a test module)."""

from __future__ import annotations

import math
from pathlib import Path

from fe_crank import model
from fe_crank.io.engine import load_engine

ENGINES = Path(__file__).resolve().parents[2] / "engines"


def engine(name: str) -> model.Engine:
    return load_engine(ENGINES / name)


def radial(i: int, *, r=0.1, l=0.4, piston=10.0, rod=0.0, link_radius=None, link_angle_master=True) -> model.Engine:
    """i cylinders on one crankpin, equally spaced; optionally articulated on cylinder 1."""
    cyls = []
    for j in range(i):
        bank = 2 * math.pi * j / i
        art = None
        if link_radius is not None and j > 0:
            art = model.Articulation("1", link_radius, bank)
        rl = l if art is None else l - link_radius
        cyls.append(model.Cylinder(str(j + 1), "pin", 0.1, model.Rod(rl, rod, rl / 3), piston, bank, articulation=art))
    return model.Engine(f"radial-{i}", 4, (model.Shaft("main"),), (model.Throw("pin", "main", 0.0, r),), tuple(cyls))
