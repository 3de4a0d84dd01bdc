"""Verification: the hot-spot convergence study by zones against the full re-meshed study.

The check's study (``fe.refinement.zone_study.zone_convergence``: only the hot spots re-meshed,
submodels driven by the assessed solution) and the former method
(``fe.refinement.convergence.fillet_convergence``: the whole throw re-meshed and re-solved at each
fillet size), on one load case's throw (parametric, or drawn: a load case with a ``[cad]``
geometry) at a mesh preset, with the check's own load sets
(``fe.refinement.loads.check_loads``: the peak pin force with the centrifugal load at
the operating speed, the peak torque) and support model.  The zones are solved at two
radii (``--radii``, in fillet radii) to show the cut-boundary error.  Writes a JSON file
and a Markdown table: per entry (load set, surface family) and level the peak of each
method and their relative difference, and the Richardson estimate (``estimate``) of each.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/verification/zone_study.py \\
        loadcases/single_cylinder.toml --preset coarse --out zone_coarse

(the full study at ``coarse`` takes about 10 min and 16 GB; at ``test`` about 1 min).
``--drive-full`` also solves the first refined level's zones driven by the full refined
solution: the zones' difference from the full mesh split into the cut's error and the two
meshes' own.  ``--stretch K`` (a parametric throw) multiplies its crank radius by
``1 + K x 1e-12`` (``mesh_scatter.stretched``): another mesh of the same solid, whose
peaks differ from ``K = 0``'s by the meshes' own scatter, so repeated runs
(``zone_scatter.py``) show whether the zones' difference from the full study is a bias
or that scatter.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import resource
import time
from pathlib import Path


def _cpu() -> float:
    r = resource.getrusage(resource.RUSAGE_SELF)
    return r.ru_utime + r.ru_stime


def drive_full(lc, tm, units, loads, opts, args) -> float:
    """Print the first refined level's zone peaks driven by the assessed and by the full
    refined solution, and the full mesh's: the zones' difference from the full mesh split
    into the cut's error and the two meshes' own.  Returns the seconds."""
    from fe_crank.cad.source import mesh_source_throw
    from fe_crank.fe import solve_unit_cases
    from fe_crank.fe.refinement import zone_study as zs
    from fe_crank.fe.refinement.levels import level_peaks
    from fe_crank.fe.refinement.zone import Interpolator, boundary_samples, solve_zone, zone_peaks

    t0 = time.perf_counter()
    f = args.factors[1]
    base = tm.options
    level = dataclasses.replace(
        base, fillet_divisions=base.fillet_divisions * f, bore_divisions=base.bore_divisions * f
    )
    fine = mesh_source_throw(lc.geometry, None, size=level, cache_dir=args.cache_dir)
    fine_units = solve_unit_cases(fine, lc.material, opts)
    fine_units.system.factorisation.free()
    drives = {
        "assessed": (units, {k: units.combine(w) for k, w in loads.items()}),
        "full": (fine_units, {k: fine_units.combine(w) for k, w in loads.items()}),
    }
    full = level_peaks(fine_units, drives["full"][1])
    solid = zs.zone_solid(lc.geometry, tm)
    spots = zs.hot_spots(solid, tm, units, drives["assessed"][1], zone_radius=args.radii[0])
    zones = zs.level_meshes(solid, [level], spots, boundary_samples(units.mesh))[0]
    every = [n for _, names in zs.FAMILIES for n in names]
    got: dict[str, dict[str, float]] = {}
    for label, (u, fields) in drives.items():
        interp = Interpolator(u.mesh, u.system.basis.dofs, u.points)
        best: dict[str, float] = {}
        for zm in zones:
            U, basis = solve_zone(zm, lc.material, units.options, units.pin, loads, fields, interp)
            for name, per in zone_peaks(zm, basis, lc.material, U, every, zs.REACH).items():
                for prefix, names in zs.FAMILIES:
                    for surface in names:
                        if surface in per:
                            best[prefix + name] = max(best.get(prefix + name, 0.0), per[surface])
        got[label] = best
    print(
        f"\nr/{level.fillet_divisions:g}: the zones driven by the assessed and by the full solution against the full mesh"
    )
    print("| entry | full, MPa | zones (assessed), diff. | zones (full), diff. |\n| --- | --- | --- | --- |")
    for k, (v, _) in full.items():
        a, b = got["assessed"][k] / v - 1, got["full"][k] / v - 1
        print(f"| {k} | {v / 1e6:.2f} | {a * 100:+.2f} % | {b * 100:+.2f} % |")
    return time.perf_counter() - t0


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase", type=Path)
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--radii", type=float, nargs="+", default=[3.0, 2.0])
    ap.add_argument("--cache-dir", type=Path, default=None, help="mesh cache (default: none)")
    ap.add_argument("--out", type=Path, default=Path("zone_study"), help="output stem (.json, .md)")
    ap.add_argument(
        "--stretch",
        type=int,
        default=0,
        help="a parametric throw's crank radius times 1 + K x 1e-12 (another mesh of the same solid)",
    )
    ap.add_argument("--no-full", action="store_true", help="the zones only (no full re-meshed study)")
    ap.add_argument("--factors", type=float, nargs="+", default=[1.0, 1.5, 2.0], help="fillet refinement factors")
    ap.add_argument(
        "--drive-full",
        action="store_true",
        help="also solve the first refined level's zones driven by the full refined solution (the cut's error)",
    )
    args = ap.parse_args(argv)

    from fe_crank.cad.source import mesh_source_throw
    from fe_crank.fe import solve_unit_cases
    from fe_crank.fe.refinement.convergence import estimate, fillet_convergence
    from fe_crank.fe.refinement.loads import check_loads
    from fe_crank.fe.refinement.zone_study import zone_convergence
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.cycles import engine_cycles

    lc = load_loadcase(args.loadcase)
    if args.stretch:
        from mesh_scatter import stretched  # this folder: the realisations' one definition

        from fe_crank.geometry.spec import CrankGeometry

        if not isinstance(lc.geometry, CrankGeometry):
            ap.error("--stretch needs a parametric geometry")
        lc = dataclasses.replace(lc, geometry=stretched(lc.geometry, args.stretch))
    cycles = engine_cycles(lc.engine, lc.operating)
    dyn = cycles.operating
    loads = check_loads(list(dyn.throws.values()), dyn.speed)
    needed = tuple(sorted({c for w in loads.values() for c in w}))
    opts = dataclasses.replace(lc.fe, cases=needed)
    t0 = time.perf_counter()
    tm = mesh_source_throw(lc.geometry, None, size=args.preset, cache_dir=args.cache_dir)
    units = solve_unit_cases(tm, lc.material, opts)
    units.system.factorisation.free()
    times = {"mesh and solve": time.perf_counter() - t0}
    studies = {}
    for r in args.radii:
        t0, c0 = time.perf_counter(), _cpu()
        studies[f"zones {r:g} r"] = zone_convergence(
            lc.geometry, lc.material, tm, units, loads, zone_radius=r, factors=tuple(args.factors)
        )
        times[f"zones {r:g} r"] = time.perf_counter() - t0
        times[f"zones {r:g} r CPU"] = _cpu() - c0
    if not args.no_full:
        t0, c0 = time.perf_counter(), _cpu()
        studies["full"] = fillet_convergence(
            lc.geometry,
            lc.material,
            base=tm.options,
            loads=loads,
            fe_options=opts,
            cache_dir=args.cache_dir,
            first=(tm, units),
            factors=tuple(args.factors),
        )
        times["full"] = time.perf_counter() - t0
        times["full CPU"] = _cpu() - c0
    if args.drive_full:
        times["zones driven by the full solution"] = drive_full(lc, tm, units, loads, opts, args)
    ref_name = "full" if "full" in studies else f"zones {args.radii[0]:g} r"
    ref = studies[ref_name]
    rows = []
    for name in ref.changes:
        for key, st in studies.items():
            peaks = [lv.peaks[name] for lv in st.levels]
            est = estimate(st, name)[0] * peaks[0]
            ref_peaks = [lv.peaks[name] for lv in ref.levels]
            ref_est = estimate(ref, name)[0] * ref_peaks[0]
            rows.append(
                {
                    "entry": name,
                    "method": key,
                    "peaks_Pa": peaks,
                    "estimate_Pa": est,
                    "difference": [a / b - 1 for a, b in zip(peaks, ref_peaks)],
                    "estimate_difference": est / ref_est - 1,
                    "where": [lv.where[name] for lv in st.levels],
                }
            )
    result = {
        "loadcase": str(args.loadcase),
        "preset": args.preset,
        "stretch": args.stretch,
        "reference": ref_name,
        "dof": {k: [lv.n_dof for lv in st.levels] for k, st in studies.items()},
        "seconds": times,
        "peak_rss_GB": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6,
        "rows": rows,
    }
    args.out.with_suffix(".json").write_text(json.dumps(result, indent=1))
    sizes = ", ".join(f"r/{lv.fillet_divisions:g}" for lv in ref.levels)
    lines = [
        f"{args.loadcase} at {args.preset}: peaks (MPa) at {sizes}, the Richardson estimate, and the "
        f"difference from the {ref_name} study",
        "",
        "| entry | method | peaks, MPa | estimate, MPa | difference of the levels | of the estimate |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for r in rows:
        lines.append(
            f"| {r['entry']} | {r['method']} | {' / '.join(f'{p / 1e6:.2f}' for p in r['peaks_Pa'])} | "
            f"{r['estimate_Pa'] / 1e6:.2f} | {' / '.join(f'{d * 100:+.2f} %' for d in r['difference'])} | "
            f"{r['estimate_difference'] * 100:+.2f} % |"
        )
    lines += ["", "| study | DOF per level | wall, s | CPU, s |", "| --- | --- | --- | --- |"]
    for k, st in studies.items():
        lines.append(
            f"| {k} | {' / '.join(str(lv.n_dof) for lv in st.levels)} | {times[k]:.1f} | {times[k + ' CPU']:.1f} |"
        )
    lines.append(f"\npeak resident memory {result['peak_rss_GB']:.2f} GB")
    args.out.with_suffix(".md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
