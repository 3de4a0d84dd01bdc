"""The whole shaft's own hot-spot convergence study (``fe.shaft.refinement``, its factors on
the whole shaft's criteria, ``assess.refinement``), on the small single on its two
bearings checked at ``test`` with the study forced on:

* a throw alone on its two bearings is statically determinate in both models, so the
  whole shaft's displacement of a load set is the per-throw model's up to a rigid motion:
  the shaft's study of the per-throw study's pin-force load set (the same weights on the
  shaft's unit cases) gives the per-throw zones' peaks (an independent
  route: condensation, force method and the piece's recovered field against the throw's
  direct solve);
* the check gives the whole shaft a study of its own per throw, its factors >= 1, and the
  whole-shaft model's values of the FE stress criteria are taken at those factors, their
  remark naming the whole-shaft model's study.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from fe_crank.assess.refinement import SURFACES, StudyFactors
from fe_crank.assess.shaft import WHOLE_SHAFT
from fe_crank.fe.refinement.convergence import estimate
from fe_crank.fe.refinement.zone_study import zone_convergence
from fe_crank.fe.shaft.refinement import shaft_throw_study, zone_loads
from fe_crank.results import Location

DATA = Path(__file__).resolve().parents[1] / "data"
pytestmark = pytest.mark.heavy


@pytest.fixture(scope="module")
def studied_single(tmp_path_factory, mesh_cache):
    """The small single (tests/data/geometry_small.toml, end journals ending at the bearing
    centres: the throw on its two bearings) at its operating speed, checked at ``test`` with
    the convergence study (``helpers.check_shaft``): the stages' outputs and the whole-shaft
    stage's own (its unit cases)."""
    from helpers.check_shaft import stage_outputs_with_shaft
    from helpers.sweep import SWEPT

    folder = tmp_path_factory.mktemp("studied_single")
    (folder / "case.toml").write_text(SWEPT.format(sweep=""))
    g = (DATA / "geometry_small.toml").read_text() + '\n[shaft]\nend_journal_length = "12 mm"\n'
    (folder / "geometry_small.toml").write_text(g)
    return stage_outputs_with_shaft(folder / "case.toml", mesh_cache, convergence=True)


def test_zone_loads_maps_the_shaft_patterns_to_the_zone_cases():
    """Pin patterns as themselves, the spin-up as the angular acceleration (the same body
    force rho (-y, x, 0)), the throw's and its counterweights' centrifugal force as the
    whole throw's when their coefficients agree, as the parts otherwise; the bearing
    surfaces' and end faces' patterns (driven faces) left out."""
    names = ("pin_x", "pin_030", "centrifugal", "centrifugal_cw", "spin_up", "journal_1.P0", "torque_end_2")
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 5.0, -3.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "angular_acceleration": -3.0, "centrifugal": 5.0}
    got = zone_loads(names, np.array([2.0, 0.0, 5.0, 0.0, 0.0, 7.0, 11.0]))
    assert got == {"pin_x": 2.0, "centrifugal_throw": 5.0}
    got = zone_loads(names, np.array([0.0, 1.0, 5.0, 4.0, 0.0, 0.0, 0.0]))
    assert got == {"pin_030": 1.0, "centrifugal_throw": 5.0, "centrifugal_cw_1": 4.0, "centrifugal_cw_2": 4.0}


def test_the_shaft_study_of_a_determinate_throw_is_the_per_throw_study(studied_single):
    """The per-throw study's pin-force load set (its pin cases and the centrifugal force)
    as weights of the whole shaft's unit cases (``pin_<deg>@1``, ``centrifugal`` and
    ``centrifugal_cw`` alike): the whole shaft's study gives the per-throw zone study's
    peaks at the assessed mesh and at a finer level's zones."""
    out, ws = studied_single
    assert ws is not None and ws.cases is not None
    (key,) = out.fe.unit_solutions
    unit_solutions = out.fe.unit_solutions[key]
    loads = {"peak pin force": dict(out.convergence[key].loads["peak pin force"])}
    assert set(loads["peak pin force"]) <= {*unit_solutions.cases, "centrifugal"} and "torque" not in loads
    one = (1.0, 1.5)  # the assessed mesh and one finer level
    per = zone_convergence(
        out.loadcase.geometry, out.loadcase.material, out.meshes.throws[key], unit_solutions, loads, factors=one
    )
    names = ws.cases.names
    w = np.zeros(len(names))
    for case, v in loads["peak pin force"].items():
        for target in ("centrifugal", "centrifugal_cw") if case == "centrifugal" else (f"{case}@1",):
            w[names.index(target)] += v
    shaft = shaft_throw_study(ws.cases, out.loadcase.material, "1", {"peak pin force": w}, factors=one)
    assert [lv.fillet_divisions for lv in shaft.levels] == [lv.fillet_divisions for lv in per.levels]
    assert [lv.zones for lv in shaft.levels[1:]] == [lv.zones for lv in per.levels[1:]]
    for a, b in zip(shaft.levels, per.levels):
        assert a.peaks["peak pin force"] == pytest.approx(b.peaks["peak pin force"], rel=1e-7)
        assert a.where == b.where


def test_the_whole_shaft_takes_its_own_study(studied_single):
    """The check's whole shaft has its own study per throw (method zones, finer levels with
    zones), its factors are >= 1, and the whole-shaft model's value of each FE stress
    criterion is its groups' value over their own factor k = max(1, sigma_est /
    sigma_assessed) of the shaft's study; the remark names that study."""
    out, _ = studied_single
    shaft = out.assessment.shaft
    assert shaft is not None and set(shaft.convergence) == {t.name for t in shaft.throws}
    factors = StudyFactors(out.convergence, shaft.convergence)
    for name, st in shaft.convergence.items():
        assert st.method == "zones" and all(lv.zones > 0 for lv in st.levels[1:])
        k = max(1.0, max(estimate(st, e)[0] for e in st.changes if not e.startswith(tuple(SURFACES)[1:])))
        for g in next(t for t in shaft.throws if t.name == name).groups:
            if g.group.startswith(("crankpin_fillet", "journal_fillet")):
                assert factors.shaft_factor(name, g.group) == pytest.approx(k, rel=1e-12) and k >= 1.0
    (value,) = [
        v for v in out.assessment.by_model if v.criterion == "criteria.min_static_safety" and v.model == WHOLE_SHAFT
    ]
    states = [st.throws for st in shaft.states] or [shaft.throws]  # every load state of its sweep
    expected = min(
        g.static_safety / factors.shaft_factor(t.name, g.group) for throws in states for t in throws for g in t.groups
    )
    assert value.value == pytest.approx(expected, rel=1e-12)
    r = factors.refinement(
        "criteria.min_static_safety", Location(throw="1", group="crankpin_fillet_1", model=WHOLE_SHAFT)
    )
    assert r is not None and "whole-shaft model's convergence study" in r.words
    assert r.factor == factors.shaft_factor("1", "crankpin_fillet_1")
