"""Property-based fuzzing of load cases (hypothesis): mutated copies of the shipped
cases, geometries and two engines, and of the test case -- keys deleted, values swapped for other types, units
swapped, extreme numbers -- must give exit 0 or 2 from ``fe-crank validate``, never
a traceback, never a hang (an alarm per example), and the cases that validate must
give finite forces and torques in the dynamics stage (or refuse with an error).

Deterministic (``derandomize``) so that CI runs the same examples every time; about
half a minute in total on the reference machine.
"""

from __future__ import annotations

import json
import math
import shutil
import signal
import tomllib
from pathlib import Path

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from fe_crank.cli import main
from fe_crank.errors import FeCrankError

ROOT = Path(__file__).resolve().parents[2]
BASES = (
    sorted(ROOT.glob("loadcases/*.toml"))
    + [ROOT / "tests" / "data" / "small_pass.toml"]
    + sorted(ROOT.glob("geometry/*.toml"))
    + [ROOT / "engines" / "single_cylinder.toml", ROOT / "engines" / "v4_90_pneumatic.toml"]
)
UNITS = [
    "mm",
    "m",
    "rpm",
    "1/min",
    "1/s",
    "Hz",
    "rad/s",
    "deg",
    "rad",
    "kg",
    "MPa",
    "bar",
    "N",
    "N*m",
    "kg*m**2",
    "kg/m^3",
    "J",
    "",
    "furlong",
    "m**9",
    "(((m)))",
    "**9**9",
    "%",
]
EXTREMES = [
    0,
    -1,
    10**30,
    -(10**30),
    1e308,
    -1e308,
    1e-308,
    0.0,
    -0.0,
    math.inf,
    -math.inf,
    math.nan,
    True,
    "",
    "x" * 200,
    "1e300 mm",
    "-5 mm",
    "0 rpm",
    "nan rpm",
    [],
    {},
    [[[]]],
]


class Hang(Exception):
    pass


def _alarm(signum, frame):
    raise Hang("no answer within the time limit")


def toml_value(v) -> str:
    """Minimal TOML writer: everything inline (quoted keys, JSON-style strings)."""
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int):
        return str(v)
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if math.isinf(v):
            return "inf" if v > 0 else "-inf"
        return repr(v)
    if isinstance(v, str):
        return json.dumps(v)
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    if isinstance(v, dict):
        return "{" + ", ".join(f"{json.dumps(str(k))} = {toml_value(x)}" for k, x in v.items()) + "}"
    raise TypeError(type(v))


def toml_text(data: dict) -> str:
    return "\n".join(f"{json.dumps(str(k))} = {toml_value(v)}" for k, v in data.items()) + "\n"


def _paths(node, prefix=()):
    """Every (path, value) below a dict/list."""
    items = node.items() if isinstance(node, dict) else enumerate(node)
    for k, v in items:
        yield prefix + (k,), v
        if isinstance(v, (dict, list)):
            yield from _paths(v, prefix + (k,))


def _set(data, path, value):
    node = data
    for k in path[:-1]:
        node = node[k]
    if value is _DELETE:
        del node[path[-1]]
    else:
        node[path[-1]] = value


_DELETE = object()


@st.composite
def mutated_case(draw):
    base = draw(st.sampled_from(BASES))
    data = tomllib.loads(base.read_text())
    for _ in range(draw(st.integers(1, 3))):
        paths = list(_paths(data))
        if not paths:
            break
        path, value = draw(st.sampled_from(paths))
        kind = draw(st.sampled_from(["delete", "extreme", "unit", "type", "number"]))
        if kind == "delete":
            new = _DELETE
        elif kind == "extreme":
            new = draw(st.sampled_from(EXTREMES))
        elif kind == "unit" and isinstance(value, str) and " " in value:
            new = value.split(" ", 1)[0] + " " + draw(st.sampled_from(UNITS))
        elif kind == "number" and isinstance(value, str) and " " in value:
            num = draw(st.floats(allow_nan=True, allow_infinity=True) | st.integers(-(10**40), 10**40))
            new = f"{num} {value.split(' ', 1)[1]}"
        else:
            new = draw(
                st.one_of(
                    st.integers(), st.floats(), st.text(max_size=20), st.booleans(), st.lists(st.integers(), max_size=3)
                )
            )
        _set(data, path, new)
    return base, data


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """A copy of the repository's input folders: mutated cases sit where the shipped
    ones do, so that their include paths resolve inside the folder tree."""
    t = tmp_path_factory.mktemp("fuzz")
    for d in ("engines", "geometry", "loadcases", "tests/data"):
        shutil.copytree(ROOT / d, t / d)
    return t


def _write(tree: Path, base: Path, data: dict) -> Path:
    p = tree / base.relative_to(ROOT).parent / "fuzzed.toml"
    p.write_text(toml_text(data))
    return p


def _run_bounded(fn, seconds: int):
    old = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(seconds)
    try:
        return fn()
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, old)


_FUZZ = settings(
    max_examples=120,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)


@_FUZZ
@given(mutated_case())
def test_validate_never_crashes(tree, capsys, case):
    base, data = case
    p = _write(tree, base, data)
    rc = _run_bounded(lambda: main(["validate", str(p)]), 20)
    err = capsys.readouterr().err
    assert rc in (0, 2), err
    assert "Traceback" not in err
    if rc == 2:
        assert str(p) in err or "fuzzed.toml" in err or ".toml" in err


@settings(
    max_examples=15,
    deadline=None,
    derandomize=True,
    database=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.function_scoped_fixture],
)
@given(mutated_case())
def test_dynamics_results_finite(tree, case):
    """Cases that validate: the dynamics stage gives finite forces and torques or a
    FeCrankError, never NaN/inf."""
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.mechanism.dynamics import analyse

    base, data = case
    p = _write(tree, base, data)
    try:
        lc = load_loadcase(p)
    except FeCrankError:
        return
    try:
        res = _run_bounded(lambda: analyse(lc.engine, lc.operating), 30)
    except FeCrankError:
        return
    assert np.all(np.isfinite(res.torque))
    for t in res.throws.values():
        assert np.all(np.isfinite(t.pin_force))
    assert math.isfinite(res.mean_torque)
