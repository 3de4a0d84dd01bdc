"""What the CAD route recognised, per throw, with the file's face numbers (SI).

Positions are in the THROW frame of ``docs/contracts.md`` (``fe_crank.geometry.spec``):
``z`` the crank axis from the front to the flywheel, the crankpin's centre on ``+y`` at
the crank radius, ``z = 0`` midway between the webs' inner faces, index 1 = front.
``ThrowFeatures.origin``/``rotation`` place that frame in the file's frame:
``p_throw = rotation (p_file - origin)``.  Face numbers are gmsh's numbering of the
file's faces after import (``fe_crank.cad.config``).
"""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank.cad.read import CadUnit
from fe_crank.geometry.mass import MassProperties, PartProperties

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class CadSource:
    """Where the geometry came from: the provenance of a CAD-route result."""

    file: str  # the file's name (no folder)
    sha256: str  # of the file's bytes
    format: str  # "STEP", "BREP", "IGES"
    unit: CadUnit
    solids: int  # solids in the file
    bodies: str  # how several solids were treated ("one", "fuse", "bolted")
    density: float  # kg/m^3
    material: str | None = None  # the library material the density came from


@dataclass(frozen=True)
class CrankAxis:
    point: Vec3  # a point of the axis, file frame, m
    direction: Vec3  # unit vector, front to rear, file frame
    faces: tuple[int, ...]  # the coaxial cylindrical faces that define it


@dataclass(frozen=True)
class Cylinder:
    """A main journal or the crankpin: its cylindrical faces."""

    name: str  # "journal_1", "crankpin", "journal_2"
    faces: tuple[int, ...]
    diameter: float
    z_min: float  # extent of the cylindrical faces along z
    z_max: float
    bore_diameter: float = 0.0  # an axial bore along its axis (hollow pin or journal); 0: none


@dataclass(frozen=True)
class Arc:
    """One torus of a fillet: tube radius, spine circle (radius, plane z)."""

    face: int
    radius: float
    spine_radius: float
    spine_z: float


@dataclass(frozen=True)
class Fillet:
    """A fillet between the crankpin or a journal and a web face."""

    name: str  # "crankpin_fillet_1", ..., "journal_fillet_2"
    faces: tuple[int, ...]
    radius: float  # smallest radius of curvature of its faces (0: a sharp corner)
    arcs: tuple[Arc, ...]  # its faces that are tori (all of them for a rolling-ball fillet)
    web_face_z: float  # the web face it meets
    undercut: float  # depth it reaches into the web beyond the web face (0: tangent)
    area: float = 0.0  # m^2, of its faces


@dataclass(frozen=True)
class OilBore:
    faces: tuple[int, ...]
    diameter: float
    ends_on: tuple[str, ...]  # "crankpin", "journal_1", "journal_2": the surfaces it opens on
    point: Vec3  # a point of its axis
    direction: Vec3  # unit vector of its axis
    angle: float  # rad in [0, pi): its direction in the xy plane from +y towards +x


@dataclass(frozen=True)
class Web:
    side: int  # 1 front, 2 rear
    inner_faces: tuple[int, ...]  # the web face towards the crankpin
    outer_faces: tuple[int, ...]  # the web face towards the journal
    z_inner: float
    z_outer: float
    thickness: float  # W, axial
    width: float  # B: the web's width (along x) at the middle of the pin/journal overlap, web mid-plane
    side_radius: float  # the web's rounded journal end (its half width at y = 0+): where a counterweight begins
    solid_width: float  # material along B's line: less than B where the line crosses a hole in the web


@dataclass(frozen=True)
class Bearing:
    side: int
    z: float  # the main bearing's centre plane: the throw model ends here
    free_end: bool  # True: the journal ends in a free end face of the shaft, taken as the centre


@dataclass(frozen=True)
class Counterweight:
    """Material of the throw farther from the axis than ``radius``, between the bearing
    centre of its side and z = 0, on the far side of the axis from the pin (y < 0) or,
    for one turned over y = 0, inside its own sector (``cad.throw``);
    ``offset``: the direction of its m r, turned from ``-y`` towards ``+x`` (rad, the
    parametric ``counterweight.offset``; 0 for one centred opposite its pin)."""

    web: int
    radius: float  # where it begins (the web's side radius, or [cad] counterweight_radius)
    fillet_faces: tuple[int, ...]  # re-entrant rounded faces where it leaves the web
    fillet_radius: float | None  # smallest radius of those (None: none)
    mass: PartProperties
    fillet_area: float = 0.0  # m^2
    offset: float = 0.0  # rad, from -y towards +x: where its m r points (cad.throw.counterweight_offset)


@dataclass(frozen=True)
class ThrowFeatures:
    name: str
    index: int  # 0-based, front to rear
    angle: float  # rad, the pin's angle from the first throw's, in the positive sense (+y towards +x)
    crank_radius: float
    origin: Vec3  # the throw frame's origin, file frame
    rotation: tuple[Vec3, Vec3, Vec3]  # the throw frame's x, y, z axes in the file frame
    crankpin: Cylinder
    journals: tuple[Cylinder, Cylinder]
    fillets: tuple[Fillet, ...]  # the recognised ones (a sharp corner has none)
    oil_bores: tuple[OilBore, ...]
    webs: tuple[Web, Web]
    bearings: tuple[Bearing, Bearing]
    counterweights: tuple[Counterweight, ...]
    mass: MassProperties  # the throw model between the bearing centres, by part

    @property
    def pin_length(self) -> float:
        """Between the webs' inner faces."""
        return self.webs[1].z_inner - self.webs[0].z_inner

    def fillet(self, name: str) -> Fillet | None:
        return next((f for f in self.fillets if f.name == name), None)


@dataclass(frozen=True)
class BoltHole:
    """A whole-round hole through a bolted body (a bolt's clearance hole), in the frame of
    the throw the body sits on."""

    faces: tuple[int, ...]
    diameter: float
    point: Vec3  # the point of its axis nearest the crank axis
    direction: Vec3  # unit vector of its axis
    pitch_radius: float  # distance of ``point`` from the crank axis


@dataclass(frozen=True)
class BoltedBody:
    """A separate solid kept out of the FE model (``[cad] bodies = "bolted"``): the throw
    whose bearing centres enclose its centroid (or the nearest), the web on whose side it
    lies, its mass properties in that throw's frame."""

    throw: str
    web: int
    mass: PartProperties
    holes: tuple[BoltHole, ...] = ()  # its bolt holes


@dataclass(frozen=True)
class ShaftEnd:
    """The nose (front) or flange (rear) of a drawn shaft, beyond its end journal
    (``fe_crank.cad.ends``): extent along z and mass properties in the frame of the
    throw it adjoins."""

    name: str  # "nose" or "flange"
    throw: str  # the throw it adjoins
    faces: tuple[int, ...]
    diameter: float  # largest whole-round cylinder about the crank axis (0: none)
    z_min: float
    z_max: float
    length: float
    mass: PartProperties


@dataclass(frozen=True)
class CadFeatures:
    """Everything recognised in one CAD file: the record the provenance carries."""

    source: CadSource
    axis: CrankAxis
    throws: tuple[ThrowFeatures, ...]
    bolted: tuple[BoltedBody, ...] = ()  # bodies kept out of the FE model (bodies = "bolted")
    ends: tuple[ShaftEnd, ...] = ()  # the nose and flange beyond the end journals, where drawn

    def throw(self, which: str | int | None = None) -> ThrowFeatures:
        """A throw by name, by 0-based index, or the first one for ``None``."""
        if which is None:
            return self.throws[0]
        if isinstance(which, int):
            return self.throws[which]
        for t in self.throws:
            if t.name == which:
                return t
        raise KeyError(f"no throw named {which!r}; throws are {[t.name for t in self.throws]}")
