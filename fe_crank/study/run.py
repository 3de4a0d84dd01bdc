"""The counterweight study end to end: candidates, their screening on the whole shaft,
the table's numbers and the recommendation by the study's rule (docs/study.md)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import partial

import numpy as np

from fe_crank.balance.mechanism import rotating_mass
from fe_crank.errors import InputError
from fe_crank.fe.shaft.whole_shaft import throw_masses
from fe_crank.geometry.shaft import engine_shaft_layout, whole_shaft_wanted
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.geometry import require_counterweight_fillets
from fe_crank.io.loadcase import LoadCase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.rules.m53.basis import m53_basis
from fe_crank.study.bodies import BodyModel, BodyScreen, body_model, candidate_bodies
from fe_crank.study.candidates import (
    Candidate,
    DrawnWeb,
    ThrowSolidCache,
    WrittenMass,
    candidates,
    drawn_webs,
    first_order,
    residual,
    turned_view,
    written_mass,
)
from fe_crank.study.film import FilmMetrics, film_metrics_of, film_rows
from fe_crank.study.joints import LIMITS as JOINT_LIMITS
from fe_crank.study.joints import JointModel, JointScreen, candidate_joints, has_bolted, joint_limits, joint_model
from fe_crank.study.m53 import LIMIT as M53_LIMIT
from fe_crank.study.m53 import M53Screen, refusal, study_m53
from fe_crank.study.screen import (
    EngineState,
    OverspeedScreen,
    StressScreen,
    StudyShaft,
    candidate_loads,
    candidate_overspeed,
    candidate_stresses,
    engine_states,
    seed_references,
    state_base,
    study_shaft,
    with_operating_dynamics,
)
from fe_crank.study.spec import StudySpec
from fe_crank.study.torsion import ThrowStiffnessCache, screen_torsion
from fe_crank.torsion.loads import assessed_loads


@dataclass(frozen=True)
class CandidateResult:
    candidate: Candidate
    counterweight_mass: float  # kg, the shaft's counterweights together
    mass_change: float  # kg against the shaft as drawn
    polar_inertia_change: float  # kg m^2 against the shaft as drawn
    unbalance: float  # kg m, sum of the counterweights' m r
    rates: dict[str, float]  # throw -> counterweights' m r / rotating m r
    peak_bearing_load: float  # N, any bearing, state, angle
    peak_where: str
    peak_specific_load: float  # Pa
    bearing_peaks: dict[str, float]  # bearing -> N over every state
    bearing_means: dict[str, float]  # bearing -> N, the largest cycle mean over the states
    web_peaks: dict[str, float]  # web "<throw>.<web>" -> N m over every state
    max_web_moment: float  # N m, any web, state, angle
    web_where: str
    free_force: float  # N, first order at the highest speed
    free_moment: float  # N m
    failed: tuple[str, ...]  # limits not met (with the values)
    written: WrittenMass | None = None  # the written shaft's mass properties and load factors
    film: FilmMetrics | None = None  # the hydrodynamic bearings' film; None without one
    #: the shaft's fillet and counterweight-junction stresses over every state (``study.screen``)
    stresses: StressScreen | None = None
    #: the stresses over the overspeed cycles (``study.screen.candidate_overspeed``; None
    #: without an overspeed or with ``stresses = "off"``)
    overspeed: OverspeedScreen | None = None
    #: UR M53's least Q, the same for every candidate without [torsion] (``study.m53``)
    m53: M53Screen | None = None
    #: the per-throw model's counterweight groups (bodies, fillets, junctions) over every
    #: state (``study.bodies``; None with ``stresses = "off"``)
    bodies: BodyScreen | None = None
    #: the bolted counterweights' VDI 2230 figures over the check's load states
    #: (``study.joints``; None without a bolted counterweight or with ``stresses = "off"``)
    joints: JointScreen | None = None
    #: the first elastic natural frequency of the candidate's torsional chain, Hz
    #: (``study.torsion``; None without [torsion] or when not screened)
    torsional_frequency: float | None = None

    @property
    def meets_limits(self) -> bool:
        return self.candidate.buildable and not self.failed


@dataclass(frozen=True)
class StudyResult:
    spec: StudySpec
    loadcase: LoadCase
    shaft: StudyShaft
    drawn: dict
    states: tuple
    results: tuple[CandidateResult, ...]
    recommended: CandidateResult | None
    why: str
    residual_speed: float  # rad/s
    notes: tuple[str, ...] = field(default_factory=tuple)
    #: the per-throw model of the drawn geometry (``study.bodies``; None with ``stresses = "off"``)
    body_model: BodyModel | None = None
    #: the joint limits judged (``study.joints.joint_limits``), plain numbers; {} when not screened
    joint_limits: dict[str, float] = field(default_factory=dict)
    #: the bolted throws' load states (``study.joints``; None when the joints are not screened)
    joint_model: JointModel | None = None
    #: per screened offset (rad): the shaft with the drawn counterweights turned to it and its
    #: drawn webs (``study.candidates.turned_view``); ``shaft`` and ``drawn`` are the first's
    by_offset: dict[float, tuple[StudyShaft, dict[tuple, DrawnWeb]]] = field(default_factory=dict)


#: how the study's whole shaft takes a ``[torsion]`` section (the check's whole shaft's way)
TORSION_SHAFT = (
    "whole shaft with [torsion] as the check's: every journal carries its own torque in every state (the "
    "torque-flow cases), the operating speed's firing state with the journal torques of the candidate's own "
    "torsional stage"
)


def _layout(lc: LoadCase):
    g = lc.geometry
    if not isinstance(g, CrankGeometry) or lc.material is None or not whole_shaft_wanted(g, lc.engine):
        raise InputError(
            "the study needs a parametric geometry on a whole shaft (several throws, or a [shaft] section) "
            "and a [material]",
            file=lc.source_file,
            key="geometry",
        )
    return engine_shaft_layout(
        g, lc.engine, geometry_file=g.file or lc.source_file, engine_file=lc.engine_file or lc.source_file
    )


def prepare(lc: LoadCase, spec: StudySpec):
    """The candidates and the drawn webs, every input check done (before any meshing)."""
    layout = _layout(lc)
    mass = throw_masses(layout)
    drawn = drawn_webs(layout, mass)
    if not drawn:
        raise InputError(
            "the geometry draws no counterweight: the study scales the drawn ones", file=spec.file, key="study"
        )
    if not any(b.law.film is not None for b in layout.bearings):
        for k in ("min_oil_film", "max_film_pressure"):
            if k in spec.limits:
                raise InputError(
                    "an oil-film limit needs a hydrodynamic main bearing "
                    '(a [shaft] bearing with model = "hydrodynamic"); the load case has none',
                    file=spec.file,
                    key=f"study.limits.{k}",
                )
    m = lc.material
    if "min_fillet_fatigue_safety" in spec.limits and (
        m is None or m.fatigue_limit_bending is None or m.tensile_strength is None
    ):
        raise InputError(
            "a fatigue-safety limit needs the material's fatigue limit in bending and tensile strength",
            file=spec.file,
            key="study.limits.min_fillet_fatigue_safety",
        )
    for k in ("min_overspeed_safety", "max_counterweight_overspeed_stress"):
        if k in spec.limits and lc.operating.overspeed is None:
            raise InputError(
                "an overspeed limit needs the load case's [operating] overspeed",
                file=spec.file,
                key=f"study.limits.{k}",
            )
    if "min_overspeed_safety" in spec.limits and (m is None or m.yield_strength is None):
        raise InputError(
            "an overspeed-safety limit needs the material's yield strength",
            file=spec.file,
            key="study.limits.min_overspeed_safety",
        )
    if "min_fillet_static_safety" in spec.limits and (m is None or m.yield_strength is None):
        raise InputError(
            "a static-safety limit needs the material's yield strength",
            file=spec.file,
            key="study.limits.min_fillet_static_safety",
        )
    if "max_counterweight_stress" in spec.limits:  # a sharp re-entrant edge: a singular stress, as the check
        require_counterweight_fillets(layout.geometry, ("counterweight_stress",), spec.file)
    for k in JOINT_LIMITS:
        if k in spec.limits and not has_bolted(layout):
            raise InputError(
                "a bolted-joint limit needs a bolted counterweight (a counterweight's bolted table in the "
                "geometry); the geometry has none",
                file=spec.file,
                key=f"study.limits.{k}",
            )
    if M53_LIMIT in spec.limits:
        why = refusal(lc)
        if why is None and lc.torsion is None and not (lc.criteria is not None and lc.criteria.m53_quasi_static_torque):
            why = (
                "UR M53 2.2 takes the torsional stress from a forced-vibration calculation: give the load case a "
                "[torsion] section (the study runs it per candidate) or, to screen Q on the quasi-static journal "
                "torque (not UR M53-conform), set criteria.m53_quasi_static_torque = true in the load case"
            )
        if why is not None:
            raise InputError(why, file=spec.file, key=f"study.limits.{M53_LIMIT}")
    return layout, drawn, candidates(spec, drawn, layout, lc.engine)


@dataclass(frozen=True)
class _LoadPeaks:
    """A candidate's main-bearing and web figures over the states (``_load_peaks``)."""

    peak: float  # N, the largest main-bearing load
    where: str
    peaks: dict[str, float]  # N per bearing
    means: dict[str, float]  # N per bearing, the largest mean over the states
    web_peaks: dict[str, float]  # N m per web
    wmax: float  # N m, the largest web bending moment
    wwhere: str


def _load_peaks(layout, loads) -> _LoadPeaks:
    """The figures of the candidate's ``loads`` (``screen.StateLoads`` per state) the table
    takes: per bearing the envelope over the law sets, per web the largest moment."""
    peak, where = 0.0, ""
    peaks: dict[str, float] = {}
    means: dict[str, float] = {}
    web_peaks: dict[str, float] = {}
    wmax, wwhere = 0.0, ""
    web_names = [f"{th.name}.{w}" for th in layout.throws for w in (1, 2)]
    for sl in loads:
        sets = sl.bearings[None] if sl.bearing_sets is None else sl.bearing_sets
        mags = np.hypot(sets[..., 0], sets[..., 1])  # (sets, n, nb)
        for j, b in enumerate(layout.bearings):
            # the envelope over the law sets: per bearing the set of the largest peak
            # (its mean with it), as the check's main-bearing criteria (fe.shaft.whole_shaft.envelope)
            s = int(np.argmax(mags[:, :, j].max(axis=1)))
            p, m = float(mags[s, :, j].max()), float(mags[s, :, j].mean())
            peaks[b.name] = max(peaks.get(b.name, 0.0), p)
            means[b.name] = max(means.get(b.name, 0.0), m)
            if p > peak:
                peak, where = p, f"bearing {b.name}, {sl.state.label} at {sl.state.speed * 30 / math.pi:.0f} rpm"
        wm = np.hypot(sl.webs[..., 0], sl.webs[..., 1])
        for i, name in enumerate(web_names):
            web_peaks[name] = max(web_peaks.get(name, 0.0), float(wm[:, i].max()))
        i = int(np.argmax(wm.max(axis=0)))
        if float(wm[:, i].max()) > wmax:
            wmax = float(wm[:, i].max())
            wwhere = f"web {web_names[i]}, {sl.state.label} at {sl.state.speed * 30 / math.pi:.0f} rpm"
    return _LoadPeaks(peak, where, peaks, means, web_peaks, wmax, wwhere)


def _metrics(
    cand: Candidate,
    lp: _LoadPeaks,
    shaft: StudyShaft,
    drawn: dict[tuple, DrawnWeb],
    lc: LoadCase,
    spec: StudySpec,
    w_max: float,
    written: WrittenMass,
    stresses: StressScreen | None = None,
    overspeed: OverspeedScreen | None = None,
    m53: M53Screen | None = None,
    bodies: BodyScreen | None = None,
    joints: JointScreen | None = None,
    joint_lims: dict[str, float] | None = None,
    torsional_frequency: float | None = None,
    film: FilmMetrics | None = None,
) -> CandidateResult:
    layout = shaft.layout
    peak, where, peaks, means, web_peaks = lp.peak, lp.where, lp.peaks, lp.means, lp.web_peaks
    wmax, wwhere = lp.wmax, lp.wwhere
    dj = layout.geometry.journal_diameter
    spec_load = max(peaks[b.name] / (dj * b.width) for b in layout.bearings)
    f1, m1 = first_order(residual(lc.engine, w_max, drawn, written.load_factors, written.planes))
    rates = {}
    for th in layout.throws:
        t = lc.engine.throw(th.name)
        mr = rotating_mass(lc.engine, th.name) * t.crank_radius
        own = sum(k * drawn[w].unbalance for w, k in written.load_factors.items() if w[0] == th.name)
        rates[th.name] = own / mr if mr > 0 else math.nan
    values = {
        "max_main_bearing_load": (peak, "N"),
        "max_main_bearing_specific_load": (spec_load, "Pa"),
        "max_web_bending_moment": (wmax, "N m"),
        "max_free_force": (f1, "N"),
        "max_free_moment": (m1, "N m"),
        "max_counterweight_mass": (written.counterweight_mass, "kg"),
        "max_film_pressure": (film.peak_pressure if film else math.nan, "Pa"),
    }
    failed = tuple(
        f"{k} {values[k][0]:.4g} > {lim:.4g} {values[k][1]}"
        for k, lim in spec.limits.items()
        if k in values and values[k][0] > lim
    )
    if stresses is not None:
        lim = spec.limits
        if "max_fillet_stress" in lim and stresses.shaft_peak > lim["max_fillet_stress"]:
            failed += (f"max_fillet_stress {stresses.shaft_peak / 1e6:.4g} > {lim['max_fillet_stress'] / 1e6:.4g} MPa",)
        for k, v in (
            ("min_fillet_static_safety", stresses.static_safety),
            ("min_fillet_fatigue_safety", stresses.fatigue_safety),
        ):
            if k in lim and v is not None and v < lim[k]:
                failed += (f"{k} {v:.4g} < {lim[k]:.4g}",)
    if overspeed is not None:
        lim = spec.limits
        if "min_overspeed_safety" in lim and overspeed.safety < lim["min_overspeed_safety"]:
            failed += (f"min_overspeed_safety {overspeed.safety:.4g} < {lim['min_overspeed_safety']:.4g}",)
        k = "max_counterweight_overspeed_stress"
        if k in lim and overspeed.counterweight_peak > lim[k]:
            failed += (f"{k} {overspeed.counterweight_peak / 1e6:.4g} > {lim[k] / 1e6:.4g} MPa",)
    k = "max_counterweight_stress"
    if k in spec.limits and bodies is not None and bodies.peak > spec.limits[k]:
        failed += (f"{k} {bodies.peak / 1e6:.4g} > {spec.limits[k] / 1e6:.4g} MPa",)
    if M53_LIMIT in spec.limits and m53 is not None and m53.acceptability < spec.limits[M53_LIMIT]:
        failed += (f"{M53_LIMIT} {m53.acceptability:.4g} < {spec.limits[M53_LIMIT]:.4g}",)
    if joints is not None and joints.refused is not None:
        failed += (f"bolted joint: {joints.refused}",)
    if joints is not None:
        for k, bound in (joint_lims or {}).items():
            v = joints.values.get(k)
            if v is not None and (v > bound if k.startswith("max_") else v < bound):
                op = ">" if k.startswith("max_") else "<"
                failed += (f"{k} {v:.4g} {op} {bound:.4g} ({joints.where[k]})",)
    if "min_oil_film" in spec.limits and film is not None and film.min_film < spec.limits["min_oil_film"]:
        failed += (f"min_oil_film {film.min_film * 1e6:.4g} < {spec.limits['min_oil_film'] * 1e6:.4g} um",)
    return CandidateResult(
        cand,
        written.counterweight_mass,
        written.mass_change,
        written.polar_inertia_change,
        written.unbalance,
        rates,
        peak,
        where,
        spec_load,
        peaks,
        means,
        web_peaks,
        wmax,
        wwhere,
        f1,
        m1,
        failed,
        written,
        film,
        stresses,
        overspeed,
        m53,
        bodies,
        joints,
        torsional_frequency,
    )


def _joint_words(jt: JointScreen) -> str:
    """The joint figures a recommendation names: each VDI 2230 safety's least value and the
    joint and state of the least of them."""
    safeties = {k: v for k, v in jt.values.items() if k.startswith("min_")}
    if not safeties:
        return ""
    least = min(safeties, key=lambda k: safeties[k])
    figures = ", ".join(f"{k.removeprefix('min_bolt_').removesuffix('_safety')} {v:.2f}" for k, v in safeties.items())
    return f"; bolted joints' least safeties {figures} (the least: {jt.where[least]})"


def _of_joint(failure: str) -> bool:
    """Whether a failed-limit line (``CandidateResult.failed``) is a bolted joint's."""
    return failure.split(" ")[0] in JOINT_LIMITS or failure.startswith("bolted joint:")


def recommend(results: tuple[CandidateResult, ...], rule: str) -> tuple[CandidateResult | None, str]:
    """The candidate the rule picks among the buildable ones meeting every limit."""
    ok = [r for r in results if r.meets_limits]
    if not ok:
        n_build = sum(r.candidate.buildable for r in results)
        why = (
            f"no candidate meets every limit ({n_build} of {len(results)} buildable; "
            "the table says which limit each misses)"
        )
        joint_fails = [(r, f) for r in results if r.candidate.buildable for f in r.failed if _of_joint(f)]
        if joint_fails:
            n = len({id(r) for r, _ in joint_fails})
            r0, f0 = joint_fails[0]
            why += f"; a bolted joint fails on {n} of the buildable ones (#{r0.candidate.index}: {f0})"
        return None, why
    if rule == "least_mass":
        best = min(ok, key=lambda r: (round(r.counterweight_mass, 9), r.peak_bearing_load, r.candidate.index))
        why = (
            f"the least counterweight mass ({best.counterweight_mass:.3f} kg) of the {len(ok)} buildable "
            f"candidates meeting every limit; peak main-bearing load {best.peak_bearing_load / 1e3:.2f} kN"
        )
    else:
        best = min(ok, key=lambda r: (round(r.peak_bearing_load, 6), r.counterweight_mass, r.candidate.index))
        why = (
            f"the least peak main-bearing load ({best.peak_bearing_load / 1e3:.2f} kN) of the {len(ok)} buildable "
            f"candidates meeting every limit; counterweight mass {best.counterweight_mass:.3f} kg"
        )
    # a candidate the rule's quantity alone would take (as light, or as little loaded) that a
    # bolted joint rules out: the reason names it
    ahead = [
        r
        for r in results
        if r.candidate.buildable
        and not r.meets_limits
        and (
            round(r.counterweight_mass, 9) <= round(best.counterweight_mass, 9)
            if rule == "least_mass"
            else round(r.peak_bearing_load, 6) <= round(best.peak_bearing_load, 6)
        )
    ]
    joint_miss = [(r, f) for r in ahead for f in r.failed if _of_joint(f)]
    if joint_miss:
        r0, f0 = joint_miss[0]
        why += f"; #{r0.candidate.index} ({r0.candidate.label}) would do by the rule, but a bolted joint misses: {f0}"
    st = best.stresses
    if st is not None:
        why += f"; fillet peak {st.shaft_peak / 1e6:.1f} MPa (static safety {st.static_safety:.2f}"
        why += ")" if st.fatigue_safety is None else f", fatigue safety {st.fatigue_safety:.2f})"
    if best.overspeed is not None:
        why += f"; overspeed safety {best.overspeed.safety:.2f}"
    if best.joints is not None:
        why += _joint_words(best.joints)
    return best, why


def _middle_candidates(cands: list[Candidate]) -> list[Candidate]:
    """Per placement (in the order of first appearance) the candidate of the middle
    balance rate: the lower median of its candidates' (rotating, reciprocating) rates, the
    first of them in the candidates' order."""
    by: dict[str, list[Candidate]] = {}
    for c in cands:
        by.setdefault(c.placement, []).append(c)
    out = []
    for group in by.values():
        rates = sorted((c.rotating, c.reciprocating) for c in group)
        mid = rates[(len(rates) - 1) // 2]
        out.append(next(c for c in group if (c.rotating, c.reciprocating) == mid))
    return out


def _sizes(stiffness: ThrowStiffnessCache) -> tuple:
    """The size, mesh cache folder and element limit ``stiffness`` meshes with."""
    return stiffness.size, stiffness.cache_dir, stiffness.max_elements


def run_study(
    lc: LoadCase, spec: StudySpec, *, size, cache_dir, max_elements=None, stiffness: ThrowStiffnessCache | None = None
) -> StudyResult:
    """The study (module doc).  ``stiffness``: an empty FE throw stiffness cache of ``lc``
    with the same size, cache folder and element limit, which the study fills (the caller
    then holds the stiffness of every written solid it solved); None: the study's own."""
    layout, drawn, cands = prepare(lc, spec)
    assert lc.material is not None
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)
    states = engine_states(lc.engine, lc.operating, cycles)
    w_max = max(s.speed for s in states)
    add = m53_basis(
        lc.engine, lc.material, lc.criteria.m53_additional_bending if lc.criteria else None, file=lc.source_file
    ).additional
    g = layout.geometry
    # per candidate with [torsion] (its torsional stage, study.torsion), else the counterweights
    # enter neither UR M53's loads nor its dimensions: once
    per_candidate = lc.torsion is not None
    q = None if lc.torsion is not None else study_m53(lc, cycles)
    # the FE throw stiffness of each candidate's written geometry (throw_stiffness = "fe")
    if stiffness is None:
        stiffness = ThrowStiffnessCache(lc, size=size, cache_dir=cache_dir, max_elements=max_elements)
    elif stiffness.lc is not lc or stiffness.solved or (size, cache_dir, max_elements) != _sizes(stiffness):
        raise ValueError("run_study: the stiffness cache must be empty and of the same load case, size and cache")
    k_fe: list[float] = []
    results = []
    pending: list[partial[CandidateResult]] = []
    films = []
    first = None
    by_offset: dict[float, tuple[StudyShaft, dict[tuple, DrawnWeb]]] = {}
    # each offset on the drawn counterweights turned to it: its own solids, mesh and unit cases
    for off in dict.fromkeys(c.offset for c in cands):
        layout_o, drawn_o, _ = turned_view(layout, drawn, off, mass={})  # the shaft takes its own
        shaft = study_shaft(
            layout_o,
            lc.material,
            lc.fe,
            size=size,
            cache_dir=cache_dir,
            max_elements=max_elements,
            stresses=spec.stresses != "off",
            torque_flow=lc.torsion is not None,
        )
        bases = [state_base(shaft, s) for s in states]
        os_bases = (
            [
                state_base(shaft, EngineState(f"overspeed ({c.gas})", c.dynamics.speed, c.dynamics))
                for c in cycles.overspeed
            ]
            if spec.stresses != "off"
            else []
        )
        solids = ThrowSolidCache(layout_o)
        bm = (
            None
            if spec.stresses == "off"
            else body_model(lc, layout_o, size=size, cache_dir=cache_dir, max_elements=max_elements)
        )
        rigid = bm is not None and lc.torsion is None  # the per-throw model's loads: the same for every candidate
        per_throw_loads = assessed_loads(lc.engine, cycles, reaction=lc.fe.torque_reaction) if rigid else None
        joints_screened = bm is not None and has_bolted(layout_o)
        jm = joint_model(lc, layout_o, bm, cycles) if joints_screened and rigid and bm is not None else None
        j_lims, j_whose = joint_limits(spec.limits, lc.criteria) if joints_screened else ({}, "")
        if first is None:
            first = (shaft, drawn_o, bm, j_lims, j_whose, jm)
        by_offset[off] = (shaft, drawn_o)
        masses: dict[int, WrittenMass] = {}
        if spec.stresses != "off":
            # each placement's middle balance rate first: its history the references of the
            # placement's stresses in every state (screen.seed_references: the same values,
            # tighter bounds than the first candidate's for the rates on either side)
            for c in _middle_candidates([c for c in cands if c.offset == off]):
                masses[c.index] = wm = written_mass(layout_o, c, drawn_o, shaft.mass, solids)
                seed_references(
                    shaft,
                    [candidate_loads(shaft, b, wm.load_factors, drawn_o, envelope=False) for b in bases],
                    [candidate_loads(shaft, b, wm.load_factors, drawn_o, envelope=False) for b in os_bases],
                )
        for c in cands:
            if c.offset != off:
                continue
            seeded = masses.pop(c.index, None)
            wm = seeded if seeded is not None else written_mass(layout_o, c, drawn_o, shaft.mass, solids)
            f1 = None
            c_loads, c_jm, c_bases = per_throw_loads, jm, bases
            if per_candidate:
                ts = screen_torsion(
                    lc, cycles, layout_o, c, drawn_o, shaft.mass, solids, bm, joints_screened, stiffness
                )
                f1, q, c_jm = ts.frequency, ts.m53, ts.joints
                if ts.fe_stiffness is not None:
                    k_fe.append(ts.fe_stiffness)
                c_loads = ts.loads if bm is not None else None
                # the operating speed's firing state with the candidate's own journal torques
                assert ts.dynamics is not None
                c_bases = with_operating_dynamics(shaft, bases, cycles.operating, ts.dynamics)
            loads = [candidate_loads(shaft, b, wm.load_factors, drawn_o) for b in c_bases]
            st = (
                None
                if spec.stresses == "off"
                else candidate_stresses(
                    shaft,
                    loads,
                    lc.material,
                    additional_bending=add,
                    diameters=(g.crankpin_diameter, g.journal_diameter),
                    fatigue=spec.stresses == "fatigue",
                )
            )
            os = candidate_overspeed(
                shaft,
                [candidate_loads(shaft, b, wm.load_factors, drawn_o, envelope=False) for b in os_bases],
                lc.material,
            )
            bd = None if bm is None or c_loads is None else candidate_bodies(bm, c_loads, wm.load_factors)
            jt = None if c_jm is None else candidate_joints(c_jm, c, solids, shaft.mass)
            # the figures once every candidate's film is known (study.film: orbits integrated together)
            films.append(film_rows(shaft.layout, loads))
            pending.append(
                partial(
                    _metrics,
                    c,
                    _load_peaks(shaft.layout, loads),
                    shaft,
                    drawn_o,
                    lc,
                    spec,
                    w_max,
                    wm,
                    st,
                    os,
                    q,
                    bd,
                    jt,
                    j_lims,
                    f1,
                )
            )
    for figures, film in zip(pending, film_metrics_of(films)):
        results.append(figures(film=film))
    results.sort(key=lambda r: r.candidate.index)
    assert first is not None
    shaft, drawn, bm, j_lims, j_whose, jm = first
    best, why = recommend(tuple(results), spec.rule)
    notes = []
    if lc.engine.gas is None:
        notes.append("the engine has no gas table: full load is the inertia load, no separate no-load state")
    if lc.torsion is not None:
        notes.append(
            "torsional stage per candidate (the check's, torsion.stage): the chain with the throws' inertias of "
            "the geometry the candidate writes (exact CAD J_z plus the rods and pistons), every cylinder firing "
            "and each misfire case; its first natural frequency in the table"
        )
        notes.append(TORSION_SHAFT)
    if lc.torsion is not None and lc.torsion.model == "cad" and lc.torsion.throw_stiffness == "carter":
        notes.append('throw stiffness Carter\'s (throw_stiffness = "carter"), which the counterweights do not change')
    if k_fe:
        notes.append(
            'FE throw stiffness per candidate (throw_stiffness = "fe"), the check\'s (torsion.stiffness'
            ".plan_throw_stiffness): the torque unit case of the first throw model of the check's mesh plan of "
            f"the geometry the candidate writes, {len(stiffness.solved)} distinct model(s) meshed and solved, "
            f"{min(k_fe):.6g} to {max(k_fe):.6g} N m/rad; a candidate that cannot be built takes the drawn throw's"
        )
    if lc.torsion is not None and q is not None:
        notes.append(
            "UR M53 Q per candidate, computed as the check does: the journal torques of the candidate's own "
            "torsional stage (vibratory, UR M53 2.2.2's hand-over of the largest alternating torque over the "
            "speed range and every misfire case)"
        )
    elif lc.torsion is not None:
        notes.append(f"UR M53 Q not screened: {refusal(lc)}")
    elif q is not None:
        notes.append(
            f"UR M53 Q {q.acceptability:.4g} ({q.where}): computed once, every candidate's (the counterweights "
            "enter neither UR M53's loads nor its dimensions without [torsion]); quasi-static journal torque"
        )
    else:
        notes.append(f"UR M53 Q not screened: {refusal(lc)}")
    if joints_screened:
        notes.append(
            "bolted joints (VDI 2230) screened by the check's own joint check over its load states, the web's "
            "deformation from the per-throw model"
            + (
                "; with the candidate's torsional angular acceleration and vibratory pin force"
                if lc.torsion is not None
                else ""
            )
            + f"; judged by {j_whose}: "
            + ", ".join(f"{k} {v:g}" for k, v in j_lims.items())
        )
    elif has_bolted(layout):
        notes.append('bolted joints not screened (stresses = "off": no per-throw model); judge them by the full check')
    return StudyResult(
        spec, lc, shaft, drawn, states, tuple(results), best, why, w_max, tuple(notes), bm, j_lims, jm, by_offset
    )
