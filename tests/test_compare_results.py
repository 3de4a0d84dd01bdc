"""benchmarks/compare_results.py: the tool that shows a restructuring left the numbers
unchanged.  Checked on hand-made report trees: it must see a change of 1e-6 relative
(well above round-off, well below any engineering change) and ignore 1e-12."""

import json
import subprocess
import sys
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[1] / "benchmarks" / "compare_results.py"


def _tree(root: Path, value: float, seconds: float, status: str = "pass") -> Path:
    case = root / "case_a"
    case.mkdir(parents=True)
    doc = {
        "case": "a",
        "source_file": str(root / "a.toml"),
        "criteria": [{"name": "criteria.min_static_safety", "value": value, "passed": True}],
    }
    (case / "results.json").write_text(json.dumps(doc))
    (case / "case.json").write_text(json.dumps({"status": status, "exit_code": 0, "worst": "x", "seconds": seconds}))
    return root


def _run(a: Path, b: Path) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, str(SCRIPT), str(a), str(b)], capture_output=True, text=True)


def test_equal_up_to_round_off_and_times(tmp_path):
    # 4.77 * (1 + 1e-12): a last-digits difference; times and paths differ and are ignored
    r = _run(_tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77 * (1 + 1e-12), 2.0))
    assert r.returncode == 0, r.stdout


def test_a_relative_change_of_1e_6_is_a_difference(tmp_path):
    r = _run(_tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77 * (1 + 1e-6), 1.0))
    assert r.returncode == 1
    assert "criteria[0].value" in r.stdout


def test_a_changed_verdict_is_a_difference(tmp_path):
    r = _run(_tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77, 1.0, status="fail"))
    assert r.returncode == 1
    assert "status" in r.stdout
