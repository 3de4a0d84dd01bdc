"""Registers the load-case sections owned by later stages.

Each stage keeps its own input model in its own module; this file only wires the
section key to the parser.  Add one line per section.
"""

from __future__ import annotations

from fe_crank.io.loadcase import SECTIONS

SECTIONS["geometry"] = __import__("fe_crank.io.geometry", fromlist=["_"]).parse_geometry  # geometry stage
SECTIONS["material"] = __import__("fe_crank.io.material", fromlist=["_"]).parse_material  # assessment stage
SECTIONS["criteria"] = __import__("fe_crank.io.criteria", fromlist=["_"]).parse_criteria  # assessment stage
SECTIONS["fe"] = __import__("fe_crank.fe.input", fromlist=["_"]).parse_fe  # FE stage
SECTIONS["balance"] = __import__("fe_crank.io.balance", fromlist=["_"]).parse_balance  # balance stage
SECTIONS["mesh"] = __import__("fe_crank.pipeline", fromlist=["_"]).parse_mesh_section  # check stage
SECTIONS["torsion"] = __import__("fe_crank.io.torsion", fromlist=["_"]).parse_torsion  # torsion stage
_ = SECTIONS
