"""The whole-shaft model of real throws: equilibrium, symmetry and the counterweights by statics.

Small shafts (tests/data/geometry_small_shaft.toml at the ``test`` mesh size) under the
inertia loads of small engines (``tests/helpers/shaft.py``).  Independent references:
the pin forces of the dynamics stage and the exact mass properties of the throws'
solids (``geometry.mass``, B-rep integrals), never the model's own numbers.
"""

from __future__ import annotations

import numpy as np
import pytest
from helpers.shaft import Steel, small_engine, small_geometry

from fe_crank import model
from fe_crank.fe.shaft.cases import solve_cases
from fe_crank.fe.shaft.cycle import ThrowCycleLoad, shaft_cycle
from fe_crank.fe.shaft.model import build_shaft_model
from fe_crank.geometry.mass import mass_properties
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.mechanism.dynamics import analyse
from fe_crank.mesh.shaft import mesh_shaft, rotation

SPEED = 4000 * 2 * np.pi / 60


def _run(angles, mesh_cache, condensed, *, counterweights=True, min_sectors=1):
    """The shaft of throws at ``angles`` with its unit cases; a throw mesh another of this
    module's shafts has is condensed once for both (``condensed``)."""
    g = small_geometry(angles, counterweights)
    e = small_engine(angles)
    layout = shaft_layout(g, e, geometry_file="g.toml", engine_file="e.toml")
    sm = mesh_shaft(layout, size="test", cache_dir=mesh_cache, min_sectors=min_sectors)
    cases = solve_cases(build_shaft_model(sm, Steel(), condensed=condensed))
    dyn = analyse(e, model.OperatingPoint(speed=SPEED))
    mass = {t.name: mass_properties(layout.geometry, t.spec) for t in layout.throws}
    loads = tuple(ThrowCycleLoad(t.name, dyn.throws[t.name].pin_force) for t in layout.throws)
    psi = dyn.throws["1"].angle_global - layout.sense * layout.throws[0].angle
    return layout, cases, dyn, mass, loads, psi


@pytest.fixture(scope="module")
def condensed() -> dict:
    """The throw condensations this module's shafts share (``build_shaft_model``)."""
    return {}


@pytest.fixture(scope="module")
def twin(mesh_cache, condensed):
    return _run([0.0, np.pi / 2], mesh_cache, condensed)


def _engine(v, psi):
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([c * v[..., 0] + s * v[..., 1], -s * v[..., 0] + c * v[..., 1]], axis=-1)


def test_bearing_loads_balance_the_pin_forces_and_the_centrifugal_force(twin):
    """At every angle the loads on the bearings add up to the pin forces plus the shaft's
    centrifugal force m e omega^2 (the exact mass properties of the solids)."""
    layout, cases, dyn, mass, loads, psi = twin
    res = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass)
    total = sum(b.load_n for b in res.bearings)
    # the pin forces in the engine frame as the dynamics stage itself turns them: its
    # simply supported bearing split carries pin force + rotating mass x R omega^2
    pins = 0.0
    for t, et in zip(layout.throws, small_engine([0.0, np.pi / 2]).throws):
        tl = dyn.throws[t.name]
        gamma = tl.angle_global
        rot = et.rotating_mass * et.crank_radius * SPEED**2 * np.stack([np.sin(gamma), np.cos(gamma)], axis=-1)
        pins = pins + tl.bearing_front + tl.bearing_rear - rot
    me = sum(rotation(t.angle)[:2, :2] @ np.asarray(mass[t.name].total.unbalance_vector) for t in layout.throws)
    centrifugal = _engine(np.broadcast_to(SPEED**2 * me, pins.shape), psi)
    assert (
        np.linalg.norm(me) > 0.01 * sum(mass[t.name].total.mass for t in layout.throws) * layout.geometry.crank_radius
    )
    scale = np.abs(centrifugal).max() + np.abs(pins).max()
    assert np.abs(total - pins - centrifugal).max() < 2e-3 * scale


@pytest.fixture(scope="module")
def flat4(mesh_cache, condensed):
    """0/180/180/0 deg with its throws' end faces split into four sectors, as ``twin``'s
    (two would join them): the same throw mesh as ``twin``'s, condensed once for both.
    The claims on it are symmetry, statics and the bearing laws; none depends on how the
    interface between the pieces is split."""
    return _run([0.0, np.pi, np.pi, 0.0], mesh_cache, condensed, min_sectors=4)


def test_a_mirror_symmetric_shaft_has_mirror_symmetric_bearing_loads(flat4):
    """0/180/180/0 deg is its own mirror image across z = 0: under a load that is too
    (the centrifugal forces alone, no pin force) bearing j carries what bearing 6 - j does."""
    layout, cases, dyn, mass, loads, psi = flat4
    zero = tuple(ThrowCycleLoad(t.throw, np.zeros_like(t.pin_force)) for t in loads)
    res = shaft_cycle(cases, zero, dyn.theta, psi, SPEED, mass, counterweights=False)
    F = np.array([b.load_n for b in res.bearings])
    scale = np.abs(F).max()
    assert scale > 0
    assert np.allclose(F, F[::-1], atol=2e-3 * scale)


def test_springs_and_rigid_bearings_carry_the_same_total(twin):
    layout, cases, dyn, mass, loads, psi = twin
    from fe_crank.geometry.spec import BearingLaw

    rigid = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass)
    soft = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass, laws=[BearingLaw("spring", 2e8)] * 3)
    a = sum(b.load_n for b in rigid.bearings)
    b = sum(b.load_n for b in soft.bearings)
    assert np.allclose(a, b, atol=1e-9 * np.abs(a).max())
    assert not np.allclose(rigid.bearings[1].load_n, soft.bearings[1].load_n, atol=1e-3 * np.abs(a).max())


@pytest.fixture(scope="module")
def single(mesh_cache, condensed):
    return _run([0.0], mesh_cache, condensed)


def test_counterweights_change_the_bearing_loads_by_their_centrifugal_shares(single):
    """One throw on two bearings is statically determinate: switching the counterweights
    on adds to each bearing's load the counterweights' centrifugal forces omega^2 U
    (exact mass properties) in the shares of the lever rule, (z_B - z_cw) / (z_B - z_A)
    and (z_cw - z_A) / (z_B - z_A)."""
    layout, cases, dyn, mass, loads, psi = single
    on = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass, counterweights=True)
    off = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass, counterweights=False)
    (a, b), t = layout.bearings, layout.throws[0]
    expect = {a.name: 0.0, b.name: 0.0}
    for web in (1, 2):
        part = mass["1"].parts[f"counterweight_{web}"]
        z = t.z + part.centroid[2]
        force = _engine(np.broadcast_to(SPEED**2 * np.asarray(part.unbalance_vector), (psi.size, 2)), psi)
        expect[a.name] = expect[a.name] + force * (b.z - z) / (b.z - a.z)
        expect[b.name] = expect[b.name] + force * (z - a.z) / (b.z - a.z)
    for x, y in zip(on.bearings, off.bearings):
        change = x.load_n - y.load_n
        scale = np.abs(expect[x.name]).max()
        assert scale > 0
        assert np.abs(change - expect[x.name]).max() < 2e-3 * scale


def test_condensed_fields_equal_a_direct_solve_of_the_joined_mesh(twin):
    """The pieces' fields from the condensation (sum a_p L_p + X v) equal the solution of
    the joined whole-shaft mesh under the same self-equilibrated loads with the same six
    held dofs, at every recovery node: the condensation is exact."""
    import scipy.sparse as sp
    from scipy.spatial import cKDTree

    from fe_crank.fe.core.assembly import assemble_stiffness
    from fe_crank.fe.core.bases import cell_basis
    from fe_crank.fe.linalg.factorise import factorise
    from fe_crank.fe.shaft.patterns import end_patterns, surface_patterns, throw_patterns
    from fe_crank.mesh.shaft import node_maps

    layout, cases, dyn, mass, loads, psi = twin
    model = cases.model
    sm = model.mesh
    whole = sm.whole()
    maps = node_maps(sm, whole)
    basis = cell_basis(whole, 2)
    c = [cases.index("pin_-y@1"), cases.index("centrifugal_cw"), cases.index("2.x")]
    f = np.zeros((3 * basis.N, len(c)))
    for pp, piece, m in zip(model.pieces, sm.pieces, maps):
        b = cell_basis(sm.meshes[piece.mesh], 2)
        faces = ("end_1", "end_2")
        pats = (
            throw_patterns(b, 7850.0, np.deg2rad(60.0), faces) if pp.kind == "throw" else end_patterns(b, 7850.0, faces)
        )
        for s, _ in piece.bearing_surfaces:
            pats.update(surface_patterns(b, s)[0])
        P = np.column_stack([pats[n] for n in pp.cond.names])
        local = P @ cases.coef[pp.index][:, c]
        dofs = (3 * m[:, None] + np.arange(3)).ravel()
        np.add.at(f, dofs, pp.to_shaft(local))
    held_pts = model.points[:, cases.held // 3].T
    _, held_nodes = cKDTree(np.asarray(whole.doflocs).T).query(held_pts)
    held = 3 * held_nodes + cases.held % 3
    K = assemble_stiffness(basis, 210e9, 0.3).tolil()
    K[held, :] = 0.0
    K[:, held] = 0.0
    K[held, held] = 1.0
    f[held] = 0.0
    u = factorise(sp.csr_matrix(K), "auto").solve(f)
    for pp, m in zip(model.pieces, maps):
        if pp.kind != "throw":
            continue
        rec = pp.cond.rec_nodes
        mine = cases.recover(pp.index, np.eye(len(cases.names))[:, c])
        direct = pp.to_local(u[(3 * m[rec][:, None] + np.arange(3)).ravel()])
        assert np.abs(mine - direct).max() < 1e-8 * np.abs(direct).max()


def test_web_moment_of_a_throw_on_two_bearings_is_the_beams(single):
    """Pin force alone (centrifugal switched off by a vanishing speed): one throw on two
    bearings is a simply supported beam, so at the web centres M = R_A (z_w - z_A) and
    M = R_B (z_B - z_w), R_A = P (z_B - z_p) / (z_B - z_A), R_B = P - R_A."""
    layout, cases, dyn, mass, loads, psi = single
    res = shaft_cycle(cases, loads, dyn.theta, psi, 1e-6, mass)
    (a, b), t = layout.bearings, layout.throws[0]
    P = _engine(loads[0].pin_force, psi)  # throw "1" at 0 deg: its frame is the shaft's
    RA = P * (b.z - t.z) / (b.z - a.z)
    g = layout.geometry  # the web mid-planes from the geometry, not from the result
    mid = {1: t.z - g.crankpin_length / 2 - g.web_thickness / 2, 2: t.z + g.crankpin_length / 2 + g.web_thickness / 2}
    for w in res.webs:
        lever = (mid[1] - a.z) if w.web == 1 else (b.z - mid[2])
        R = RA if w.web == 1 else P - RA
        expect = lever * np.hypot(R[:, 0], R[:, 1])
        got = np.hypot(*w.bending_moment_nm.T)
        assert np.allclose(got, expect, atol=1e-6 * expect.max())


@pytest.mark.parametrize("c", [5e-6, 20e-6, 40e-6])
def test_every_bearing_in_clearance_solves_at_every_angle(flat4, c):
    """Five bearings, every one with a clearance (inertia loads of a four-throw engine at
    4000 rpm, contact stiffness 2e9 N/m): at every angle the bearings carry the same total
    as rigid ones (statics) and each journal's force is k (|d| - c)_+ along its displacement
    (the law).  At 20 and 40 um there are angles where a single journal touches (the
    shaft's loads balanced about it, the others free inside their circles)."""
    from fe_crank.geometry.spec import BearingLaw

    layout, cases, dyn, mass, loads, psi = flat4
    k = 2e9
    rigid = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass)
    res = shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass, laws=[BearingLaw("clearance", k, c)] * 5)
    total = sum(b.load_n for b in rigid.bearings)
    scale = np.abs(total).max()
    assert np.abs(sum(b.load_n for b in res.bearings) - total).max() < 1e-9 * scale
    d = _engine(res.displacement, psi[:, None])
    F = np.stack([b.load_n for b in res.bearings], axis=1)
    r = np.hypot(d[..., 0], d[..., 1])
    assert np.allclose(np.hypot(F[..., 0], F[..., 1]), k * np.maximum(r - c, 0.0), atol=1e-8 * scale)
    assert np.abs(F[..., 0] * d[..., 1] - F[..., 1] * d[..., 0]).max() < 1e-8 * scale * r.max()
    assert np.all(np.einsum("nbi,nbi->nb", F, d) >= -1e-8 * scale * r.max())
    if c > 10e-6:  # angles where one journal alone touches: the shaft free to tilt about it
        assert np.any((r > c).sum(axis=1) == 1)


def test_main_bearing_loads_are_the_envelope_over_the_stiffness_range(twin):
    """bearings_of: per bearing the largest peak of the stated law (rigid) and springs of
    3e8, 9.5e8 and 3e9 N/m (the default range, its geometric mean between), each law
    computed here on its own; the governing law is named with the loads, which are that
    law's whole cycle (peak and specific load from them)."""
    from fe_crank.fe.shaft.whole_shaft import bearings_of
    from fe_crank.geometry.spec import BearingLaw

    layout, cases, dyn, mass, loads, psi = twin
    assert layout.stiffness_range == (3e8, 3e9)
    res = bearings_of(cases, layout, mass, dyn)
    laws = {"rigid": [BearingLaw()] * 3}
    for k in (3e8, np.sqrt(3e8 * 3e9), 3e9):
        laws[f"spring {k:.3g} N/m"] = [BearingLaw("spring", k)] * 3
    for cw in (True, False):
        runs = {
            name: shaft_cycle(cases, loads, dyn.theta, psi, SPEED, mass, counterweights=cw, laws=w)
            for name, w in laws.items()
        }
        for j, b in enumerate(res):
            got = b.with_counterweights if cw else b.without_counterweights
            peaks = {name: r.bearings[j].peak_n for name, r in runs.items()}
            best = max(peaks, key=peaks.get)
            assert got.law == best
            assert got.peak_n == pytest.approx(peaks[best], rel=1e-12)
            assert np.allclose(got.load_n, runs[best].bearings[j].load_n, rtol=0, atol=1e-9 * got.peak_n)
            assert got.specific_load_pa == pytest.approx(got.peak_n / (got.diameter * got.width), rel=1e-12)
    assert any(b.with_counterweights.law != "rigid" for b in res)  # the range governs somewhere
