"""Main-bearing loads and the shaft's internal bending moments over the engine's cycle.

``shaft_cycle(cases, loads, shaft_angle, speed, laws=...)`` superposes the unit cases of
``fe.shaft.cases`` at every crank angle: each throw's pin force (throw frame, N) by the two
pin cases that bracket it, the centrifugal cases times omega^2, and the bearings' forces
from their laws (``fe.shaft.bearings``); once with the counterweights as built and once without
them (their centrifugal case switched off, and the forces of counterweights bolted on and
not meshed, ``EndCycleLoad.counterweight``, ``ShaftLayout.bolted``).  Results are frozen and in the engine frame:
the shaft frame turned by the shaft's angle psi(theta) (``model.crank_angle_global`` of
the reference throw, from +y towards +x).

* ``BearingLoads``: the force of the journal on the bearing (N, engine frame) at every
  angle, its peak and mean magnitude, the angle of the peak, the specific load
  peak / (d x w) (journal diameter d, bearing width w);
* ``WebMoment``: the bending moment (M_x, M_y, N m, engine frame) at each web's mid-plane:
  the moment about the section's centre of every load in front of it (pin forces,
  bearing forces, a pulley's or flywheel's loads and the centrifugal forces of the parts, from the exact mass properties of
  the throw's solid, ``geometry.mass``; a web and a counterweight flush with its outer
  face are prisms along z, so the part of each in front of the mid-plane is its share of
  the thickness).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import InputError
from fe_crank.fe.shaft.bearings import BearingSystem, bearing_forces
from fe_crank.fe.shaft.cases import ShaftCases
from fe_crank.fe.throw.pin_directions import pin_case_weights, pin_cases
from fe_crank.mesh.shaft import rotation


@dataclass(frozen=True)
class ThrowCycleLoad:
    throw: str
    pin_force: np.ndarray  # (n, 2) N, force of the rod(s) on the crankpin, throw frame
    #: (n,) the weight of the throw's ``spin_up@<throw>`` case (its body force of a unit
    #: angular acceleration about z; ``whole_shaft.torque_flow_loads``), None: no such case
    spin_up: np.ndarray | None = None


@dataclass(frozen=True)
class EndCycleLoad:
    """A load beyond an end of the shaft (flywheel, pulley: ``whole_shaft.end_load_cases``)."""

    name: str  # its unit cases are ``<name>.x``, ``<name>.y`` (1 N at its reference point)
    z: float  # m, its centre plane
    force: np.ndarray  # (n, 2) N on the shaft, shaft frame
    counterweight: bool = False  # a bolted counterweight's force: left out of the cycle without counterweights


@dataclass(frozen=True)
class BearingLoads:
    name: str
    z: float  # m
    width: float  # m
    diameter: float  # m
    load_n: np.ndarray  # (n, 2) N, engine frame: force of the journal on the bearing
    peak_n: float
    mean_n: float
    peak_angle_deg: float  # cycle angle of the peak
    specific_load_pa: float  # peak / (d w)
    mean_specific_load_pa: float
    law: str = ""  # the bearing law these loads are of (``law_text``)
    #: (n, 2) the journal's mean slope (dx/dz, dy/dz) in the bearing, engine frame, relative
    #: to the bearings' line (None: not computed)
    slope: np.ndarray | None = None


@dataclass(frozen=True)
class WebMoment:
    throw: str
    web: int  # 1 front, 2 rear
    z: float  # m, the web's mid-plane
    bending_moment_nm: np.ndarray  # (n, 2) N m, engine frame (M_x, M_y)


@dataclass(frozen=True)
class ShaftCycle:
    crank_angle_deg: np.ndarray  # (n,) cycle angle
    speed: float  # rad/s
    bearings: tuple[BearingLoads, ...]
    webs: tuple[WebMoment, ...]
    weights: np.ndarray  # (n, n_cases) of ShaftCases.names (redundant bearings' forces included)
    displacement: np.ndarray  # (n, n_bearings, 2) m, bearings' radial displacements, shaft frame
    counterweights: bool


def _to_engine(v: np.ndarray, psi: np.ndarray) -> np.ndarray:
    c, s = np.cos(psi), np.sin(psi)
    return np.stack([c * v[..., 0] + s * v[..., 1], -s * v[..., 0] + c * v[..., 1]], axis=-1)


def case_weights(
    cases: ShaftCases,
    loads: dict[str, np.ndarray],
    speed: float,
    counterweights: bool,
    extra: dict[str, np.ndarray] | None = None,
) -> np.ndarray:
    """(n, n_cases) weights of the applied cases (pins, centrifugal, ``extra``: further
    cases by name, (n,) each); bearing cases zero."""
    n = next(iter(loads.values())).shape[0]
    W = np.zeros((n, len(cases.names)))
    for name, w in (extra or {}).items():
        W[:, cases.index(name)] = w
    for pp in cases.model.pieces:
        if pp.kind != "throw":
            continue
        if pp.throw not in loads:
            raise InputError(f"no pin force for throw {pp.throw!r}")
        names = [f"{p}@{pp.throw}" for p in pin_cases()]
        W[:, [cases.index(x) for x in names]] += pin_case_weights(loads[pp.throw], pin_cases())
    W[:, cases.index("centrifugal")] = speed**2
    W[:, cases.index("centrifugal_cw")] = speed**2 if counterweights else 0.0
    return W


def solve_cycle(cases: ShaftCases, W: np.ndarray, laws) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Bearing forces on the shaft (n, nb, 2), displacements (n, nb, 2) (shaft frame), and
    W with the redundant bearings' forces filled in."""
    nb = cases.d.shape[0]
    A, B = cases.base_bearings
    red = list(cases.redundant)
    unit = [cases.index(f"{cases.model.bearings[j].name}.{c}") for j in red for c in "xy"]
    applied = [i for i in range(len(cases.names)) if i not in unit]
    C = cases.d_rel[red][:, :, unit].reshape(2 * len(red), len(unit))
    Q = cases.base[:4][:, unit]
    z = np.array([b.z for b in cases.model.bearings])
    sysb = BearingSystem(tuple(laws), (A, B), tuple(red), C, Q, (z - z[A]) / (z[B] - z[A]))
    Wa = W[:, applied]
    d0 = Wa @ cases.d_rel[:, :, applied].reshape(2 * nb, -1).T
    R0 = np.zeros_like(d0)
    base = Wa @ cases.base[:4][:, applied].T
    R0[:, 2 * A : 2 * A + 2], R0[:, 2 * B : 2 * B + 2] = base[:, :2], base[:, 2:]
    f, d = bearing_forces(sysb, d0, R0)
    W = W.copy()
    W[:, unit] = f[:, red].reshape(f.shape[0], -1)
    return f, d, W


def journal_slopes(cases: ShaftCases, W: np.ndarray, d: np.ndarray) -> np.ndarray | None:
    """(n, n_bearings, 2) the journals' mean slopes (dx/dz, dy/dz, shaft frame) in their
    bearings at every angle: the unit cases' (``ShaftCases.slope``, relative to the base
    line) weighted by ``W`` (bearing forces filled in), plus the base line's own slope
    from the base bearings' displacements ``d`` (n, n_bearings, 2) under their laws."""
    if cases.slope is None:
        return None
    nb = cases.slope.shape[0]
    A, B = cases.base_bearings
    z = np.array([b.z for b in cases.model.bearings])
    out = (W @ cases.slope.reshape(2 * nb, -1).T).reshape(W.shape[0], nb, 2)
    return out + ((d[:, B] - d[:, A]) / (z[B] - z[A]))[:, None, :]


def law_text(law) -> str:
    """A bearing law in words: "rigid", "spring 1e+09 N/m", "clearance 40 um, 2e+09 N/m"."""
    if law.model == "rigid":
        return "rigid"
    if law.model == "spring":
        return f"spring {law.stiffness:.3g} N/m"
    return f"clearance {law.clearance * 1e6:.3g} um, {law.stiffness:.3g} N/m"


def bearing_loads(
    layout, f: np.ndarray, cycle_angle: np.ndarray, shaft_angle: np.ndarray, laws, slopes: np.ndarray | None = None
) -> tuple:
    """``BearingLoads`` of every bearing from the bearings' forces on the shaft ``f``
    (n, nb, 2), shaft frame, under ``laws``; ``slopes`` (n, nb, 2), shaft frame: the
    journals' slopes in their bearings (``journal_slopes``), None where not computed."""
    deg = np.rad2deg(cycle_angle)
    dj = layout.geometry.journal_diameter
    out = []
    for j, b in enumerate(layout.bearings):
        load = _to_engine(-f[:, j], shaft_angle)
        mag = np.hypot(load[:, 0], load[:, 1])
        k = int(np.argmax(mag))
        out.append(
            BearingLoads(
                b.name,
                b.z,
                b.width,
                dj,
                load,
                float(mag[k]),
                float(mag.mean()),
                float(deg[k]),
                float(mag[k] / (dj * b.width)),
                float(mag.mean() / (dj * b.width)),
                law_text(laws[j]),
                None if slopes is None else _to_engine(slopes[:, j], shaft_angle),
            )
        )
    return tuple(out)


def _weights(cases, loads, speed, counterweights, front_torque, ends=()):
    by = {t.throw: np.asarray(t.pin_force, float) for t in loads}
    extra = {f"spin_up@{t.throw}": np.asarray(t.spin_up, float) for t in loads if t.spin_up is not None}
    if front_torque is not None:
        extra["torque_front"] = np.asarray(front_torque, float)
    for e in ends:
        F = np.asarray(e.force, float) * (1.0 if counterweights or not e.counterweight else 0.0)
        extra[f"{e.name}.x"], extra[f"{e.name}.y"] = F[:, 0], F[:, 1]
    return by, case_weights(cases, by, speed, counterweights, extra)


def bearing_cycle(
    cases: ShaftCases,
    loads: tuple[ThrowCycleLoad, ...],
    cycle_angle: np.ndarray,
    shaft_angle: np.ndarray,
    speed: float,
    *,
    counterweights: bool = True,
    laws=None,
    front_torque: np.ndarray | None = None,
    ends: tuple[EndCycleLoad, ...] = (),
) -> tuple[BearingLoads, ...]:
    """The main bearings' loads alone (``shaft_cycle`` without its web moments and weights):
    another bearing law on the same cycle costs one bearing solve."""
    return bearing_solve(
        cases,
        loads,
        cycle_angle,
        shaft_angle,
        speed,
        counterweights=counterweights,
        laws=laws,
        front_torque=front_torque,
        ends=ends,
    )[0]


def bearing_solve(
    cases: ShaftCases,
    loads: tuple[ThrowCycleLoad, ...],
    cycle_angle: np.ndarray,
    shaft_angle: np.ndarray,
    speed: float,
    *,
    counterweights: bool = True,
    laws=None,
    front_torque: np.ndarray | None = None,
    ends: tuple[EndCycleLoad, ...] = (),
) -> tuple[tuple[BearingLoads, ...], np.ndarray]:
    """``bearing_cycle`` and the case weights of its solve (``ShaftCycle.weights``: the same
    numbers ``shaft_cycle`` gives for this law), without the web moments."""
    layout = cases.model.mesh.layout
    laws = laws or [b.law for b in layout.bearings]
    _, W = _weights(cases, loads, speed, counterweights, front_torque, ends)
    f, d, W = solve_cycle(cases, W, laws)
    return bearing_loads(layout, f, cycle_angle, shaft_angle, laws, journal_slopes(cases, W, d)), W


def shaft_cycle(
    cases: ShaftCases,
    loads: tuple[ThrowCycleLoad, ...],
    cycle_angle: np.ndarray,
    shaft_angle: np.ndarray,
    speed: float,
    mass,
    *,
    counterweights: bool = True,
    laws=None,
    front_torque: np.ndarray | None = None,
    ends: tuple[EndCycleLoad, ...] = (),
) -> ShaftCycle:
    """The cycle (module doc).  ``cycle_angle`` (n,) rad; ``shaft_angle`` psi (n,) rad;
    ``speed`` rad/s; ``mass``: throw name -> ``geometry.mass.MassProperties`` of its solid;
    ``laws``: per bearing (default the layout's); ``front_torque`` (n,): the weight of the
    ``torque_front`` case (M_z on the shaft's front face), with the throws' ``spin_up``;
    ``ends``: the loads beyond the shaft's ends (flywheel, pulley)."""
    layout = cases.model.mesh.layout
    laws = laws or [b.law for b in layout.bearings]
    by, W = _weights(cases, loads, speed, counterweights, front_torque, ends)
    f, d, W = solve_cycle(cases, W, laws)
    bearings = bearing_loads(layout, f, cycle_angle, shaft_angle, laws, journal_slopes(cases, W, d))
    spin = {t.throw: np.asarray(t.spin_up, float) for t in loads if t.spin_up is not None}
    webs = _web_moments(cases, by, f, speed, shaft_angle, mass, counterweights, spin, ends)
    return ShaftCycle(np.rad2deg(cycle_angle), speed, bearings, webs, W, d, counterweights)


def _web_moments(cases, by, f, speed, psi, mass, counterweights, spin=None, ends=()) -> tuple[WebMoment, ...]:
    layout = cases.model.mesh.layout
    g = layout.geometry
    zp, t = g.crankpin_length / 2, g.web_thickness
    spin = spin or {}
    # loads on the shaft as (z, force (n, 2) shaft frame)
    items = []
    for th in layout.throws:
        R = rotation(layout.sense * th.angle)[:2, :2]
        items.append((th.z, by[th.name] @ R.T))
        for z0, z1, u in _mass_pieces(mass[th.name], g, th.spec, counterweights):
            F = np.broadcast_to(speed**2 * (R @ u), f[:, 0].shape)
            items.append(((th.z + z0, th.z + z1), F) if z1 > z0 else (th.z + z0, F))
        if th.name in spin:  # the body force of the spin-up case, rho (e_z x x): resultant e_z x (m c) per part
            for z0, z1, u in _mass_pieces(mass[th.name], g, th.spec, True):
                F = spin[th.name][:, None] * (R @ np.array([-u[1], u[0]]))[None, :]
                items.append(((th.z + z0, th.z + z1), F) if z1 > z0 else (th.z + z0, F))
    for j, b in enumerate(layout.bearings):
        items.append((b.z, f[:, j]))
    for e in ends:
        if counterweights or not e.counterweight:
            items.append((e.z, np.asarray(e.force, float)))
    out = []
    for th in layout.throws:
        for web, zc in ((1, th.z - zp - t / 2), (2, th.z + zp + t / 2)):
            M = np.zeros_like(f[:, 0])
            for where, F in items:
                if isinstance(where, tuple):  # a prism part over [z0, z1]: its share in front
                    z0, z1 = where
                    a, b_ = z0, min(z1, zc)
                    if b_ <= a:
                        continue
                    share, lever = (b_ - a) / (z1 - z0), 0.5 * (a + b_) - zc
                    F = share * F
                else:
                    if where >= zc:
                        continue
                    lever = where - zc
                M += lever * np.stack([-F[:, 1], F[:, 0]], axis=-1)
            out.append(WebMoment(th.name, web, zc, _to_engine(M, psi)))
    return tuple(out)


def _mass_pieces(mp, g, spec, counterweights: bool):
    """(z0, z1, unbalance (2,) kg m) of each part of a throw along z (throw frame): webs and
    counterweights are prisms over [z0, z1] (a counterweight the spec does not size, a
    drawn one, over its web's thickness); the other parts, never cut by a web's
    mid-plane, act at their centroid (z0 = z1)."""
    zp, t, L = g.crankpin_length / 2, g.web_thickness, g.journal_length
    span = {
        "journal_1": (-zp - t - L, -zp - t),
        "web_1": (-zp - t, -zp),
        "crankpin": (-zp, zp),
        "web_2": (zp, zp + t),
        "journal_2": (zp + t, zp + t + L),
    }
    for cw in spec.counterweights:
        span[f"counterweight_{cw.web}"] = (
            (-zp - t, -zp - t + cw.thickness) if cw.web == 1 else (zp + t - cw.thickness, zp + t)
        )
    out = []
    for name, part in mp.parts.items():
        if name.startswith("counterweight") and not counterweights:
            continue
        # a counterweight the spec does not size (a drawn one, ``cad.whole``): over its web's thickness
        z0, z1 = span.get(name, span.get(name.replace("counterweight", "web"), (0.0, 0.0)))
        if not name.startswith(("web", "counterweight")):
            z0 = z1 = part.centroid[2]
        out.append((z0, z1, np.asarray(part.unbalance_vector)))
    return out
