"""The main bearings' oil film at every speed and load state, and its criteria.

For every hydrodynamic main bearing (``[shaft]`` bearing ``model = "hydrodynamic"``,
``geometry.oil.FilmSpec``) and every state of the whole shaft's bearing sweep
(``assess.shaft.BearingState``: each speed of the full-load curve, all cylinders firing
and each misfire case), with the counterweights as built and without them, the journal's
periodic orbit under the bearing's load over the cycle (``fe.oil_film``: the finite
bearing as the short bearing with the finite-length factor of its land's width /
diameter, half-Sommerfeld, Booker's mobility, all orbits integrated at once).  The loads are the
whole shaft's from its structural bearing law (rigid, or a stated spring): the film's own
stiffness is not fed back into the shaft (docs/shaft.md).  The journal turns at the
state's constant speed, in the shaft's sense.

Per orbit: the minimum oil film thickness h_min = c (1 - eps_max) and its crank angle, the
largest eccentricity ratio, the peak film pressure (the short bearing's at the middle of
a land over the finite-length factor) and its angle, the orbit, whether it repeated (else the film criterion takes h_min = 0: a
journal that runs towards the clearance has no film to credit), and from the whole shaft's
deflection the journal's slope in the bearing: its largest value, the misalignment it
means at the bearing's edges (|slope| B/2) and the edges' film, c - max |c eps +- slope B/2|
(the rigid journal tilted about the orbit's point at mid-width; the film is not solved
again for the tilt).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.assess.shaft import BearingState
from fe_crank.assess.speeds import Found, Located, over_states
from fe_crank.fe.oil_film import (
    ORBIT_TOL,
    JournalBearing,
    Orbits,
    finite_factor,
    peak_pressure_factor,
    periodic_orbits,
)
from fe_crank.geometry.oil import FilmSpec
from fe_crank.geometry.shaft import ShaftLayout
from fe_crank.results import Location, Sense

#: how the film is modelled, for the report and results.json
FILM_MODEL = (
    "finite bearing: the short bearing (Ocvirk) over a finite-length factor fitted to finite-difference "
    "solutions of Reynolds' equation (land width / diameter up to 0.5), half-Sommerfeld cavitation, rigid "
    "journal and bearing, isoviscous film, Booker's mobility: periodic orbit by implicit BDF2 steps at every "
    "load angle"
)


@dataclass(frozen=True)
class FilmOrbit:
    """One bearing's film over the cycle in one state (module doc); angles are cycle angles."""

    eps: np.ndarray  # (n, 2) eccentricity ratio, engine frame
    min_film_m: float
    min_film_angle_deg: float
    max_eccentricity: float
    peak_pressure_pa: float
    peak_pressure_angle_deg: float
    converged: bool
    cycles: int
    change: float  # max |delta eps| between the last two cycles
    max_slope: float | None = None  # rad
    edge_misalignment_m: float | None = None  # max |slope| B / 2
    min_edge_film_m: float | None = None

    @property
    def judged_min_film_m(self) -> float:
        """h_min for the criterion: 0 when the orbit did not repeat (module doc)."""
        return self.min_film_m if self.converged else 0.0

    def to_dict(self) -> dict[str, float | bool | int | None]:
        return {
            "min_film_m": self.min_film_m,
            "min_film_angle_deg": self.min_film_angle_deg,
            "max_eccentricity": self.max_eccentricity,
            "peak_pressure_pa": self.peak_pressure_pa,
            "peak_pressure_angle_deg": self.peak_pressure_angle_deg,
            "converged": self.converged,
            "cycles": self.cycles,
            "max_slope_rad": self.max_slope,
            "edge_misalignment_m": self.edge_misalignment_m,
            "min_edge_film_m": self.min_edge_film_m,
        }


@dataclass(frozen=True)
class BearingFilm:
    name: str
    bearing: JournalBearing
    oil: str  # how the viscosity was found
    with_counterweights: FilmOrbit
    without_counterweights: FilmOrbit


@dataclass(frozen=True)
class FilmState:
    """The hydrodynamic bearings' films in one load state at one speed (rad/s)."""

    speed: float
    case: str
    bearings: tuple[BearingFilm, ...]


def journal_bearing(spec: FilmSpec, width: float, journal_diameter: float | None) -> JournalBearing:
    """The film model of a main bearing of ``width`` with film ``spec`` (``FilmSpec``; its
    diameter, else ``journal_diameter``)."""
    diameter = spec.diameter or journal_diameter
    if diameter is None:
        raise ValueError("a hydrodynamic main bearing needs its diameter: the film's or the journal's")
    return JournalBearing(
        diameter=diameter,
        width=width,
        clearance=spec.clearance,
        viscosity=spec.viscosity,
        groove=spec.groove,
        groove_width=spec.groove_width,
    )


def film_pressure(b: JournalBearing, eps: np.ndarray, squeeze: np.ndarray, omega: float) -> np.ndarray:
    """The peak film pressure (Pa) at each angle of a journal orbit ``eps`` (n, 2) with its
    squeeze velocities, the shaft at ``omega`` (rad/s): the short bearing's peak over the
    finite-length factor of ``b``'s land (``fe.oil_film.finite_factor``)."""
    e = np.minimum(np.hypot(eps[:, 0], eps[:, 1]), 1.0 - 1e-12)
    return np.asarray(
        b.pressure_scale() * omega * peak_pressure_factor(eps, squeeze) / finite_factor(e, b.land_aspect)[0]
    )


def journal_orbits(
    bearings: list[JournalBearing], loads: list[np.ndarray], speeds: list[float], turns: float, sense: int
) -> Orbits:
    """The periodic orbits (``fe.oil_film.periodic_orbits``, every one at once) of journals
    in ``bearings`` under ``loads`` (each (n, 2), N, engine frame) at shaft ``speeds``
    (rad/s), ``turns`` journal revolutions per cycle, the journal turning in the shaft's
    ``sense`` (+1 turns from +y towards +x, negative about +z)."""
    stack = np.stack([np.asarray(f, float) / (b.k0 * w) for b, f, w in zip(bearings, loads, speeds)])
    aspect = np.asarray([b.land_aspect for b in bearings])
    return periodic_orbits(stack, turns, mean_speed=-0.5 * sense, tol=ORBIT_TOL, aspect=aspect)


def _orbit(
    b: JournalBearing,
    eps: np.ndarray,
    squeeze: np.ndarray,
    omega: float,
    deg: np.ndarray,
    slope: np.ndarray | None,
    conv: bool,
    cycles: int,
    change: float,
) -> FilmOrbit:
    r = np.hypot(eps[:, 0], eps[:, 1])
    k = int(np.argmax(r))
    p = film_pressure(b, eps, squeeze, omega)
    kp = int(np.argmax(p))
    ms = mis = edge = None
    if slope is not None:
        s = np.hypot(slope[:, 0], slope[:, 1])
        ms = float(s.max())
        mis = ms * b.width / 2
        e = b.clearance * eps
        off = slope * b.width / 2
        reach = np.maximum(np.hypot(*(e + off).T), np.hypot(*(e - off).T))
        edge = float(np.min(b.clearance - reach))
    return FilmOrbit(
        eps,
        float(b.clearance * (1 - r[k])),
        float(deg[k]),
        float(r[k]),
        float(p[kp]),
        float(deg[kp]),
        bool(conv),
        int(cycles),
        float(change),
        ms,
        mis,
        edge,
    )


def film_sweep(
    layout: ShaftLayout, states: tuple[BearingState, ...], crank_angle_deg: ArrayLike
) -> tuple[FilmState, ...]:
    """The films (module doc) of ``layout``'s hydrodynamic bearings (``ShaftLayout``) in
    every state; () when none has a film.  ``crank_angle_deg``: the cycle's angles (equally
    spaced over the cycle)."""
    films = [(j, b, b.law.film) for j, b in enumerate(layout.bearings) if b.law.film is not None]
    if not films or not states:
        return ()
    deg = np.asarray(crank_angle_deg, float)
    n = deg.size
    turns = (deg[1] - deg[0]) * n / 360.0  # journal revolutions per cycle
    d_j = layout.geometry.journal_diameter if layout.geometry is not None else None
    jb = {j: journal_bearing(film, b.width, d_j) for j, b, film in films}
    rows: list[tuple[int, int, bool, ArrayLike | None]] = []
    loads: list[np.ndarray] = []
    bearings: list[JournalBearing] = []
    speeds: list[float] = []
    for si, st in enumerate(states):
        by_name = {r.name: r for r in st.bearings}
        for j, b, _ in films:
            res = by_name[b.name]
            for cw, loads_of in ((True, res.with_counterweights), (False, res.without_counterweights)):
                rows.append((si, j, cw, loads_of.slope))
                loads.append(np.asarray(loads_of.load_n, float))
                bearings.append(jb[j])
                speeds.append(float(st.speed))
    orbits = journal_orbits(bearings, loads, speeds, turns, layout.sense)
    done: dict[tuple[int, int, bool], FilmOrbit] = {}
    for i, (si, j, cw, slope) in enumerate(rows):
        done[(si, j, cw)] = _orbit(
            jb[j],
            orbits.eps[i],
            orbits.squeeze[i],
            states[si].speed,
            deg,
            None if slope is None else np.asarray(slope, float),
            orbits.converged[i],
            orbits.cycles[i],
            orbits.change[i],
        )
    return tuple(
        FilmState(
            st.speed,
            st.case,
            tuple(
                BearingFilm(b.name, jb[j], film.oil, done[(si, j, True)], done[(si, j, False)]) for j, b, film in films
            ),
        )
        for si, st in enumerate(states)
    )


def _thinnest(bearings: tuple[BearingFilm, ...]) -> Found:
    vals = []
    for b in bearings:
        o = b.with_counterweights
        why = ""
        if not o.converged:
            why = f"no periodic orbit after {o.cycles} cycles: the journal runs towards the clearance; taken as 0"
        vals.append(
            (o.judged_min_film_m, Location("bearing", group=b.name, angle_deg=o.min_film_angle_deg, detail=why))
        )
    return min(vals, key=lambda v: v[0]) if vals else None


def _peak_pressure(bearings: tuple[BearingFilm, ...]) -> Found:
    vals = [
        (
            b.with_counterweights.peak_pressure_pa,
            Location("bearing", group=b.name, angle_deg=b.with_counterweights.peak_pressure_angle_deg),
        )
        for b in bearings
    ]
    return max(vals, key=lambda v: v[0]) if vals else None


#: the film's quantities: quantity -> its finder over the bearings of one state
FILM_FINDERS = {"oil_film_thickness": _thinnest, "oil_film_pressure": _peak_pressure}


def film_criterion(quantity: str, sense: Sense, states: tuple[FilmState, ...]) -> Located | None:
    """The worst value of a film quantity over every state (``speeds.over_states``: each
    speed's worst load state, the worst speed governing), with the counterweights as built."""
    return over_states(FILM_FINDERS[quantity], sense, [(s.speed, s.case, s.bearings) for s in states])


def governing_state(states: tuple[FilmState, ...], k: int) -> FilmState:
    """The state in which bearing ``k`` has its thinnest film (counterweights as built; the
    first of equals)."""
    return min(states, key=lambda s: s.bearings[k].with_counterweights.judged_min_film_m)


def _governing_orbit(states: tuple[FilmState, ...], k: int) -> dict[str, Any]:
    st = governing_state(states, k)
    b = st.bearings[k]
    return {
        "name": b.name,
        "speed_rpm": st.speed * 30.0 / math.pi,
        "case": st.case,
        "eccentricity_ratio": b.with_counterweights.eps.tolist(),
        "without_counterweights_eccentricity_ratio": b.without_counterweights.eps.tolist(),
    }


def film_json(states: tuple[FilmState, ...]) -> dict[str, Any]:
    """The ``oil_film`` object of results.json's ``whole_shaft``: the model, each
    hydrodynamic bearing's data and its film at every speed and load state."""
    if not states:
        return {}
    first = states[0].bearings
    return {
        "model": FILM_MODEL,
        "orbit_tolerance": ORBIT_TOL,
        "bearings": [
            {
                "name": b.name,
                "diameter_m": b.bearing.diameter,
                "width_m": b.bearing.width,
                "radial_clearance_m": b.bearing.clearance,
                "viscosity_pa_s": b.bearing.viscosity,
                "oil": b.oil,
                "groove": b.bearing.groove,
                "groove_width_m": b.bearing.groove_width,
                "land_width_to_diameter": b.bearing.land_width / b.bearing.diameter,
                "film_model": "finite bearing (short bearing over the finite-length factor of its land)",
            }
            for b in first
        ],
        "orbits": [_governing_orbit(states, k) for k in range(len(first))],
        "per_speed": [
            {
                "speed_rpm": s.speed * 30.0 / math.pi,
                "case": s.case,
                "bearings": [
                    {
                        "name": b.name,
                        **b.with_counterweights.to_dict(),
                        "without_counterweights": b.without_counterweights.to_dict(),
                    }
                    for b in s.bearings
                ],
            }
            for s in states
        ],
    }
