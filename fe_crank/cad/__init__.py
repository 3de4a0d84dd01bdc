"""A crankshaft drawn in CAD (STEP, BREP, IGES) as the geometry of the check.

* :mod:`fe_crank.cad.config` -- ``CadInput``: the file and what its ``[cad]`` section states;
* :mod:`fe_crank.cad.recognise` -- ``recognise``: read the file and recognise the crank
  axis, throws, journals, pins, fillets, webs, oil bores and counterweights
  (``CadFeatures``, :mod:`fe_crank.cad.features`);
* :mod:`fe_crank.cad.mesh` -- ``mesh_cad_throw``: a throw's ``fe_crank.mesh.ThrowMesh``
  with the parametric route's named groups and mesh rules;
* :mod:`fe_crank.cad.record` -- the source and features for the provenance and the report;
* :mod:`fe_crank.cad.engine` -- ``engine_keys``: the recognised throws against the engine's
  (count, names, crank radius, angles), the mesh plan's keys;
* :mod:`fe_crank.cad.source` -- ``mesh_models``: the check's one meshing entry point (every model of
  the mesh plan, throws and whole shaft, parametric or drawn); ``mesh_source_throw``: one throw of
  either source.

The parser of the ``[cad]`` section and of a load case's CAD geometry is
``fe_crank.io.cad``; the UR M53 dimensions and counterweight data for the assessment are
in ``fe_crank.assess.cad_inputs``; the check's geometry stage for a CAD file is
``fe_crank.pipeline.cad_geometry``.
"""

from fe_crank.cad.config import CadInput, FaceOverride
from fe_crank.cad.features import (
    Arc,
    Bearing,
    BoltHole,
    CadFeatures,
    CadSource,
    Counterweight,
    CrankAxis,
    Cylinder,
    Fillet,
    OilBore,
    ShaftEnd,
    ThrowFeatures,
    Web,
)
from fe_crank.cad.mesh import mesh_cad_throw
from fe_crank.cad.read import CadUnit
from fe_crank.cad.recognise import recognise
from fe_crank.cad.record import cad_record, feature_lines

__all__ = [
    "Arc",
    "Bearing",
    "BoltHole",
    "CadFeatures",
    "CadInput",
    "CadSource",
    "CadUnit",
    "Counterweight",
    "CrankAxis",
    "Cylinder",
    "FaceOverride",
    "Fillet",
    "OilBore",
    "ShaftEnd",
    "ThrowFeatures",
    "Web",
    "cad_record",
    "feature_lines",
    "mesh_cad_throw",
    "recognise",
]
