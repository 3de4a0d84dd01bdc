"""``fe-crank compare``: the command that shows a change left the numbers of the report
trees as they were.  Checked on hand-made report trees: it must see a change of 1e-6
relative (well above round-off, well below any engineering change) and ignore 1e-12;
``--rtol 0`` asks for equal numbers; bad input is exit 2 with one message naming it."""

import json
import math
from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.compare import compare_trees
from fe_crank.errors import InputError


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


def _run(capsys, *args) -> tuple[int, str, str]:
    code = main(["compare", *map(str, args)])
    out = capsys.readouterr()
    return code, out.out, out.err


def test_equal_up_to_round_off_and_times(tmp_path, capsys):
    # 4.77 * (1 + 1e-12): a last-digits difference; times and paths differ and are ignored
    code, out, _ = _run(capsys, _tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77 * (1 + 1e-12), 2.0))
    assert code == 0, out
    assert out == "1 case(s) compared: no difference beyond 1e-09 relative\n"


def test_a_relative_change_of_1e_6_is_a_difference(tmp_path, capsys):
    code, out, _ = _run(capsys, _tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77 * (1 + 1e-6), 1.0))
    assert code == 1
    assert "criteria[0].value" in out


def test_a_changed_verdict_is_a_difference(tmp_path, capsys):
    code, out, _ = _run(capsys, _tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", 4.77, 1.0, status="fail"))
    assert code == 1
    assert "case_a: case.json status: 'pass' != 'fail'" in out


def test_rtol_zero_asks_for_equal_numbers(tmp_path):
    up = math.nextafter(4.77, math.inf)  # one unit in the last place
    a, b = _tree(tmp_path / "a", 4.77, 1.0), _tree(tmp_path / "b", up, 3.0)
    (d,) = compare_trees(a, b, 0.0).differences
    assert d.startswith(f"case_a: criteria[0].value: 4.77 != {up!r} (relative ")
    assert compare_trees(a, b, 1e-15).differences == ()
    assert compare_trees(a, _tree(tmp_path / "c", 4.77, 5.0), 0.0).differences == ()


def test_a_case_or_a_results_file_in_one_tree_only(tmp_path):
    a, b = _tree(tmp_path / "a", 1.0, 1.0), _tree(tmp_path / "b", 1.0, 1.0)
    (a / "case_b").mkdir()
    (a / ".case_c.tmp").mkdir()  # hidden: an unfinished case folder, not compared
    (b / "case_a" / "results.json").unlink()
    got = compare_trees(a, b, 1e-9)
    assert got.cases == 2
    assert got.differences == (f"case_b: only in {a}", "case_a: results.json only in the first tree")


def test_bad_input_is_exit_2_with_one_message(tmp_path, capsys):
    a = _tree(tmp_path / "a", 1.0, 1.0)
    code, out, err = _run(capsys, a, tmp_path / "missing")
    assert code == 2 and not out
    assert err == f"fe-crank compare: error: {tmp_path / 'missing'}: no such folder (a report tree of fe-crank check)\n"
    for bad in ("-1", "nan", "inf"):
        code, _, err = _run(capsys, a, a, "--rtol", bad)
        assert code == 2 and err.startswith("fe-crank compare: error: --rtol: must be a finite number >= 0"), bad
    b = _tree(tmp_path / "b", 1.0, 1.0)
    (b / "case_a" / "results.json").write_text('{"case": "a", ')
    code, _, err = _run(capsys, a, b)
    assert code == 2
    assert err == f"fe-crank compare: error: {b / 'case_a' / 'results.json'}: not a JSON document (line 1, column 15)\n"


def test_deep_nesting_is_refused_not_a_crash(tmp_path):
    a, b = _tree(tmp_path / "a", 1.0, 1.0), _tree(tmp_path / "b", 1.0, 1.0)
    for root in (a, b):
        (root / "case_a" / "results.json").write_text("[" * 100 + "]" * 100)
    with pytest.raises(InputError, match="nested deeper than 64 levels"):
        compare_trees(a, b, 0.0)
