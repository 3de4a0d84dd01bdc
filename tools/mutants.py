"""A spot check of the tests' power: hand-written physical slips, one at a time.

Each mutant is a slip a person could make in the physics (a frame turned the wrong way,
a load left in, a lever from the wrong plane): a file, a text in it, the text it
becomes, and the test files that target that code.  The script copies the repository
(the files git tracks and the untracked ones it does not ignore, so work not yet
committed is checked too) to a scratch folder, applies each mutant alone there, runs its
test files with pytest (stopping at the first failure) and restores the file.  A mutant
is *caught* when a test fails, *missed* when all pass; *stale* when its text is no
longer in the file (the code moved on: update the list), *error* when pytest could not
run the tests (exit code other than 0 and 1).

    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/mutants.py             # every mutant
    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/mutants.py --list      # the list
    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/mutants.py shaft-web-sense joint-slip-friction

Exit status 0 when every mutant is caught.  Not run in CI (each mutant runs real meshes
and solves); docs/testing.md records the last run.
"""

from __future__ import annotations

import argparse
import os
import shutil
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


@dataclass(frozen=True)
class Mutant:
    name: str
    file: str
    old: str
    new: str
    tests: tuple[str, ...]
    what: str


_SHAFT_TESTS = ("tests/fe/test_fe_shaft_frames.py", "tests/fe/test_fe_shaft_throws.py")

MUTANTS = (
    Mutant(
        "shaft-reference-offset",
        "fe_crank/fe/shaft/whole_shaft.py",
        "psi = np.asarray(dynamics.throws[first.name].angle_global) - layout.sense * first.angle",
        "psi = np.asarray(dynamics.throws[first.name].angle_global)",
        _SHAFT_TESTS,
        "a throw's angle in the whole shaft without the reference throw's offset (the throw frame used as the shaft frame)",
    ),
    Mutant(
        "shaft-web-sense",
        "fe_crank/fe/shaft/cycle.py",
        "R = rotation(layout.sense * th.angle)[:2, :2]",
        "R = rotation(th.angle)[:2, :2]",
        _SHAFT_TESTS,
        "the web moments without the shaft's sense of rotation",
    ),
    Mutant(
        "shaft-web-counterweights",
        "fe_crank/fe/shaft/cycle.py",
        '        if name.startswith("counterweight") and not counterweights:\n            continue\n',
        "",
        _SHAFT_TESTS,
        'the "without counterweights" web moments still carrying the counterweights\' centrifugal load',
    ),
    Mutant(
        "shaft-web-plane",
        "fe_crank/fe/shaft/cycle.py",
        "for web, zc in ((1, th.z - zp - t / 2), (2, th.z + zp + t / 2)):",
        "for web, zc in ((1, th.z - zp - t - g.journal_length), (2, th.z + zp + t + g.journal_length)):",
        _SHAFT_TESTS,
        "the web moment taken at the bearing centre instead of the web's mid-plane",
    ),
    Mutant(
        "shaft-front-torque-sense",
        "fe_crank/fe/shaft/whole_shaft.py",
        "return spin, -sense * np.asarray(dynamics.throws[first].torque_front, float)",
        "return spin, -np.asarray(dynamics.throws[first].torque_front, float)",
        ("tests/fe/test_fe_shaft_frames.py",),
        "the journal torque entering at the front without the shaft's sense of rotation",
    ),
    Mutant(
        "shaft-spin-up-sense",
        "fe_crank/fe/shaft/whole_shaft.py",
        "spin[pp.throw] = -sense * rest / jz",
        "spin[pp.throw] = -rest / jz",
        ("tests/fe/test_fe_shaft_frames.py",),
        "a throw's inertia torque (torque flow) without the shaft's sense of rotation",
    ),
    Mutant(
        "shaft-end-unbalance-sense",
        "fe_crank/fe/shaft/whole_shaft.py",
        "alpha = layout.sense * (a1 + e.unbalance_angle)",
        "alpha = a1 + e.unbalance_angle",
        ("tests/fe/test_fe_shaft_frames.py",),
        "a flywheel's or pulley's unbalance placed without the shaft's sense of rotation",
    ),
    Mutant(
        "shaft-end-lever",
        "fe_crank/fe/shaft/whole_shaft.py",
        "c = model.coupling(e.name, z + sign * e.offset, [(k, face)])",
        "c = model.coupling(e.name, z, [(k, face)])",
        ("tests/fe/test_fe_shaft_frames.py",),
        "an overhung flywheel's or pulley's load put on the end face (its lever lost)",
    ),
    Mutant(
        "bearing-envelope-best",
        "fe_crank/fe/shaft/whole_shaft.py",
        "return tuple(max(loads, key=lambda b: b.peak_n) for loads in zip(*per_law))",
        "return tuple(min(loads, key=lambda b: b.peak_n) for loads in zip(*per_law))",
        ("tests/fe/test_fe_shaft_throws.py",),
        "the main-bearing envelope taking the least loaded law instead of the most",
    ),
    Mutant(
        "bearing-clearance-gap",
        "fe_crank/fe/shaft/bearings.py",
        "F = -k * np.where(on, r - c, 0.0)[:, None] * e",
        "F = -k * np.where(on, r, 0.0)[:, None] * e",
        ("tests/fe/test_fe_shaft_beam.py",),
        "the clearance law without its gap (the contact force on the whole displacement)",
    ),
    Mutant(
        "joint-slip-friction",
        "fe_crank/assess/cw_joint.py",
        "mu_t = joint.interface_friction",
        "mu_t = joint.thread_friction",
        ("tests/assess/test_assess_bolt_eccentric.py", "tests/assess/test_assess_cw_joint.py"),
        "the VDI 2230 slip safety (R12) with the thread friction instead of the joint interface friction",
    ),
)


def _copy(dest: Path) -> None:
    files = subprocess.run(
        ["git", "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        cwd=ROOT,
        check=True,
        capture_output=True,
    ).stdout.split(b"\0")
    for f in files:
        if not f:
            continue
        src = ROOT / os.fsdecode(f)
        if src.is_file():
            out = dest / os.fsdecode(f)
            out.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, out)


def run(mutant: Mutant, scratch: Path, timeout: float) -> tuple[str, float, str]:
    """(result, seconds, the first failing test or a note)."""
    path = scratch / mutant.file
    text = path.read_text()
    if text.count(mutant.old) != 1:
        return "stale", 0.0, f"the text occurs {text.count(mutant.old)} times in {mutant.file}"
    env = dict(os.environ, PYTHONPATH=str(scratch), OPENBLAS_NUM_THREADS="1", PYTHONDONTWRITEBYTECODE="1")
    cmd = [sys.executable, "-m", "pytest", "-q", "-x", "-rf", "-p", "no:cacheprovider", *mutant.tests]
    t0 = time.perf_counter()
    try:
        path.write_text(text.replace(mutant.old, mutant.new))
        proc = subprocess.run(cmd, cwd=scratch, env=env, capture_output=True, text=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return "caught", time.perf_counter() - t0, "timed out"
    finally:
        path.write_text(text)
    dt = time.perf_counter() - t0
    failed = [ln.split(" ", 2)[1] for ln in proc.stdout.splitlines() if ln.startswith("FAILED ")]
    if proc.returncode == 1:
        return "caught", dt, failed[0] if failed else "a test failed"
    if proc.returncode == 0:
        return "missed", dt, ""
    return "error", dt, f"pytest exit {proc.returncode}: {proc.stdout.strip().splitlines()[-1:]}"


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("names", nargs="*", help="mutants to run (default: all)")
    ap.add_argument("--list", action="store_true", help="list the mutants and exit")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per mutant (a hang counts as caught)")
    ap.add_argument("--keep", action="store_true", help="keep the scratch copy")
    args = ap.parse_args(argv)
    chosen = [m for m in MUTANTS if not args.names or m.name in args.names]
    unknown = set(args.names) - {m.name for m in MUTANTS}
    if unknown:
        ap.error(f"no mutant named {', '.join(sorted(unknown))}")
    if args.list:
        for m in chosen:
            print(f"{m.name}: {m.what}\n    {m.file}; tests: {' '.join(m.tests)}")
        return 0
    scratch = Path(tempfile.mkdtemp(prefix="fe-crank-mutants-"))
    try:
        _copy(scratch)
        results = []
        for m in chosen:
            res, dt, note = run(m, scratch, args.timeout)
            results.append(res)
            print(f"{m.name:28s} {res:7s} {dt:6.0f} s  {note}", flush=True)
        print(f"{results.count('caught')} of {len(chosen)} caught")
        return 0 if all(r == "caught" for r in results) else 1
    finally:
        if args.keep:
            print(f"scratch copy: {scratch}")
        else:
            shutil.rmtree(scratch, ignore_errors=True)


if __name__ == "__main__":
    sys.exit(main())
