"""The load-case sections owned by later stages: section key -> parser.

Each stage keeps its own input model in its own module; this file only wires the
section key to the parser (``callable(value, file, key) -> frozen object``).  Add
one line per section.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from fe_crank.fe.input import parse_fe
from fe_crank.io.balance import parse_balance
from fe_crank.io.criteria import parse_criteria
from fe_crank.io.geometry import parse_geometry
from fe_crank.io.material import parse_material
from fe_crank.io.mesh import parse_mesh_section
from fe_crank.io.torsion import parse_torsion

SectionParser = Callable[[Any, Any, str], object]

SECTIONS: dict[str, SectionParser] = {
    "geometry": parse_geometry,  # geometry stage
    "material": parse_material,  # assessment stage
    "criteria": parse_criteria,  # assessment stage
    "fe": parse_fe,  # FE stage
    "balance": parse_balance,  # balance stage
    "mesh": parse_mesh_section,  # check stage
    "torsion": parse_torsion,  # torsion stage
}
