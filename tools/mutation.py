"""Mutation testing of the core physics modules with mutmut (not run in CI).

Each module is mutated on its own, in a fresh copy of the repository, and each mutant is
run against that module's fast tests only (a per-module selection: the whole suite takes
too long per mutant).  A mutant is *killed* when a test fails, *survived* otherwise;
`timeout` counts as killed (the mutant made a test hang).  The score per module is
killed / (killed + survived); docs/testing.md records the last run and every survivor.

    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/mutation.py            # all modules
    OPENBLAS_NUM_THREADS=1 .venv/bin/python tools/mutation.py kinematics # one module
    ... tools/mutation.py kinematics --only 'fe_crank.mechanism.kinematics.x_piston_motion__mutmut_*'

Needs `pip install mutmut` (>= 3) in the venv.  One worker (`--max-children 1`) by default:
the machine is shared.
"""

from __future__ import annotations

import argparse
import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: every fast test of the mechanism and balance stages (about 25 s in all): mutmut 3 runs
#: for each mutant only those of the selected tests that execute the mutated function, so a
#: wide selection costs little and no survivor is left to tests outside the selection.
_MECHANISM_TESTS = [
    "tests/mechanism/test_mechanism_kinematics.py",
    "tests/mechanism/test_mechanism_kinematics_coefficients.py",
    "tests/mechanism/test_mechanism_kinetostatics.py",
    "tests/mechanism/test_mechanism_dynamics.py",
    "tests/mechanism/test_mechanism_dynamics_inputs.py",
    "tests/mechanism/test_mechanism_geared_shaft.py",
    "tests/balance/test_balance_harmonics.py",
    "tests/balance/test_balance_hodograph.py",
    "tests/balance/test_balance_layouts.py",
    "tests/balance/test_balance_seed000.py",
    "tests/balance/test_balance_seed003.py",
    "tests/balance/test_balance_crosscheck.py",
    "tests/balance/test_balance_counterweights.py",
    "tests/balance/test_balance_inputs.py",
    "tests/balance/test_balance_forces_terms.py",
    "tests/balance/test_balance_roundoff.py",
    "tests/balance/test_balance_counterweight_planes.py",
    "tests/balance/test_balance_yoke_terms.py",
    "tests/mechanism/test_mechanism_dynamics_excess_work.py",
    "tests/balance/test_balance_sector_limits.py",
    "tests/mechanism/test_mechanism_kinetostatics_reactions.py",
    "tests/balance/test_balance_mechanism_exact.py",
]

#: the balance stage's whole call and its balance shafts: the mechanism selection plus the
#: tests that design balance shafts (the `fe-crank balance` command, free placement)
_BALANCE_SHAFT_TESTS = _MECHANISM_TESTS + [
    "tests/balance/test_balance_cli.py",
    "tests/torsion/test_torsion_balance_shafts.py",
    "tests/balance/test_balance_shafts_design.py",
    "tests/balance/test_balance_analysis_record.py",
]

#: the torsional-vibration physics: closed forms of the free and forced chain, Carter's
#: stiffness, the harmonics of the cylinder torques, and the stage on the shipped case
_TORSION_TESTS = [
    "tests/torsion/test_torsion_free.py",
    "tests/torsion/test_torsion_forced.py",
    "tests/torsion/test_torsion_excitation.py",
    "tests/torsion/test_torsion_stiffness.py",
    "tests/torsion/test_torsion_analysis.py",
    "tests/torsion/test_torsion_holzer_table.py",
]

#: the fast tests of the cycle assessment (hand-built unit stresses, closed-form cycles, the
#: one-cylinder dynamics and the small bar meshes of test_assess_superpose / test_assess_case;
#: about 30 s in all): shared by superpose, stress, peak, overspeed and case as above.  The
#: tests on the gmsh throw (marked heavy: 20 s of meshing and solving) are left out.
_ASSESS_TESTS = [
    "tests/assess/test_assess_superpose.py",
    "tests/assess/test_assess_stress.py",
    "tests/assess/test_assess_amplitude.py",
    "tests/assess/test_assess_peak.py",
    "tests/assess/test_assess_overspeed.py",
    "tests/assess/test_assess_case.py",
    "tests/assess/test_assess_throw.py",
    "tests/assess/test_assess_stress_layouts.py",
    "tests/assess/test_assess_group.py",
    "tests/assess/test_assess_fatigue.py::test_max_and_first_is_max_and_argmax",
]

#: module -> (file to mutate, its fast tests)
MODULES: dict[str, tuple[str, list[str]]] = {
    "kinematics": ("fe_crank/mechanism/kinematics.py", _MECHANISM_TESTS),
    "dynamics": ("fe_crank/mechanism/dynamics.py", _MECHANISM_TESTS),
    "slider_crank": ("fe_crank/mechanism/slider_crank.py", _MECHANISM_TESTS),
    "balance.harmonics": ("fe_crank/balance/harmonics.py", _MECHANISM_TESTS),
    "balance.hodograph": ("fe_crank/balance/hodograph.py", _MECHANISM_TESTS),
    "balance.forces": ("fe_crank/balance/forces.py", _MECHANISM_TESTS),
    "balance.counterweights": ("fe_crank/balance/counterweights.py", _MECHANISM_TESTS),
    "balance.nordberg": ("fe_crank/balance/nordberg.py", _MECHANISM_TESTS),
    "balance.sector": ("fe_crank/balance/sector.py", _MECHANISM_TESTS),
    "balance.terms": ("fe_crank/balance/terms.py", _MECHANISM_TESTS),
    "balance.mechanism": ("fe_crank/balance/mechanism.py", _MECHANISM_TESTS),
    "balance.analysis": ("fe_crank/balance/analysis.py", _BALANCE_SHAFT_TESTS),
    "balance.shafts": ("fe_crank/balance/shafts.py", _BALANCE_SHAFT_TESTS),
    "torsion.model": ("fe_crank/torsion/model.py", _TORSION_TESTS),
    "torsion.free": ("fe_crank/torsion/free.py", _TORSION_TESTS),
    "torsion.forced": ("fe_crank/torsion/forced.py", _TORSION_TESTS),
    "torsion.stiffness": ("fe_crank/torsion/stiffness.py", _TORSION_TESTS),
    "torsion.excitation": ("fe_crank/torsion/excitation.py", _TORSION_TESTS),
    "rules.m53.calculation": (
        "fe_crank/rules/m53/calculation.py",
        [
            "tests/assess/test_assess_m53.py",
            "tests/assess/test_assess_m53_oil_bore.py",
            "tests/assess/test_assess_adapters.py",
            "tests/assess/test_assess_m53_bores.py",
            "tests/assess/test_assess_m53_sections.py",
        ],
    ),
    "rules.m53.oil_bore": (
        "fe_crank/rules/m53/oil_bore.py",
        [
            "tests/assess/test_assess_m53_oil_bore.py",
            "tests/assess/test_assess_m53.py",
            "tests/assess/test_assess_adapters.py",
            "tests/assess/test_assess_m53_oil_bore_limits.py",
        ],
    ),
    "assess.fatigue": (
        "fe_crank/assess/fatigue.py",
        [
            "tests/assess/test_assess_fatigue.py",
            "tests/assess/test_assess_fatigue_means.py",
            "tests/assess/test_assess_amplitude.py",
        ],
    ),
    "assess.factors": (
        "fe_crank/assess/factors.py",
        [
            "tests/assess/test_assess_factors.py",
            "tests/assess/test_assess_factors_edges.py",
            "tests/assess/test_assess_fatigue.py",
            "tests/assess/test_assess_fatigue_means.py",
        ],
    ),
    "assess.criteria.verdict": (
        "fe_crank/assess/criteria/verdict.py",
        ["tests/assess/test_assess_verdict.py", "tests/assess/test_assess_fatigue.py"],
    ),
    "assess.superpose": ("fe_crank/assess/superpose.py", _ASSESS_TESTS),
    "assess.stress": ("fe_crank/assess/stress.py", _ASSESS_TESTS),
    "assess.group.peak": ("fe_crank/assess/group/peak.py", _ASSESS_TESTS),
    "mechanism.cycles": ("fe_crank/mechanism/cycles.py", _ASSESS_TESTS),
    "assess.throw": (
        "fe_crank/assess/throw.py",
        _ASSESS_TESTS
        + [
            "tests/assess/test_assess_verdict.py",
            "tests/assess/test_assess_fatigue.py",
            "tests/assess/test_assess_fatigue_means.py",
            "tests/assess/test_assess_m53_oil_bore.py",
        ],
    ),
    "assess.group.assessment": (
        "fe_crank/assess/group/assessment.py",
        _ASSESS_TESTS + ["tests/assess/test_assess_fatigue.py", "tests/assess/test_assess_fatigue_means.py"],
    ),
    "assess.group.nodes": (
        "fe_crank/assess/group/nodes.py",
        [
            "tests/assess/test_assess_groups.py",
            "tests/assess/test_assess_case.py",
            "tests/assess/test_assess_superpose.py",
        ],
    ),
    "assess.recovery": (
        "fe_crank/assess/recovery.py",
        ["tests/assess/test_assess_groups.py", "tests/assess/test_assess_case.py"],
    ),
    # the FE load and support modules: tiny meshes only (a few seconds per test file); the
    # unit-case tests on the seed throw (tests/fe/test_fe_unit_cases.py, test_fe_determinate*.py
    # of the throw, test_assess_superpose.py) solve FE models for tens of seconds a mutant
    "fe.core.loads": (
        "fe_crank/fe/core/loads.py",
        [
            "tests/fe/test_fe_loads_closed_form.py",
            "tests/fe/test_fe_determinate_statics.py",
            "tests/fe/test_fe_loads_boundaries.py",
            "tests/fe/test_fe_assembly.py",
            "tests/fe/test_fe_verification.py",
        ],
    ),
    "fe.core.determinate": (
        "fe_crank/fe/core/determinate.py",
        ["tests/fe/test_fe_determinate_statics.py", "tests/fe/test_fe_loads_boundaries.py"],
    ),
    "fe.throw.pin_directions": (
        "fe_crank/fe/throw/pin_directions.py",
        ["tests/fe/test_fe_loads_pin_directions.py", "tests/fe/test_fe_loads_closed_form.py"],
    ),
    "fe.core.forms": (
        "fe_crank/fe/core/forms.py",
        ["tests/fe/test_fe_assembly.py", "tests/fe/test_fe_verification.py"],
    ),
}


def run_module(name: str, children: int, only: list[str] | None = None, tests: list[str] | None = None) -> dict:
    """Mutate one module; with ``only`` (mutant names or fnmatch patterns, as ``mutmut
    show`` prints them) run just those mutants, e.g. the survivors of an earlier run."""
    target, selected = MODULES[name]
    tests = tests or selected
    with tempfile.TemporaryDirectory(prefix=f"mutmut-{name}-") as tmp:
        work = Path(tmp) / "repo"
        files = subprocess.run(["git", "ls-files"], cwd=ROOT, check=True, capture_output=True, text=True).stdout.split()
        for f in files:
            dst = work / f
            dst.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(ROOT / f, dst)
        sel = "\n    ".join(["-x", "-q", "-p", "no:cacheprovider", "-m", "not heavy", *tests])
        (work / "setup.cfg").write_text(
            "[mutmut]\nsource_paths = fe_crank\n"
            f"only_mutate = {target}\n"
            "also_copy =\n    tests\n    engines\n    geometry\n    loadcases\n"
            f"pytest_add_cli_args_test_selection =\n    {sel}\n"
        )
        env = dict(os.environ, OPENBLAS_NUM_THREADS="1")
        mutmut = str(Path(sys.executable).parent / "mutmut")
        subprocess.run(
            [mutmut, "run", "--max-children", str(children), *(only or [])],
            cwd=work,
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
        )
        out = subprocess.run(
            [mutmut, "results", "--all", "true"], cwd=work, env=env, capture_output=True, text=True
        ).stdout
        status: dict[str, list[str]] = {}
        by_function: dict[str, dict[str, int]] = {}
        for line in out.splitlines():
            if ":" in line:
                mutant, st = line.rsplit(":", 1)
                mutant, st = mutant.strip(), st.strip()
                if only and st == "not checked":
                    continue  # outside the requested subset
                status.setdefault(st, []).append(mutant)
                fn = by_function.setdefault(mutant.split("__mutmut_")[0], {})
                fn[st] = fn.get(st, 0) + 1
        diffs = {
            m: subprocess.run([mutmut, "show", m], cwd=work, env=env, capture_output=True, text=True).stdout
            for m in status.get("survived", [])
        }
    killed = len(status.get("killed", [])) + len(status.get("timeout", []))
    survived = len(status.get("survived", []))
    total = killed + survived
    return {
        "module": name,
        "file": target,
        "tests": tests,
        "killed": killed,
        "survived": survived,
        "other": {k: len(v) for k, v in status.items() if k not in ("killed", "timeout", "survived")},
        "score": killed / total if total else None,
        "by_function": by_function,
        "survivors": diffs,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("modules", nargs="*", default=list(MODULES), choices=list(MODULES))
    ap.add_argument("--max-children", type=int, default=1)
    ap.add_argument("--json", type=Path, help="write the per-module results here")
    ap.add_argument(
        "--only",
        nargs="+",
        metavar="MUTANT",
        help="run only these mutants (names or fnmatch patterns), e.g. earlier survivors",
    )
    ap.add_argument(
        "--tests",
        nargs="+",
        metavar="FILE",
        help="test files instead of the module's selection (e.g. to confirm that new tests kill "
        "the survivors of a full run; the score of such a run covers only those tests)",
    )
    a = ap.parse_args()
    results = []
    for m in a.modules:
        r = run_module(m, a.max_children, a.only, a.tests)
        results.append(r)
        score = "n/a" if r["score"] is None else f"{100 * r['score']:.1f} %"
        print(f"{m:24s} killed {r['killed']:4d}  survived {r['survived']:4d}  {score}  {r['other']}", flush=True)
        for diff in r["survivors"].values():
            print(diff, flush=True)
    if a.json:
        a.json.write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
