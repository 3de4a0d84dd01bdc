"""Engine and load-case input: the seed files load; every kind of bad input gives one
message naming file and key, ``validate`` exits 2, and no traceback; gas input forms."""

import re

import numpy as np
import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.engine import load_engine
from fe_crank.io.gas import read_gas_csv
from fe_crank.io.loadcase import load_loadcase

ENGINE = """\
name = "test single"
strokes = 4

[[throws]]
name = "1"
angle = "0 deg"
crank_radius = "64 mm"
rotating_mass = "0.17 kg"

[[cylinders]]
name = "1"
throw = "1"
bore = "92 mm"
rod_length = "307 mm"
rod_mass = "1.9 kg"
rod_cg_from_big_end = "138 mm"
piston_mass = "1.1 kg"

[gas]
angle_unit = "deg"
pressure_unit = "MPa"
points = [[0, 4.0], [30, 2.0], [180, 0.3], [360, 0.1], [540, 0.1], [700, 1.5], [720, 4.0]]
"""

CASE = """\
name = "test case"
engine = "engine.toml"

[operating]
speed = "2800 rpm"
"""


def _write(tmp_path, engine=ENGINE, case=CASE):
    (tmp_path / "engine.toml").write_text(engine)
    (tmp_path / "case.toml").write_text(case)
    return tmp_path / "case.toml"


def test_seed_files_load(root):
    lc = load_loadcase(root / "loadcases/single_cylinder.toml")
    e = lc.engine
    assert e.throws[0].crank_radius == pytest.approx(0.064)
    assert e.cylinders[0].rod.length == pytest.approx(0.307)
    assert lc.operating.speed == pytest.approx(2800 * np.pi / 30)  # 293.215 rad/s (seed: 293.07 with pi = 3.14)
    assert e.gas is not None and e.gas.pressure.max() > 3e6
    assert (
        main(
            [
                "validate",
                str(root / "loadcases/single_cylinder.toml"),
                str(root / "engines/single_cylinder.toml"),
            ]
        )
        == 0
    )


def test_good_file_loads(tmp_path):
    lc = load_loadcase(_write(tmp_path))
    assert lc.engine.gas.angle[-1] == pytest.approx(4 * np.pi)
    assert lc.engine.gas.pressure[0] == pytest.approx(4e6)


BAD = [
    (
        "missing key",
        lambda e, c: (e.replace('bore = "92 mm"\n', ""), c),
        "engine.toml",
        "cylinders[0].bore",
        "required key is missing",
    ),
    (
        "unknown key",
        lambda e, c: (e.replace('bore = "92 mm"', 'bore = "92 mm"\nboree = "92 mm"'), c),
        "engine.toml",
        "cylinders[0].boree",
        "unknown key",
    ),
    (
        "value without unit",
        lambda e, c: (e.replace('"92 mm"', "92"), c),
        "engine.toml",
        "cylinders[0].bore",
        "without a unit",
    ),
    (
        "unit-less string",
        lambda e, c: (e, c.replace('"2800 rpm"', '"2800"')),
        "case.toml",
        "operating.speed",
        "has no unit",
    ),
    (
        "wrong dimension",
        lambda e, c: (e.replace('crank_radius = "64 mm"', 'stroke = "66 kg"'), c),
        "engine.toml",
        "throws[0].stroke",
        "is a mass, not a length",
    ),
    (
        "negative size",
        lambda e, c: (e.replace('"92 mm"', '"-92 mm"'), c),
        "engine.toml",
        "cylinders[0]",
        "bore must be positive",
    ),
    (
        "zero size",
        lambda e, c: (e.replace('"64 mm"', '"0 mm"'), c),
        "engine.toml",
        "throws[0]",
        "crank radius must be positive",
    ),
    (
        "rod shorter than crank",
        lambda e, c: (e.replace('"307 mm"', '"50 mm"').replace('"138 mm"', '"20 mm"'), c),
        "engine.toml",
        "cylinders[0].rod_length",
        "must exceed crank radius",
    ),
    (
        "firing order names a missing cylinder",
        lambda e, c: (e.replace("strokes = 4", 'strokes = 4\nfiring_order = ["1", "7"]'), c),
        "engine.toml",
        "firing_order[1]",
        "'7'",
    ),
    ("malformed TOML", lambda e, c: (e.replace('name = "1"', 'name = "1'), c), "engine.toml", "line", "malformed TOML"),
    (
        "unknown top-level key in the load case",
        lambda e, c: (e, c + 'speeed = "1 rpm"\n'),
        "case.toml",
        "speeed",
        "unknown key",
    ),
    (
        "missing operating point",
        lambda e, c: (e, c.replace('[operating]\nspeed = "2800 rpm"\n', "")),
        "case.toml",
        "operating",
        "required key is missing",
    ),
    (
        "gas unit wrong",
        lambda e, c: (e.replace('pressure_unit = "MPa"', 'pressure_unit = "mm"'), c),
        "engine.toml",
        "gas",
        "not a pressure unit",
    ),
    (
        "gas beyond the cycle",
        lambda e, c: (e.replace("[720, 4.0]", "[800, 4.0]"), c),
        "engine.toml",
        "gas.points",
        "within one cycle",
    ),
]


@pytest.mark.parametrize("label,edit,file,key,reason", BAD, ids=[b[0] for b in BAD])
def test_bad_input_one_message_naming_file_and_key(tmp_path, capsys, label, edit, file, key, reason):
    eng, case = edit(ENGINE, CASE)
    path = _write(tmp_path, eng, case)
    with pytest.raises(InputError) as info:
        load_loadcase(path)
    msg = str(info.value)
    assert file in msg and key in msg and reason in msg, msg
    assert main(["validate", str(path)]) == 2
    cap = capsys.readouterr()
    assert "Traceback" not in cap.err and "Error:" not in cap.err
    lines = [ln for ln in cap.err.splitlines() if ln.strip()]
    assert len(lines) == 1, cap.err
    assert re.search(re.escape(file), lines[0]) and key in lines[0]
    # the dynamics command reports the same error, also with exit 2
    assert main(["dynamics", str(path), "-o", str(tmp_path / "out")]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_gas_csv_round_trip(tmp_path):
    ang = np.linspace(0, 720, 73)
    p = 0.1 + 4.0 * np.exp(-(((ang - 370) / 30) ** 2))
    lines = ["angle [deg], pressure [MPa]"] + [f"{a:.10g}, {q:.10g}" for a, q in zip(ang, p)]
    (tmp_path / "p.csv").write_text("\n".join(lines) + "\n")
    eng = ENGINE.split("[gas]")[0] + '[gas]\nmodel = "csv"\nfile = "p.csv"\n'
    lc = load_loadcase(_write(tmp_path, eng))
    np.testing.assert_allclose(lc.engine.gas.angle, np.radians(ang), rtol=1e-12)
    np.testing.assert_allclose(lc.engine.gas.pressure, p * 1e6, rtol=1e-9)
    # a header without units is an error naming the file
    (tmp_path / "p.csv").write_text("angle, pressure\n0, 1\n720, 1\n")
    with pytest.raises(InputError, match=r"p\.csv.*unit"):
        read_gas_csv(tmp_path / "p.csv")
    (tmp_path / "p.csv").write_text("angle [deg], pressure [MPa]\n0, 1\n720, x\n")
    with pytest.raises(InputError, match=r"p\.csv: row 3"):
        read_gas_csv(tmp_path / "p.csv")


def test_gas_wiebe_model_input(tmp_path):
    eng = (
        ENGINE.split("[gas]")[0]
        + """[gas]
model = "wiebe"
compression_ratio = 8.5
intake_pressure = "0.09 MPa"
exhaust_pressure = "0.11 MPa"
heat_released = "1.8 kJ"
combustion_start = "-15 deg"
combustion_duration = "50 deg"
"""
    )
    e = load_engine(_write(tmp_path, eng).parent / "engine.toml")
    assert 3e6 < e.gas.pressure.max() < 8e6
    with pytest.raises(InputError, match=r"engine\.toml: gas\.heat_released"):
        load_engine(_write(tmp_path, eng.replace('"1.8 kJ"', '"1.8 kg"')).parent / "engine.toml")
