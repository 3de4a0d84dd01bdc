"""``fe-crank dynamics FILE [-o DIR]``: kinematics and dynamics over the cycle.

Writes into DIR (each file atomically: a temporary file in DIR, then renamed):

* ``dynamics.json``: summary and every cycle array (SI units, listed under ``units``);
* ``piston_motion.png``, ``forces.png``, ``torque.png``, ``crankpin_polar.png``.

Prints a summary table on stdout.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from fe_crank.errors import InputError
from fe_crank.files import write_atomic
from fe_crank.report.stage_plots import dynamics_plots

PLOTS = ("piston_motion.png", "forces.png", "torque.png", "crankpin_polar.png")


def add_arguments(p) -> None:
    p.add_argument("file", type=Path, help="load-case .toml file (engine + operating point)")
    p.add_argument(
        "-o",
        "--output",
        type=Path,
        default=Path("reports"),
        metavar="DIR",
        help="folder for dynamics.json and the plots (default: reports/)",
    )
    p.add_argument("--step", type=float, default=1.0, help="crank-angle step in degrees (default 1)")
    p.add_argument(
        "--speed-fluctuation",
        type=float,
        default=0.01,
        help="target coefficient of speed fluctuation for the flywheel (default 0.01)",
    )
    p.add_argument("--no-plots", action="store_true", help="write the JSON only")


def _round(a, digits=6):
    return [float(f"{x:.{digits}g}") for x in np.asarray(a, float).ravel()]


def result_to_dict(res, loadcase) -> dict:
    """Everything of a DynamicsResult as plain JSON-able data (SI)."""
    cyls = {}
    for name, c in res.cylinders.items():
        m = c.motion
        cyls[name] = {
            "throw": c.throw,
            "phi": _round(c.phi),
            "gas_angle": _round(c.gas_angle),
            "pressure": _round(c.pressure),
            "s": _round(m.s),
            "v": _round(m.v),
            "a": _round(m.a),
            "beta": _round(m.beta),
            "beta_dot": _round(m.beta_dot),
            "beta_ddot": _round(m.beta_ddot),
            "gas": _round(c.gas),
            "inertia": _round(c.inertia),
            "rod_force": _round(c.rod_force),
            "side_thrust": _round(c.side_thrust),
            "tangential": _round(c.tangential),
            "radial": _round(c.radial),
            "torque": _round(c.torque),
        }
    throws = {}
    for name, t in res.throws.items():
        throws[name] = {
            "shaft": t.shaft,
            "pin_force_x": _round(t.pin_force[:, 0]),
            "pin_force_y": _round(t.pin_force[:, 1]),
            "pin_force_max": float(t.pin_force_magnitude.max()),
            "pin_force_mean": float(t.pin_force_magnitude.mean()),
            "torque": _round(t.torque),
            "torque_front": _round(t.torque_front),
            "torque_rear": _round(t.torque_rear),
            "bearing_front_x": _round(t.bearing_front[:, 0]),
            "bearing_front_y": _round(t.bearing_front[:, 1]),
            "bearing_rear_x": _round(t.bearing_rear[:, 0]),
            "bearing_rear_y": _round(t.bearing_rear[:, 1]),
        }
    return {
        "load_case": loadcase.name,
        "source_file": loadcase.source_file,
        "engine": res.engine,
        "speed": res.speed,
        "speed_rpm": res.speed * 30.0 / np.pi,
        "summary": {
            "mean_torque": res.mean_torque,
            "power": res.power,
            "indicated_work": res.indicated_work,
            "torque_max": float(res.torque.max()),
            "torque_min": float(res.torque.min()),
            "torque_nonuniformity": res.torque_nonuniformity,
            "speed_fluctuation": res.speed_fluctuation,
            "excess_energy": res.excess_energy,
            "flywheel_inertia": res.flywheel_inertia,
        },
        "warnings": list(res.warnings),
        "units": {
            "angles": "rad",
            "force": "N",
            "torque": "N m",
            "pressure": "Pa",
            "length": "m",
            "velocity": "m/s",
            "acceleration": "m/s^2",
            "power": "W",
            "energy": "J",
            "inertia": "kg m^2",
            "frames": "pin_force: throw frame (x tangential for sense +1, "
            "y radial outward); bearings: engine frame (x, y)",
        },
        "theta": _round(res.theta),
        "torque": _round(res.torque),
        "shaft_torque": {k: _round(v) for k, v in res.shaft_torque.items()},
        "cylinders": cyls,
        "throws": throws,
    }


def run(args) -> int:
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.dynamics import analyse

    if not args.step > 0 or not np.isfinite(args.step):
        raise InputError(f"--step must be a positive number of degrees (got {args.step})", key="--step")
    if not args.speed_fluctuation > 0:
        raise InputError(
            f"--speed-fluctuation must be positive (got {args.speed_fluctuation})", key="--speed-fluctuation"
        )
    lc = load_loadcase(args.file)
    res = analyse(lc.engine, lc.operating, step=np.radians(args.step), speed_fluctuation=args.speed_fluctuation)
    out: Path = args.output
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"cannot create output folder: {exc.strerror}", file=str(out)) from None
    data = result_to_dict(res, lc)
    write_atomic(out / "dynamics.json", json.dumps(data, indent=1))
    if not args.no_plots:
        dynamics_plots(res, out)

    s = data["summary"]
    rows = [
        ("engine", res.engine, ""),
        ("speed", f"{data['speed_rpm']:.1f}", "rpm"),
        ("mean indicated torque", f"{s['mean_torque']:.2f}", "N m"),
        ("indicated power", f"{s['power'] / 1e3:.3f}", "kW"),
        ("indicated work per cycle", f"{s['indicated_work']:.2f}", "J"),
        ("torque max / min", f"{s['torque_max']:.1f} / {s['torque_min']:.1f}", "N m"),
        ("torque non-uniformity", f"{s['torque_nonuniformity']:.3f}", "-"),
        (f"flywheel inertia (delta = {res.speed_fluctuation:g})", f"{s['flywheel_inertia']:.4g}", "kg m^2"),
    ]
    for name, t in res.throws.items():
        rows.append(
            (
                f"crankpin {name} load max / mean",
                f"{t.pin_force_magnitude.max() / 1e3:.2f} / {t.pin_force_magnitude.mean() / 1e3:.2f}",
                "kN",
            )
        )
    w = max(len(r[0]) for r in rows)
    for k, v, u in rows:
        print(f"{k:<{w}}  {v} {u}".rstrip())
    for msg in res.warnings:
        print(f"warning: {msg}")
    print(f"written: {out / 'dynamics.json'}" + ("" if args.no_plots else f" and {len(PLOTS)} plots"))
    return 0
