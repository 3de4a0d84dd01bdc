"""What the assessment takes from the geometry of each throw of the engine, either route.

``ThrowGeometry`` holds, for one engine throw: the crankpin length between the webs'
inner faces (where the rods sit on the pin, UR M53 2.1), the webs' mid-planes (the
SCF mode of UR M53 App. III measures the nominal stresses there), the UR M53
dimensions or why there are none, and the counterweights' built m r against the
balance stage's required m r.  The check's geometry stage computes them once:

* ``parametric_throws``: from a ``CrankGeometry`` (``adapters.m53_geometry_of``; the
  counterweights from the B-rep mass properties of ``geometry.mass.throw_solids``,
  ``adapters.counterweights_of``);
* ``cad_throws``: from the throws recognised in a CAD file (``cad_inputs``: the
  dimensions measured on the B-rep; a throw outside the empirical formulas' scope has
  none, and the reason, ``m53_scope``).
"""

from __future__ import annotations

from dataclasses import dataclass

from fe_crank import model
from fe_crank.assess.adapters import counterweights_of, m53_geometry_of
from fe_crank.assess.cad_inputs import counterweights_of_cad, m53_geometry_of_cad, m53_scope
from fe_crank.assess.counterweight import CounterweightData
from fe_crank.balance.counterweights import CounterweightDesign
from fe_crank.cad.config import CadInput
from fe_crank.cad.features import CadFeatures
from fe_crank.geometry.mass import ThrowSolids
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.rules.m53.calculation import M53Geometry
from fe_crank.rules.m53.scf_mode import web_centres_of
from fe_crank.throw_scope import throws_of


@dataclass(frozen=True)
class ThrowGeometry:
    """The geometry of one engine throw as the assessment reads it (SI, THROW frame)."""

    crankpin_length: float  # m, between the webs' inner faces
    web_centres: tuple[float, float]  # m, z of the webs' mid-planes (front, rear)
    m53: M53Geometry | None  # UR M53 dimensions; None: the M53 route is not run
    m53_note: str | None = None  # why there are none
    counterweights: tuple[CounterweightData, ...] = ()


def parametric_throws(
    g: CrankGeometry,
    models: dict[str, str],
    engine: model.Engine,
    solids: ThrowSolids | None,
    design: CounterweightDesign | None,
) -> dict[str, ThrowGeometry]:
    """Engine throw name -> ``ThrowGeometry`` of a parametric geometry; ``models``: the
    mesh plan's key -> geometry throw name; ``solids``: the mass properties of the
    geometry throws with counterweights (None: none)."""
    m53 = m53_geometry_of(g)
    centres = web_centres_of(g)
    out = {}
    for key, name in models.items():
        spec = g.throw(name)
        for tname in throws_of(key, [t.name for t in engine.throws]):
            throw = engine.throw(tname)
            cws = (
                counterweights_of(
                    spec,
                    solids.of(spec.name),
                    throw.axial_position,
                    throw.shaft,
                    design,
                    g,
                    frame=(throw.angle, engine.shaft(throw.shaft).sense),
                )
                if spec.counterweights and solids is not None
                else ()
            )
            out[tname] = ThrowGeometry(g.crankpin_length, centres, m53, None, cws)
    return out


def cad_throws(
    features: CadFeatures,
    cad: CadInput,
    models: dict[str, str],
    engine: model.Engine,
    design: CounterweightDesign | None,
) -> dict[str, ThrowGeometry]:
    """Engine throw name -> ``ThrowGeometry`` of the throws recognised in a CAD file;
    ``models``: the mesh plan's key -> recognised throw name."""
    out = {}
    for key, name in models.items():
        t = features.throw(name)
        scope = m53_scope(t)
        m53 = m53_geometry_of_cad(t, cad)
        note = None
        if m53 is None:
            note = f"UR M53's empirical formulas do not describe this throw of the CAD file: {scope}"
        centres = tuple(0.5 * (w.z_inner + w.z_outer) for w in t.webs)
        bolted = tuple((i, b) for i, b in enumerate(features.bolted, start=1) if b.throw == t.name)
        for tname in throws_of(key, [e.name for e in engine.throws]):
            throw = engine.throw(tname)
            frame = (throw.angle, engine.shaft(throw.shaft).sense)
            cws = counterweights_of_cad(t, throw.axial_position, throw.shaft, design, bolted, frame=frame)
            out[tname] = ThrowGeometry(t.pin_length, (centres[0], centres[1]), m53, note, cws)
    return out
