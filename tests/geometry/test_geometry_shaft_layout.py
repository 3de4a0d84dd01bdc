"""The shaft placed by the engine: bearing stubs and centres, and the refusals."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from fe_crank.errors import InputError
from fe_crank.geometry.engine_fit import bearing_stub, throw_at_bearings
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.io.base import read_toml
from fe_crank.io.engine import load_engine
from fe_crank.io.geometry import geometry_from_dict, load_geometry

ROOT = Path(__file__).resolve().parents[2]
GF, EF = "geometry/inline4.toml", "engines/inline4.toml"


@pytest.fixture(scope="module")
def inline4():
    return load_geometry(ROOT / GF), load_engine(ROOT / EF)


def layout(g, e):
    return shaft_layout(g, e, geometry_file=GF, engine_file=EF)


def test_inline4_bearings_sit_at_mid_gap(inline4):
    """92 mm pitch, webs 17 mm, pin 24 mm: gap 92 - 58 = 34 mm, the stub reaches 17 mm
    from the web to the bearing centre, the lever to the web centre is 25.5 mm; the
    bearings are the [shaft] section's 20 mm wide, else the journal's flat."""
    g, e = inline4
    L = layout(g, e)
    assert L.stub == pytest.approx(0.017)
    assert L.stub + g.web_thickness / 2 == pytest.approx(0.0255)
    assert [b.z for b in L.bearings] == pytest.approx([-0.184, -0.092, 0.0, 0.092, 0.184])
    assert [b.name for b in L.bearings] == ["1", "2", "3", "4", "5"]
    assert [b.thrust for b in L.bearings] == [False] * 4 + [True]  # next to the flywheel
    assert [b.width for b in L.bearings] == pytest.approx([0.020] * 5)  # [shaft] bearing_width
    assert all(b.width_stated for b in L.bearings)
    # without a stated width: the journal's flat, 34 - 2 x 2.5 mm
    flat = layout(dataclasses.replace(g, shaft=None), e)
    assert [b.width for b in flat.bearings] == pytest.approx([0.029] * 5)
    assert not any(b.width_stated for b in flat.bearings)
    assert throw_at_bearings(g, e, geometry_file=GF, engine_file=EF).journal_length == pytest.approx(0.017)
    assert bearing_stub(g, e, geometry_file=GF, engine_file=EF) == pytest.approx(0.017)


def test_single_throw_keeps_the_geometrys_journal(inline4):
    g, _ = inline4
    from helpers.shaft import small_engine

    one = dataclasses.replace(g, throws=g.throws[:1])
    e = small_engine([0.0], crank_radius=g.crank_radius)
    assert bearing_stub(one, e, geometry_file=GF, engine_file=EF) == g.journal_length


def _refused(g, e, *words, engine=True):
    with pytest.raises(InputError) as err:
        layout(g, e)
    text = str(err.value)
    for w in (GF, *((EF,) if engine else ()), *words):
        assert w in text, (w, text)
    return err.value


def test_refuses_another_throw_count(inline4):
    g, e = inline4
    err = _refused(dataclasses.replace(g, throws=g.throws[:3]), e, "3 throw(s)", "4 in the engine")
    assert err.key == "throws"


def test_refuses_another_angle(inline4):
    g, e = inline4
    throws = list(g.throws)
    throws[1] = dataclasses.replace(throws[1], angle=0.0)
    err = _refused(dataclasses.replace(g, throws=tuple(throws)), e, "0 deg here", "180 deg in the engine")
    assert err.key == "throws[1].angle"


def test_refuses_another_name(inline4):
    g, e = inline4
    throws = list(g.throws)
    throws[2] = dataclasses.replace(throws[2], name="X")
    err = _refused(dataclasses.replace(g, throws=tuple(throws)), e, "'X' here", "'3' in the engine")
    assert err.key == "throws[2].name"


def test_refuses_another_stroke(inline4):
    g, e = inline4
    err = _refused(dataclasses.replace(g, crank_radius=0.064), e, "stroke 128 mm", "stroke 86 mm")
    assert err.key == "stroke"


def test_refuses_a_stated_pitch_the_engine_does_not_have(inline4):
    g, e = inline4
    data = read_toml(ROOT / GF)
    data["shaft"] = {"pitch": "90 mm"}
    g2 = geometry_from_dict(data, GF)
    err = _refused(g2, e, "pitch 90 mm", "92 mm")
    assert err.key == "shaft.pitch"


def test_refuses_uneven_throw_spacing(inline4):
    g, e = inline4
    throws = list(e.throws)
    throws[3] = dataclasses.replace(throws[3], axial_position=0.15)
    with pytest.raises(InputError) as err:
        layout(g, dataclasses.replace(e, throws=tuple(throws)))
    assert err.value.file == EF and "not evenly spaced" in str(err.value)


def test_refuses_webs_that_leave_no_journal(inline4):
    g, e = inline4
    err = _refused(dataclasses.replace(g, web_thickness=0.032), e, "no room")
    assert err.key == "web.thickness"


def _with_shaft(section):
    data = read_toml(ROOT / GF)
    data["shaft"] = section
    return geometry_from_dict(data, GF)


def test_refuses_a_bearing_without_its_journal(inline4):
    _, e = inline4
    g = _with_shaft({"bearings": [{"name": "A", "journal": 0}, {"name": "B", "journal": 7}]})
    err = _refused(g, e, "journal 7", "journals 0 (front) to 4 (rear)")
    assert err.key == "shaft.bearings[1].journal"


def test_refuses_a_thrust_bearing_on_no_bearing(inline4):
    _, e = inline4
    err = _refused(_with_shaft({"thrust_bearing": "9"}), e, "'9' is none of the main bearings", engine=False)
    assert err.key == "shaft.thrust_bearing"


@pytest.mark.parametrize(
    "section, words",
    [
        ({"bearing": {"model": "spring", "stiffness": "-1e9 N/m"}}, "greater than 0"),
        (
            {"bearing": {"model": "clearance", "clearance": "-40 um", "stiffness": "1e9 N/m"}},
            "greater than or equal to 0",
        ),
        ({"bearing": {"model": "spring"}}, "needs its radial stiffness"),
        ({"bearing": {"model": "clearance", "stiffness": "1e9 N/m"}}, "needs its radial clearance"),
        ({"bearing": {"model": "spring", "stiffness": "1e9 N/m^3"}}, "not a stiffness"),
        ({"bearing": {"model": "rigid", "stiffness": "1e9 N/m"}}, "takes no stiffness"),
        ({"nose": {"diameter": "nan mm", "length": "40 mm"}}, "nose.diameter"),
        ({"bearings": [{"name": "A", "journal": 0}, {"name": "A", "journal": 1}]}, "two bearings with one name"),
        ({"bearings": [{"name": "A", "journal": 1}, {"name": "B", "journal": 1}]}, "two bearings on one journal"),
    ],
)
def test_refuses_bad_bearing_input(section, words):
    with pytest.raises(InputError) as err:
        _with_shaft(section)
    assert GF in str(err.value) and words in str(err.value), str(err.value)


def test_shaft_section_read_in_si():
    g = _with_shaft(
        {
            "nose": {"diameter": "40 mm", "length": "45 mm"},
            "bearing": {"model": "clearance", "clearance": "40 um", "stiffness": "2e9 N/m"},
            "power_takeoff": "front",
        }
    )
    assert g.shaft.nose.diameter == pytest.approx(0.04)
    assert g.shaft.bearing_law.clearance == pytest.approx(40e-6)
    assert g.shaft.bearing_law.stiffness == pytest.approx(2e9)
    assert g.shaft.power_takeoff == "front"
    assert np.isfinite(g.shaft.nose.length)


def test_explicit_bearings_on_some_journals(inline4):
    _, e = inline4
    g = _with_shaft(
        {
            "bearings": [
                {"name": "F", "journal": 0},
                {"name": "M", "journal": 2, "width": "30 mm", "bearing": {"model": "spring", "stiffness": "1e9 N/m"}},
                {"name": "R", "journal": 4},
            ],
            "thrust_bearing": "M",
        }
    )
    L = layout(g, e)
    assert [b.name for b in L.bearings] == ["F", "M", "R"]
    assert [b.z for b in L.bearings] == pytest.approx([-0.184, 0.0, 0.184])
    assert L.bearings[1].width == pytest.approx(0.03) and L.bearings[1].law.stiffness == pytest.approx(1e9)
    assert L.thrust_bearing.name == "M"
