"""Firing order and firing offsets: either or both, and when both they must agree; the
shipped engine files fire in the order their names state."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.engine import load_engine
from fe_crank.io.firing import order_of_offsets
from fe_crank.io.loadcase import load_loadcase

ROOT = Path(__file__).resolve().parents[2]

FOUR = """\
name = "flat four"
strokes = 4
{order}

[cylinder_defaults]
bore = "86 mm"
rod_length = "143.5 mm"
rod_mass = "0.55 kg"
rod_cg_from_big_end = "37 mm"
piston_mass = "0.40 kg"
"""
THROW = '\n[[throws]]\nname = "{n}"\nangle = "{a} deg"\nstroke = "86 mm"\n'
CYL = '\n[[cylinders]]\nname = "{n}"\nthrow = "{n}"\n{offset}\n'


def four(tmp_path, order: str | None, offsets: dict[str, float] | None) -> Path:
    text = FOUR.format(order="" if order is None else f"firing_order = {order}")
    for n, a in zip("1234", (0, 180, 180, 0), strict=True):
        text += THROW.format(n=n, a=a)
    for n in "1234":
        off = "" if offsets is None or n not in offsets else f'firing_offset = "{offsets[n]} deg"'
        text += CYL.format(n=n, offset=off)
    p = tmp_path / "engine.toml"
    p.write_text(text)
    return p


def offsets_deg(engine) -> dict[str, float]:
    return {c.name: float(np.degrees(c.firing_offset)) for c in engine.cylinders}


def test_order_alone_is_evenly_spaced(tmp_path):
    e = load_engine(four(tmp_path, '["1", "3", "4", "2"]', None))
    assert offsets_deg(e) == pytest.approx({"1": 0.0, "3": 180.0, "4": 360.0, "2": 540.0})


def test_order_and_offsets_that_agree_load_and_keep_the_offsets(tmp_path):
    """The offsets are kept as given (the order only checks them), counted from the
    order's first cylinder and modulo the cycle: 3 (180), 4 (360), 2 (540), 1 (720 = 0)."""
    offs = {"1": 720, "2": 540, "3": 180, "4": 360}
    e = load_engine(four(tmp_path, '["3", "4", "2", "1"]', offs))
    assert offsets_deg(e) == pytest.approx({k: float(v) for k, v in offs.items()})


def test_order_that_contradicts_the_offsets_is_refused_with_both_orders(tmp_path, capsys):
    """The shipped inline-4 used to say 1-3-4-2 and fire 1-2-4-3: refused, naming the file,
    the key and both orders."""
    p = four(tmp_path, '["1", "3", "4", "2"]', {"1": 0, "2": 180, "3": 540, "4": 360})
    with pytest.raises(InputError) as err:
        load_engine(p)
    assert err.value.file == str(p) and err.value.key == "firing_order"
    assert "firing order 1-3-4-2 contradicts" in err.value.reason
    assert "fire 1-2-4-3 (1 at 0 deg, 2 at 180 deg, 4 at 360 deg, 3 at 540 deg)" in err.value.reason
    assert main(["validate", str(p)]) == 2
    out = capsys.readouterr()
    assert "firing_order" in out.err and "Traceback" not in out.err


def test_offsets_for_only_some_cylinders_with_an_order_are_refused(tmp_path):
    with pytest.raises(InputError, match="firing offsets for only some cylinders") as err:
        load_engine(four(tmp_path, '["1", "3", "4", "2"]', {"1": 0, "3": 180}))
    assert err.value.key == "firing_order"


def test_an_order_naming_a_cylinder_twice_is_refused(tmp_path):
    with pytest.raises(InputError, match=r"named twice: \['1'\]") as err:
        load_engine(four(tmp_path, '["1", "3", "4", "1"]', None))
    assert err.value.key == "firing_order"


def test_cylinders_firing_together_may_be_listed_in_either_order():
    """Ties keep the order given: two cylinders at one angle (e.g. opposed pistons)."""
    cyc = 4 * np.pi
    offs = {"a": 0.0, "b": np.pi, "c": np.pi}
    assert order_of_offsets(offs, cyc) == ["a", "b", "c"]
    assert order_of_offsets({"a": 0.0, "c": np.pi, "b": np.pi}, cyc) == ["a", "c", "b"]


def test_inline_engine_in_a_load_case_is_checked_with_its_key(tmp_path):
    text = four(tmp_path, '["1", "3", "4", "2"]', {"1": 0, "2": 180, "3": 540, "4": 360}).read_text()
    text = re.sub(r"^\[(\[?)(\w)", r"[\1engine.\2", text, flags=re.M)
    case = tmp_path / "case.toml"
    case.write_text('name = "c"\n\n[operating]\nspeed = "3000 rpm"\n\n[engine]\n' + text)
    with pytest.raises(InputError) as err:
        load_loadcase(case)
    assert err.value.file == str(case) and err.value.key == "engine.firing_order"


def _engine_files():
    """Engine files and load cases with an inline [engine] table whose name states an order."""
    files = [*(ROOT / "engines").glob("*.toml"), *(ROOT / "loadcases").glob("**/*.toml")]
    files += (ROOT / "tests" / "data").glob("*.toml")
    for p in sorted(files):
        text = p.read_text()
        inline = p.parent.name != "engines" and "[engine]" in text
        if (p.parent.name == "engines" or inline) and re.search(r'^name = ".*firing \w+-', text, re.M):
            yield p


@pytest.mark.parametrize("path", list(_engine_files()), ids=lambda p: p.name)
def test_shipped_engines_fire_in_the_order_their_names_state(path):
    """Every shipped engine (engine files and inline [engine] tables) whose name states
    "firing a-b-c" fires in that order by its offsets, and states it as firing_order (so
    that the file is refused if the two ever part again)."""
    e = load_engine(path) if path.parent.name == "engines" else load_loadcase(path).engine
    stated = re.search(r"firing ((?:\w+-)+\w+)", e.name).group(1).split("-")
    offs = {c.name: c.firing_offset for c in e.cylinders}
    assert order_of_offsets(offs, e.cycle_angle, first=stated[0]) == stated
    assert re.search(r"^firing_order = \[", path.read_text(), re.M)


def test_the_labelled_engines_are_found():
    names = {p.name for p in _engine_files()}
    assert {"inline3.toml", "inline4.toml", "inline6.toml", "inline4_genset_torsion.toml"} <= names
