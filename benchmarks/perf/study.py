"""Benchmark: the counterweight study (``fe-crank study``) against one whole-shaft check of
the same case.

The shipped inline-4 (``loadcases/inline4_rated.toml``) with its full-load curve resampled
to ``--speeds`` speeds from 1000 rpm to its operating speed (20 by default; each speed
also without gas load in the study): ``--candidates`` candidates (two placements, eight
and four counterweights, times evenly spaced balance rates 30-100 %) screened by the
study, and ``fe-crank check`` of the same load case with the same speeds.  Each runs in a
process of its own with a mesh cache of its own (both mesh: the study's own meshing is
included), so the CPU seconds and peak memory are each one's.

    .venv/bin/python benchmarks/perf/study.py --preset test
    .venv/bin/python benchmarks/perf/study.py --preset coarse     # the target's figures (idle machine)

Prints per part the wall and CPU seconds, the peak resident memory and the load average,
and the study's ratio to the check (target: at most 2x in time, no more memory).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
LOADCASE = ROOT / "loadcases" / "inline4_rated.toml"


def _loadcase(folder: Path, n_speeds: int) -> Path:
    """The shipped load case with ``n_speeds`` speeds and absolute file paths."""
    text = LOADCASE.read_text()
    for key in ("engine", "geometry"):
        m = re.search(rf'^{key} = "(.+)"$', text, flags=re.M)
        assert m, key
        text = text.replace(m.group(0), f'{key} = "{(LOADCASE.parent / m.group(1)).resolve()}"')
    lo, hi = 1000.0, 6000.0
    speeds = ", ".join(f'"{lo + (hi - lo) * i / (n_speeds - 1):.6g} rpm"' for i in range(n_speeds))
    text = re.sub(r"^speed_range = .*$", f"speeds = [{speeds}]", text, flags=re.M)
    text = re.sub(r"^speed_step = .*$\n", "", text, flags=re.M)
    path = folder / "bench_loadcase.toml"
    path.write_text(text)
    return path


def _study(folder: Path, n: int) -> Path:
    half = max(1, n // 2)
    rates = ", ".join(f"{30 + 70 * i / max(1, half - 1):.6g}" for i in range(half))
    path = folder / "bench_study.toml"
    path.write_text(
        f"""[study]
name = "benchmark"
rotating_rate_percent = [{rates}]
envelope = "90 mm"
[study.limits]
max_main_bearing_specific_load = "20 MPa"
[[study.placements]]
name = "8"
webs = "all"
[[study.placements]]
name = "4"
webs = ["1.1", "2.2", "3.1", "4.2"]
"""
    )
    return path


def _child(cmd: list[str]) -> dict:
    t0 = time.perf_counter()
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    env = {**os.environ, "FE_CRANK_ALLOW_OUTSIDE_PATHS": "1"}  # the load case names the shipped files
    proc = subprocess.run(cmd, capture_output=True, text=True, check=False, env=env)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    if proc.returncode not in (0, 1):
        sys.exit(f"{' '.join(cmd)} failed ({proc.returncode}):\n{proc.stderr[-3000:]}")
    return {
        "wall_s": time.perf_counter() - t0,
        "cpu_s": (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime),
        "peak_rss_gb": after.ru_maxrss / 1e6,  # the largest child so far: run the study first
        "load_average": os.getloadavg(),
        "tail": proc.stdout.strip().splitlines()[-3:],
    }


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--preset", default="test", choices=("test", "coarse", "medium"))
    ap.add_argument("--candidates", type=int, default=20)
    ap.add_argument("--speeds", type=int, default=20)
    ap.add_argument("--json", type=Path, default=None, help="also write the figures here")
    args = ap.parse_args()
    fe = [sys.executable, "-c", "import sys; from fe_crank.cli import main; sys.exit(main(sys.argv[1:]))"]
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        lc, st = _loadcase(d, args.speeds), _study(d, args.candidates)
        common = ["--mesh-size", args.preset]
        study = _child(fe + ["study", str(lc), str(st), "-o", str(d / "study"), "--cache-dir", str(d / "c1"), *common])
        print("study:", json.dumps(study), flush=True)
        check = _child(
            fe
            + ["check", str(lc), "-o", str(d / "check"), "--cache-dir", str(d / "c2"), "--allow-outside-paths"]
            + ["--no-render", "--no-vtu", "--no-convergence", *common]
        )
    out = {
        "preset": args.preset,
        "candidates": args.candidates,
        "speeds": args.speeds,
        "study": study,
        "check": check,
        "cpu_ratio": study["cpu_s"] / check["cpu_s"],
        "wall_ratio": study["wall_s"] / check["wall_s"],
        "cpus": os.cpu_count(),
    }
    print(json.dumps(out, indent=1))
    if args.json:
        args.json.write_text(json.dumps(out, indent=1))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
