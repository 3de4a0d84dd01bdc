"""The whole-shaft model's typed entry point: main-bearing loads and web moments over the cycle.

``analyse_whole_shaft(shaft_mesh, material, dynamics, mass=...)`` takes the shaft's mesh
(``mesh.shaft.ShaftMesh``, meshed by ``cad.source.mesh_models`` in a check; this module
meshes nothing), condenses it onto its bearing-centre planes (``fe.shaft.model``), solves
the unit cases on the determinate base (``fe.shaft.cases``) and superposes them over the
dynamics stage's cycle with the bearings' laws (``fe.shaft.cycle``), with the
counterweights as built and without them (counterweights bolted on and not meshed,
``ShaftLayout.bolted``: their centrifugal forces at their centroids, coupled to the
journal beside their web, ``end_load_cases``).  ``dynamics``: the dynamics stage's result
(``theta``, ``speed`` and per throw ``pin_force`` (n, 2) in the throw frame and
``angle_global``).  ``WholeShaftResult.to_dict()`` gives the fields of results.json.

The main bearings' loads (``BearingResult``, the main-bearing criteria's) are the
envelope of the stated bearing law and radial springs across the layout's stiffness
range (``envelope_laws``: its ends and their geometric mean, a clearance keeping its
gap): per bearing the law that gives its largest peak, named with the loads.  A rigid
support under-states the end bearings of a shaft on several bearings (a softer
support moves load from the inner bearings outwards); the real radial stiffness of
oil film, shell and housing is rarely known better than within a decade.  The stresses
and web moments stay those of the stated law.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np

from fe_crank.fe.shaft.cases import ShaftCases, solve_cases
from fe_crank.fe.shaft.cycle import (
    BearingLoads,
    EndCycleLoad,
    ShaftCycle,
    ThrowCycleLoad,
    WebMoment,
    bearing_solve,
    shaft_cycle,
)
from fe_crank.fe.shaft.model import ShaftFeOptions, build_shaft_model
from fe_crank.geometry.mass import mass_properties
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.geometry.spec import BearingLaw
from fe_crank.mesh.shaft import ShaftMesh, rotation


@dataclass(frozen=True)
class BearingResult:
    with_counterweights: BearingLoads
    without_counterweights: BearingLoads

    @property
    def name(self) -> str:
        return self.with_counterweights.name

    def to_dict(self, angles: np.ndarray) -> dict:
        a, b = self.with_counterweights, self.without_counterweights
        return {
            "name": a.name,
            "z": a.z,
            "width": a.width,
            "bearing_law": a.law,
            "crank_angle_deg": [float(x) for x in angles],
            "load_n": a.load_n.tolist(),
            "peak_n": a.peak_n,
            "peak_angle_deg": a.peak_angle_deg,
            "mean_n": a.mean_n,
            "specific_load_pa": a.specific_load_pa,
            "mean_specific_load_pa": a.mean_specific_load_pa,
            "without_counterweights": {
                "bearing_law": b.law,
                "load_n": b.load_n.tolist(),
                "peak_n": b.peak_n,
                "peak_angle_deg": b.peak_angle_deg,
                "mean_n": b.mean_n,
                "specific_load_pa": b.specific_load_pa,
            },
        }


@dataclass(frozen=True)
class WebResult:
    with_counterweights: WebMoment
    without_counterweights: WebMoment

    def to_dict(self) -> dict:
        a, b = self.with_counterweights, self.without_counterweights
        return {
            "throw": a.throw,
            "web": a.web,
            "z": a.z,
            "bending_moment_nm": a.bending_moment_nm.tolist(),
            "without_counterweights": {"bending_moment_nm": b.bending_moment_nm.tolist()},
        }


@dataclass(frozen=True)
class WholeShaftResult:
    crank_angle_deg: np.ndarray
    speed: float  # rad/s
    n_dof: int
    bearings: tuple[BearingResult, ...]
    webs: tuple[WebResult, ...]
    support_model: str
    cycles: tuple[ShaftCycle, ShaftCycle]  # with, without counterweights (weights for stresses)
    overspeed: tuple[ShaftCycle, ...] = ()  # the overspeed cycles, with counterweights
    timings: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {
            "support_model": self.support_model,
            "n_dof": self.n_dof,
            "speed_rad_s": self.speed,
            "main_bearings": [b.to_dict(self.crank_angle_deg) for b in self.bearings],
            "webs": [w.to_dict() for w in self.webs],
        }


def support_text(layout: ShaftLayout) -> str:
    laws = {b.law for b in layout.bearings}
    if len(laws) == 1:
        law = next(iter(laws))
        if law.model == "rigid":
            how = "rigid"
        elif law.model == "spring":
            how = f"radial springs of {law.stiffness:.3g} N/m"
        else:
            how = f"radial clearance {law.clearance * 1e6:.3g} um, contact stiffness {law.stiffness:.3g} N/m"
    else:
        how = "laws per bearing"
    thrust = layout.thrust_bearing.name
    lo, hi = layout.stiffness_range
    return (
        f"whole shaft on {len(layout.bearings)} main bearings ({how}), each a reference point at its "
        f"centre with a distributing coupling to its journal; thrust bearing {thrust}; the torque leaves "
        f"at the {layout.power_takeoff} end; the main-bearing loads are the envelope of this law and "
        f"radial bearing stiffnesses of {lo:.3g} to {hi:.3g} N/m"
    )


def throw_masses(layout: ShaftLayout) -> dict:
    """Throw name -> the exact mass properties of its solid (``geometry.mass``; one solid per
    set of counterweights: the name and angle do not change it)."""
    by_shape: dict = {}
    for th in layout.throws:
        if th.spec.counterweights not in by_shape:
            by_shape[th.spec.counterweights] = mass_properties(layout.geometry, th.spec)
    return {th.name: by_shape[th.spec.counterweights] for th in layout.throws}


def torque_flow_cases(model) -> dict[str, dict[tuple[int, str], float]]:
    """The cases that let every journal carry its own torque (``torque_flow_loads``): the
    body force of a unit angular acceleration of each throw (``spin_up@<throw>``) and M_z
    = 1 N m on the shaft's front face (``torque_front``)."""
    out: dict[str, dict[tuple[int, str], float]] = {
        f"spin_up@{pp.throw}": {(pp.index, "spin_up"): 1.0} for pp in model.pieces if pp.kind == "throw"
    }
    out["torque_front"] = {(0, "torque_end_1"): 1.0}
    return out


def torque_flow_loads(cases: ShaftCases, layout: ShaftLayout, dynamics) -> tuple[dict[str, np.ndarray], np.ndarray]:
    """Weights of the ``torque_flow_cases`` over the cycle of ``dynamics``: per throw
    (``spin_up@<throw>``) the body force carrying the rest of its rear journal's torque,
    T_rear - T_front - T_own = (the throw's inertia and damping torque with torsional
    vibration, zero quasi-statically; ``torsion.flow``), and the
    first throw's front journal torque on the shaft's front face (``torque_front``); the
    power take-off's face reacts the last throw's rear journal torque, so every journal
    carries its own torque.  Signs: a torque T in the sense of rotation is M_z = -sense T;
    the spin-up case's moment about z is J_z = its resultant's M_z."""
    sense = layout.sense
    spin = {}
    for pp in cases.model.pieces:
        if pp.kind != "throw":
            continue
        assert pp.throw is not None
        tl = dynamics.throws[pp.throw]
        jz = float(pp.cond.resultant[5, pp.cond.column("spin_up")])
        rest = np.asarray(tl.torque_rear) - np.asarray(tl.torque_front) - np.asarray(tl.torque)
        spin[pp.throw] = -sense * rest / jz
    first = layout.throws[0].name
    return spin, -sense * np.asarray(dynamics.throws[first].torque_front, float)


def _end_face(layout: ShaftLayout, end: str) -> tuple[int, str, float, int]:
    """(piece index, face, z of the face, outward sign) of the shaft's ``end``."""
    if end == "front":
        return 0, "end_1", layout.journals[0].z0, -1
    return -1, "end_2", layout.journals[-1].z1, 1


def _bolted_face(sm, b) -> tuple[int, str, float]:
    """(piece index, surface, shaft-frame z) of a bolted body (``ShaftLayout.bolted``): the
    journal beside its web, in its throw's piece, at its centroid's z."""
    k = next(i for i, p in enumerate(sm.pieces) if p.kind == "throw" and p.throw == b.throw)
    return k, f"journal_{b.web}", sm.pieces[k].z + b.z


def end_load_surfaces(sm) -> dict[str, tuple[str, ...]]:
    """Mesh key -> the end faces whose coupling patterns the loads beyond the ends need,
    and the journals that carry bolted bodies (``build_shaft_model``'s ``extra_surfaces``)."""
    out: dict[str, tuple[str, ...]] = {}
    faces = [_end_face(sm.layout, e.end)[:2] for e in sm.layout.end_loads]
    faces += [_bolted_face(sm, b)[:2] for b in sm.layout.bolted]
    for k, face in faces:
        key = sm.pieces[k].mesh
        out[key] = tuple(dict.fromkeys(out.get(key, ()) + (face,)))
    return out


def end_load_cases(model) -> dict[str, dict[tuple[int, str], float]]:
    """Unit cases ``<name>.x``, ``<name>.y`` of each flywheel or pulley (``ShaftLayout.end_loads``):
    1 N (shaft frame) at a reference point on the axis at its centre plane, ``offset``
    beyond the end face, coupled to that face by a distributing coupling (RBE3, as the
    bearings: the face takes the force and its moment about the face)."""
    layout = model.mesh.layout
    out = {}
    for e in layout.end_loads:
        k, face, z, sign = _end_face(layout, e.end)
        k = k % len(model.pieces)
        c = model.coupling(e.name, z + sign * e.offset, [(k, face)])
        out[f"{e.name}.x"], out[f"{e.name}.y"] = dict(c.terms[0]), dict(c.terms[1])
    for b in layout.bolted:  # a bolted body: at its centroid, on the journal beside its web
        k, face, z = _bolted_face(model.mesh, b)
        c = model.coupling(b.name, z, [(k, face)])
        out[f"{b.name}.x"], out[f"{b.name}.y"] = dict(c.terms[0]), dict(c.terms[1])
    return out


def end_loads_of(layout: ShaftLayout, speed: float, psi: np.ndarray) -> tuple[EndCycleLoad, ...]:
    """The loads of each flywheel or pulley over the cycle, shaft frame: the centrifugal
    force omega^2 m e of its unbalance, turning with the shaft (at ``unbalance_angle`` from
    the first throw's crankpin in the sense of rotation: shaft-frame angle
    sense (angle_1 + unbalance_angle) from +y towards +x), and its belt pull, fixed in the
    engine frame (direction ``belt_angle``), turned into the shaft frame by -psi."""
    out = []
    a1 = layout.throws[0].angle
    c, s = np.cos(psi), np.sin(psi)
    for e in layout.end_loads:
        z = _end_face(layout, e.end)[2] + _end_face(layout, e.end)[3] * e.offset
        alpha = layout.sense * (a1 + e.unbalance_angle)
        F = np.zeros((psi.size, 2))
        F += speed**2 * e.unbalance * np.array([np.sin(alpha), np.cos(alpha)])
        b0, b1 = e.belt_pull * np.sin(e.belt_angle), e.belt_pull * np.cos(e.belt_angle)
        F[:, 0] += c * b0 - s * b1
        F[:, 1] += s * b0 + c * b1
        out.append(EndCycleLoad(e.name, z, F))
    throws = {t.name: t for t in layout.throws}
    for b in layout.bolted:  # its centrifugal force turns with the shaft: fixed in the shaft frame
        t = throws[b.throw]
        R = rotation(layout.sense * t.angle)[:2, :2]
        F = np.broadcast_to(speed**2 * (R @ np.asarray(b.unbalance, float)), (psi.size, 2)).copy()
        out.append(EndCycleLoad(b.name, t.z + b.z, F, counterweight=True))
    return tuple(out)


def _cycle_inputs(cases: ShaftCases, layout: ShaftLayout, dynamics):
    """(throw loads, shaft angle psi, the torque_front weights or None, end loads) of ``dynamics``."""
    first = layout.throws[0]
    psi = np.asarray(dynamics.throws[first.name].angle_global) - layout.sense * first.angle
    spin, front = (None, None)
    if "torque_front" in cases.names:
        spin, front = torque_flow_loads(cases, layout, dynamics)
    loads = tuple(
        ThrowCycleLoad(th.name, dynamics.throws[th.name].pin_force, None if spin is None else spin[th.name])
        for th in layout.throws
    )
    return loads, psi, front, end_loads_of(layout, float(dynamics.speed), psi)


def shaft_cycle_of(
    cases: ShaftCases, layout: ShaftLayout, mass: dict, dynamics, *, counterweights: bool = True, laws=None
) -> ShaftCycle:
    """The whole shaft over the cycle of ``dynamics`` (the dynamics stage's result: ``theta``,
    ``speed``, per throw ``pin_force`` (n, 2) in the throw frame, ``angle_global`` and the
    journal torques); with the torque-flow cases when the model has them."""
    loads, psi, front, ends = _cycle_inputs(cases, layout, dynamics)
    return shaft_cycle(
        cases,
        loads,
        dynamics.theta,
        psi,
        dynamics.speed,
        mass,
        counterweights=counterweights,
        laws=laws,
        front_torque=front,
        ends=ends,
    )


#: stiffnesses across the range: its ends and their geometric mean
ENVELOPE_POINTS = 3


def envelope_laws(layout: ShaftLayout, laws=None) -> tuple[tuple[BearingLaw, ...], ...]:
    """The law sets the main-bearing loads are enveloped over: the stated one (``laws``,
    default the layout's) first, then every bearing on radial springs of each stiffness of
    the range (``ENVELOPE_POINTS``, log-spaced; a clearance bearing keeps its gap with
    that contact stiffness)."""
    stated = tuple(laws or [b.law for b in layout.bearings])
    out = [stated]
    for k in np.geomspace(*layout.stiffness_range, ENVELOPE_POINTS):
        k = float(k)
        out.append(
            tuple(
                BearingLaw("clearance", k, w.clearance) if w.model == "clearance" else BearingLaw("spring", k)
                for w in stated
            )
        )
    return tuple(out)


def envelope(per_law: list[tuple[BearingLoads, ...]]) -> tuple[BearingLoads, ...]:
    """Per bearing the loads of the law with the largest peak (the first of equal ones)."""
    return tuple(max(loads, key=lambda b: b.peak_n) for loads in zip(*per_law))


def bearings_of(
    cases: ShaftCases, layout: ShaftLayout, mass: dict, dynamics, *, laws=None
) -> tuple[BearingResult, ...]:
    """The main bearings' loads over the cycle of ``dynamics`` (another speed or load state
    on the same condensed shaft), with and without counterweights: the envelope over
    ``envelope_laws``."""
    return bearing_state_of(cases, layout, dynamics, laws=laws)[0]


def bearing_state_of(
    cases: ShaftCases,
    layout: ShaftLayout,
    dynamics,
    *,
    laws=None,
    stated: tuple[ShaftCycle, ShaftCycle] | None = None,
) -> tuple[tuple[BearingResult, ...], np.ndarray]:
    """``bearings_of`` and the case weights of the stated law with the counterweights
    (``shaft_cycle_of(...).weights``, the stresses' weights): the stated law's solve
    is the envelope's first, made once for both.  ``stated``: the stated law's cycles of
    ``dynamics`` with and without counterweights when they are solved already
    (``shaft_cycle_of``), taken as the envelope's first instead of solving them again."""
    loads, psi, front, ends = _cycle_inputs(cases, layout, dynamics)
    sets = envelope_laws(layout, laws)
    weights = None
    per_cw = []
    for cw in (True, False):
        per_law = []
        for k, w in enumerate(sets):
            if k == 0 and stated is not None:
                done = stated[0] if cw else stated[1]
                assert done.counterweights == cw
                if cw:
                    weights = done.weights
                per_law.append(done.bearings)
                continue
            bearings, W = bearing_solve(
                cases,
                loads,
                dynamics.theta,
                psi,
                dynamics.speed,
                counterweights=cw,
                laws=w,
                front_torque=front,
                ends=ends,
            )
            if cw and k == 0:
                weights = W
            per_law.append(bearings)
        per_cw.append(envelope(per_law))
    on, off = per_cw
    assert weights is not None
    return tuple(BearingResult(a, b) for a, b in zip(on, off)), weights


def condensed_shaft(
    sm, material, options: ShaftFeOptions | None = None, *, torque_flow: bool = False, condensed: dict | None = None
):
    """The condensed shaft, its unit cases (the torque-flow cases when asked, a flywheel's
    and a pulley's, ``end_load_cases``, when the layout has them) and the seconds the
    cases took.  ``condensed``: throw condensations shared with other models
    (``build_shaft_model``)."""
    model = build_shaft_model(sm, material, options, extra_surfaces=end_load_surfaces(sm), condensed=condensed)
    t0 = time.perf_counter()
    extra = {**(torque_flow_cases(model) if torque_flow else {}), **end_load_cases(model)}
    cases = solve_cases(model, extra or None)
    return model, cases, time.perf_counter() - t0


def analyse_whole_shaft(
    sm: ShaftMesh,
    material,
    dynamics,
    *,
    mass: dict,
    options: ShaftFeOptions | None = None,
    laws=None,
    torque_flow: bool = False,
    overspeed=(),
) -> tuple[WholeShaftResult, ShaftCases]:
    """The whole shaft of the mesh ``sm`` (its layout ``sm.layout``) over the cycle (module
    doc); also returns the unit cases (stresses by superposition: ``ShaftCases.recover``
    with ``WholeShaftResult.cycles[i].weights``).  ``mass``: throw name -> the mass
    properties of its solid (``throw_masses`` of a parametric layout; a drawn shaft's,
    ``fe_crank.cad.whole.cad_throw_masses``); ``torque_flow``: every journal carries its
    own torque (``torque_flow_loads``: the dynamics' journal torques, e.g. with the
    torsional stage's vibratory torque); ``overspeed``: dynamics results of the overspeed
    cycles (with counterweights)."""
    layout = sm.layout
    t = {}
    t0 = time.perf_counter()
    model, cases, t["cases"] = condensed_shaft(sm, material, options, torque_flow=torque_flow)
    t["condensation"] = time.perf_counter() - t0 - t["cases"]
    t0 = time.perf_counter()
    on, off = (shaft_cycle_of(cases, layout, mass, dynamics, counterweights=cw, laws=laws) for cw in (True, False))
    os_cycles = tuple(shaft_cycle_of(cases, layout, mass, d, laws=laws) for d in overspeed)
    bearings = bearing_state_of(cases, layout, dynamics, laws=laws, stated=(on, off))[0]
    t["cycle"] = time.perf_counter() - t0
    result = WholeShaftResult(
        crank_angle_deg=on.crank_angle_deg,
        speed=float(dynamics.speed),
        n_dof=sm.n_dof,
        bearings=bearings,
        webs=tuple(WebResult(a, b) for a, b in zip(on.webs, off.webs)),
        support_model=support_text(layout),
        cycles=(on, off),
        overspeed=os_cycles,
        timings={**t, **{f"condensation.{k}": v for k, v in model.timings.items()}},
    )
    return result, cases
