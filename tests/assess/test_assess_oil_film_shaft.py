"""The oil film on the shipped inline-4's whole shaft (``assess.oil_film.film_sweep``).

The shipped geometry with every main bearing given a grooved hydrodynamic film: the
bearing with the highest peak load has the thinnest film, and without the counterweights,
whose loss raises every bearing's load, every film is thinner.  And the film does not
change the shaft's bearing loads (it is not fed back)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank.assess.loads import FIRING
from fe_crank.assess.oil_film import film_sweep
from fe_crank.assess.shaft import BearingState
from fe_crank.check.stages import shaft_layout
from fe_crank.fe.whole_shaft import analyse_whole_shaft
from fe_crank.geometry.oil import FilmSpec
from fe_crank.io.loadcase import load_loadcase
from fe_crank.mechanism.cycles import engine_cycles

ROOT = Path(__file__).resolve().parents[2]


@pytest.mark.heavy
def test_inline4_film_follows_the_bearing_loads(mesh_cache):
    lc = load_loadcase(ROOT / "loadcases" / "inline4_rated.toml")
    layout = shaft_layout(lc)
    film = FilmSpec(clearance=25e-6, viscosity=7e-3, groove="full", groove_width=3e-3)
    with_film = dataclasses.replace(
        layout,
        bearings=tuple(dataclasses.replace(b, law=dataclasses.replace(b.law, film=film)) for b in layout.bearings),
    )
    dyn = engine_cycles(lc.engine, lc.operating).operating
    result, cases = analyse_whole_shaft(with_film, lc.material, dyn, size="test", cache_dir=mesh_cache)
    cases.model.free_factors()
    # the film is judged from the loads, not fed back: the structural law is the rigid one
    assert all(b.law.model == "rigid" for b in with_film.bearings)
    (state,) = film_sweep(with_film, (BearingState(float(dyn.speed), FIRING, result.bearings),), result.crank_angle_deg)
    films = state.bearings
    assert all(f.with_counterweights.converged and f.without_counterweights.converged for f in films)
    peaks = [b.with_counterweights.peak_n for b in result.bearings]
    h = [f.with_counterweights.min_film_m for f in films]
    assert int(np.argmax(peaks)) == int(np.argmin(h))
    for b, f in zip(result.bearings, films):
        assert b.without_counterweights.peak_n > b.with_counterweights.peak_n
        assert f.without_counterweights.min_film_m < f.with_counterweights.min_film_m
        assert f.with_counterweights.max_slope is not None and f.with_counterweights.max_slope > 0
