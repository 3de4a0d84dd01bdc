"""The counterweight study (docs/study.md) on the small inline-4 of tests/data/small_shaft.toml
at the ``test`` mesh: its superposition against full whole-shaft solves of the geometry it
writes, its balance residual and the counterweights' share of the bearing loads against
m r sums computed here, and its refusals of bad input."""

from __future__ import annotations

import dataclasses
import json
import math
import tomllib
from pathlib import Path

import numpy as np
import pytest
from helpers.bolted_study import bolted_case
from helpers.cw_peak import brute_peak, counterweight_peak
from skfem import Basis, ElementTetP2, Functional

from fe_crank.assess.loads import FIRING
from fe_crank.assess.oil_film import film_sweep
from fe_crank.assess.shaft import BearingState, assess_shaft_throws, piece_unit_stresses
from fe_crank.assess.throw import throw_joints
from fe_crank.balance.mechanism import rotating_mass
from fe_crank.cli import main
from fe_crank.fe.throw.node_groups import group_kind
from fe_crank.geometry.oil import FilmSpec
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.study.bodies import candidate_bodies
from fe_crank.study.candidates import Candidate, ThrowSolidCache, web_shape, written_mass
from fe_crank.study.film import film_metrics
from fe_crank.study.joints import candidate_counterweights, candidate_joints
from fe_crank.study.outputs import to_toml, write_candidate
from fe_crank.study.run import recommend, run_study
from fe_crank.study.screen import (
    COUNTERWEIGHT_KINDS,
    SHAFT_KINDS,
    EngineState,
    candidate_loads,
    candidate_overspeed,
    candidate_stresses,
    state_base,
)
from fe_crank.study.spec import JOINT_LIMITS, parse_study
from fe_crank.torsion.loads import assessed_loads

DATA = Path(__file__).resolve().parents[1] / "data"
CASE = DATA / "small_shaft.toml"
STUDY = """
[study]
name = "small inline-4"
rotating_rate_percent = [0, 50, 100]
envelope = "45 mm"
[study.limits]
max_main_bearing_load = "20 kN"
min_fillet_static_safety = 1.0
min_overspeed_safety = 1.0
[[study.placements]]
name = "8"
webs = "all"
[[study.placements]]
name = "4"
webs = ["1.1", "2.2", "3.1", "4.2"]
[[study.placements]]
name = "4 twisted"
webs = ["1.1", "2.2", "3.2", "4.1"]
"""


@pytest.fixture(scope="module")
def study(tmp_path_factory, mesh_cache):
    d = tmp_path_factory.mktemp("study")
    (d / "study.toml").write_text(STUDY)
    lc = load_loadcase(bolted_case(d))
    cache = mesh_cache  # the run's meshes: the bolted inline-4's are test_study_torsion's too
    res = run_study(lc, parse_study(d / "study.toml"), size="test", cache_dir=cache)
    return res, d, cache


def _written_path(res, folder: Path) -> Path:
    """The load case the study writes with every drawn counterweight at mass factor 1 (the
    drawn shapes, the same meshes), UR M53's Q with the quasi-static journal torque and the
    joint criteria judged with limits low enough to pass (its check's values are compared)."""
    drawn = res.drawn
    shapes = tuple(
        web_shape(w, 1.0, drawn[w], res.shaft.layout, res.spec, res.shaft.layout.geometry.density) for w in drawn
    )
    cand = Candidate(99, "all at 1", math.nan, 0.0, 0.0, dict.fromkeys(drawn, 1.0), shapes)
    _, lc_path = write_candidate(res, dataclasses.replace(res.results[0], candidate=cand), folder)
    data = tomllib.loads(lc_path.read_text())
    data["criteria"]["min_m53_acceptability"] = 1.0
    data["criteria"]["m53_quasi_static_torque"] = True
    for key in JOINT_LIMITS:  # judged, not limiting: the check's values are compared
        data["criteria"][key] = 1.0 if key.startswith("max_") else 0.01
    lc_path.write_text(to_toml(data))
    return lc_path


@pytest.fixture(scope="module")
def written_check(study):
    """The check of the load case the study writes with every drawn counterweight at mass
    factor 1 (``_written_path``): the outputs of every stage ``fe-crank check`` runs
    (``test`` mesh, the study's cached meshes; no pictures, no .vtu fields) and its
    whole-shaft stage with its unit cases (``helpers.check_shaft``)."""
    from helpers.check_shaft import stage_outputs_with_shaft

    res, d, cache = study
    lc_path = _written_path(res, d / "written")
    checked, ws = stage_outputs_with_shaft(lc_path, cache)
    assert ws is not None and ws.cases is not None
    return lc_path, checked, ws


@pytest.fixture(scope="module")
def full_solve(written_check):
    """A full whole-shaft solve (same mesh) of the geometry the study writes for every drawn
    counterweight at mass factor 1 (the drawn geometry): its result and unit cases.  The
    check's whole-shaft stage of the written load case (``written_check``): the shaft
    meshed from the written geometry file and solved over the operating cycle (the study's
    first state) with its overspeed cycle, with and without counterweights; the criteria
    the written case states do not enter it."""
    _, _, ws = written_check
    return ws.result, ws.cases


def _u(psi):
    return np.stack([np.sin(psi), np.cos(psi)], axis=-1)


@pytest.mark.heavy
def test_superposition_equals_a_full_solve_of_the_geometry_it_writes(study, full_solve):
    """Every drawn counterweight at mass factor 1: the candidate's geometry file is the
    drawn one; a full whole-shaft solve of it (same mesh) gives the same bearing loads and
    web moments to 1e-9, its cycle without counterweights the factor-0 candidate's, and,
    the bearings rigid (linear), a factor k the line between the two."""
    res, d, cache = study
    drawn = res.drawn
    ones = dict.fromkeys(drawn, 1.0)
    shapes = tuple(
        web_shape(w, 1.0, drawn[w], res.shaft.layout, res.spec, res.shaft.layout.geometry.density) for w in drawn
    )
    cand = Candidate(99, "all at 1", math.nan, 0.0, 0.0, ones, shapes)
    wm = written_mass(res.shaft.layout, cand, drawn, res.shaft.mass, ThrowSolidCache(res.shaft.layout))
    assert all(abs(k - 1.0) <= 1e-12 for k in wm.load_factors.values())  # the written shaft is the drawn one
    full, _ = full_solve
    base = state_base(res.shaft, res.states[0])
    on = candidate_loads(res.shaft, base, ones, drawn)
    off = candidate_loads(res.shaft, base, dict.fromkeys(drawn, 0.0), drawn)
    # the stated bearing law's loads (the check's main-bearing criteria envelope them over a
    # stiffness range; the screening stays on the stated law, docs/study.md)
    ref_on = np.stack([b.load_n for b in full.cycles[0].bearings], axis=1)
    ref_off = np.stack([b.load_n for b in full.cycles[1].bearings], axis=1)
    scale = np.abs(ref_on).max()
    assert np.abs(on.bearings - ref_on).max() <= 1e-9 * scale
    assert np.abs(off.bearings - ref_off).max() <= 1e-9 * scale
    # the main-bearing criteria's envelope over the stiffness range: the check's per bearing
    env = np.hypot(on.bearing_sets[..., 0], on.bearing_sets[..., 1]).max(axis=1)  # (sets, nb)
    for j, b in enumerate(full.bearings):
        assert env[:, j].max() == pytest.approx(b.with_counterweights.peak_n, rel=1e-9)
    assert len(res.shaft.law_sets) == 4  # the stated law and three stiffnesses of the range
    # the oil film of hydrodynamic bearings: the check's film stage on the full solve's loads
    spec = FilmSpec(clearance=25e-6, viscosity=7e-3, groove="full", groove_width=3e-3)
    lay_f = dataclasses.replace(
        res.shaft.layout,
        bearings=tuple(
            dataclasses.replace(b, law=dataclasses.replace(b.law, film=spec)) for b in res.shaft.layout.bearings
        ),
    )
    mine = film_metrics(lay_f, [on])
    (st,) = film_sweep(lay_f, (BearingState(res.states[0].speed, FIRING, full.bearings),), full.crank_angle_deg)
    h = min(f.with_counterweights.judged_min_film_m for f in st.bearings)
    p = max(f.with_counterweights.peak_pressure_pa for f in st.bearings)
    assert mine is not None and mine.converged and h > 0
    assert mine.min_film == pytest.approx(h, rel=2e-3)  # the orbits' repeat tolerance, 1e-4 in eps
    assert mine.peak_pressure == pytest.approx(p, rel=2e-3)
    web_on = np.stack([w.with_counterweights.bending_moment_nm for w in full.webs], axis=1)
    web_off = np.stack([w.without_counterweights.bending_moment_nm for w in full.webs], axis=1)
    assert np.abs(on.webs - web_on).max() <= 1e-9 * np.abs(web_on).max()
    assert np.abs(off.webs - web_off).max() <= 1e-9 * np.abs(web_on).max()
    k = 0.37
    mid = candidate_loads(res.shaft, base, dict.fromkeys(drawn, k), drawn)
    assert np.abs(mid.bearings - (ref_off + k * (ref_on - ref_off))).max() <= 1e-9 * scale


@pytest.mark.heavy
def test_screened_stresses_equal_a_full_solve(study, full_solve):
    """Fillet and counterweight-junction stresses: the screening (``candidate_stresses``) of
    every drawn counterweight at factor 1 and 0, and at 0.37, against a full whole-shaft
    solve of the drawn geometry (same mesh): its cycles with and without counterweights
    (the latter the shaft with massless counterweights) and, the bearings rigid (linear),
    the history of 0.37 times the counterweights' density, (1 - k) off + k on at every
    angle; the largest von Mises over every node and angle to 1e-9, the static safety the
    yield strength over it; the least fatigue safety the check's own assessment of the full
    solve (``assess_shaft_throws``, every node evaluated), and at factor 1 the overspeed
    (``candidate_overspeed``) that assessment's with the full solve's overspeed cycle: the
    largest overspeed von Mises over every group, the least overspeed safety and the
    counterweight groups' largest."""
    res, _, _ = study
    full, cases = full_solve
    mat = res.loadcase.material
    base = state_base(res.shaft, res.states[0])
    g = res.shaft.layout.geometry
    add = m53_basis(res.loadcase.engine, mat, None).additional
    dia = (g.crankpin_diameter, g.journal_diameter)
    on_w, off_w = full.cycles[0].weights, full.cycles[1].weights
    by_piece = {i: piece_unit_stresses(cases, i, mat) for i, pp in enumerate(cases.model.pieces) if pp.kind == "throw"}
    units = list(by_piece.values())
    for k, W in ((1.0, on_w), (0.0, off_w), (0.37, (1 - 0.37) * off_w + 0.37 * on_w)):
        loads = candidate_loads(res.shaft, base, dict.fromkeys(res.drawn, k), res.drawn)
        st = candidate_stresses(res.shaft, [loads], mat, additional_bending=add, diameters=dia)
        ref = brute_peak(units, W, SHAFT_KINDS)
        assert st.shaft_peak == pytest.approx(ref, rel=1e-9)
        assert st.static_safety == pytest.approx(mat.yield_strength / ref, rel=1e-9)
        ref_cw = brute_peak(units, W, COUNTERWEIGHT_KINDS)
        assert st.counterweight_peak == pytest.approx(ref_cw, rel=1e-9)
        if k != 1.0:
            continue
        result = dataclasses.replace(full, cycles=(full.cycles[0 if k == 1.0 else 1],))
        throws, _ = assess_shaft_throws(
            cases,
            result,
            res.states[0].dynamics.theta,
            mat,
            crank_radius=g.crank_radius,
            overspeed=res.loadcase.operating.overspeed,
            diameters={t.name: dia for t in res.shaft.layout.throws},
            additional_bending=add,
            units=by_piece,  # the unit stresses above, not taken twice
        )
        least = min(
            gr.fatigue_safety.value
            for t in throws
            for gr in t.groups
            if gr.fatigue_safety is not None and group_kind(gr.group) in SHAFT_KINDS
        )
        assert st.fatigue_safety == pytest.approx(least, rel=1e-9)
        # the overspeed: the same assessment's overspeed peaks and safety (its overspeed cycle)
        assert full.overspeed
        cyc = engine_cycles(res.loadcase.engine, res.loadcase.operating).overspeed
        os_loads = [
            candidate_loads(
                res.shaft,
                state_base(res.shaft, EngineState("overspeed", c.dynamics.speed, c.dynamics)),
                dict.fromkeys(res.drawn, 1.0),
                res.drawn,
                envelope=False,
            )
            for c in cyc
        ]
        os = candidate_overspeed(res.shaft, os_loads, mat)
        groups = [gr for t in throws for gr in t.groups]
        cw = (gr.max_von_mises_overspeed.value for gr in groups if group_kind(gr.group) in COUNTERWEIGHT_KINDS)
        assert os is not None
        assert os.peak == pytest.approx(max(gr.max_von_mises_overspeed.value for gr in groups), rel=1e-9)
        assert os.safety == pytest.approx(min(gr.overspeed_safety for gr in groups), rel=1e-9)
        assert os.counterweight_peak == pytest.approx(max(cw), rel=1e-9)
    assert all(r.overspeed is not None and r.overspeed.safety > 0 for r in res.results)


@pytest.mark.heavy
def test_balance_residual_of_every_candidate_against_m_r_sums(study):
    """First-order free force and couple: the throws' rotating m_rot R and the written
    shaft's counterweight m r per web (its solids' m r, at the plane of their first
    moment) as vectors turning with their throws, summed here; the flat-4's first-order
    reciprocating force and couple cancel."""
    res, _, _ = study
    lc = res.loadcase
    w = res.residual_speed
    scale = sum(rotating_mass(lc.engine, t.name) * t.crank_radius for t in lc.engine.throws) * w**2
    for r in res.results:
        F, M = 0j, 0j
        for t in lc.engine.throws:
            e = np.exp(1j * t.angle)
            F += rotating_mass(lc.engine, t.name) * t.crank_radius * e
            M += rotating_mass(lc.engine, t.name) * t.crank_radius * t.axial_position * e
        wm = r.written  # the written shaft's m r per web and its plane
        for web, k in wm.load_factors.items():
            dw = res.drawn[web]
            e = np.exp(1j * lc.engine.throw(web[0]).angle)
            F -= k * dw.unbalance * e
            M -= k * dw.unbalance * wm.planes[web] * e
        assert r.free_force == pytest.approx(abs(F) * w**2, rel=1e-9, abs=1e-9 * scale)
        assert r.free_moment == pytest.approx(abs(M) * w**2, rel=1e-9, abs=1e-9 * scale * 0.1)
    # one web per throw: each throw's counterweight beside its pin makes a couple c U omega^2;
    # on webs 1.1, 2.2, 3.1, 4.2 the four cancel, on 1.1, 2.2, 3.2, 4.1 they add up
    for r in res.results:
        if r.candidate.rotating > 0 and r.candidate.placement != "8":
            assert (r.free_moment > 1e-6 * r.free_force + 1.0) == (r.candidate.placement == "4 twisted")


@pytest.mark.heavy
def test_counterweight_share_of_the_summed_bearing_loads_is_its_m_r_omega_squared(study):
    """One counterweight alone (web 1.1 at factor 1.6): the bearings' summed loads change
    by its centrifugal force, m r omega^2 opposite throw 1's pin at every angle, m r
    integrated here over the counterweight's elements of the mesh (and within the mesh's
    geometric error, 2e-3, of the solid's exact m r)."""
    res, _, _ = study
    base = state_base(res.shaft, res.states[0])
    web = ("1", 1)
    k = 1.6
    only = dict.fromkeys(res.drawn, 0.0) | {web: k}
    a = candidate_loads(res.shaft, base, only, res.drawn)
    b = candidate_loads(res.shaft, base, dict.fromkeys(res.drawn, 0.0), res.drawn)
    diff = (a.bearings - b.bearings).sum(axis=1)  # on the bearings = the added load
    pp = next(p for p in res.shaft.cases.model.pieces if p.kind == "throw" and p.throw == "1")
    basis = pp.cond.basis
    cw = np.asarray(basis.mesh.subdomains["counterweight_1"])
    sub = Basis(basis.mesh, ElementTetP2(), mapping=basis.mapping, quadrature=(basis.X, basis.W), elements=cw)
    rho = res.shaft.layout.geometry.density
    mr = np.hypot(Functional(lambda w: rho * w.x[0]).assemble(sub), Functional(lambda w: rho * w.x[1]).assemble(sub))
    w2 = res.states[0].speed ** 2
    psi = np.asarray(res.states[0].dynamics.throws["1"].angle_global)
    expect = -k * mr * w2 * _u(psi)
    assert np.abs(diff - expect).max() <= 1e-6 * k * mr * w2
    assert np.abs(np.hypot(*diff.T) - k * mr * w2).max() <= 1e-9 * k * mr * w2
    assert mr == pytest.approx(res.drawn[web].unbalance, rel=2e-3)


@pytest.mark.heavy
def test_table_plot_and_recommendation_written(study, tmp_path):
    from fe_crank.study.outputs import pareto_plot, write_tables

    res, _, _ = study
    paths = write_tables(res, tmp_path)
    pareto_plot(res, tmp_path / "p.png")
    assert (tmp_path / "p.png").stat().st_size > 0
    text = paths["csv"].read_text().splitlines()
    assert len(text) == 1 + len(res.results)  # every candidate, the ones that cannot be built too
    for col in (
        "fillet_static_safety",
        "fillet_fatigue_safety",
        "fillet_peak_von_mises_mpa",
        "overspeed_safety",
        "overspeed_peak_von_mises_mpa",
        "counterweight_overspeed_peak_mpa",
        "bolt_working_safety",
        "bolt_fatigue_safety",
        "bolt_separation_safety",
        "bolt_slip_safety",
    ):
        assert col in text[0].split(",")
    assert all(r.stresses is not None and r.stresses.fatigue_safety is not None for r in res.results)
    # the bolted joints: screened on every candidate with a counterweight, judged by VDI 2230's
    # usual limits (neither the study nor the load case names one); a thickness solved below
    # the bolt hole leaves no joint interface: the check's own refusal, reported as a miss
    assert res.joint_limits["min_bolt_slip_safety"] == 1.8
    assert all((r.joints is None) == (r.candidate.rotating == 0) for r in res.results)
    thin = next(r for r in res.results if r.candidate.placement == "8" and r.candidate.rotating == 0.5)
    assert thin.joints is not None and "smaller than its bolt hole" in (thin.joints.refused or "")
    assert not thin.meets_limits and any(f.startswith("bolted joint: throw") for f in thin.failed)
    assert f"#{thin.candidate.index} " in paths["md"].read_text()
    # the reason names the joint that rules out a candidate the rule would take
    best, why = recommend(tuple(r for r in res.results if r.candidate.rotating > 0), "least_mass")
    assert (
        best is not None
        and best.joints is not None
        and best.counterweight_mass == pytest.approx(thin.counterweight_mass, rel=1e-12)
    )
    assert f"#{thin.candidate.index} (" in why and "a bolted joint misses: bolted joint: throw" in why
    assert "bolted joints' least safeties" in why and best.joints.where["min_bolt_working_safety"] in why
    assert recommend((thin,), "least_mass")[1].endswith(
        f"a bolted joint fails on 1 of the buildable ones (#{thin.candidate.index}: {thin.failed[0]})"
    )
    doc = json.loads(paths["json"].read_text())
    assert doc["joint_limits"] == res.joint_limits
    ok_joint = next(c for c in doc["candidates"] if c["bolt_slip_safety"] is not None)
    assert set(ok_joint["bolt_where"]) == set(JOINT_LIMITS)
    assert res.recommended is not None and res.recommended.meets_limits
    ok = [r for r in res.results if r.meets_limits]
    assert res.recommended.counterweight_mass == min(r.counterweight_mass for r in ok)


BAD = [
    ("rotating_rate_percent = []", "study.rotating_rate_percent"),
    ("rotating_rate_percent = [50, 130]", "study.rotating_rate_percent[1]"),
    ("rotating_rate_percent = [-5]", "study.rotating_rate_percent[0]"),
    (
        'rotating_rate_percent = [50]\n[study.limits]\nmax_counterweight_mass = "-1 kg"',
        "study.limits.max_counterweight_mass",
    ),
    ('rotating_rate_percent = [50]\nenvelope = "30 mm"', "study.envelope"),
    (
        'rotating_rate_percent = [50]\n[study.limits]\nmin_fillet_fatigue_safety = "2"',
        "study.limits.min_fillet_fatigue_safety",
    ),
    (
        "rotating_rate_percent = [50]\n[study.limits]\nmin_fillet_static_safety = -1",
        "study.limits.min_fillet_static_safety",
    ),
    ('rotating_rate_percent = [50]\nstresses = "some"', "study.stresses"),
    (
        'rotating_rate_percent = [50]\nstresses = "static"\n[study.limits]\nmin_fillet_fatigue_safety = 2',
        "study.limits.min_fillet_fatigue_safety",
    ),
    ('rotating_rate_percent = [50]\noffset = ["100 deg"]', "study.offset[0]"),
    ('rotating_rate_percent = [50]\n[[study.placements]]\nname = "x"\nwebs = ["1.3"]', "study.placements[0].webs[0]"),
    ('rotating_rate_percent = [50]\n[[study.placements]]\nname = "x"\nwebs = ["1.1"]', "study.placements[0].webs"),
    # UR M53 2.2: the load case does not accept the quasi-static journal torque
    ("rotating_rate_percent = [50]\n[study.limits]\nmin_m53_acceptability = 1.2", "study.limits.min_m53_acceptability"),
    # the bolted joints' limits: plain positive numbers, a per-throw model, a bolted counterweight
    ('rotating_rate_percent = [50]\n[study.limits]\nmin_bolt_slip_safety = "2"', "study.limits.min_bolt_slip_safety"),
    (
        "rotating_rate_percent = [50]\n[study.limits]\nmin_bolt_working_safety = 0",
        "study.limits.min_bolt_working_safety",
    ),
    (
        'rotating_rate_percent = [50]\nstresses = "off"\n[study.limits]\nmin_bolt_fatigue_safety = 1.2',
        "study.limits.min_bolt_fatigue_safety",
    ),
    # small_shaft.toml's counterweights are not bolted
    (
        "rotating_rate_percent = [50]\n[study.limits]\nmin_bolt_separation_safety = 1",
        "study.limits.min_bolt_separation_safety",
    ),
]


@pytest.mark.parametrize("body, key", BAD)
def test_bad_study_input_is_one_message_with_file_and_key(tmp_path, capsys, body, key):
    f = tmp_path / "bad.toml"
    f.write_text("[study]\n" + body + "\n")
    rc = main(["study", str(CASE), str(f), "-o", str(tmp_path / "out"), "--cache-dir", str(tmp_path / "c")])
    err = capsys.readouterr().err
    assert rc == 2
    assert str(f) in err and key in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1
    assert not (tmp_path / "c").exists()  # refused before any meshing


@pytest.mark.heavy
def test_screened_mass_properties_are_the_written_shafts(study):
    """Candidate "4" at 50 % (angle and thickness solved on one web per throw, the other
    web's counterweight left out): the geometry the study writes, read back from its file,
    built and integrated here (``geometry.mass``, exact B-rep integrals): per throw the
    screened m r (sum of k_eff U_w over its webs) equals the written throw's total m r
    minus the drawn throw's without its counterweights, and the table's mass and polar
    inertia changes the written shaft's, to round-off."""
    from fe_crank.geometry.mass import mass_properties

    res, d, _ = study
    r = next(x for x in res.results if x.candidate.placement == "4" and x.candidate.rotating == 0.5)
    assert r.candidate.buildable and r.written is not None and r.written.exact
    _, lc_path = write_candidate(res, r, d / "written_4_50")
    g2 = load_loadcase(lc_path).geometry
    layout = res.shaft.layout
    dm = dj = 0.0
    for th in layout.throws:
        old = res.shaft.mass[th.name]
        new = mass_properties(g2, th.name)
        dm += new.total.mass - old.total.mass
        dj += new.total.inertia_axis - old.total.inertia_axis
        bare = np.asarray(old.total.unbalance_vector) - sum(
            np.asarray(res.drawn[(th.name, w)].unbalance_vector) for w in (1, 2) if (th.name, w) in res.drawn
        )
        want = np.asarray(new.total.unbalance_vector) - bare
        got = sum(
            k * np.asarray(res.drawn[w].unbalance_vector) for w, k in r.written.load_factors.items() if w[0] == th.name
        )
        assert np.abs(got - want).max() <= 1e-9 * np.abs(want).max()
    assert r.mass_change == pytest.approx(dm, rel=1e-9, abs=1e-12)
    assert r.polar_inertia_change == pytest.approx(dj, rel=1e-9, abs=1e-15)


@pytest.mark.heavy
def test_m53_q_counterweight_stress_and_joints_equal_the_checks_of_the_written_case(study, written_check, tmp_path):
    """The load case the study writes with every drawn counterweight at mass factor 1 (the
    drawn shapes, the same meshes).  UR M53's Q the study reports (computed once, the same
    on every candidate, ``study.m53``) equals the ``min_m53_acceptability`` of a full
    check (``test`` mesh; every stage ``fe-crank check`` runs, ``helpers.pipeline``, and
    its results.json) of it, quasi-static journal torque accepted, to 1e-9; so do the bolted joints' VDI 2230 figures the study screens for that candidate
    (``study.joints``: the worst assembly utilisation, working, fatigue, separation and
    slip safety over the joints and load states) and the check's joint criteria, limits
    set low enough to pass.  The counterweight groups' peak screened at factors 1 (``study.bodies``: the
    drawn per-throw model with the centrifugal case split per counterweight body) equals,
    to 1e-9, the largest von Mises over every counterweight node, angle and load state of
    the check's own per-throw model of that load case (its FE stage, ``pipeline.stages``:
    the whole centrifugal case; the same cached meshes), its stress histories superposed
    with the check's coefficients and evaluated at every node here (the check's
    ``max_counterweight_stress`` criterion needs a counterweight fillet, which this
    geometry does not draw)."""
    from helpers.pipeline import write_report

    from fe_crank.assess.superpose import cycle_coefficients
    from fe_crank.fe.throw.pin_patches import rod_loads
    from fe_crank.pipeline.options import CheckOptions

    res, _, _ = study
    q = res.results[0].m53
    assert q is not None
    assert {x.m53 for x in res.results} == {q}
    drawn = res.drawn
    shapes = tuple(
        web_shape(w, 1.0, drawn[w], res.shaft.layout, res.spec, res.shaft.layout.geometry.density) for w in drawn
    )
    cand = Candidate(99, "all at 1", math.nan, 0.0, 0.0, dict.fromkeys(drawn, 1.0), shapes)
    # the check's stages on it (``fe-crank check``'s calls, the same cache: ``written_check``)
    # and its results.json as the check writes it (figures only: no pictures, no .vtu fields)
    lc_path, checked, _ = written_check
    folder = tmp_path / "out" / "written"
    assert write_report(folder, checked, CheckOptions(render=False, write_vtu=False)).status == "pass"
    got = json.loads((folder / "results.json").read_text())
    crit = next(c for c in got["criteria"] if c["quantity"] == "m53_acceptability")
    assert q.acceptability == pytest.approx(crit["value"], rel=1e-9, abs=0.0)
    assert res.joint_model is not None
    solids = ThrowSolidCache(res.shaft.layout)  # each distinct throw solid built once, for both
    joints = candidate_joints(res.joint_model, cand, solids, res.shaft.mass)
    assert joints is not None and joints.refused is None and joints.joints == len(drawn)
    # the web's deformation onto the joint by the per-throw model's section (not the lever bound)
    jm = res.joint_model
    cws = candidate_counterweights(jm, cand, solids, res.shaft.mass)
    ts = jm.states[0]
    checks = throw_joints(
        jm.body.units[ts.throw],
        cws[ts.throw],
        ts.pin_force,
        ts.torque,
        omega=ts.omega,
        sense=ts.sense,
        overspeed=jm.overspeed,
        material=jm.material,
        joint_speed=ts.joint_speed,
        coeffs=ts.coeffs,
        rod_loads=ts.rods,
        overspeed_loads=ts.overspeed_loads,
    )
    assert len(checks) == 2 and all(j.loads.web_model.startswith("FE: sigma_yy") for j in checks)
    for key in JOINT_LIMITS:
        quantity = key.split("_", 1)[1]
        crit = next(c for c in got["criteria"] if c["quantity"] == quantity)
        assert joints.values[key] == pytest.approx(crit["value"], rel=1e-9, abs=0.0), key
    # the check's per-throw model of the written load case (its FE stage's unit solutions),
    # brute force over every node
    lc2 = load_loadcase(lc_path)
    solved = checked.unit_solutions
    assert solved
    loads = assessed_loads(lc2.engine, engine_cycles(lc2.engine, lc2.operating), reaction=lc2.fe.torque_reaction)
    ref = counterweight_peak(
        lc2,
        solved,
        loads.speeds,
        lambda unit, tc, state, sense, places: cycle_coefficients(
            unit, tc.pin_force, tc.torque_in, state.speed, sense=sense, rod_loads=rod_loads(tc, places)
        ),
    )
    assert res.body_model is not None
    screened = candidate_bodies(res.body_model, loads, dict.fromkeys(drawn, 1.0))
    assert screened.peak == pytest.approx(ref, rel=1e-9, abs=0.0)
    assert all(r.bodies is not None and r.bodies.peak > 0 for r in res.results)


def test_counterweight_stress_limit_needs_a_counterweight_fillet(tmp_path, capsys):
    """As the check's criterion: a sharp counterweight-web edge is a stress singularity, so
    the study's ``max_counterweight_stress`` is refused on the geometry's key, before meshing."""
    f = tmp_path / "s.toml"
    f.write_text('[study]\nrotating_rate_percent = [50]\n[study.limits]\nmax_counterweight_stress = "100 MPa"\n')
    rc = main(["study", str(CASE), str(f), "-o", str(tmp_path / "out"), "--cache-dir", str(tmp_path / "c")])
    err = capsys.readouterr().err
    assert rc == 2 and "counterweight.fillet_radius" in err and "max_counterweight_stress" in err
    assert len(err.strip().splitlines()) == 1 and "Traceback" not in err
    assert not (tmp_path / "c").exists()
