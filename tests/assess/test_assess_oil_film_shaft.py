"""The oil film on the shipped inline-4's whole shaft (``assess.oil_film.film_sweep``).

The shipped geometry's main bearings (geometry/inline4.toml [shaft]: 20 mm wide, full
groove, 28 um, a 5W-30 at 120 degC) at the operating speed: the bearing with the highest
peak load has the thinnest film, and without the counterweights every bearing whose peak
load rises has a thinner film.  And the film does not change the shaft's bearing loads
(it is not fed back)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank.assess.loads import FIRING
from fe_crank.assess.oil_film import film_sweep, journal_bearing
from fe_crank.assess.shaft import BearingState
from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
from fe_crank.geometry.oil import FilmSpec
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles
from fe_crank.mesh.shaft import mesh_shaft
from fe_crank.pipeline.stages import shaft_layout

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.heavy
def test_inline4_film_follows_the_bearing_loads(mesh_cache):
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    layout = shaft_layout(lc)
    assert layout is not None
    # the shipped bearings carry their film; the shaft's static law is the rigid one
    assert all(b.law.film is not None and b.law.model == "rigid" for b in layout.bearings)
    assert {(b.width, b.law.film.clearance, b.law.film.groove) for b in layout.bearings} == {(0.02, 28e-6, "full")}
    dyn = engine_cycles(lc.engine, lc.operating).operating
    sm = mesh_shaft(layout, size="test", cache_dir=mesh_cache)
    result, cases = analyse_whole_shaft(sm, lc.material, dyn, mass=throw_masses(layout))
    cases.model.free_factors()
    (state,) = film_sweep(layout, (BearingState(float(dyn.speed), FIRING, result.bearings),), result.crank_angle_deg)
    films = state.bearings
    assert all(f.with_counterweights.converged and f.without_counterweights.converged for f in films)
    peaks = [b.with_counterweights.peak_n for b in result.bearings]
    h = [f.with_counterweights.min_film_m for f in films]
    assert int(np.argmax(peaks)) == int(np.argmin(h))
    rising = [
        (b, f) for b, f in zip(result.bearings, films) if b.without_counterweights.peak_n > b.with_counterweights.peak_n
    ]
    assert rising
    for _b, f in rising:
        assert f.without_counterweights.min_film_m < f.with_counterweights.min_film_m
        assert f.with_counterweights.max_slope is not None and f.with_counterweights.max_slope > 0


def test_the_film_takes_its_diameter_or_the_journals_and_without_either_is_refused():
    spec = FilmSpec(clearance=50e-6, viscosity=0.01)
    assert journal_bearing(spec, 0.03, 0.08).diameter == 0.08
    assert journal_bearing(dataclasses.replace(spec, diameter=0.07), 0.03, 0.08).diameter == 0.07
    with pytest.raises(ValueError, match="a hydrodynamic main bearing needs its diameter"):
        journal_bearing(spec, 0.03, None)
