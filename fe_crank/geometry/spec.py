"""Frozen description of a crankshaft's geometry (SI floats), as the core sees it.

All throws of a crankshaft share the journal, pin and web dimensions; each throw has
its own angle and counterweights.  Dimensions are given in the THROW frame of
``docs/contracts.md``: ``z`` the crank axis, crankpin centre on ``+y`` at distance
``crank_radius``, counterweights centred on ``-y`` (opposite the pin) unless turned by
their ``offset``, index 1 = front (smaller ``z``).

Axial layout of one throw (``zp = crankpin_length / 2``, ``t = web_thickness``,
``L = journal_length``)::

    journal_1  z in [-zp - t - L, -zp - t]     end_1 at z = -zp - t - L
    web_1      z in [-zp - t, -zp]
    crankpin   z in [-zp, zp]
    web_2      z in [zp, zp + t]
    journal_2  z in [zp + t, zp + t + L]       end_2 at z = zp + t + L

An undercut fillet (``undercut = u > 0``) is a circular arc of radius ``r_f`` tangent to
the pin (journal) whose centre lies ``r_f - u`` off the web face, so that the arc dips
``u`` into the web: a groove round the pin in the web face.

A counterweight on web 1 fills ``z in [-zp - t, -zp - t + thickness]`` (flush with the
web's outer face), on web 2 ``z in [zp + t - thickness, zp + t]``.  Its ``fillet_radius``
rounds the concave edges where the sector's faces meet the web's (a sharp edge there is
a stress singularity: the elastic stress grows without bound as the mesh is refined).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

from fe_crank.geometry.oil import FilmSpec

#: the end of the shaft where the power is taken off
PowerTakeoff = Literal["rear", "front"]

WEB_OUTLINES = ("stadium", "pear")


@dataclass(frozen=True)
class WebOutline:
    """Web outline in the xy plane: convex hull of two circles.

    ``journal_end_radius`` about the crank axis and ``pin_end_radius`` about the
    crankpin centre.  ``kind = "stadium"`` (rectangle with rounded ends) has both radii
    equal to half the web width; ``"pear"`` (oval) has different radii.
    """

    kind: str
    journal_end_radius: float
    pin_end_radius: float


#: ISO 261 coarse pitch (mm) of the metric threads M3-M48 by nominal diameter (mm)
COARSE_PITCH_MM = {
    3: 0.5,
    4: 0.7,
    5: 0.8,
    6: 1.0,
    8: 1.25,
    10: 1.5,
    12: 1.75,
    14: 2.0,
    16: 2.0,
    18: 2.5,
    20: 2.5,
    22: 2.5,
    24: 3.0,
    27: 3.0,
    30: 3.5,
    33: 3.5,
    36: 4.0,
    39: 4.0,
    42: 4.5,
    45: 4.5,
    48: 5.0,
}
#: the joint data the VDI 2230 check cannot do without
VDI_REQUIRED = ("clamp_length", "bearing_diameter", "hole_diameter", "clamped_diameter", "tightening_factor")


@dataclass(frozen=True)
class BoltedJoint:
    """Bolted counterweight: the joint's data for the VDI 2230 check (``assess.cw_joint``).
    The FE model does not model the joint: the counterweight is fused to the web (its
    stiffness and mass are the counterweight's, its contact and bolts are not meshed)."""

    count: int
    diameter: float  # m, nominal thread diameter
    pitch_radius: float  # m, radius of the bolt positions from the crank axis
    preload: float | None = None  # N per bolt: the upper assembly preload F_M,max (None: F_M,zul)
    yield_strength: float | None = None  # Pa, bolt material (or property_class)
    pitch: float | None = None  # m, thread pitch (None: ISO coarse)
    property_class: str | None = None  # ISO 898-1: "8.8", "10.9", "12.9"
    clamp_length: float | None = None  # m, l_K
    bearing_diameter: float | None = None  # m, d_W of the head bearing
    hole_diameter: float | None = None  # m, d_h of the clearance hole
    clamped_diameter: float | None = None  # m, D_A: outside diameter of the clamped parts round the bolt
    tightening_factor: float | None = None  # alpha_A = F_M,max / F_M,min (VDI 2230 table A8)
    direction: str = "radial"  # bolt axis: "radial" (through the crank axis) or "axial"
    tapped: bool = True  # screwed into the web (VDI's ESV); False: through-bolted with a nut
    thread_friction: float = 0.10  # mu_G, its smallest value
    head_friction: float = 0.10  # mu_K
    interface_friction: float = 0.10  # mu_T between counterweight and web, its smallest value
    roughness: str = "10_to_40"  # Rz class of the contact faces, um: below_10 | 10_to_40 | 40_to_160
    rolled_after_heat_treatment: bool = False
    load_introduction: float | None = None  # n of VDI 2230 5.2.2 (None: the bounds 1 and 0)
    shank_length: float = 0.0  # m, unthreaded shank inside the clamp length
    shank_diameter: float | None = None  # m (None: d)

    def _coarse_pitch(self) -> float | None:
        """The ISO 261 coarse pitch of the diameter (m); None for a diameter off the table."""
        p = COARSE_PITCH_MM.get(round(self.diameter * 1e3))
        if p is None or abs(self.diameter * 1e3 - round(self.diameter * 1e3)) > 1e-6:
            return None
        return p * 1e-3

    @property
    def thread_pitch(self) -> float:
        """P: given, else the ISO coarse pitch of the diameter."""
        if self.pitch is not None:
            return self.pitch
        p = self._coarse_pitch()
        if p is None:
            raise ValueError(f"no coarse pitch for d = {self.diameter * 1e3:g} mm: state the pitch")
        return p

    def vdi_missing(self) -> list[str]:
        """The keys the VDI 2230 check needs that the joint does not give (``pitch`` for a
        diameter without an ISO coarse pitch)."""
        miss = [k for k in VDI_REQUIRED if getattr(self, k) is None]
        if self.yield_strength is None and self.property_class is None:
            miss.append("property_class")
        if self.pitch is None and self._coarse_pitch() is None:
            miss.append("pitch")
        return miss


@dataclass(frozen=True)
class CounterweightSpec:
    """Annular-sector counterweight on one web, centred on ``-y`` (opposite the pin)
    turned by ``offset``: its mid-line runs along ``(sin offset, -cos offset)``, the
    angle measured from ``-y`` towards ``+x`` in the throw frame (the sense in which
    ``OilBore.angle`` is measured from ``+y``), ``|offset| < 180 deg``."""

    web: int  # 1 (front) or 2 (rear)
    outer_radius: float  # m, r1
    inner_radius: float  # m, r2
    angle: float  # rad, included angle
    thickness: float  # m, axial (b)
    bolted: BoltedJoint | None = None
    fillet_radius: float | None = None  # m, transition radius to the web; None: a sharp edge
    offset: float = 0.0  # rad, the mid-line's angle from -y towards +x (class doc)


@dataclass(frozen=True)
class OilBore:
    """Straight oil bore through the crankpin centre at mid-length, in the xy plane.

    ``angle`` is its direction from ``+y`` towards ``+x`` (throw frame).
    """

    diameter: float
    angle: float


@dataclass(frozen=True)
class PlainCylinder:
    """A plain cylinder on the crank axis (front nose, flywheel flange)."""

    diameter: float
    length: float


BEARING_MODELS = ("rigid", "spring", "clearance")


@dataclass(frozen=True)
class BearingLaw:
    """Radial law of a main bearing in the whole-shaft model (``fe_crank.fe.shaft.bearings``).

    ``rigid``: the journal's reference point does not move radially; ``spring``: force
    = -stiffness x displacement (bearing, shell and housing in series, N/m);
    ``clearance``: no force while the journal moves less than ``clearance`` (radial, m),
    beyond it the contact stiffness ``stiffness`` (N/m) on the excess.
    """

    model: str = "rigid"
    stiffness: float | None = None
    clearance: float = 0.0
    #: the oil film of a hydrodynamic bearing (``fe.oil_film``), judged over the cycle from
    #: the loads this law (``rigid`` or ``spring``) gives; None: no film model
    film: FilmSpec | None = None


@dataclass(frozen=True)
class BearingInput:
    """A main bearing as the geometry file states it: ``journal`` 0 is the front end
    journal, i (1 .. n - 1) the journal between throws i and i + 1, n the rear end."""

    name: str
    journal: int
    width: float | None = None  # m, for the specific load; None: the journal's cylindrical length
    law: BearingLaw | None = None  # None: the shaft's default


#: N/m: the main bearings' radial stiffness range the whole shaft's bearing loads are
#: enveloped over when the geometry states none (``[shaft] stiffness_range``; docs/shaft.md)
DEFAULT_STIFFNESS_RANGE = (3e8, 3e9)


@dataclass(frozen=True)
class EndLoad:
    """A flywheel or pulley on one end of the shaft, beyond its end journal: the
    centrifugal force of its unbalance m e, turning with the shaft (``unbalance_angle``
    from the first throw's crankpin in the sense of rotation), and a belt pull fixed in the
    engine frame (``belt_angle`` from +y towards +x), both at its centre plane ``offset``
    beyond the shaft's end face.  Its weight is not a load of the model (gravity is not
    modelled: neither the shaft's weight nor this)."""

    name: str  # "flywheel" | "pulley"
    end: str  # "front" | "rear"
    mass: float  # kg
    offset: float  # m, beyond the end journal's outer face
    eccentricity: float = 0.0  # m, of its centre of mass from the axis
    unbalance_angle: float = 0.0  # rad
    belt_pull: float = 0.0  # N
    belt_angle: float = 0.0  # rad

    @property
    def unbalance(self) -> float:
        """m e, kg m."""
        return self.mass * self.eccentricity


@dataclass(frozen=True)
class ShaftSpec:
    """The ``[shaft]`` section of a geometry file: what lies beyond the throws and how
    the shaft is supported (``fe_crank.geometry.shaft`` resolves it against the engine)."""

    pitch: float | None = None  # m, stated throw pitch (checked against the engine)
    end_journal_length: float | None = None  # m, outer web face to the end of an end journal
    nose: PlainCylinder | None = None  # front, beyond the front end journal
    flange: PlainCylinder | None = None  # rear, beyond the rear end journal
    bearing_width: float | None = None  # m, default width of every bearing
    bearing_law: BearingLaw = BearingLaw()
    bearings: tuple[BearingInput, ...] | None = None  # None: one at every journal
    #: N/m, the realistic range of the bearings' radial stiffness (oil film, shell, housing)
    #: over which the main-bearing loads are enveloped; None: ``DEFAULT_STIFFNESS_RANGE``
    stiffness_range: tuple[float, float] | None = None
    thrust_bearing: str | None = None  # None: the bearing nearest the power take-off
    power_takeoff: PowerTakeoff = "rear"  # "rear" (flywheel end) or "front"
    end_loads: tuple[EndLoad, ...] = ()  # flywheel, pulley


@dataclass(frozen=True)
class BoltedMass:
    """A body bolted to a web of a throw and not meshed (a drawn counterweight given as a
    separate solid, ``[cad] bodies = "bolted"``): a counterweight's centrifugal force on the
    shaft, ``omega^2`` times its ``unbalance``, turning with the shaft, at its centroid's
    ``z``, carried into the throw by the journal beside its web."""

    name: str
    throw: str
    web: int  # 1 or 2: the throw's journal_<web> carries it
    z: float  # m, its centroid along the throw frame's z
    unbalance: tuple[float, float]  # kg m, its mass times its centroid's (x, y), throw frame


@dataclass(frozen=True)
class ThrowSpec:
    name: str
    angle: float  # rad, position on the shaft (model.Throw.angle)
    counterweights: tuple[CounterweightSpec, ...] = ()


@dataclass(frozen=True)
class CrankGeometry:
    """A crankshaft of ``len(throws)`` equal throws (SI)."""

    name: str
    density: float  # kg/m^3
    crank_radius: float
    journal_diameter: float
    journal_length: float  # per side of a throw
    crankpin_diameter: float
    crankpin_length: float
    web_thickness: float
    web: WebOutline
    crankpin_fillet: float  # m, radius where pin meets web
    journal_fillet: float  # m, radius where journal meets web
    throws: tuple[ThrowSpec, ...]
    oil_bore: OilBore | None = None
    crankpin_undercut: float = 0.0  # m, depth of the fillet's recess into the web (0: tangent fillet)
    journal_undercut: float = 0.0
    require_overlap: bool = False
    shaft: ShaftSpec | None = None  # the [shaft] section (whole-shaft model), None when absent
    description: str = ""
    source: str = ""
    file: str = ""

    def throw(self, which: str | int | None = None) -> ThrowSpec:
        """A throw by name, by 0-based index, or the first one for ``None``."""
        if which is None:
            return self.throws[0]
        if isinstance(which, int):
            if not 0 <= which < len(self.throws):
                raise IndexError(f"throw index {which} out of range (0..{len(self.throws) - 1})")
            return self.throws[which]
        for t in self.throws:
            if t.name == which:
                return t
        raise KeyError(f"no throw named {which!r}; throws are {[t.name for t in self.throws]}")

    @property
    def pin_overlap(self) -> float:
        """Radial overlap of crankpin and journal, ``(d_j + d_p)/2 - R`` (m)."""
        return 0.5 * (self.journal_diameter + self.crankpin_diameter) - self.crank_radius
