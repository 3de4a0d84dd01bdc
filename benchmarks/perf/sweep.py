"""The ``sweep`` stage of ``run.py``: what a full-load sweep adds to the check.

The load case is checked twice on the same cached mesh, as ``fe-crank check --no-render
--no-vtu --no-convergence`` runs it (``fe_crank.pipeline.case.run_case``, the report
written): once at its operating speed alone (its ``[operating]`` without the full-load
keys) and once over ``speeds`` speeds spread evenly over ``[lo, hi]`` rpm (``speeds =
[...]``, the operating speed among them; the engine's one diagram at every speed).
Each variant runs ``repeat`` times, alternating, each in this process; the best wall
and CPU seconds of each and the ratio sweep / single are the figures.  The variants are
written as temporary files beside the load case (its relative paths resolve) and
removed afterwards.
"""

from __future__ import annotations

import os
import re
import tempfile
import time
from pathlib import Path

import numpy as np

FULL_LOAD_KEYS = ("speeds", "speed_range", "speed_step")


def variants(text: str, speeds_rpm: list[float]) -> tuple[str, str]:
    """(single-speed text, sweep text) of a load case's TOML ``text``: the full-load keys
    of ``[operating]`` removed, and ``speeds = [...]`` added after its ``speed``."""
    out, section = [], ""
    for line in text.splitlines():
        head = re.match(r"\s*\[+([^\]]+)\]+", line)
        if head:
            section = head.group(1).strip()
        key = line.split("=", 1)[0].strip()
        if section == "operating" and key in FULL_LOAD_KEYS:
            continue
        out.append(line)
    single = "\n".join(out) + "\n"
    listed = ", ".join(f'"{w:.6g} rpm"' for w in speeds_rpm)
    sweep, section, added = [], "", False
    for line in out:
        head = re.match(r"\s*\[+([^\]]+)\]+", line)
        if head:
            section = head.group(1).strip()
        sweep.append(line)
        if section == "operating" and not added and line.split("=", 1)[0].strip() == "speed":
            sweep.append(f"speeds = [{listed}]")
            added = True
    if not added:
        raise ValueError("the load case has no [operating] speed line to add the sweep after")
    return single, "\n".join(sweep) + "\n"


def _check(path: Path, preset: str, cache: str, out_dir: str) -> dict:
    from fe_crank.pipeline.case import run_case
    from fe_crank.pipeline.options import CheckOptions

    opts = CheckOptions(mesh_size=preset, cache_dir=cache, render=False, write_vtu=False, convergence=False)
    t = os.times()
    c0, w0 = t.user + t.system, time.perf_counter()
    res = run_case(path, out_dir, opts)
    t = os.times()
    stages = {s.stage: s.seconds for s in res.timings}
    return {
        "wall_s": time.perf_counter() - w0,
        "cpu_s": t.user + t.system - c0,
        "status": res.status,
        "assess_s": stages.get("assess", 0.0),
        "dynamics_s": stages.get("dynamics", 0.0),
    }


def sweep(loadcase: str, preset: str, cache: str, speeds: int, lo: float, hi: float, repeat: int) -> dict:
    """The figures of the module docstring."""
    from fe_crank.io.loadcase import load_loadcase

    case = Path(loadcase).resolve()
    op = load_loadcase(case).operating.speed * 30 / np.pi
    grid = sorted({*np.linspace(lo, hi, speeds).round(6).tolist(), round(op, 6)})
    single, swept = variants(case.read_text(), grid)
    files = []
    try:
        for name, text in (("single", single), ("sweep", swept)):
            p = case.with_name(f".perf_{os.getpid()}_{name}.toml")
            p.write_text(text)
            files.append(p)
        runs: dict[str, list[dict]] = {"single": [], "sweep": []}
        with tempfile.TemporaryDirectory() as out:
            _check(files[0], preset, cache, out)  # the mesh into the cache
            for _ in range(repeat):
                for name, p in zip(("single", "sweep"), files, strict=True):
                    runs[name].append(_check(p, preset, cache, out))
    finally:
        for p in files:
            p.unlink(missing_ok=True)
    best = {
        k: {f: min(r[f] for r in v) for f in ("wall_s", "cpu_s", "assess_s", "dynamics_s")} for k, v in runs.items()
    }
    return {
        "preset": preset,
        "speeds": len(grid),
        "range_rpm": f"{grid[0]:.0f}-{grid[-1]:.0f}",
        "single_wall_s": best["single"]["wall_s"],
        "single_cpu_s": best["single"]["cpu_s"],
        "sweep_wall_s": best["sweep"]["wall_s"],
        "sweep_cpu_s": best["sweep"]["cpu_s"],
        "single_assess_s": best["single"]["assess_s"],
        "sweep_assess_s": best["sweep"]["assess_s"],
        "sweep_dynamics_s": best["sweep"]["dynamics_s"],
        "added_wall_pct": 100 * (best["sweep"]["wall_s"] / best["single"]["wall_s"] - 1),
        "added_cpu_pct": 100 * (best["sweep"]["cpu_s"] / best["single"]["cpu_s"] - 1),
        "status": runs["sweep"][-1]["status"],
    }
