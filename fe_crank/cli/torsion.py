"""``fe-crank torsion CASE -o DIR``: torsional vibration of the crank train.

Needs the load case's ``[torsion]`` section (docs/torsion.md).  Writes into DIR
``torsion.json`` (natural frequencies, mode shapes, resonances in the speed range,
vibratory torque of every shaft segment vs speed, the governing speed of each segment)
and ``campbell.png``, ``torsion_response.png``, ``torsion_modes.png``; prints a summary.
``--fe-stiffness`` also meshes one throw and measures its stiffness with the FE model as
the check does (always done when the section says ``throw_stiffness = "fe"``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, cast

from fe_crank.errors import InputError
from fe_crank.files import write_atomic

if TYPE_CHECKING:
    from fe_crank.io.loadcase import LoadCase


def add_arguments(p) -> None:
    p.add_argument("file", type=Path, help="load-case .toml file with a [torsion] section")
    p.add_argument(
        "-o",
        "--output",
        type=Path,
        default=Path("reports"),
        metavar="DIR",
        help="output folder (created if missing; default: reports/)",
    )
    p.add_argument(
        "--fe-stiffness",
        action="store_true",
        help="also measure the throw stiffness on the FE throw model and report it beside Carter's",
    )
    p.add_argument("--mesh-size", default=None, help="mesh preset for --fe-stiffness (default: the case's [mesh])")
    p.add_argument(
        "--cache-dir",
        type=Path,
        default=Path(".cache/meshes"),
        metavar="DIR",
        help="mesh cache folder (default: .cache/meshes)",
    )
    p.add_argument("--no-plots", action="store_true", help="write the JSON only")


def fe_stiffness_of(lc: LoadCase, size: str | None, cache_dir) -> float:
    """The FE throw stiffness the check's chain takes (N m/rad, FE span): the torque unit
    case of the first throw model of the check's mesh plan at ``size`` (default: the
    case's ``[mesh]``), ``torsion.stiffness.plan_throw_stiffness``."""
    from fe_crank.geometry.spec import CrankGeometry
    from fe_crank.mesh.plan import plan_meshes
    from fe_crank.pipeline.stages import shaft_layout
    from fe_crank.torsion.stiffness import plan_throw_stiffness

    if not isinstance(lc.geometry, CrankGeometry) or lc.material is None:
        raise InputError(
            "the FE throw stiffness needs a parametric geometry and the [material] section", file=lc.source_file
        )
    plan = plan_meshes(
        lc.geometry,
        tuple(t.name for t in lc.engine.throws),
        lc.mesh,
        size=size,
        cache_dir=str(cache_dir) if cache_dir is not None else None,
        file=lc.source_file,
        shaft=shaft_layout(lc),
    )
    k = plan_throw_stiffness(lc.geometry, plan, lc.material, lc.fe)
    assert k is not None  # the [fe] section holds the torque case (fe.input)
    return k


def run(args) -> int:
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.cycles import engine_cycles
    from fe_crank.report.torsion import RPM, governing_table, result_to_dict, stiffness_text, write_plots
    from fe_crank.torsion import analyse_torsion
    from fe_crank.torsion.model import TorsionCase

    lc = load_loadcase(args.file)
    settings = lc.torsion
    if settings is None:
        raise InputError("the load case has no [torsion] section (docs/torsion.md)", file=str(args.file), key="torsion")
    k_fe = None
    if args.fe_stiffness or settings.throw_stiffness == "fe":
        k_fe = fe_stiffness_of(lc, args.mesh_size, args.cache_dir)
    # a [torsion] section beside a CAD geometry is refused when the load case is read
    cycles = engine_cycles(lc.engine, lc.operating, file=lc.source_file)  # the dynamics stage
    res = analyse_torsion(cast(TorsionCase, lc), cycles.firing_torques, fe_stiffness=k_fe)
    out = Path(args.output)
    out.mkdir(parents=True, exist_ok=True)
    data = {"load_case": lc.name, "source_file": lc.source_file, **result_to_dict(res)}
    write_atomic(out / "torsion.json", json.dumps(data, indent=1, allow_nan=False))
    if not args.no_plots:
        write_plots(res, out)
    print(
        f"{lc.name}: {res.model.size} masses, natural frequencies [Hz]: "
        + ", ".join(f"{f:.1f}" for f in res.modes.elastic_hz[:5])
    )
    print(stiffness_text(res))
    print(f"{'segment':<22}{'max M_TN [N m]':>16}{'at [rpm]':>10}{'vibratory [N m]':>17}{'at op. [N m]':>14}")

    for r in governing_table(res):
        print(
            f"{r['segment']:<22}{r['max_half_range']:>16.4g}{r['governing_speed_rpm']:>10.0f}"
            f"{r['vibratory_half_range_at_governing']:>17.4g}{r['half_range_at_operating']:>14.4g}"
        )
    print(f"flywheel speed fluctuation at {res.operating_speed * RPM:.0f} rpm: {100 * res.flywheel_fluctuation:.3g} %")
    print(f"written: {out / 'torsion.json'}")
    return 0
