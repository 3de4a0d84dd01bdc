"""``fe-crank balance FILE [-o DIR]``: free forces and moments by order and source,
counterweight design and residual; hodograph PNGs and a JSON summary.

FILE is a load case (speed and ``[balance]`` taken from it) or an engine file (then
``--speed`` is required; counterweights balance the rotating masses per throw unless
``--fraction`` / ``--couple`` / ``--planes`` say otherwise).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.files import write_atomic
from fe_crank.io.base import read_toml
from fe_crank.report.stage_plots import plot_hodographs


def add_arguments(p) -> None:
    p.add_argument("file", type=Path, help="load-case or engine .toml file")
    p.add_argument(
        "-o",
        "--output",
        type=Path,
        default=Path("reports"),
        metavar="DIR",
        help="folder for balance.json and the hodograph PNGs (default: reports/)",
    )
    p.add_argument("--speed", default=None, help='speed for an engine file, with its unit, e.g. "3000 rpm"')
    p.add_argument(
        "--fraction",
        type=float,
        default=None,
        help="share of the first-order reciprocating mass balanced by counterweights (engine file)",
    )
    p.add_argument(
        "--couple",
        choices=("per_throw", "whole_shaft"),
        default=None,
        help="counterweight couple balance (engine file)",
    )
    p.add_argument(
        "--planes", default=None, help='counterweight planes for whole_shaft, e.g. "-100 mm, 100 mm" (engine file)'
    )
    p.add_argument("--no-plots", action="store_true", help="skip the hodograph PNGs")


def _settings_from_args(args, file: Path):
    from fe_crank.io.balance import parse_balance

    table = {}
    if args.fraction is not None:
        table["reciprocating_fraction"] = args.fraction
    if args.couple is not None:
        table["couple"] = args.couple
    if args.planes is not None:
        table["planes"] = [s.strip() for s in args.planes.split(",") if s.strip()]
    return parse_balance(table, file, "command line")


def load_inputs(args):
    """(engine, speed, settings) from a load case or an engine file."""
    data = read_toml(args.file)
    if "operating" in data or "engine" in data:
        from fe_crank.io.loadcase import load_loadcase

        lc = load_loadcase(args.file)
        if args.speed is not None:
            raise InputError("--speed is only for engine files; the load case gives [operating].speed", key="--speed")
        settings = lc.balance
        if any(v is not None for v in (args.fraction, args.couple, args.planes)):
            settings = _settings_from_args(args, args.file)
        return lc.engine, lc.operating.speed, settings
    from fe_crank.io.engine import load_engine
    from fe_crank.io.units import to_si

    engine = load_engine(args.file)
    if args.speed is None:
        raise InputError('an engine file needs --speed, e.g. --speed "3000 rpm"', file=str(args.file), key="--speed")
    try:
        speed = to_si(args.speed, "speed")
    except ValueError as exc:
        raise InputError(str(exc), key="--speed") from None
    return engine, speed, _settings_from_args(args, args.file)


def _fmt(x: float) -> str:
    return f"{x:10.4g}"


def format_report(res) -> str:
    from fe_crank.balance.analysis import forces_table

    lines = [
        f"balance of '{res.engine}' at {res.speed * 30 / math.pi:.0f} rpm "
        f"(moments about z = {res.forces.reference_z * 1e3:.4g} mm)",
        "",
        "free forces and moments (amplitudes: semi-axes of the hodograph ellipse)",
        f"{'source':<15}{'order':>6} {'F max N':>10} {'F min N':>10} {'kind':>8} {'tilt deg':>9} "
        f"{'M max N m':>10} {'M min N m':>10} {'kind':>8}",
    ]
    for r in forces_table(res.forces):
        lines.append(
            f"{r['source']:<15}{r['order']:>6g} {_fmt(r['force_max'])} {_fmt(r['force_min'])} "
            f"{r['force_kind']:>8} {r['force_tilt_deg']:9.2f} {_fmt(r['moment_max'])} "
            f"{_fmt(r['moment_min'])} {r['moment_kind']:>8}"
        )
    from fe_crank.balance.analysis import exact_peak

    ex = exact_peak(res.forces)
    lines.append(
        f"{'recip. exact':<15}{'all':>6} {_fmt(ex['force_max'])} {'':>10} {'peak':>8} {'':>9} {_fmt(ex['moment_max'])}"
    )
    st = res.design.strategy
    lines += [
        "",
        f"counterweights: rotating {st.rotating_fraction:g}, first-order reciprocating "
        f"{st.reciprocating_fraction:g}, couple {st.couple}",
        f"{'shaft':<8}{'z mm':>9} {'m r kg m':>10} {'angle deg':>10}  sector",
    ]
    for cw, sec in zip(res.design.counterweights, res.sectors):
        s = (
            ""
            if sec is None
            else (
                f"r1 {sec.r_outer * 1e3:.1f} r2 {sec.r_inner * 1e3:.1f} b {sec.thickness * 1e3:.1f} mm "
                f"{math.degrees(sec.angle):.1f} deg: m {sec.mass:.4g} kg at {sec.centroid_radius * 1e3:.2f} mm"
            )
        )
        lines.append(
            f"{cw.shaft:<8}{cw.z * 1e3:9.2f} {cw.unbalance:10.4g} {math.degrees(cw.angle_on_shaft):10.2f}  {s}"
        )
    for d in res.shafts:
        lines += ["", f"balance shafts for the order-{d.order} {d.component}:"]
        for s in d.shafts:
            lines.append(
                f"  {s.name:<16} speed {s.speed_ratio:+d} x crank, m r {s.unbalance:.4g} kg m at "
                f"{math.degrees(s.angle):.1f} deg, z {', '.join(f'{z * 1e3:.1f}' for z in s.z)} mm; {s.constraint}"
            )
    lines += [
        "",
        "residual after counterweights and balance shafts (all sources)",
        f"{'order':>6} {'F max N':>10} {'M max N m':>10}",
    ]
    for r in forces_table(res.residual):
        if r["source"] == "total":
            lines.append(f"{r['order']:>6g} {_fmt(r['force_max'])} {_fmt(r['moment_max'])}")
    return "\n".join(lines)


def run(args) -> int:
    from fe_crank.balance.analysis import analyse_balance, result_to_dict

    engine, speed, settings = load_inputs(args)
    try:
        res = analyse_balance(engine, speed, settings)
    except InputError as exc:
        if exc.file:
            raise
        raise InputError(exc.reason, file=str(args.file), key=exc.key) from None
    print(format_report(res))
    if args.output is not None:
        out = Path(args.output)
        write_atomic(out / "balance.json", json.dumps(result_to_dict(res), indent=2).encode())
        written = [out / "balance.json"]
        if not args.no_plots:
            written += plot_hodographs(res, out)
        print("", *(f"wrote {p}" for p in written), sep="\n")
    return 0
