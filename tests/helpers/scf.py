"""The small throw's UR M53 geometry and the small geometry with fillets outside UR M53 3.1's range, meshed coarse."""

from __future__ import annotations

import dataclasses
from pathlib import Path

from fe_crank.io.geometry import load_geometry
from fe_crank.mesh import MeshOptions, mesh_throw
from fe_crank.rules.m53 import calculation as m53

DATA = Path(__file__).resolve().parents[1] / "data"


SMALL = m53.M53Geometry(
    pin_diameter=0.028,
    journal_diameter=0.032,
    crank_radius=0.02,
    web_thickness=0.012,
    web_width=0.04,
    pin_fillet_radius=0.0025,
    journal_fillet_radius=0.0025,
    bearing_to_web=0.018,
)


def big_fillet_throw(cache_dir: Path):
    """geometry_small with 3.8 mm fillets: r/D = 3.8/28 = 0.1357 > 0.13, outside UR M53 3.1."""
    g = load_geometry(DATA / "geometry_small.toml")
    g = dataclasses.replace(g, crankpin_fillet=0.0038, journal_fillet=0.0038)
    tm = mesh_throw(
        g,
        size=MeshOptions(coarse_divisions=1.2, fillet_divisions=0.8, grading=2.5),
        cache_dir=cache_dir,
    )
    return g, tm


#: the UR M53 geometry of ``big_fillet_throw``: SMALL with its 3.8 mm fillets
BIG_FILLET = dataclasses.replace(SMALL, pin_fillet_radius=0.0038, journal_fillet_radius=0.0038)


def big_fillet_scf(g, tm):
    """The SCF mode (42CrMo4) on ``big_fillet_throw``'s coarse mesh as it is: far coarser
    than UR M53 App. III asks, so not accepted."""
    from fe_crank.io.material import load_material
    from fe_crank.rules.m53.scf_mode import compute_scf, web_centres_of

    return compute_scf(tm, load_material("42CrMo4"), BIG_FILLET, web_centres=web_centres_of(g))
