"""The whole shaft's frames and web moments against statics the test does itself.

One throw on its two bearings is statically determinate, so its bearing loads and web
moments follow from statics alone.  The references are computed here from the dynamics
stage's engine-frame quantities (each throw's crank direction gamma, ``angle_global``:
throw frame x -> (cos gamma, -sin gamma), y -> (sin gamma, cos gamma); its pin force;
its simply supported bearing split) and the exact mass properties of the throw's solid
(``geometry.mass``, B-rep integrals), the lever from the geometry's own web mid-plane
(crankpin length and web thickness), never from the model's results.  The throw stands
at 90 deg and at 37 deg (a throw at 0 deg hides a missing offset of the reference
throw: its frame is the shaft's) and at 37 deg on a shaft turning the other way (a throw
away from 0 and 180 deg there shows a lost sense of rotation), at 3000 and 4000 rpm
(centrifugal loads that count).  The tolerance, 2e-3 of the loads' size, is the FE
mesh's centrifugal resultant against the exact solid's (measured 2e-4); a frame turned by
the throw's angle, a lost sense, a counterweight left in or a lever from another plane
changes the result by tens of per cent.
"""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers.shaft import Steel, small_engine, small_geometry

from fe_crank import model
from fe_crank.fe.shaft.cases import solve_cases
from fe_crank.fe.shaft.whole_shaft import condensed_shaft, shaft_cycle_of
from fe_crank.geometry.mass import mass_properties
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.geometry.spec import EndLoad
from fe_crank.mechanism.dynamics import analyse
from fe_crank.mesh.shaft import mesh_shaft

RPM = 2 * np.pi / 60
CASES = [(90.0, 1), (37.0, -1)]


#: a pulley in front (unbalance and a belt pull) and a flywheel behind (unbalance), both
#: overhung beyond the end journals
ENDS = (
    EndLoad("pulley", "front", 1.5, 0.035, 2e-4, np.deg2rad(-60.0), 1200.0, np.deg2rad(100.0)),
    EndLoad("flywheel", "rear", 12.0, 0.04, 1e-4, np.deg2rad(30.0)),
)


@pytest.fixture(scope="module")
def shafts(mesh_cache):
    """(angle in deg, sense) -> one throw at that angle with ``ENDS``: one mesh for every
    angle (its cache key ignores the angle), condensed once in its own frame for all of
    them (``build_shaft_model``'s ``condensed``), each shaft placing it at its angle and in
    its sense."""
    built: dict = {}
    condensed: dict = {}

    def get(angle_deg: float, sense: int):
        if (angle_deg, sense) not in built:
            angle = np.deg2rad(angle_deg)
            g = small_geometry([angle])
            g = dataclasses.replace(g, shaft=dataclasses.replace(g.shaft, end_loads=ENDS))
            e = small_engine([angle], sense=sense)
            layout = shaft_layout(g, e, geometry_file="g.toml", engine_file="e.toml")
            assert layout.sense == sense and layout.end_loads == ENDS
            _, cases, _ = condensed_shaft(
                mesh_shaft(layout, size="test", cache_dir=mesh_cache), Steel(), condensed=condensed
            )
            mass = {t.name: mass_properties(layout.geometry, t.spec) for t in layout.throws}
            built[angle_deg, sense] = (layout, cases, mass, e)
        return built[angle_deg, sense]

    return get


@pytest.fixture(scope="module", params=CASES, ids=[f"{a:g}deg-sense{s:+d}" for a, s in CASES])
def one_throw(request, shafts):
    """The throw without its pulley and flywheel (their cases weighted zero)."""
    layout, cases, mass, e = shafts(*request.param)
    return dataclasses.replace(layout, end_loads=()), cases, mass, e


def _engine_frame(v, gamma):
    """Throw-frame vectors (n, 2) or (2,) at crank directions gamma (n,) -> engine frame."""
    v = np.broadcast_to(np.asarray(v, float), (gamma.size, 2))
    ex = np.stack([np.cos(gamma), -np.sin(gamma)], axis=-1)
    ey = np.stack([np.sin(gamma), np.cos(gamma)], axis=-1)
    return v[:, :1] * ex + v[:, 1:] * ey


def _cross_z(lever, F):
    """(z - z_w) e_z x F: the moment about the section centre of a radial force F at z."""
    return lever * np.stack([-F[..., 1], F[..., 0]], axis=-1)


def test_bearing_loads_add_up_to_the_engine_frame_loads(one_throw):
    """At every angle the two bearings carry the pin force (the dynamics stage's, in the
    engine frame: its bearing split less the rotating mass's share) plus the throw's
    centrifugal force omega^2 U, U the solid's unbalance turned to gamma."""
    layout, cases, mass, e = one_throw
    speed = 4000 * RPM
    dyn = analyse(e, model.OperatingPoint(speed=speed))
    res = shaft_cycle_of(cases, layout, mass, dyn)
    tl, et = dyn.throws["1"], e.throws[0]
    gamma = np.asarray(tl.angle_global)
    rot = _engine_frame([0.0, et.rotating_mass * et.crank_radius * speed**2], gamma)
    pins = tl.bearing_front + tl.bearing_rear - rot
    assert np.allclose(pins, _engine_frame(tl.pin_force, gamma), atol=1e-9 * np.abs(pins).max())
    cf = _engine_frame(speed**2 * np.asarray(mass["1"].total.unbalance_vector), gamma)
    expect = pins + cf
    total = sum(b.load_n for b in res.bearings)
    scale = np.abs(expect).max()
    assert np.abs(cf).max() > 0.05 * scale  # the centrifugal part counts
    assert np.abs(total - expect).max() < 2e-3 * scale


def _centrifugal_only(dyn):
    zero = {k: dataclasses.replace(t, pin_force=np.zeros_like(t.pin_force)) for k, t in dyn.throws.items()}
    return dataclasses.replace(dyn, throws=zero)


@pytest.mark.parametrize("counterweights", [True, False], ids=["with", "without"])
def test_web_moments_under_centrifugal_loads_are_the_beams(one_throw, counterweights):
    """Centrifugal loads alone at 3000 rpm: each part p of the throw's solid pulls with
    omega^2 U_p at its centroid (the counterweights' only with them), the bearings react
    by the lever rule, and the bending moment at a web's mid-plane (z_w from the crankpin
    length and the web thickness) is the moment of everything in front of it: the front
    bearing's reaction, the parts wholly in front, and of each prism cut by the plane
    (web, counterweight) the share in front at the middle of that share."""
    layout, cases, mass, e = one_throw
    speed = 3000 * RPM
    dyn = _centrifugal_only(analyse(e, model.OperatingPoint(speed=speed)))
    res = shaft_cycle_of(cases, layout, mass, dyn, counterweights=counterweights)
    g, th = layout.geometry, layout.throws[0]
    gamma = np.asarray(dyn.throws["1"].angle_global)
    zp, t = g.crankpin_length / 2, g.web_thickness
    span = {"web_1": (-zp - t, -zp), "web_2": (zp, zp + t)}
    for cw in th.spec.counterweights:
        span[f"counterweight_{cw.web}"] = (
            (-zp - t, -zp - t + cw.thickness) if cw.web == 1 else (zp + t - cw.thickness, zp + t)
        )
    parts = []  # (z0, z1, force (n, 2) engine frame), z0 == z1 at a centroid
    for name, p in mass["1"].parts.items():
        if name.startswith("counterweight") and not counterweights:
            continue
        F = _engine_frame(speed**2 * np.asarray(p.unbalance_vector), gamma)
        z0, z1 = span.get(name, (p.centroid[2], p.centroid[2]))
        parts.append((th.z + z0, th.z + z1, th.z + p.centroid[2], F))
    a, b = layout.bearings
    RA = -sum(F * (b.z - zc) / (b.z - a.z) for _, _, zc, F in parts)
    webs = {(w.throw, w.web): w for w in res.webs}
    for web, zw in ((1, th.z - zp - t / 2), (2, th.z + zp + t / 2)):
        terms = [_cross_z(a.z - zw, RA)]
        for z0, z1, _, F in parts:
            if z1 > z0:  # a prism along z: its share in front of the plane
                hi = min(z1, zw)
                if hi > z0:
                    terms.append(_cross_z(0.5 * (z0 + hi) - zw, F * (hi - z0) / (z1 - z0)))
            elif z0 < zw:
                terms.append(_cross_z(z0 - zw, F))
        M = sum(terms)
        got = webs[("1", web)].bending_moment_nm
        scale = sum(np.abs(x).max() for x in terms)  # the terms' size, the sum may nearly cancel
        assert scale > 1.0  # N m: loads that count
        assert np.abs(got - M).max() < 2e-3 * scale, (web, np.abs(got - M).max() / scale)


@pytest.fixture(scope="module")
def overhung(shafts):
    """One throw at 37 deg, turning the other way, with ``ENDS``."""
    return shafts(37.0, -1)


def test_overhung_pulley_and_flywheel_load_the_bearings_by_the_lever_rule(overhung):
    """What the pulley and the flywheel add at 3000 rpm: their centrifugal forces
    omega^2 m e (turning with the crank: at gamma + sense x unbalance_angle in the engine
    frame) and the belt pull (fixed, direction belt_angle), at their centre planes beyond
    the end faces; one throw on two bearings takes them by the lever rule, an overhung
    load pressing its near bearing by (z_B - z)/(z_B - z_A) > 1 and lifting the far one;
    the web moments change by the moments of the pulley's load and of the front bearing's
    change about the webs' mid-planes."""
    layout, cases, mass, e = overhung
    speed = 3000 * RPM
    dyn = analyse(e, model.OperatingPoint(speed=speed))
    on = shaft_cycle_of(cases, layout, mass, dyn)
    off = shaft_cycle_of(cases, dataclasses.replace(layout, end_loads=()), mass, dyn)
    gamma = np.asarray(dyn.throws["1"].angle_global)
    sense = layout.sense
    zf, zr = layout.journals[0].z0, layout.journals[-1].z1
    forces = []
    for ld, z in ((layout.end_loads[0], zf - 0.035), (layout.end_loads[1], zr + 0.04)):
        u = gamma + sense * ld.unbalance_angle
        F = speed**2 * ld.mass * ld.eccentricity * np.stack([np.sin(u), np.cos(u)], axis=-1)
        F = F + ld.belt_pull * np.array([np.sin(ld.belt_angle), np.cos(ld.belt_angle)])
        forces.append((z, F))
    a, b = layout.bearings
    dA = sum(F * (b.z - z) / (b.z - a.z) for z, F in forces)
    dB = sum(F * (z - a.z) / (b.z - a.z) for z, F in forces)
    scale = max(np.abs(F).max() for _, F in forces)
    assert scale > 1000.0
    assert np.abs(on.bearings[0].load_n - off.bearings[0].load_n - dA).max() < 1e-8 * scale
    assert np.abs(on.bearings[1].load_n - off.bearings[1].load_n - dB).max() < 1e-8 * scale
    g, th = layout.geometry, layout.throws[0]
    zp, t = g.crankpin_length / 2, g.web_thickness
    webs_on = {w.web: w.bending_moment_nm for w in on.webs}
    webs_off = {w.web: w.bending_moment_nm for w in off.webs}
    zP, FP = forces[0]
    for web, zw in ((1, th.z - zp - t / 2), (2, th.z + zp + t / 2)):
        expect = _cross_z(zP - zw, FP) + _cross_z(a.z - zw, -dA)
        got = webs_on[web] - webs_off[web]
        assert np.abs(got - expect).max() < 1e-8 * np.abs(expect).max()


def test_every_journal_carries_its_own_torque_turning_the_other_way(overhung):
    """The torque-flow cases on the shaft turning the other way: with a journal torque
    entering at the front (T_f, as a driven pulley's) and the throw's own inertia torque
    under vibration (T_r - T_f - T_own, any function of the angle), the moment about the
    axis of the forces the neighbours exert on the throw is -sense T_f on its front face
    and sense T_r on its rear face (a torque T acts about -sense z), at every angle."""
    from fe_crank.fe.shaft.whole_shaft import end_load_cases, torque_flow_cases

    layout, cases0, mass, e = overhung
    shaft = cases0.model
    cases = solve_cases(shaft, {**torque_flow_cases(shaft), **end_load_cases(shaft)})
    dyn = analyse(e, model.OperatingPoint(speed=1500 * RPM))
    tl = dyn.throws["1"]
    th = np.asarray(dyn.theta)
    front = 40.0 + 25.0 * np.sin(2 * th)
    rear = front + np.asarray(tl.torque) + 15.0 * np.cos(3 * th + 0.4)
    dyn = dataclasses.replace(dyn, throws={"1": dataclasses.replace(tl, torque_front=front, torque_rear=rear)})
    W = shaft_cycle_of(cases, layout, mass, dyn).weights
    k = next(i for i, pp in enumerate(shaft.pieces) if pp.kind == "throw")
    c = shaft.pieces[k].cond
    f = c.S @ (cases.V[k] @ W.T) - c.g @ (cases.coef[k] @ W.T)  # forces of the neighbours on the throw
    x = c.basis.doflocs
    n1 = 3 * c.faces["end_1"].size
    assert layout.sense == -1
    for face, rows, torque, sign in (("end_1", slice(0, n1), front, -1.0), ("end_2", slice(n1, None), rear, 1.0)):
        nodes = c.faces[face]
        ff = f[rows].reshape(nodes.size, 3, -1)
        mz = np.einsum("n,nk->k", x[0, nodes], ff[:, 1]) - np.einsum("n,nk->k", x[1, nodes], ff[:, 0])
        np.testing.assert_allclose(mz, sign * layout.sense * torque, rtol=0, atol=2e-5 * np.abs(rear).max())
