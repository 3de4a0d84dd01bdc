"""UR M53's acceptability factor Q in the counterweight study (docs/study.md).

UR M53's nominal stresses are those of the rods' forces and the journal torque on the
statically determinate throw (IACS UR M53 Rev.1 2.1-2.2), its dimensions the pin's,
journal's and web's (``assess.adapters.m53_geometry_of``): the counterweights enter
neither, and without torsional vibration the engine's loads at each state's steady speed
do not depend on them.  Q is then the same for every candidate; ``study_m53`` computes it
once, with the check's own code on the check's own loads: the torque flow of every speed
and load state (``torsion.loads.assessed_loads``, the power take-off end of ``[fe]``),
each rod at its place on the pin (``fe.throw.pin_patches``), UR M53's sigma_add and K_e
(``rules.m53.basis``) and, per throw, ``assess.throw.m53_fillets``; the least Q over every
state, throw and fillet (the check's ``min_m53_acceptability``, ``assess.criteria``).

With a ``[torsion]`` section the journal torques are the torsional stage's (their
vibratory part, and UR M53's hand-over of the largest alternating torque, depend on the
shaft's inertia, which the counterweights change): ``study_m53`` then takes the loads of
the candidate's own torsional stage (``study.torsion``, ``torsion.stage.torsional_loads``),
as the check takes its torsional stage's; Q is the candidate's."""

from __future__ import annotations

import math
from dataclasses import dataclass

from fe_crank.assess.adapters import m53_geometry_of
from fe_crank.assess.loads import AssessedLoads
from fe_crank.assess.throw import m53_fillets
from fe_crank.fe.throw.pin_patches import rod_loads, rod_positions
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import EngineCycles
from fe_crank.rules.m53 import scf_empirical
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.rules.m53.oil_bore import where
from fe_crank.torsion.loads import assessed_loads

#: the study's limit on Q: the load case's criterion key
LIMIT = "min_m53_acceptability"


@dataclass(frozen=True)
class M53Screen:
    acceptability: float  # Q, the least over every state, throw and fillet
    where: str  # throw, fillet and load state of it
    speed: float  # rad/s of that state


def refusal(lc: LoadCase) -> str | None:
    """Why the study cannot give the check's Q of its candidates (None: it can)."""
    g = lc.geometry
    m = lc.material
    if m is None or m.tensile_strength is None or m.m53_k is None:
        return "UR M53 needs the material's tensile strength and its UR M53 factor K (material.m53_k)"
    m53g = m53_geometry_of(g) if isinstance(g, CrankGeometry) else None
    if m53g is None:
        return "the geometry gives no UR M53 dimensions"
    if any(scf_empirical.out_of_range(m53g.related(f)) for f in ("pin", "journal")):
        return (
            "the throw is outside the validity range of UR M53's empirical SCFs; the check takes FE SCFs "
            "from UR M53 App. III's own models, which the study does not solve"
        )
    return None


def study_m53(lc: LoadCase, cycles: EngineCycles, loads: AssessedLoads | None = None) -> M53Screen | None:
    """Q (module doc): without ``[torsion]`` every candidate's, on the rigid shaft's torque
    flow; ``loads``: a candidate's loads with its torsional vibration
    (``torsion.stage.torsional_loads``).  None when ``refusal`` says why not."""
    if refusal(lc) is not None:
        return None
    g, mat = lc.geometry, lc.material
    assert isinstance(g, CrankGeometry) and mat is not None
    m53g = m53_geometry_of(g)
    basis = m53_basis(lc.engine, mat, lc.criteria.m53_additional_bending if lc.criteria else None, file=lc.source_file)
    if loads is None:
        loads = assessed_loads(lc.engine, cycles, reaction=lc.fe.torque_reaction)
    places = {t.name: rod_positions(lc.engine, t.name, g.crankpin_length) for t in lc.engine.throws}
    best = M53Screen(math.inf, "", math.nan)
    for states in loads.speeds:
        for state in states:
            for name, tc in state.throws.items():
                fillets, _ = m53_fillets(
                    name,
                    m53g,
                    mat,
                    tc.pin_force,
                    (tc.torque_in, tc.torque_out, *loads.m53_torques.get(name, ())),
                    fe_scf=None,
                    scf=None,
                    additional=basis.additional,
                    ke=basis.ke,
                    rod_loads=rod_loads(tc, places[name]),
                )
                for f in fillets:
                    if f.acceptability < best.acceptability:
                        rpm = state.speed * 30 / math.pi
                        best = M53Screen(
                            f.acceptability,
                            f"throw {name}, {where(f.fillet)}, {state.case} at {rpm:.0f} rpm",
                            state.speed,
                        )
    return best if math.isfinite(best.acceptability) else None


__all__ = ["LIMIT", "M53Screen", "refusal", "study_m53"]
