"""Verification: how far apart two equally good ``test`` meshes of one solid put its peaks.

The CAD tests compare two meshes of one solid at the ``test`` preset (a fillet's edge
about its radius): the drawn whole shaft against the parametric one, the hot-spot zones
of a drawn throw against its whole re-mesh.  Neither mesh is the other's, so the two
differ by the meshes' own scatter, which one pair of meshes does not measure.  This
script makes realisations of each solid that differ only at the round-off level, where
gmsh's meshes already differ (a last-bit change of a cut or a size field is another
mesh), and measures the scatter over them:

* drawn: the STEP file translated along the crank axis by ``k x 10 nm``, ``k = 0`` the file
  itself (the recognition
  places the throw frame on the drawing, so the solid meshed is the same to 1e-17 m);
* parametric: the crank radius times ``1 + k 1e-12``.

``zones``: the shipped single-cylinder throw written to STEP (``helpers.cad_files``),
each realisation meshed at ``test`` and solved for the zone test's load sets
(tests/cad/test_cad_zone_study.py); the study's r/2 level by zones and by the whole
throw re-meshed; per entry the zones' difference from the full mesh, and the full mesh's
spread over the realisations.  ``shaft``: the shipped inline-4 as the parametric model
builds it and as drawn (the whole-shaft tests' file: its layout written to STEP with a
nose and a flange, read back with the geometry's bearings), each realisation analysed at
its rated speed (tests/helpers/inline4_shaft.py); per pair of realisations the
differences of the 24 whole-shaft fillet peaks (largest, mean, rms), of the main-bearing
peak loads and of the oil film.  ``throws``: the shipped V4 and inline-4 throws, drawn and
parametric, under the four unit cases of tests/cad/test_cad_fe.py: each fillet pair's
peak, drawn against parametric over every pair of realisations.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/verification/mesh_scatter.py \\
        --realisations 4 --out scatter

(about 15 min and 3 GB at 5 realisations; ``--only`` one part).  Writes ``<out>.json`` and ``<out>.md``.
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import json
import math
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tests"))

SHIFT = 1e-8  # m, the drawn realisations' step along the axis
STRETCH = 1e-12  # the parametric realisations' step of the crank radius, relative


def stretched(g, k: int):
    """Realisation ``k`` of the parametric geometry ``g``: its crank radius times
    ``1 + k STRETCH`` (``k = 0``: ``g`` itself)."""
    return dataclasses.replace(g, crank_radius=g.crank_radius * (1 + k * STRETCH))


def translated(src: Path, dst: Path, dz: float) -> Path:
    """``src`` read, moved by ``dz`` along z and written to ``dst`` (gmsh's OpenCASCADE
    writer, millimetres, as ``fe_crank.geometry.step`` writes); ``dz = 0``: ``src`` itself,
    the file the tests mesh."""
    from fe_crank.gmsh_io import gmsh_session

    if dz == 0.0:
        return src

    with gmsh_session() as gmsh:
        gmsh.option.setString("Geometry.OCCTargetUnit", "M")
        out = gmsh.model.occ.importShapes(str(src))
        gmsh.model.occ.translate(out, 0, 0, dz)
        gmsh.model.occ.synchronize()
        gmsh.write(str(dst))
    return dst


def zone_realisation(step: Path, density: float, cache: Path) -> dict:
    """The zone test's comparison on one drawn throw: r/1 and r/2 peaks of both methods."""
    from helpers.drawn_zones import OPTIONS, zones_and_full
    from helpers.verification_meshes import Steel

    from fe_crank.cad import CadInput, mesh_cad_throw
    from fe_crank.fe import solve_unit_cases

    cad = CadInput(step, density=density)
    tm = mesh_cad_throw(cad, "1", size="test", cache_dir=cache)
    units = solve_unit_cases(tm, Steel(), OPTIONS)
    units.system.factorisation.free()
    zones, full = zones_and_full(cad, tm, units, cache)
    return {
        "nodes": int(tm.mesh.p.shape[1]),
        "assessed": dict(full.levels[0].peaks),
        "zones": dict(zones.levels[1].peaks),
        "full": dict(full.levels[1].peaks),
    }


def shaft_realisation(route: str, k: int, drawing: Path, cache: Path) -> dict:
    """The inline-4 whole shaft at its rated speed: fillet peaks, bearing peak loads, film."""
    from helpers.inline4_shaft import analyse_route, rated_inline4

    from fe_crank.cad import CadInput, recognise
    from fe_crank.cad.engine import engine_keys
    from fe_crank.cad.source import mesh_source_shaft
    from fe_crank.cad.whole import cad_shaft_layout, cad_throw_masses
    from fe_crank.fe.shaft.whole_shaft import throw_masses
    from fe_crank.mesh.shaft import mesh_shaft
    from fe_crank.pipeline.stages import shaft_layout

    lc, dyn = rated_inline4()
    if route == "parametric":
        g = lc.geometry
        lc = dataclasses.replace(lc, geometry=stretched(g, k))
        layout = shaft_layout(lc)
        sm = mesh_shaft(layout, size="test", cache_dir=cache)
        run = analyse_route(sm, layout, lc, dyn, throw_masses(layout))
    else:
        g = shaft_layout(lc).geometry
        step = translated(drawing, drawing.with_name(f"inline4_{k}.step"), k * SHIFT)
        bearings = dataclasses.replace(g.shaft, pitch=None, end_journal_length=None, nose=None, flange=None)
        cad = CadInput(step, density=g.density, shaft=bearings)
        features = recognise(CadInput(step, density=g.density))
        engine_keys(features, cad, lc.engine, engine_file="e.toml", loadcase="case.toml")
        layout = cad_shaft_layout(features, cad, lc.engine, engine_file="e.toml")
        sm = mesh_source_shaft(cad, layout, size="test", cache_dir=cache, features=features)
        run = analyse_route(sm, layout, lc, dyn, cad_throw_masses(features, layout))
    return {
        "nodes": sum(int(tm.mesh.p.shape[1]) for tm in sm.throw_meshes.values()),
        "peaks": {f"{t}|{grp}": v for (t, grp), v in run.peaks.items()},
        "loads": {b.name: b.with_counterweights.peak_n for b in run.result.bearings},
        "film": [
            [b.with_counterweights.min_film_m, b.with_counterweights.peak_pressure_pa] for b in run.films[0].bearings
        ],
    }


#: the fillet pairs and unit cases of tests/cad/test_cad_fe.py
PAIRS = (("crankpin_fillet_1", "crankpin_fillet_2"), ("journal_fillet_1", "journal_fillet_2"))
THROW_CASES = ("centrifugal", "pin_x", "pin_y", "torque")
THROWS = ("v4_90_pneumatic", "inline4")


def throw_realisation(throw_mesh) -> dict[str, float]:
    """The largest von Mises stress over each mirror pair of fillets per unit case (Pa)."""
    import numpy as np
    from helpers.verification_meshes import Steel

    from fe_crank.assess.group.nodes import unit_stresses
    from fe_crank.fe import FeOptions, solve_unit_cases
    from fe_crank.fe.core.stress import von_mises

    us = unit_stresses(solve_unit_cases(throw_mesh, Steel(), FeOptions(cases=THROW_CASES)))
    out = {}
    for names in PAIRS:
        idx = np.concatenate([us.groups[n] for n in names])
        for i, case in enumerate(us.cases):
            out[f"{names[0]}|{case}"] = float(von_mises(us.stress[i][:, idx]).max())
    return out


def throw_scatter(n: int, folder: Path, cache: Path) -> dict:
    """The shipped V4 and inline-4 throws, each drawn (``parametric_step``, translated) and
    parametric (crank radius stretched) in ``n`` realisations: their pair peaks."""
    from helpers.cad_files import parametric_step

    from fe_crank.cad import CadInput, mesh_cad_throw
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import mesh_throw

    out = {}
    for name in THROWS:
        g = load_geometry(ROOT / "geometry" / f"{name}.toml")
        step = parametric_step(g, folder / f"{name}.step")
        runs = {}
        for k in range(n):
            drawn = translated(step, folder / f"{name}_{k}.step", k * SHIFT)
            runs[f"drawn{k}"] = throw_realisation(
                mesh_cad_throw(CadInput(drawn, density=g.density), size="test", cache_dir=cache)
            )
            runs[f"parametric{k}"] = throw_realisation(mesh_throw(stretched(g, k), size="test", cache_dir=cache))
        out[name] = runs
    return out


def pair(a: dict, b: dict) -> dict:
    """Differences of realisation ``a`` from ``b``: fillet peaks (largest, mean, rms), loads, film."""
    d = [a["peaks"][k] / b["peaks"][k] - 1 for k in sorted(b["peaks"])]
    return {
        "peak_max": max(abs(x) for x in d),
        "peak_mean": sum(d) / len(d),
        "peak_rms": math.sqrt(sum(x * x for x in d) / len(d)),
        "load_max": max(abs(a["loads"][k] / b["loads"][k] - 1) for k in b["loads"]),
        "film_max": max(abs(x / y - 1) for p, q in zip(a["film"], b["film"], strict=True) for x, y in zip(p, q)),
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--realisations", type=int, default=4)
    ap.add_argument("--only", choices=("zones", "shaft", "throws"), default=None)
    ap.add_argument("--out", type=Path, default=Path("scatter"))
    args = ap.parse_args()
    from helpers.cad_files import layout_step, parametric_step

    from fe_crank.geometry.shaft import engine_shaft_layout
    from fe_crank.io.engine import load_engine
    from fe_crank.io.geometry import load_geometry

    n = args.realisations
    out: dict = {"realisations": n, "shift_m": SHIFT, "stretch": STRETCH}
    t0 = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(tmp)
        cache = folder / "cache"
        if args.only in (None, "zones"):
            g = load_geometry(ROOT / "geometry" / "single_cylinder.toml")
            step = parametric_step(g, folder / "throw.step")
            out["zones"] = [
                zone_realisation(translated(step, folder / f"throw_{k}.step", k * SHIFT), g.density, cache)
                for k in range(n)
            ]
            print(f"zones: {time.perf_counter() - t0:.0f} s", flush=True)
        if args.only in (None, "shaft"):
            g = load_geometry(ROOT / "geometry" / "inline4.toml")
            layout = engine_shaft_layout(
                g, load_engine(ROOT / "engines" / "inline4.toml"), geometry_file="g", engine_file="e"
            )
            drawing = layout_step(layout, folder / "inline4.step", nose=(0.04, 0.03), flange=(0.1, 0.012))
            runs = {(r, k): shaft_realisation(r, k, drawing, cache) for r in ("drawn", "parametric") for k in range(n)}
            out["shaft"] = {f"{r}{k}": v for (r, k), v in runs.items()}
            out["shaft_pairs"] = {
                f"{a[0]}{a[1]} vs {b[0]}{b[1]}": pair(runs[a], runs[b])
                for a, b in itertools.chain(
                    itertools.product([("drawn", k) for k in range(n)], [("parametric", k) for k in range(n)]),
                    itertools.combinations([("parametric", k) for k in range(n)], 2),
                    itertools.combinations([("drawn", k) for k in range(n)], 2),
                )
            }
            print(f"shaft: {time.perf_counter() - t0:.0f} s", flush=True)
        if args.only in (None, "throws"):
            out["throws"] = throw_scatter(n, folder, cache)
            print(f"throws: {time.perf_counter() - t0:.0f} s", flush=True)
    out["seconds"] = time.perf_counter() - t0
    args.out.with_suffix(".json").write_text(json.dumps(out, indent=1))
    args.out.with_suffix(".md").write_text(markdown(out))
    print(markdown(out))


def markdown(out: dict) -> str:
    lines = []
    if "zones" in out:
        z = out["zones"]
        lines += [
            "| entry | full r/2 over the realisations, MPa | zones - full, each realisation |",
            "| --- | --- | --- |",
        ]
        for name in z[0]["full"]:
            full = [r["full"][name] / 1e6 for r in z]
            diff = [r["zones"][name] / r["full"][name] - 1 for r in z]
            lines.append(
                f"| {name} | {min(full):.1f} - {max(full):.1f} | {', '.join(f'{100 * d:+.1f} %' for d in diff)} |"
            )
        lines.append("")
    if "shaft_pairs" in out:
        lines += ["| pair | fillet peaks: largest, mean, rms | bearing loads | film |", "| --- | --- | --- | --- |"]
        for name, p in out["shaft_pairs"].items():
            lines.append(
                f"| {name} | {100 * p['peak_max']:.1f} %, {100 * p['peak_mean']:+.2f} %, {100 * p['peak_rms']:.2f} % "
                f"| {100 * p['load_max']:.3f} % | {100 * p['film_max']:.3f} % |"
            )
    for name, runs in out.get("throws", {}).items():
        n = out["realisations"]
        lines += [
            "",
            f"{name}: drawn - parametric over the {n} x {n} pairs of realisations, per fillet pair and unit case",
            "",
            "| entry | parametric realisation 0, Pa per unit load | smallest | largest |",
            "| --- | --- | --- | --- |",
        ]
        for key in runs["parametric0"]:
            d = [runs[f"drawn{i}"][key] / runs[f"parametric{j}"][key] - 1 for i in range(n) for j in range(n)]
            lines.append(f"| {key} | {runs['parametric0'][key]:.4g} | {100 * min(d):+.1f} % | {100 * max(d):+.1f} % |")
    return "\n".join(lines) + "\n"


if __name__ == "__main__":
    main()
