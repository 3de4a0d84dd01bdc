"""The oil film on the shipped inline-4's whole shaft (``assess.oil_film.film_sweep``).

The shipped geometry's main bearings (geometry/inline4.toml [shaft]: 20 mm wide, full
groove, 28 um, a 5W-30 at 120 degC) at the operating speed: the bearing with the highest
peak load has the thinnest film, and without the counterweights every bearing whose peak
load rises has a thinner film.  And the film does not change the shaft's bearing loads
(it is not fed back)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest
from helpers.inline4_shaft import CASE, parametric_inline4

from fe_crank.assess.oil_film import journal_bearing
from fe_crank.geometry.oil import FilmSpec
from fe_crank.io.loadcase import load_loadcase
from fe_crank.pipeline.stages import shaft_layout


@pytest.mark.heavy
def test_inline4_film_follows_the_bearing_loads(tmp_path_factory, mesh_cache):
    """The parametric whole shaft at ``test``, analysed once in the run
    (``helpers.inline4_shaft``: tests/cad/test_cad_whole_shaft.py compares the drawn shaft
    with the same analysis)."""
    shaft = parametric_inline4(tmp_path_factory, mesh_cache)
    lc = load_loadcase(CASE)
    layout = shaft_layout(lc)
    assert layout is not None and shaft.layout == layout
    # the shipped bearings carry their film; the shaft's static law is the rigid one
    assert all(b.law.film is not None and b.law.model == "rigid" for b in layout.bearings)
    assert {(b.width, b.law.film.clearance, b.law.film.groove) for b in layout.bearings} == {(0.02, 28e-6, "full")}
    result = shaft.result
    assert result.speed == lc.operating.speed  # the operating speed
    (state,) = shaft.films
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
