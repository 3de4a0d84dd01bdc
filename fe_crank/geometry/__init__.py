"""Crank geometry: frozen specification, input checks, OCC solids and mass properties.

* :mod:`fe_crank.geometry.spec` -- ``CrankGeometry`` and its parts (SI);
* :mod:`fe_crank.geometry.checks` -- ``check_geometry``: impossible inputs refused;
* :mod:`fe_crank.geometry.solid` -- ``throw_solid``: the one OpenCASCADE solid of a throw;
* :mod:`fe_crank.geometry.throw` -- ``add_throw``: that solid split into named parts;
* :mod:`fe_crank.geometry.mass` -- ``mass_properties``: volume, mass, centroid, m r, inertia.
"""

from fe_crank.geometry.checks import check_geometry
from fe_crank.geometry.mass import MassProperties, PartProperties, mass_properties
from fe_crank.geometry.spec import (
    BoltedJoint,
    CounterweightSpec,
    CrankGeometry,
    OilBore,
    ThrowSpec,
    WebOutline,
)

__all__ = [
    "BoltedJoint",
    "CounterweightSpec",
    "CrankGeometry",
    "MassProperties",
    "OilBore",
    "PartProperties",
    "ThrowSpec",
    "WebOutline",
    "check_geometry",
    "mass_properties",
]
