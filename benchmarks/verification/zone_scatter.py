"""Verification: the hot-spot zones against the full re-meshed study over round-off
realisations of one parametric throw.

``zone_study.py`` compares the zones with one full re-mesh; but two meshes of the same
solid at the same element size put a peak apart by their own scatter (a crank radius
changed in its twelfth digit gives another mesh: benchmarks/verification/mesh_scatter.py),
so one pair cannot tell the method's error from that scatter.  This script runs
``zone_study.py --stretch K`` for ``K = 0 .. N-1``, each in its own process (the crank
radius times ``1 + K x 1e-12``), and summarises per entry (load set, hot-spot family) and
method: the finest level's and the estimate's difference from the full study in each
realisation, their mean (the method's bias) and standard deviation, and the full study's
own spread over the realisations (its finest peak's largest minus smallest, over their
mean).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python benchmarks/verification/zone_scatter.py \\
        loadcases/single_cylinder.toml --preset coarse --realisations 3 --radii 3 4 --out zone_scatter

(at ``coarse`` about 8 min and 16 GB per realisation with both radii; a realisation whose
``<out>/k<K>.json`` exists is not run again).  Writes ``<out>/summary.json`` and
``<out>/summary.md``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import subprocess
import sys
from pathlib import Path

HERE = Path(__file__).resolve().parent


def run(args: argparse.Namespace, k: int) -> dict:
    """Realisation ``k``'s comparison (``zone_study.py --stretch k``), run unless on file."""
    out = args.out / f"k{k}"
    if not out.with_suffix(".json").exists():
        cmd = [sys.executable, str(HERE / "zone_study.py"), str(args.loadcase), "--preset", args.preset]
        cmd += ["--radii", *map(str, args.radii), "--factors", *map(str, args.factors)]
        cmd += ["--stretch", str(k), "--out", str(out)]
        subprocess.run(cmd, check=True, stdout=subprocess.DEVNULL)
    return json.loads(out.with_suffix(".json").read_text())


def summary(runs: list[dict]) -> dict:
    """Per entry and method: the differences from the full study in every realisation, their
    mean, and the full study's own spread (module docstring)."""
    out: dict = {}
    for i, row in enumerate(runs[0]["rows"]):
        entry, method = row["entry"], row["method"]
        rows = [r["rows"][i] for r in runs]
        if any(r["entry"] != entry or r["method"] != method for r in rows):
            raise ValueError("the realisations were run with different entries or methods")
        finest = [r["difference"][-1] for r in rows]
        est = [r["estimate_difference"] for r in rows]
        peaks = [r["peaks_Pa"][-1] for r in rows]
        estimates = [r["estimate_Pa"] for r in rows]
        out.setdefault(entry, {})[method] = {
            "finest_Pa": peaks,
            "estimate_Pa": estimates,
            "finest_difference": finest,
            "estimate_difference": est,
            "finest_mean": statistics.fmean(finest),
            "estimate_mean": statistics.fmean(est),
            "finest_sd": statistics.stdev(finest),
            "estimate_sd": statistics.stdev(est),
            "finest_spread": (max(peaks) - min(peaks)) / statistics.fmean(peaks),
            "estimate_spread": (max(estimates) - min(estimates)) / statistics.fmean(estimates),
        }
    return out


def markdown(s: dict, runs: list[dict]) -> str:
    def pct(x: float) -> str:
        return f"{100 * x:+.2f} %"

    lines = [
        f"{runs[0]['loadcase']} at {runs[0]['preset']}, {len(runs)} realisations: the finest level "
        "(and the estimate) against the full study in each, their mean, and the full study's own spread",
        "",
        "| entry | method | finest level - full, each | mean, sd | estimate - full, each | mean, sd |",
        "| --- | --- | --- | --- | --- | --- |",
    ]
    for entry, methods in s.items():
        for method, m in methods.items():
            if method == "full":
                lines.append(
                    f"| {entry} | full: its peaks, their spread | "
                    f"{', '.join(f'{p / 1e6:.2f}' for p in m['finest_Pa'])} MPa | {100 * m['finest_spread']:.2f} % | "
                    f"{', '.join(f'{p / 1e6:.2f}' for p in m['estimate_Pa'])} MPa | {100 * m['estimate_spread']:.2f} % |"
                )
            else:
                lines.append(
                    f"| {entry} | {method} | {', '.join(map(pct, m['finest_difference']))} | "
                    f"{pct(m['finest_mean'])}, {100 * m['finest_sd']:.2f} % | "
                    f"{', '.join(map(pct, m['estimate_difference']))} | "
                    f"{pct(m['estimate_mean'])}, {100 * m['estimate_sd']:.2f} % |"
                )
    lines += ["", "| realisation | study | DOF per level | wall, s | CPU, s |", "| --- | --- | --- | --- | --- |"]
    for r in runs:
        for k, dof in r["dof"].items():
            sec = r["seconds"]
            lines.append(
                f"| {r.get('stretch', 0)} | {k} | {' / '.join(map(str, dof))} | {sec[k]:.1f} | {sec[k + ' CPU']:.1f} |"
            )
    lines.append(f"\npeak resident memory {max(r['peak_rss_GB'] for r in runs):.2f} GB (one realisation's process)")
    return "\n".join(lines) + "\n"


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("loadcase", type=Path)
    ap.add_argument("--preset", default="coarse")
    ap.add_argument("--realisations", type=int, default=3)
    ap.add_argument("--radii", type=float, nargs="+", default=[3.0])
    ap.add_argument("--factors", type=float, nargs="+", default=[1.0, 1.5, 2.0])
    ap.add_argument("--out", type=Path, default=Path("zone_scatter"), help="output folder")
    args = ap.parse_args(argv)
    if args.realisations < 2:
        ap.error("--realisations: at least 2")
    args.out.mkdir(parents=True, exist_ok=True)
    runs = [run(args, k) for k in range(args.realisations)]
    s = summary(runs)
    (args.out / "summary.json").write_text(json.dumps(s, indent=1))
    text = markdown(s, runs)
    (args.out / "summary.md").write_text(text)
    print(text)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
