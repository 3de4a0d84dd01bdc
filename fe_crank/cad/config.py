"""What the ``[cad]`` section says about a CAD file (SI), as the CAD route reads it.

::

    [cad]
    file = "crank.step"          # STEP (.step/.stp), BREP (.brep/.brp) or IGES (.iges/.igs)
    length_unit = "mm"           # the unit of the file's numbers; required when the file
                                 # states none (BREP), and it overrides what the file states
    density = "7850 kg/m^3"      # or: material = "42CrMo4" (its density from the library)
    axis = "+z"                  # optional: the crank axis, front (free end) to flywheel,
                                 # as "+x" ... "-z" or [x, y, z] in the file's frame
    throws = ["1", "2"]          # optional: the throws' names from the front
    bodies = "one"               # "one" (default), "fuse" (separate bodies touching the
                                 # shaft, fused to it) or "bolted" (kept out of the FE model)
    counterweight_radius = "40 mm"  # optional: where a web's counterweight begins
    pin_recess = "0 mm"          # UR M53 T_H / T_G of recessed fillets (required when the
    journal_recess = "0 mm"      # CAD shows a fillet recessed into the web)
    bearing_width = "16 mm"      # optional: the main bearings' shell width on a drawn whole
                                 # shaft (for the bearing specific load)

    [cad.shaft]                  # optional, a drawn whole shaft: its main bearings as a
    bearing_width = "20 mm"      # geometry's [shaft] states them (widths, laws, oil film,
    bearing = { model = "hydrodynamic", clearance = "28 um", viscosity = "6 mPa*s" }
                                 # stiffness range, thrust bearing, power take-off, flywheel,
                                 # pulley; fe_crank.io.shaft); not pitch, end_journal_length,
                                 # nose or flange: the drawing gives those

    [cad.faces]                  # optional: face numbers fe-crank reports, naming a feature
    axis = [15, 33]              # faces whose common axis is the crank axis
    journal_1 = [15]             # a single-throw file: the throw model's group names
    # [cad.faces."2"]            # a file with several throws: one table per throw name
    # crankpin = [41]

In a load case, ``geometry = "crank.step"`` names the file and the load case's own
``[cad]`` section (without ``file``) says how to read it; or ``geometry =
"crank_cad.toml"`` names a TOML file holding the ``[cad]`` section above.

Face numbers are gmsh's numbering of the file's faces after import (stable for a given
file and gmsh version); fe-crank lists them with every recognised feature.
"""

from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

from fe_crank.geometry.spec import ShaftSpec

#: how separate solids in the file are treated
BODIES = ("one", "fuse", "bolted")

#: feature names a ``[cad.faces]`` entry may give for a throw (the throw model's groups)
THROW_FACE_GROUPS = (
    "crankpin",
    "journal_1",
    "journal_2",
    "crankpin_fillet_1",
    "crankpin_fillet_2",
    "journal_fillet_1",
    "journal_fillet_2",
    "oil_bore",
)


@dataclass(frozen=True)
class FaceOverride:
    """``[cad.faces]`` entry: the faces that make ``group`` of ``throw`` (None: the
    shaft-level ``axis`` or a single-throw file)."""

    group: str
    faces: tuple[int, ...]
    throw: str | None = None

    @property
    def key(self) -> str:
        """The TOML key that states it."""
        return f'cad.faces."{self.throw}".{self.group}' if self.throw is not None else f"cad.faces.{self.group}"


@dataclass(frozen=True)
class CadInput:
    """A CAD file and what its ``[cad]`` section states (SI)."""

    file: Path  # the CAD file
    density: float  # kg/m^3
    length_unit: float | None = None  # m per unit of the file's numbers; None: as the file states
    length_unit_text: str | None = None  # as written ("mm")
    material: str | None = None  # library name the density came from
    axis: tuple[float, float, float] | None = None  # unit vector, front to rear, file frame
    throws: tuple[str, ...] | None = None
    bodies: str = "one"
    counterweight_radius: float | None = None  # m
    pin_recess: float | None = None  # m, UR M53 T_H
    journal_recess: float | None = None  # m, UR M53 T_G
    bearing_width: float | None = None  # m, every main bearing's shell on a drawn whole shaft
    shaft: ShaftSpec | None = (
        None  # ``[cad.shaft]``: a drawn whole shaft's main bearings (no pitch, ends, nose, flange)
    )
    faces: tuple[FaceOverride, ...] = ()
    toml: str = ""  # the file holding the [cad] section ("" when built in Python)
    file_key: str = "cad.file"  # the key that names the CAD file ("geometry" in a load case)

    def override(self, group: str, throw: str | None = None) -> FaceOverride | None:
        """The ``[cad.faces]`` entry for ``group`` of ``throw`` (a single-throw file's
        entries have no throw name and serve its one throw)."""
        for f in self.faces:
            if f.group == group and (f.throw == throw or f.throw is None):
                return f
        return None

    @property
    def where(self) -> str:
        """The file a key of the ``[cad]`` section is set in, for messages."""
        return self.toml or "the [cad] section"
