"""Benchmark: the sign-off -- the check with the hot-spot convergence study -- per stage.

Runs the check of each load case (default: the single-cylinder case and the inline-4
whole shaft) at a mesh preset with the study in the verdict, the mesh NOT cached (a fresh
empty cache folder per case), each case in its own process (its own peak memory) through
``tools/check_profile.py`` (the ``fe-crank check -j 1`` path, no pictures, no ``.vtu``),
and writes per stage the wall seconds, the CPU seconds (user + system of all threads)
and the peak resident memory, with the load average before and after each case (the
figures of a shared machine are its CPU seconds), as JSON and as a Markdown table.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/perf/signoff.py --preset coarse
    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/perf/signoff.py --preset coarse \\
        --cases loadcases/single_cylinder.toml --out signoff_single
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CASES = ("loadcases/single_cylinder.toml", "loadcases/inline4_rated.toml")


def run_case(case: str, preset: str) -> dict:
    """One case's sign-off in a child process: its stage rows and totals."""
    with tempfile.TemporaryDirectory(prefix="signoff-") as tmp:
        out = Path(tmp) / "figures.json"
        before = os.getloadavg()[0]
        cmd = [
            sys.executable,
            str(ROOT / "tools" / "check_profile.py"),
            str(ROOT / case),
            "--preset",
            preset,
            "--convergence",
            "--cache-dir",
            str(Path(tmp) / "meshes"),
            "--out",
            str(Path(tmp) / "report"),
            "--json",
            str(out),
        ]
        env = dict(os.environ, OPENBLAS_NUM_THREADS=os.environ.get("OPENBLAS_NUM_THREADS", "1"))
        subprocess.run(cmd, check=True, env=env, cwd=ROOT)
        got = json.loads(out.read_text())
        got["load_average_before"] = before
        got["load_average_after"] = os.getloadavg()[0]
        return got


def table(results: list[dict]) -> str:
    lines = []
    for r in results:
        stages = {s["stage"]: s for s in r["stages"]}
        study = stages.get("convergence", {"wall_s": 0.0, "cpu_s": 0.0})
        rest_wall = r["total"]["wall_s"] - study["wall_s"]
        rest_cpu = r["total"]["cpu_s"] - study["cpu_s"]
        lines += [
            f"`{r['loadcase']}` at `{r['preset']}` (status {r['status']}; load average "
            f"{r['load_average_before']:.1f} before, {r['load_average_after']:.1f} after)",
            "",
            "| stage | wall, s | CPU, s | peak RSS, GB |",
            "| --- | --- | --- | --- |",
        ]
        lines += [
            f"| {s['stage']} | {s['wall_s']:.1f} | {s['cpu_s']:.1f} | {s['peak_rss_gb']:.2f} |" for s in r["stages"]
        ]
        t = r["total"]
        lines += [
            f"| **total** | **{t['wall_s']:.1f}** | **{t['cpu_s']:.1f}** | **{t['ru_maxrss_gb']:.2f}** |",
            "",
            f"the study / the rest of the check: wall {study['wall_s'] / max(rest_wall, 1e-9):.2f}, "
            f"CPU {study['cpu_s'] / max(rest_cpu, 1e-9):.2f}",
            "",
        ]
    return "\n".join(lines)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--cases", nargs="+", default=list(CASES))
    ap.add_argument("--out", type=Path, default=Path("signoff"), help="output stem (.json, .md)")
    args = ap.parse_args(argv)
    results = [run_case(c, args.preset) for c in args.cases]
    args.out.with_suffix(".json").write_text(json.dumps(results, indent=1))
    text = table(results)
    args.out.with_suffix(".md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
