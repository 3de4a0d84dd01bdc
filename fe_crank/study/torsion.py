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

The chain's throw stiffness is Carter's (``throw_stiffness = "carter"``), which the
counterweights do not change; the FE throw stiffness (``throw_stiffness = "fe"``) is that
of each candidate's own mesh, which the study does not solve: not screened
(``refusal``).  A chain of stated stations (``model = "lumped"``) does not depend on the
geometry: the same response for every candidate."""

from __future__ import annotations

from dataclasses import dataclass
from typing import cast

from fe_crank.assess.loads import AssessedLoads
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.mechanism.dynamics import DynamicsResult
from fe_crank.study.bodies import BodyModel
from fe_crank.study.candidates import Candidate, DrawnWeb, ThrowSolidCache, Web, written_throw
from fe_crank.study.joints import JointModel, joint_model
from fe_crank.study.m53 import M53Screen, study_m53
from fe_crank.study.m53 import refusal as m53_refusal
from fe_crank.torsion.build import with_cylinders
from fe_crank.torsion.model import TorsionCase
from fe_crank.torsion.stage import TorsionalResponse, operating_dynamics, torsional_loads, torsional_response


def refusal(lc: LoadCase) -> str | None:
    """Why the study cannot run the check's torsional stage per candidate (None: it can,
    or the load case has no ``[torsion]``)."""
    t = lc.torsion
    if t is not None and t.model == "cad" and t.throw_stiffness == "fe":
        return (
            'with throw_stiffness = "fe" the chain takes each throw\'s stiffness from the FE torque case of the '
            'candidate\'s own mesh, which the study does not solve; screen with throw_stiffness = "carter" '
            "or judge the torsional figures by the full check of the chosen candidate"
        )
    return None


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


def candidate_torsion(lc: LoadCase, cycles: EngineCycles, geometry_inertia: dict[str, float]) -> TorsionalResponse:
    """The check's torsional stage on the chain of the candidate's throws (module doc;
    ``geometry_inertia``: ``geometry_inertias``)."""
    # the study's geometry is parametric (``run.prepare``): the case is a TorsionCase
    return torsional_response(cast(TorsionCase, lc), cycles, inertias=with_cylinders(lc.engine, geometry_inertia))


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
) -> TorsionScreen:
    """One candidate's torsional stage (module doc) and what the study screens on its loads
    as the check does on its torsional stage's: UR M53's Q (``study.m53``) and, with
    ``joints`` and the per-throw model ``body``, the bolted joints' load states
    (``study.joints.joint_model``: the throw's torsional angular acceleration and the
    vibratory pin force).  The loads' FE inertia (``torsion.flow.fe_loads``) is that of the
    drawn per-throw model's angular-acceleration case (``study.bodies``), the check's for
    the geometry written with the drawn counterweights; without that model (UR M53 alone,
    which reads neither the FE pin force nor that case) the CAD J_z stands for it."""
    gi = geometry_inertias(layout, cand, drawn, mass, solids)
    response = candidate_torsion(lc, cycles, gi)
    fe_j = body.fe_inertia if body is not None else gi
    loads = torsional_loads(lc.engine, cycles, response, fe_j, reaction=lc.fe.torque_reaction)
    q = study_m53(lc, cycles, loads) if m53_refusal(lc) is None else None
    jm = joint_model(lc, layout, body, cycles, loads) if joints and body is not None else None
    return TorsionScreen(response.first_frequency, loads, q, jm, operating_dynamics(cycles, response))


__all__ = ["TorsionScreen", "candidate_torsion", "geometry_inertias", "refusal", "screen_torsion"]
