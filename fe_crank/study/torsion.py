"""The torsional stage of each counterweight candidate in the counterweight study
(docs/study.md): with a ``[torsion]`` section the candidate's counterweights change the
throws' inertias about the crank axis, hence the chain's natural frequencies, its forced
response and the vibratory journal torques.  Per candidate the throws' inertias are
those the check builds for the geometry the candidate writes (``torsion.build
.with_cylinders`` on the written throw's exact CAD J_z, ``geometry.mass``: the study's
``ThrowSolidCache``; a candidate that cannot be built: the drawn throw's J_z plus
(k_w - 1) times each drawn counterweight's own), and the check's own torsional stage
runs on them (``torsion.stage.torsional_response``: every cylinder firing and each
misfire case, UR M53's hand-over of the journal torques).

The chain's throw stiffness: Carter's (``throw_stiffness = "carter"``), which the
counterweights do not change; or the FE throw stiffness (``throw_stiffness = "fe"``),
which they do (a counterweight stiffens its web, and the written sector is another solid
than the drawn one): per candidate the check's own (``torsion.stiffness
.plan_throw_stiffness``: the torque unit case of the first throw model of the check's
mesh plan) on the geometry the candidate writes, each distinct throw model meshed and
solved once (``ThrowStiffnessCache``); a candidate that cannot be built: the drawn
throw's.  A chain of stated stations (``model = "lumped"``) does not depend on the
geometry: the same response for every candidate."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import cast

from fe_crank.assess.loads import AssessedLoads
from fe_crank.errors import InputError
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.mesh.cache import cache_key
from fe_crank.mesh.plan import plan_meshes
from fe_crank.study.bodies import BodyModel
from fe_crank.study.candidates import Candidate, DrawnWeb, ThrowSolidCache, Web, written_throw
from fe_crank.study.joints import JointModel, joint_model
from fe_crank.study.m53 import M53Screen, study_m53
from fe_crank.study.m53 import refusal as m53_refusal
from fe_crank.torsion.build import with_cylinders
from fe_crank.torsion.model import TorsionCase
from fe_crank.torsion.stage import TorsionalResponse, operating_dynamics, torsional_loads, torsional_response
from fe_crank.torsion.stiffness import plan_throw_stiffness


def written_geometry(layout: ShaftLayout, cand: Candidate) -> CrankGeometry:
    """The geometry the candidate writes (``study.outputs.write_candidate``): each throw
    with its written counterweights (``written_throw``)."""
    g = layout.geometry
    return dataclasses.replace(g, throws=tuple(written_throw(t, cand) for t in g.throws))


class ThrowStiffnessCache:
    """The chain's FE throw stiffness (N m/rad, ``throw_stiffness = "fe"``) of the geometry
    each candidate writes (module doc): the check's mesh plan of that geometry
    (``mesh.plan.plan_meshes`` with the study's size, element limit and cache, the whole
    shaft's options as the check's) and the check's ``torsion.stiffness
    .plan_throw_stiffness`` on it; each distinct throw model (its mesh cache key,
    ``mesh.cache.cache_key``) solved once."""

    def __init__(self, lc: LoadCase, *, size, cache_dir, max_elements=None):
        self.lc = lc
        self.size, self.cache_dir, self.max_elements = size, cache_dir, max_elements
        self._by: dict[str, float] = {}

    def of(self, layout: ShaftLayout, cand: Candidate) -> float:
        """The stiffness for ``cand`` on the study shaft ``layout`` (its offset's view);
        a candidate that cannot be built: the drawn throw's (its geometry stands in)."""
        lc = self.lc
        assert lc.material is not None  # study.run.prepare
        g = written_geometry(layout, cand) if cand.buildable else layout.geometry
        # the check's plan takes the written shaft's layout: the throw models' options depend
        # on the throws' angles alone (``mesh.shaft.shaft_options``), the study shaft's
        plan = plan_meshes(
            g,
            tuple(t.name for t in lc.engine.throws),
            lc.mesh,
            size=self.size,
            max_elements=self.max_elements,
            cache_dir=self.cache_dir,
            file=lc.source_file,
            shaft=layout,
        )
        key = cache_key(g, g.throw(next(iter(plan.throws.values()))), plan.options)
        if key not in self._by:
            k = plan_throw_stiffness(g, plan, lc.material, lc.fe)
            if k is None:  # the [fe] section holds it (fe.input); options built otherwise may not
                raise InputError(
                    "throw_stiffness = 'fe' needs the FE torque unit case",
                    file=lc.source_file,
                    key="torsion.throw_stiffness",
                )
            self._by[key] = k
        return self._by[key]

    @property
    def solved(self) -> dict[str, float]:
        """Mesh cache key -> the stiffness (N m/rad) of each throw model solved so far."""
        return dict(self._by)


def geometry_inertias(
    layout: ShaftLayout, cand: Candidate, drawn: dict[Web, DrawnWeb], mass: dict, solids: ThrowSolidCache
) -> dict[str, float]:
    """Engine throw -> the CAD J_z (kg m^2) of the throw the candidate writes (module doc);
    ``mass``: the drawn throws' properties."""
    out = {}
    for th in layout.throws:
        if cand.buildable:
            out[th.name] = solids.of(written_throw(th.spec, cand)).total.inertia_axis
        else:
            out[th.name] = mass[th.name].total.inertia_axis + sum(
                (k - 1.0) * drawn[w].polar_inertia for w, k in cand.factors.items() if w[0] == th.name
            )
    return out


def candidate_torsion(
    lc: LoadCase, cycles: EngineCycles, geometry_inertia: dict[str, float], fe_stiffness: float | None = None
) -> TorsionalResponse:
    """The check's torsional stage on the chain of the candidate's throws (module doc;
    ``geometry_inertia``: ``geometry_inertias``; ``fe_stiffness``: the candidate's FE
    throw stiffness, ``ThrowStiffnessCache``, with ``throw_stiffness = "fe"``)."""
    # the study's geometry is parametric (``run.prepare``): the case is a TorsionCase
    return torsional_response(
        cast(TorsionCase, lc), cycles, inertias=with_cylinders(lc.engine, geometry_inertia), fe_stiffness=fe_stiffness
    )


@dataclass(frozen=True)
class TorsionScreen:
    """What one candidate's torsional stage gives the study."""

    frequency: float  # Hz, the chain's first elastic natural frequency
    loads: AssessedLoads  # every speed and state with the candidate's vibration
    m53: M53Screen | None  # UR M53's least Q on them (None: ``study.m53.refusal``)
    joints: JointModel | None  # the bolted throws' load states on them (None: not asked for)
    #: the operating cycle with the journal torques the candidate's torsional stage hands
    #: over (``torsion.stage.operating_dynamics``): the whole shaft's operating firing state
    dynamics: DynamicsResult | None = None
    #: the chain's FE throw stiffness, N m/rad (None: Carter's or stated stations)
    fe_stiffness: float | None = None


def screen_torsion(
    lc: LoadCase,
    cycles: EngineCycles,
    layout: ShaftLayout,
    cand: Candidate,
    drawn: dict[Web, DrawnWeb],
    mass: dict,
    solids: ThrowSolidCache,
    body: BodyModel | None,
    joints: bool,
    stiffness: ThrowStiffnessCache | None = None,
) -> TorsionScreen:
    """One candidate's torsional stage (module doc) and what the study screens on its loads
    as the check does on its torsional stage's: UR M53's Q (``study.m53``) and, with
    ``joints`` and the per-throw model ``body``, the bolted joints' load states
    (``study.joints.joint_model``: the throw's torsional angular acceleration and the
    vibratory pin force).  The loads' FE inertia (``torsion.flow.fe_loads``) is that of the
    drawn per-throw model's angular-acceleration case (``study.bodies``), the check's for
    the geometry written with the drawn counterweights; without that model (UR M53 alone,
    which reads neither the FE pin force nor that case) the CAD J_z stands for it.  With
    ``throw_stiffness = "fe"`` on a chain of the geometry the FE throw stiffness is the
    candidate's (``stiffness``, required then)."""
    gi = geometry_inertias(layout, cand, drawn, mass, solids)
    k_fe = None
    t = lc.torsion
    if t is not None and t.model == "cad" and t.throw_stiffness == "fe":
        if stiffness is None:
            raise ValueError('throw_stiffness = "fe": give the candidates\' ThrowStiffnessCache')
        k_fe = stiffness.of(layout, cand)
    response = candidate_torsion(lc, cycles, gi, k_fe)
    fe_j = body.fe_inertia if body is not None else gi
    loads = torsional_loads(lc.engine, cycles, response, fe_j, reaction=lc.fe.torque_reaction)
    q = study_m53(lc, cycles, loads) if m53_refusal(lc) is None else None
    jm = joint_model(lc, layout, body, cycles, loads) if joints and body is not None else None
    return TorsionScreen(response.first_frequency, loads, q, jm, operating_dynamics(cycles, response), k_fe)


__all__ = [
    "ThrowStiffnessCache",
    "TorsionScreen",
    "candidate_torsion",
    "geometry_inertias",
    "screen_torsion",
    "written_geometry",
]
