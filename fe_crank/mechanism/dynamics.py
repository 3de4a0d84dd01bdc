"""Engine dynamics over one working cycle: forces, torque, crankpin and bearing loads.

Per cylinder the exact slider-crank dynamics of ``fe_crank.mechanism.slider_crank`` (piston and
rigid rod at constant crank speed, no lambda series; Kolchin & Demidov, *Design of
automotive engines*, ch. 4-5; Heywood, *Internal Combustion Engine Fundamentals*,
sec. 2.2 and 13.2), with the gas force ``F_g = (p - p_cc) A`` of the engine's pressure
table.

All angles and frames as in ``fe_crank/model.py``.  A cylinder's frame has ``u``
along its axis towards the head and ``w`` towards the side its crankpin moves to
just after TDC.  Reported per cylinder (arrays over the cycle grid):

* ``gas``: ``F_g``, N, positive towards the crank axis;
* ``inertia``: classical reciprocating inertia force ``-m_j a`` with
  ``m_j = m_p + m c / l``, N, positive towards the crank axis (for reference: the
  exact solution below does not use the split);
* ``rod_force``: component along the rod (compression positive) of the force the rod
  exerts on the piston pin, N (with the two-mass model this is the link force
  ``(F_g - m_j a)/cos(beta)`` less the small-end mass's own inertia);
* ``side_thrust``: force of the piston on the cylinder wall along ``w``, N;
* ``tangential``, ``radial``: force of the rod on the crankpin, tangential in the
  sense of rotation and radial outward from the shaft axis, N;
* ``torque``: ``tangential * r``, N m, positive driving.

Per throw: the crankpin load in the throw frame (x tangential for sense +1, y radially
outward; all rods summed, crank's own rotating mass excluded; each rod's own: ``rods``),
the journal torques either side (cumulative from the free end, the front, of each
shaft, statically determinate as in IACS UR M53) and the main-bearing loads from
the simply supported split (the pin at mid-span between its two bearings, each
taking half of the pin load plus the centrifugal force of the throw's rotating
mass; counterweights are not included here: the balance stage adds them).

Engine totals: torque reduced to the reference shaft (``sum T_s * speed_ratio_s``,
power-equivalent), mean indicated torque and power, torque non-uniformity
``(T_max - T_min) / T_mean`` and the flywheel inertia
``J = dE_max / (delta omega^2)`` for a coefficient of speed fluctuation
``delta = (omega_max - omega_min) / omega_mean`` (Kolchin & Demidov, ch. 5).

Articulated (link) rods are treated as plain rods on the crankpin here; their exact
kinematics belong to the balance stage.  Gravity is neglected (it is below 0.1 % of
the inertia forces at running speed).
"""

from __future__ import annotations

import numpy as np

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.mechanism.gas import pressure_at
from fe_crank.mechanism.results import CylinderForces, DynamicsResult, RodLoad, ThrowLoads
from fe_crank.mechanism.slider_crank import solve_cylinder

__all__ = ["CylinderForces", "RodLoad", "ThrowLoads", "DynamicsResult", "analyse", "solve_cylinder", "cylinder_angle"]


def cylinder_angle(engine: model.Engine, cyl: model.Cylinder, theta) -> np.ndarray:
    """Crank angle ``phi`` of a cylinder (from its axis, in its shaft's sense) at cycle
    angle ``theta``: the crankpin lies at the global angle
    ``gamma = phase + sense (ratio theta + throw.angle)`` and
    ``phi = sense (gamma - bank_angle)``."""
    throw = engine.throw(cyl.throw)
    shaft = engine.shaft(throw.shaft)
    theta = np.asarray(theta, dtype=float)
    return shaft.sense * (shaft.phase - cyl.bank_angle) + shaft.speed_ratio * theta + throw.angle


def _grid(cycle: float, step: float) -> np.ndarray:
    if not step > 0:
        raise InputError(f"angle step must be positive (got {step} rad)", key="step")
    n = int(round(cycle / step))
    if n < 8:
        raise InputError(f"angle step {np.degrees(step):.4g} deg is too coarse for the cycle", key="step")
    return cycle * np.arange(n) / n


def analyse(
    engine: model.Engine,
    operating: model.OperatingPoint,
    *,
    step: float = np.radians(1.0),
    speed_fluctuation: float = 0.01,
    cylinder_gas: dict | None = None,
) -> DynamicsResult:
    """Forces and torques of the whole engine over one cycle (module docstring).

    Parameters
    ----------
    engine, operating
        Frozen engine and operating point (SI).
    step : float
        Cycle-angle step, rad; the cycle is split into ``round(cycle / step)`` equal steps.
    speed_fluctuation : float
        Target coefficient ``delta`` for the flywheel inertia.
    cylinder_gas : dict, optional
        Cylinder name -> its own ``GasPressure`` (None: zero gauge pressure) instead of
        the engine's, e.g. a misfiring cylinder's motored curve.
    """
    cycle = engine.cycle_angle
    theta = _grid(cycle, step)
    omega = operating.speed
    warnings: list[str] = []
    if engine.gas is None:
        warnings.append("engine has no gas pressure: inertia forces only")
    cylinders: dict[str, CylinderForces] = {}
    work = 0.0
    for cyl in engine.cylinders:
        throw = engine.throw(cyl.throw)
        shaft = engine.shaft(throw.shaft)
        phi = cylinder_angle(engine, cyl, theta)
        # firing TDC: phi at the firing offset, rounded to its revolution
        phi_f = float(cylinder_angle(engine, cyl, cyl.firing_offset))
        turns = np.round(phi_f / (2 * np.pi))
        if abs(phi_f - 2 * np.pi * turns) > 1e-6:
            warnings.append(
                f"cylinder {cyl.name}: firing_offset {np.degrees(cyl.firing_offset):.6g} deg is not at its TDC "
                f"(crank {np.degrees(phi_f - 2 * np.pi * turns):.6g} deg from the axis); the gas table is "
                "applied from the nearest TDC"
            )
        gas_angle = np.mod(phi - 2 * np.pi * turns, cycle)
        gas = (cylinder_gas or {}).get(cyl.name, engine.gas)
        if gas is not None:
            p = pressure_at(gas, gas_angle, cycle)
            pcc = gas.crankcase_pressure
        else:
            p = np.full_like(theta, 101325.0)
            pcc = 101325.0
        area = cyl.piston_area
        fg = (p - pcc) * area
        rod = cyl.rod
        sol = solve_cylinder(
            phi,
            r=throw.crank_radius,
            l=rod.length,
            omega=omega * shaft.speed_ratio,
            gas_force=fg,
            piston_mass=cyl.piston_mass,
            rod_mass=rod.mass,
            rod_cg=rod.cg_from_big_end,
            rod_inertia=rod.inertia_cg,
            offset=cyl.pin_offset,
        )
        m = sol["motion"]
        m_j = cyl.piston_mass + rod.mass * rod.reciprocating_fraction
        vol = area * m.s
        # closed integral of p dV over the cycle (periodic trapezoid)
        dv = np.roll(vol, -1) - vol
        pm = 0.5 * (p + np.roll(p, -1))
        work += float(np.sum(pm * dv))
        cylinders[cyl.name] = CylinderForces(
            name=cyl.name,
            throw=cyl.throw,
            phi=phi,
            gas_angle=gas_angle,
            pressure=p,
            motion=m,
            gas=fg,
            inertia=-m_j * m.a,
            rod_force=sol["rod_force"],
            side_thrust=sol["side_thrust"],
            tangential=sol["tangential"],
            radial=sol["radial"],
            torque=sol["torque"],
            volume_swept=vol,
        )

    throws: dict[str, ThrowLoads] = {}
    shaft_torque: dict[str, np.ndarray] = {}
    for shaft in engine.shafts:
        on_shaft = sorted((t for t in engine.throws if t.shaft == shaft.name), key=lambda t: t.axial_position)
        cumulative = np.zeros_like(theta)
        for t in on_shaft:
            cyls = [c for c in engine.cylinders if c.throw == t.name]
            cf = [cylinders[c.name] for c in cyls]
            xy = [np.column_stack([shaft.sense * f.tangential, f.radial]) for f in cf]
            rods = tuple(RodLoad(c.name, f, c.pin_position) for c, f in zip(cyls, xy))
            tq = sum((f.torque for f in cf), np.zeros_like(theta))
            pin = sum((r.pin_force for r in rods), np.zeros((theta.size, 2)))
            gamma = model.crank_angle_global(engine, t.name, theta)
            ey = np.stack([np.sin(gamma), np.cos(gamma)], axis=-1)
            ex = np.stack([np.cos(gamma), -np.sin(gamma)], axis=-1)
            w = omega * shaft.speed_ratio
            centrifugal = t.rotating_mass * t.crank_radius * w**2
            total_global = pin[:, :1] * ex + (pin[:, 1:] + centrifugal) * ey
            front = cumulative.copy()
            cumulative = cumulative + tq
            throws[t.name] = ThrowLoads(
                name=t.name,
                shaft=shaft.name,
                angle_global=gamma,
                pin_force=pin,
                torque=tq,
                torque_front=front,
                torque_rear=cumulative.copy(),
                bearing_front=0.5 * total_global,
                bearing_rear=0.5 * total_global,
                rods=rods,
            )
        shaft_torque[shaft.name] = cumulative

    torque = np.sum([shaft_torque[s.name] * s.speed_ratio for s in engine.shafts], axis=0)
    mean_torque = float(np.mean(torque))
    power = mean_torque * omega
    if abs(mean_torque) > 0:
        nonuni = float((torque.max() - torque.min()) / mean_torque)
    else:
        nonuni = float("inf")
    # excess work E(theta) = int (T - T_mean) dtheta (trapezoid, periodic)
    dtheta = cycle / theta.size
    excess = np.concatenate(
        [[0.0], np.cumsum(0.5 * ((torque - mean_torque) + np.roll(torque - mean_torque, -1)) * dtheta)]
    )
    de = float(excess.max() - excess.min())
    if not speed_fluctuation > 0:
        raise InputError(f"speed_fluctuation must be positive (got {speed_fluctuation})", key="speed_fluctuation")
    j_fly = de / (speed_fluctuation * omega**2)
    return DynamicsResult(
        engine=engine.name,
        speed=omega,
        theta=theta,
        cycle=cycle,
        cylinders=cylinders,
        throws=throws,
        shaft_torque=shaft_torque,
        torque=torque,
        mean_torque=mean_torque,
        power=power,
        torque_nonuniformity=nonuni,
        indicated_work=work,
        speed_fluctuation=speed_fluctuation,
        excess_energy=de,
        flywheel_inertia=j_fly,
        warnings=tuple(warnings),
    )
