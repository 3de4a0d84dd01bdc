"""The oil film of a candidate's hydrodynamic main bearings, from its screened loads.

For every main bearing with a film (``[shaft]`` bearing ``model = "hydrodynamic"``,
``geometry.oil.FilmSpec``) and every engine state of the study, the journal's periodic
orbit under the candidate's bearing load over the cycle (of the law set the main-bearing
envelope takes for that bearing, as the check's film stage reads the enveloped loads)
(``assess.oil_film.journal_orbits``: the finite bearing of the check, half-Sommerfeld,
Booker's mobility, all orbits of a candidate integrated at once), as the check's film stage takes it
(``assess.oil_film.film_sweep``, with the same bearing model ``journal_bearing``, the
journal turning in the shaft's sense): the minimum oil film thickness h_min = c (1 -
eps_max), 0 where the orbit did not repeat (a journal running towards the clearance has
no film to credit), and the peak film pressure (``assess.oil_film.film_pressure``).  Journal
tilt is not screened (the check's edge film uses the whole shaft's deflection).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fe_crank.assess.oil_film import film_pressure, journal_bearing, journal_orbits


@dataclass(frozen=True)
class FilmMetrics:
    min_film: float  # m, the least h_min over the hydrodynamic bearings and the states
    min_film_where: str
    peak_pressure: float  # Pa
    peak_pressure_where: str
    converged: bool  # every orbit repeated


def film_metrics(layout, loads) -> FilmMetrics | None:
    """The film of ``layout``'s hydrodynamic bearings under ``loads`` (the candidate's
    ``screen.StateLoads`` per state); None when no bearing has a film."""
    films = [(j, b) for j, b in enumerate(layout.bearings) if b.law.film is not None]
    if not films or not loads:
        return None
    d_j = layout.geometry.journal_diameter
    jb = {j: journal_bearing(b.law.film, b.width, d_j) for j, b in films}
    deg = np.degrees(np.asarray(loads[0].state.dynamics.theta, float))
    turns = (deg[1] - deg[0]) * deg.size / 360.0  # journal revolutions per cycle
    rows, stack, bearings, speeds = [], [], [], []
    for si, sl in enumerate(loads):
        sets = sl.bearings[None] if sl.bearing_sets is None else sl.bearing_sets
        for j, _ in films:
            # the law set of the bearing's largest peak, as the check's enveloped loads
            s = int(np.argmax(np.hypot(sets[:, :, j, 0], sets[:, :, j, 1]).max(axis=1)))
            rows.append((si, j))
            stack.append(np.asarray(sets[s, :, j], float))
            bearings.append(jb[j])
            speeds.append(float(sl.state.speed))
    orbits = journal_orbits(bearings, stack, speeds, turns, layout.sense)
    h_min, h_where, p_max, p_where = math.inf, "", 0.0, ""
    for i, (si, j) in enumerate(rows):
        st = loads[si].state
        at = f"bearing {layout.bearings[j].name}, {st.label} at {st.speed * 30 / math.pi:.0f} rpm"
        eps = orbits.eps[i]
        r = float(np.hypot(eps[:, 0], eps[:, 1]).max())
        h = jb[j].clearance * (1.0 - r) if orbits.converged[i] else 0.0
        if h < h_min:
            h_min, h_where = h, at
        p = float(film_pressure(jb[j], eps, orbits.squeeze[i], st.speed).max())
        if p > p_max:
            p_max, p_where = p, at
    return FilmMetrics(h_min, h_where, p_max, p_where, bool(np.all(orbits.converged)))
