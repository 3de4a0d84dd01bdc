"""Benchmark: ``fe-crank check`` of a whole shaft given as STEP against the same shaft given
parametrically.

The load case's parametric shaft (``pipeline.stages.shaft_layout``: its throws placed by the
engine, the end journals to their length) is written to STEP by fe-crank itself (each
throw's solid, ``geometry.solid.throw_solid``, turned and placed, fused, gmsh's
OpenCASCADE writer), with a nose and a flange beyond the end journals so that these end
in shoulders and their bearings sit at their middles as the parametric layout puts them.
A copy of the load case reads that file (``[cad]``, the geometry's density, its ``[shaft]``
bearings as ``[cad.shaft]``), with the criteria a drawing cannot feed dropped (the bolt
criteria: no bolt data).  Both cases run through ``fe-crank check`` in their own process, each
with its own empty mesh cache (the meshing is part of the cost), one after the other:

    .venv/bin/python benchmarks/perf/cad_shaft.py --preset coarse
    .venv/bin/python benchmarks/perf/cad_shaft.py --preset test

Prints per case the CPU seconds (user + system of the process and its children), the
wall seconds, the peak resident memory, the verdict and the main-bearing peak loads and whole-shaft fillet peaks of
both, and the ratio of the CPU seconds (STEP / parametric).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]


def write_step(lc_path: Path, path: Path) -> float:
    """The load case's parametric shaft as one STEP solid (``geometry.step.write_shaft_step``,
    a nose of 0.8 and a flange of 1.6 journal diameters); returns the geometry's density."""
    from fe_crank.geometry.step import write_shaft_step
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.pipeline.stages import shaft_layout

    lc = load_loadcase(lc_path)
    layout = shaft_layout(lc)
    assert layout is not None, "the load case models no whole shaft"
    d = layout.geometry.journal_diameter
    write_shaft_step(layout, path, nose=(0.8 * d, 0.03), flange=(1.6 * d, 0.015))
    return layout.geometry.density


def cad_case(lc_path: Path, step: Path, density: float, folder: Path) -> Path:
    """A copy of the load case that reads ``step`` (absolute paths: it lives in ``folder``),
    with the geometry's ``[shaft]`` bearings (widths, law, oil) as ``[cad.shaft]``: the
    bearings are the engine's, not the drawing's (what the drawing gives, its pitch, end
    journals, nose and flange, left out)."""
    text = lc_path.read_text()
    geometry = re.search(r'^geometry = "(.*)"$', text, flags=re.M)
    assert geometry is not None
    shaft = re.search(r"^\[shaft\]\n(.*?)(?=^\[|\Z)", (lc_path.parent / geometry[1]).read_text(), flags=re.M | re.S)
    bearings = ""
    if shaft is not None:
        kept = [
            line
            for line in shaft[1].splitlines()
            if not re.match(r"\s*(pitch|end_journal_length|nose|flange)\s*=", line)
        ]
        bearings = "\n[cad.shaft]\n" + "\n".join(kept).strip() + "\n"
    text = re.sub(r'^engine = "(.*)"$', lambda m: f'engine = "{(lc_path.parent / m[1]).resolve()}"', text, flags=re.M)
    text = re.sub(r'^geometry = ".*"$', f'geometry = "{step}"', text, flags=re.M)
    text = re.sub(r"^(min|max)_bolt_.*\n", "", text, flags=re.M)  # a drawing gives no bolt data
    text = text.replace("\n[material]", f'\n[cad]\ndensity = "{density} kg/m^3"\n{bearings}\n[material]', 1)
    out = folder / "case_step.toml"
    out.write_text(text)
    return out


def run_check(case: Path, preset: str, folder: Path, name: str) -> dict:
    """One ``fe-crank check`` in its own process: its CPU seconds (user + system, its own
    children included), wall seconds and peak resident memory (``wait4``'s ``ru_maxrss``
    of that process: the largest of it and its waited-for children)."""
    t0 = time.perf_counter()
    cmd = [sys.executable, "-c", "import sys; from fe_crank.cli import entry; sys.exit(entry())"]
    cmd += ["check", str(case), "--mesh-size", preset, "--no-render", "--no-vtu", "--allow-outside-paths"]
    cmd += ["--cache-dir", str(folder / f"cache_{name}"), "-o", str(folder / f"out_{name}"), "-q"]
    err = folder / f"stderr_{name}.txt"
    with open(err, "w") as stderr:
        proc = subprocess.Popen(cmd, stdout=subprocess.DEVNULL, stderr=stderr)
        _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    wall = time.perf_counter() - t0
    cpu = usage.ru_utime + usage.ru_stime
    stderr_text = err.read_text()
    results = sorted((folder / f"out_{name}").glob("**/results.json"))
    r = json.loads(results[0].read_text()) if results else {}
    ws = r.get("whole_shaft") or {}
    peaks = {
        f"{t['name']}/{g['group']}": g["max_von_mises"]["value"]
        for t in ws.get("throws", [])
        for g in t.get("groups", [])
        if g.get("max_von_mises") and "fillet" in g["group"] and "counterweight" not in g["group"]
    }
    return {
        "cpu_s": cpu,
        "wall_s": wall,
        "peak_gb": usage.ru_maxrss * 1024 / 1e9,
        "returncode": proc.returncode,
        "passed": r.get("passed"),
        "stderr": stderr_text[-2000:] if proc.returncode not in (0, 1) else "",
        "bearings": {
            b["name"]: (b["peak_n"], b["without_counterweights"]["peak_n"]) for b in ws.get("main_bearings", [])
        },
        "fillet_peaks": peaks,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--loadcase", default=str(ROOT / "loadcases" / "inline4_rated.toml"))
    ap.add_argument("--preset", default="coarse", choices=("test", "coarse", "medium", "fine"))
    ap.add_argument("--keep", help="folder for the STEP file, the cases and their reports (default: a temporary one)")
    ap.add_argument("--only", choices=("parametric", "step"), help="run one of the two cases alone")
    a = ap.parse_args()
    lc_path = Path(a.loadcase).resolve()
    with tempfile.TemporaryDirectory() as tmp:
        folder = Path(a.keep or tmp)
        folder.mkdir(parents=True, exist_ok=True)
        step = folder / "shaft.step"
        density = write_step(lc_path, step)
        case = cad_case(lc_path, step, density, folder)
        skip = {
            "cpu_s": float("nan"),
            "wall_s": float("nan"),
            "peak_gb": float("nan"),
            "returncode": None,
            "passed": None,
            "stderr": "",
        }
        skip |= {"bearings": {}, "fillet_peaks": {}}
        par = run_check(lc_path, a.preset, folder, "parametric") if a.only != "step" else skip
        cad = run_check(case, a.preset, folder, "step") if a.only != "parametric" else skip
    for name, r in (("parametric", par), ("STEP", cad)):
        print(
            f"{name:10s} preset {a.preset}: {r['cpu_s']:.1f} CPU s, {r['wall_s']:.1f} s wall, "
            f"peak {r['peak_gb']:.2f} GB, "
            f"exit {r['returncode']}, passed {r['passed']}"
        )
        if r["stderr"]:
            print(r["stderr"])
    print("main bearing  peak with / without counterweights (N): parametric | STEP")
    for b, (on, off) in (par["bearings"] or cad["bearings"]).items():
        con, coff = cad["bearings"].get(b, (float("nan"), float("nan")))
        print(f"  {b:4s} {on:10.1f} {off:10.1f} | {con:10.1f} {coff:10.1f}  ({con / on - 1:+.2%} with)")
    print("whole-shaft fillet peak von Mises (MPa): parametric | STEP")
    for k, v in (par["fillet_peaks"] or cad["fillet_peaks"]).items():
        c = cad["fillet_peaks"].get(k, float("nan"))
        print(f"  {k:24s} {v / 1e6:8.2f} | {c / 1e6:8.2f}  ({c / v - 1:+.2%})")
    print(f"CPU ratio STEP / parametric: {cad['cpu_s'] / par['cpu_s']:.2f}")


if __name__ == "__main__":
    main()
