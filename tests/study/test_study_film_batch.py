"""The study's oil film with the orbits of several candidates integrated together
(``study.film.film_metrics_of``) against each candidate's orbits integrated on their own."""

from __future__ import annotations

import math

import numpy as np
import pytest

from fe_crank.fe.oil_film import ORBIT_TOL, JournalBearing
from fe_crank.study.film import FilmRows, film_metrics_of

N = 120  # angles over the cycle (two journal turns)
BEARING = JournalBearing(diameter=0.05, width=0.02, clearance=25e-6, viscosity=0.01)


def _rows(scale: float) -> FilmRows:
    """Three orbits: a steady load, a rotating one and a firing-like pulse, at two speeds."""
    th = np.linspace(0.0, 4 * np.pi, N, endpoint=False)
    steady = np.tile([0.0, -2000.0 * scale], (N, 1))
    rotating = 1500.0 * scale * np.stack([np.cos(th / 2), np.sin(th / 2)], axis=1)
    pulse = np.stack([300.0 * np.sin(th), -1000.0 - 6000.0 * scale * np.exp(-(((th - 0.3) / 0.4) ** 2))], axis=1)
    loads = (steady, rotating, pulse)
    speeds = (300.0, 400.0, 600.0)
    return FilmRows((BEARING,) * 3, loads, speeds, ("a", "b", "c"), 2.0, 1)


def test_batched_film_equals_each_alone():
    cands = [_rows(1.0), None, _rows(1.6), _rows(0.5)]
    together = film_metrics_of(cands)
    alone = film_metrics_of(cands, batch=1)  # one candidate per batch: its orbits on their own
    assert together[1] is None and alone[1] is None
    for t, a in zip(together, alone):
        if a is None:
            continue
        assert a.converged and t.converged
        assert (t.min_film_where, t.peak_pressure_where) == (a.min_film_where, a.peak_pressure_where)
        # an orbit carried on after it repeated moves by less than the repeat tolerance in eps
        assert abs(t.min_film - a.min_film) <= ORBIT_TOL * BEARING.clearance
        assert t.peak_pressure == pytest.approx(a.peak_pressure, rel=2e-3)
        assert math.isfinite(t.peak_pressure) and t.min_film > 0


def test_batch_bound_splits_candidates_not_orbits():
    """A batch smaller than a candidate's orbits still takes the candidate whole; equal
    candidates in one batch get equal figures."""
    a = _rows(1.0)
    one, two = film_metrics_of([a, a], batch=2)
    assert one == two
    assert film_metrics_of([a], batch=1)[0] == film_metrics_of([a])[0]
