"""The whole shaft's load sets of the hot-spot convergence study.

The per-throw study (``fe.refinement.zone_study``) refines the hot spots of a throw mesh
under the per-throw model's two load sets (``fe.refinement.loads.check_loads``: the largest
crankpin force of the cycle with the centrifugal load; the largest journal torque).  The
whole shaft carries the same throws on all its main bearings: its fillet stresses, and
where they peak, are its own.  The whole shaft's load sets of a throw mesh follow the same
rule in the whole-shaft model (``shaft_load_sets``):

* "peak pin force": the state of the cycle at the angle of the largest crankpin force on
  any throw of that mesh, read on that throw;
* "peak torque": the state at the angle of the largest journal torque through any throw
  of that mesh, read on that throw;

each the whole shaft's unit-case weights at that angle (``ShaftCycle.weights``, with the
counterweights), so every throw, bearing reaction and web moment of the state is in it.
Each load set is given to the zone study as

* the throw piece's displacement in that state on its whole mesh, in its own frame
  (``fe.shaft.fields.piece_states``: u = sum_p a_p L_p + X v), which drives the zones on
  their cut, journal surfaces and end faces as the per-throw model's solution does;
* the loads that act inside a zone (``zone_loads``): the piece's pin patterns as the same
  pin unit cases, the centrifugal and spin-up body forces; the bearing couplings and end
  face torques act on faces the zone drives.

The zone study solves them in the same zones as the per-throw load sets (one mesh and
one factorisation a zone for both models' load sets); a throw mesh's study then holds
both models' load sets, and each hot-spot family's factor is the largest over all of
them (``assess.refinement``).
"""

from __future__ import annotations

import numpy as np

from fe_crank.fe.core.loads import COUNTERWEIGHT_BODIES
from fe_crank.fe.refinement.loads import peak_states
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.shaft.fields import piece_states
from fe_crank.fe.throw.pin_directions import pin_cases
from fe_crank.mechanism.results import DynamicsResult

#: the whole shaft's body patterns (``fe.shaft.patterns``) -> the zone's body unit cases
#: (``fe.core.loads.BODY_CASES``): the same body force on the same elements
BODY_PATTERNS = {"centrifugal": "centrifugal_throw", "spin_up": "angular_acceleration"}
#: relative difference under which the throw's and its counterweights' centrifugal
#: coefficients are taken as one (the whole throw's ``centrifugal``: no subdomain needed)
SAME_SPEED = 1e-12
#: the prefix of the whole shaft's load sets' names in a study
WHOLE_SHAFT_SET = "whole shaft, "

#: (mesh key, load set name) -> (displacement (3 N,) on the throw mesh, loads inside a zone)
LoadSets = dict[str, dict[str, tuple[np.ndarray, dict[str, float]]]]


def piece_of(cases: ShaftCases, throw: str) -> int:
    """The index of the piece of throw ``throw`` in the shaft model."""
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind == "throw" and str(pp.throw) == throw:
            return k
    raise ValueError(f"the whole shaft has no throw {throw!r}")


def zone_loads(names: tuple[str, ...], coef: np.ndarray) -> dict[str, float]:
    """The loads inside a zone of a throw piece with local pattern coefficients ``coef``
    (n_pat,) of its patterns ``names`` (``fe.shaft.patterns``), as the zone's unit cases
    with their weights: the pin patterns as themselves, the spin-up as the angular
    acceleration's body force, the throw's and its counterweights' centrifugal force as the
    whole throw's when their coefficients agree (else the parts).  The bearing surfaces'
    and end faces' patterns act on faces the zone drives (``zone.driven_boundaries``): they
    are left out."""
    a = dict(zip(names, (float(x) for x in coef)))
    out: dict[str, float] = {}
    pins = set(pin_cases())
    for name, w in a.items():
        if name in pins and w != 0.0:
            out[name] = w
        elif name == "spin_up" and w != 0.0:
            out[BODY_PATTERNS[name]] = w
    own, cw = a.get("centrifugal", 0.0), a.get("centrifugal_cw", 0.0)
    webs = {f"centrifugal_cw_{b[-1]}": a.get(f"centrifugal_cw_{b[-1]}", 0.0) for b in COUNTERWEIGHT_BODIES}
    if abs(own - cw) <= SAME_SPEED * max(abs(own), abs(cw)) and not any(webs.values()):
        if own != 0.0:
            out["centrifugal"] = own
        return out
    if own != 0.0:
        out[BODY_PATTERNS["centrifugal"]] = own
    for name, w in webs.items():
        if w + cw != 0.0:
            out[name] = w + cw
    return out


def governing_states(dynamics: DynamicsResult, throws: list[str]) -> dict[str, tuple[str, int]]:
    """{load set name: (throw, cycle angle index)} of the throws ``throws`` (module doc):
    the per-throw study's two states (``fe.refinement.loads.peak_states``: the largest
    crankpin force and the largest journal torque over them and the cycle); the torque's
    set is left out when no torque passes, a state already taken is not repeated."""
    theta = np.asarray(dynamics.theta, float)
    force, torque = peak_states({t: dynamics.throws[t] for t in throws})
    out: dict[str, tuple[str, int]] = {}
    for words, found in (("peak pin force", force), ("peak torque", torque)):
        if found is None or (str(found[0]), found[1]) in out.values():
            continue
        t, i = str(found[0]), found[1]
        out[f"{WHOLE_SHAFT_SET}{words} (throw {t}, {np.degrees(theta[i]):.1f} deg)"] = (t, i)
    return out


def shaft_load_sets(
    cases: ShaftCases, weights: np.ndarray, dynamics: DynamicsResult, material, solver: str = "auto"
) -> LoadSets:
    """The whole shaft's load sets of each throw mesh (module doc), keyed by the mesh's
    ``ThrowMesh.key``: ``weights`` (n_angles, n_cases) the operating cycle's case weights
    over ``dynamics``' angles (``WholeShaftResult.cycles[0].weights``).  One interior solve
    per distinct piece for all its states (``piece_states``)."""
    sm = cases.model.mesh
    by_mesh: dict[str, list[str]] = {}
    for k, pp in enumerate(cases.model.pieces):
        if pp.kind == "throw" and str(pp.throw) in dynamics.throws:
            by_mesh.setdefault(sm.pieces[k].mesh, []).append(str(pp.throw))
    chosen = {key: governing_states(dynamics, throws) for key, throws in by_mesh.items()}
    columns: dict[int, list[tuple[str, str, int]]] = {}
    for key, states in chosen.items():
        for name, (t, i) in states.items():
            columns.setdefault(piece_of(cases, t), []).append((key, name, i))
    W = {k: np.asarray(weights, float)[[i for _, _, i in cols]].T for k, cols in columns.items()}
    U = piece_states(cases, W, material, solver)
    out: LoadSets = {}
    for k, cols in columns.items():
        names = cases.model.pieces[k].cond.names
        coef = cases.coef[k] @ W[k]
        for j, (key, name, _) in enumerate(cols):
            out.setdefault(sm.throw_meshes[key].key, {})[name] = (U[k][:, j], zone_loads(names, coef[:, j]))
    return out


__all__ = ["WHOLE_SHAFT_SET", "LoadSets", "governing_states", "piece_of", "shaft_load_sets", "zone_loads"]
