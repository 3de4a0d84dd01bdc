"""One message per fault, without the input library's internals.

Every shipped geometry, engine and load case (and the test suite's small ones) is taken
apart leaf by leaf: each value in turn is replaced by one of the wrong kind (a number for
a text, a text for a number, a number for a table or a list), and the file parsed again by
the input layer.  Each refusal must be one message (one line naming the file and the key)
without pydantic's union members or class names (``tests/helpers/messages.py``); the conftest
applies the same check to every refusal any test provokes.  The cases the review named
are checked by name: the bolted joint's keys and a misfire given as a number.
"""

from __future__ import annotations

import copy
import tomllib
from pathlib import Path

import pytest
from helpers.messages import internals

from fe_crank.errors import InputError
from fe_crank.io.engine import build_engine
from fe_crank.io.geometry import geometry_from_dict
from fe_crank.io.includes import input_root
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.operating import parse_operating
from fe_crank.io.sections import parse_sections

ROOT = Path(__file__).resolve().parents[2]
GEOMETRIES = sorted(ROOT.glob("geometry/*.toml")) + sorted(ROOT.glob("tests/data/geometry_*.toml"))
ENGINES = sorted(ROOT.glob("engines/*.toml"))
CASES = sorted(ROOT.glob("loadcases/*.toml")) + [
    ROOT / "tests" / "data" / f"{n}.toml" for n in ("small_pass", "small_torsion")
]


def _leaves(node, path=()):
    """(path, value) of every value of a TOML tree, tables and lists included."""
    items = node.items() if isinstance(node, dict) else enumerate(node) if isinstance(node, list) else ()
    for k, v in items:
        yield (*path, k), v
        yield from _leaves(v, (*path, k))


def _wrong(value) -> list:
    """Values of the wrong kind for ``value``."""
    if isinstance(value, bool):
        return ["x"]
    if isinstance(value, (int, float)):
        return ["x"]
    if isinstance(value, str):
        return [3]
    return [3]  # a table or a list


def _set(tree, path, value):
    out = copy.deepcopy(tree)
    node = out
    for k in path[:-1]:
        node = node[k]
    node[path[-1]] = value
    return out


def _one_clean_message(exc: InputError, where: str) -> None:
    text = str(exc)
    assert not internals(text), (where, text)
    assert "\n" not in text, (where, text)  # one fault, one message
    assert exc.key, (where, text)


def _mutations(tree):
    for path, value in _leaves(tree):
        for bad in _wrong(value):
            yield path, _set(tree, path, bad)


@pytest.mark.parametrize("path", GEOMETRIES, ids=lambda p: p.name)
def test_every_wrong_value_of_a_geometry_gives_one_clean_message(path):
    tree = tomllib.loads(path.read_text())
    for where, data in _mutations(tree):
        try:
            geometry_from_dict(data, path)
        except InputError as exc:
            _one_clean_message(exc, f"{path.name}: {where}")


@pytest.mark.parametrize("path", ENGINES, ids=lambda p: p.name)
def test_every_wrong_value_of_an_engine_gives_one_clean_message(path):
    tree = tomllib.loads(path.read_text())
    for where, data in _mutations(tree):
        try:
            build_engine(data, path)
        except InputError as exc:
            _one_clean_message(exc, f"{path.name}: {where}")


@pytest.mark.parametrize("path", CASES, ids=lambda p: p.name)
def test_every_wrong_value_of_a_load_case_section_gives_one_clean_message(path):
    tree = tomllib.loads(path.read_text())
    engine = load_loadcase(path).engine
    with input_root(path, None):
        for where, data in _mutations({k: v for k, v in tree.items() if k not in ("engine", "name", "description")}):
            if where[:2] == ("operating", "gas") and len(where) > 3 and where[2] > 0:
                # the full-load curve's later diagrams have the first one's keys and parser:
                # their leaves are the first's (each parse of [operating] builds every diagram)
                continue
            try:
                if where[0] == "operating":
                    parse_operating(data["operating"], engine, path)
                elif where[0] != "geometry" or len(where) > 1:
                    parse_sections(data, path)
            except InputError as exc:
                _one_clean_message(exc, f"{path.name}: {where}")


BOLTED = tomllib.loads((ROOT / "geometry" / "inline4.toml").read_text())


@pytest.mark.parametrize(
    "key",
    ["count", "diameter", "pitch_radius", "preload", "yield_strength", "pitch", "property_class", "clamp_length",
     "bearing_diameter", "hole_diameter", "clamped_diameter", "tightening_factor", "direction", "tapped",
     "thread_friction", "head_friction", "interface_friction", "roughness", "rolled_after_heat_treatment",
     "load_introduction", "shank_length", "shank_diameter"],
)  # fmt: skip
@pytest.mark.parametrize("bad", ["nonsense", -5, {"x": 1}])
def test_a_bad_bolted_joint_value_names_its_key_once(key, bad):
    data = copy.deepcopy(BOLTED)
    data["throws"][0]["counterweight"]["bolted"][key] = bad
    with pytest.raises(InputError) as err:
        geometry_from_dict(data, "inline4.toml")
    _one_clean_message(err.value, key)
    assert err.value.key.startswith("throws[0].counterweight.bolted"), str(err.value)
    assert "counterweight.literal" not in str(err.value) and "CounterweightInput" not in str(err.value)


@pytest.mark.parametrize("value", ["3", "true", '"all"', "{ a = 1 }", "[3]"])
def test_a_misfire_that_is_not_each_or_names_is_one_message(tmp_path, value):
    text = (ROOT / "loadcases" / "single_cylinder.toml").read_text()
    for d in ("engines", "geometry"):
        (tmp_path / d).mkdir()
    (tmp_path / "loadcases").mkdir()
    for f in ("engines/single_cylinder.toml", "geometry/single_cylinder.toml"):
        (tmp_path / f).write_text((ROOT / f).read_text())
    p = tmp_path / "loadcases" / "case.toml"
    assert '\nspeed = "2800 rpm"' in text
    p.write_text(text.replace('\nspeed = "2800 rpm"', f'\nspeed = "2800 rpm"\nmisfire = {value}', 1))
    with pytest.raises(InputError) as err:
        load_loadcase(p)
    _one_clean_message(err.value, value)
    assert err.value.key.startswith("operating.misfire")
    assert "constrained-str" not in str(err.value)
