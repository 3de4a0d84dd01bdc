"""The oil film of a candidate's hydrodynamic main bearings, from its screened loads.

For every main bearing with a film (``[shaft]`` bearing ``model = "hydrodynamic"``,
``geometry.oil.FilmSpec``) and every engine state of the study, the journal's periodic
orbit under the candidate's bearing load over the cycle (of the law set the main-bearing
envelope takes for that bearing, as the check's film stage reads the enveloped loads)
(``assess.oil_film.journal_orbits``: the finite bearing of the check, half-Sommerfeld,
Booker's mobility), as the check's film stage takes it
(``assess.oil_film.film_sweep``, with the same bearing model ``journal_bearing``, the
journal turning in the shaft's sense): the minimum oil film thickness h_min = c (1 -
eps_max), 0 where the orbit did not repeat (a journal running towards the clearance has
no film to credit), and the peak film pressure (``assess.oil_film.film_pressure``).  Journal
tilt is not screened (the check's edge film uses the whole shaft's deflection).

The orbits of many candidates are integrated together (``film_metrics_of``: batches of at
most ``BATCH`` orbits, one time step of every orbit of a batch at once), as the check's
film stage integrates all of its orbits together.  Each orbit is integrated as on its own
to the solver's tolerances, except that a batch runs until every orbit in it has
repeated: an orbit that repeated earlier is carried on for the remaining cycles, which
moves it by less than the repeat tolerance (``fe.oil_film.ORBIT_TOL`` in eps), so a
candidate's film figures depend on its batch-mates only within that tolerance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.oil_film import film_pressure, journal_bearing, journal_orbits

#: orbits integrated together at most: beyond about a thousand one more orbit in a batch
#: costs its arithmetic only (docs/study.md); the bound keeps the batch's arrays (orbits x
#: angles, about 60 kB an orbit at 720 angles) near 60 MB
BATCH = 1024


@dataclass(frozen=True)
class FilmMetrics:
    min_film: float  # m, the least h_min over the hydrodynamic bearings and the states
    min_film_where: str
    peak_pressure: float  # Pa
    peak_pressure_where: str
    converged: bool  # every orbit repeated


@dataclass(frozen=True)
class FilmRows:
    """One candidate's orbits to integrate: per orbit its bearing model, load (n, 2) N,
    engine frame, shaft speed (rad/s) and where it is (for the table)."""

    bearings: tuple
    loads: tuple[np.ndarray, ...]
    speeds: tuple[float, ...]
    where: tuple[str, ...]
    turns: float  # journal revolutions per cycle
    sense: int


def film_rows(layout, loads) -> FilmRows | None:
    """The orbits of ``layout``'s hydrodynamic bearings under ``loads`` (the candidate's
    ``screen.StateLoads`` per state); None when no bearing has a film."""
    films = [(j, b) for j, b in enumerate(layout.bearings) if b.law.film is not None]
    if not films or not loads:
        return None
    d_j = layout.geometry.journal_diameter
    jb = {j: journal_bearing(b.law.film, b.width, d_j) for j, b in films}
    deg = np.degrees(np.asarray(loads[0].state.dynamics.theta, float))
    turns = (deg[1] - deg[0]) * deg.size / 360.0  # journal revolutions per cycle
    stack, bearings, speeds, where = [], [], [], []
    for sl in loads:
        st = sl.state
        sets = sl.bearings[None] if sl.bearing_sets is None else sl.bearing_sets
        for j, _ in films:
            # the law set of the bearing's largest peak, as the check's enveloped loads
            s = int(np.argmax(np.hypot(sets[:, :, j, 0], sets[:, :, j, 1]).max(axis=1)))
            stack.append(np.array(sets[s, :, j], float))
            bearings.append(jb[j])
            speeds.append(float(st.speed))
            where.append(f"bearing {layout.bearings[j].name}, {st.label} at {st.speed * 30 / math.pi:.0f} rpm")
    return FilmRows(tuple(bearings), tuple(stack), tuple(speeds), tuple(where), turns, layout.sense)


def _metrics(rows: FilmRows, eps, squeeze, converged) -> FilmMetrics:
    h_min, h_where, p_max, p_where = math.inf, "", 0.0, ""
    for i, (b, w, at) in enumerate(zip(rows.bearings, rows.speeds, rows.where)):
        r = float(np.hypot(eps[i][:, 0], eps[i][:, 1]).max())
        h = b.clearance * (1.0 - r) if converged[i] else 0.0
        if h < h_min:
            h_min, h_where = h, at
        p = float(film_pressure(b, eps[i], squeeze[i], w).max())
        if p > p_max:
            p_max, p_where = p, at
    return FilmMetrics(h_min, h_where, p_max, p_where, bool(np.all(converged)))


def film_metrics_of(candidates: list[FilmRows | None], batch: int = BATCH) -> list[FilmMetrics | None]:
    """The film figures of each candidate's orbits (``film_rows``; None: no film), the
    orbits of consecutive candidates integrated together in batches of at most ``batch``
    orbits (module doc; a candidate with more orbits is a batch of its own)."""
    out: list[FilmMetrics | None] = [None] * len(candidates)
    todo = [(k, r) for k, r in enumerate(candidates) if r is not None]
    while todo:
        group = [todo.pop(0)]
        size = len(group[0][1].loads)
        while todo and size + len(todo[0][1].loads) <= batch:
            nxt = todo[0][1]
            if (nxt.turns, nxt.sense) != (group[0][1].turns, group[0][1].sense):
                break
            size += len(nxt.loads)
            group.append(todo.pop(0))
        rows = group[0][1]
        orbits = journal_orbits(
            [b for _, r in group for b in r.bearings],
            [f for _, r in group for f in r.loads],
            [w for _, r in group for w in r.speeds],
            rows.turns,
            rows.sense,
        )
        at = 0
        for k, r in group:
            sl = slice(at, at + len(r.loads))
            out[k] = _metrics(r, orbits.eps[sl], orbits.squeeze[sl], orbits.converged[sl])
            at = sl.stop
    return out


def film_metrics(layout, loads) -> FilmMetrics | None:
    """The film of ``layout``'s hydrodynamic bearings under ``loads`` (the candidate's
    ``screen.StateLoads`` per state), its orbits integrated on their own; None when no
    bearing has a film."""
    return film_metrics_of([film_rows(layout, loads)])[0]
