"""The load-case sections owned by later stages, each parsed by its stage's own parser.

Each stage keeps its input model in its own module (``parser(value, file, key) ->
frozen object``); this file only calls them, one typed field per section.  Add one
field and one line per section.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path
from typing import Any

from fe_crank.cad.config import CadInput
from fe_crank.fe.input import parse_fe
from fe_crank.fe.throw.options import FeOptions
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.balance import BalanceSettings, parse_balance
from fe_crank.io.cad import parse_geometry_source
from fe_crank.io.criteria import Criteria, parse_criteria
from fe_crank.io.material import Material, parse_material
from fe_crank.io.mesh import parse_mesh_section
from fe_crank.io.torsion import TorsionSettings, parse_torsion
from fe_crank.mesh.options import MeshSection

#: the top-level keys of a load case that name a section (the stage that parses it)
SECTION_KEYS = ("geometry", "cad", "material", "criteria", "fe", "balance", "mesh", "torsion")


@dataclass(frozen=True)
class Sections:
    """The parsed sections of one load-case file (None: not given)."""

    geometry: CrankGeometry | CadInput | None = None  # geometry stage (with [cad]: fe_crank.io.cad)
    material: Material | None = None  # assessment stage
    criteria: Criteria | None = None  # assessment stage
    fe: FeOptions | None = None  # FE stage
    balance: BalanceSettings | None = None  # balance stage
    mesh: MeshSection | None = None  # mesh stage
    torsion: TorsionSettings | None = None  # torsion stage


def parse_sections(data: dict[str, Any], file: Path) -> Sections:
    """Every section ``data`` holds, parsed by its stage's parser (InputError naming file
    and key on bad input)."""
    return Sections(
        geometry=parse_geometry_source(data, file),
        material=parse_material(data["material"], file, "material") if "material" in data else None,
        criteria=parse_criteria(data["criteria"], file, "criteria") if "criteria" in data else None,
        fe=parse_fe(data["fe"], file, "fe") if "fe" in data else None,
        balance=parse_balance(data["balance"], file, "balance") if "balance" in data else None,
        mesh=parse_mesh_section(data["mesh"], file, "mesh") if "mesh" in data else None,
        torsion=parse_torsion(data["torsion"], file, "torsion") if "torsion" in data else None,
    )
