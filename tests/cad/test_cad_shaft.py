"""CAD route: a whole multi-throw crankshaft drawn in one solid, against its engine.

The shipped parametric inline-4 written to STEP as ``fe_crank.geometry.shaft`` places
it (throws at the engine's ``axial_position``s, journals between the webs, end journals,
a nose and a flange) is read back: four throws, their dimensions to 1e-6 m, the main
bearings at the layout's centres, and it passes the engine check.  The same drawing
against an engine that spaces or turns its throws otherwise is refused with both
values before any meshing."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest
from helpers.cad_files import layout_step
from helpers.shared import copy_of

from fe_crank.cad import CadInput, recognise
from fe_crank.cad.engine import engine_keys
from fe_crank.errors import InputError
from fe_crank.geometry.shaft import engine_shaft_layout
from fe_crank.io.engine import load_engine
from fe_crank.io.geometry import load_geometry

pytestmark = pytest.mark.heavy
ROOT = Path(__file__).resolve().parents[2]
POS = 1e-6  # m
KW = dict(engine_file="engines/inline4.toml", loadcase="loadcases/x.toml")


@pytest.fixture(scope="module")
def inline4(tmp_path_factory, inline4_drawing):
    """The run's one drawing of the inline-4 and its recognition (``tests/cad/conftest.py``:
    ``geometry/inline4.toml`` on ``engines/inline4.toml``, a nose 40 x 30 mm, a flange
    100 x 12 mm), the file copied into a folder of this module."""
    layout, shared_step, features = inline4_drawing
    engine = load_engine(ROOT / "engines" / "inline4.toml")
    step = copy_of(shared_step, tmp_path_factory.mktemp("i4") / shared_step.name)
    return layout, engine, CadInput(step, density=layout.geometry.density), features


def test_the_inline4_drawn_whole_is_recognised_throw_by_throw(inline4):
    layout, _, _, f = inline4
    g = layout.geometry
    assert [t.name for t in f.throws] == ["1", "2", "3", "4"]
    assert [round(math.degrees(t.angle), 9) for t in f.throws] == [0.0, 180.0, 180.0, 0.0]
    s0 = None
    for t, placed in zip(f.throws, layout.throws, strict=True):
        assert t.crank_radius == pytest.approx(g.crank_radius, abs=POS)
        assert t.crankpin.diameter == pytest.approx(g.crankpin_diameter, abs=POS)
        assert t.pin_length == pytest.approx(g.crankpin_length, abs=POS)
        for j in t.journals:
            assert j.diameter == pytest.approx(g.journal_diameter, abs=POS)
        for w in t.webs:
            assert w.thickness == pytest.approx(g.web_thickness, abs=POS)
        radii = {x.name: x.radius for x in t.fillets}
        assert radii["crankpin_fillet_1"] == pytest.approx(g.crankpin_fillet, abs=POS)
        assert radii["journal_fillet_2"] == pytest.approx(g.journal_fillet, abs=POS)
        # the bearing centres where the layout puts the main bearings
        zw = g.crankpin_length / 2 + g.web_thickness
        for b, sign in zip(t.bearings, (-1.0, 1.0), strict=True):
            assert b.z == pytest.approx(sign * (zw + layout.stub), abs=POS)
            assert not b.free_end
        s = sum(o * e for o, e in zip(t.origin, f.axis.direction, strict=True))
        s0 = s - placed.z if s0 is None else s0
        assert s - placed.z == pytest.approx(s0, abs=POS)
        assert sorted(c.web for c in t.counterweights) == [1, 2]


def test_the_nose_and_the_flange(inline4):
    layout, _, _, f = inline4
    ends = {e.name: e for e in f.ends}
    assert sorted(ends) == ["flange", "nose"]
    zw = layout.half_length
    end_len = 2 * layout.stub
    for name, throw, (d, length), z in (
        ("nose", "1", (0.04, 0.03), (-zw - end_len - 0.03, -zw - end_len)),
        ("flange", "4", (0.1, 0.012), (zw + end_len, zw + end_len + 0.012)),
    ):
        e = ends[name]
        assert e.throw == throw
        assert e.diameter == pytest.approx(d, abs=POS) and e.length == pytest.approx(length, abs=POS)
        assert (e.z_min, e.z_max) == (pytest.approx(z[0], abs=POS), pytest.approx(z[1], abs=POS))
        # a plain cylinder: m = rho pi d^2 / 4 L, on the axis
        assert e.mass.mass == pytest.approx(layout.geometry.density * math.pi * d**2 / 4 * length, rel=1e-9)
        assert e.mass.unbalance == pytest.approx(0.0, abs=1e-12)


def test_the_inline4_drawing_passes_its_engines_check(inline4):
    _, engine, cad, f = inline4
    assert engine_keys(f, cad, engine, **KW) == {n: n for n in ("1", "2", "3", "4")}


def _spaced(engine, pitch: float):
    n = len(engine.throws)
    return dataclasses.replace(
        engine,
        throws=tuple(
            dataclasses.replace(t, axial_position=(k - (n - 1) / 2) * pitch) for k, t in enumerate(engine.throws)
        ),
    )


def test_an_engine_that_spaces_the_throws_otherwise_is_refused_with_both_values(inline4):
    _, engine, cad, f = inline4
    with pytest.raises(InputError) as e:
        engine_keys(f, cad, _spaced(engine, 0.15), **KW)
    msg = str(e.value)
    assert e.value.file == str(cad.file) and e.value.key == cad.file_key
    assert "throws 1 and 2 of the CAD file are 92 mm apart" in msg and "the engine's 150 mm" in msg, msg
    assert "throws[1].axial_position less throws[0].axial_position" in msg


def test_a_two_throw_drawing_150_mm_apart_against_an_engine_92_mm_apart(tmp_path):
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    engine = load_engine(ROOT / "engines" / "inline4.toml")
    two = dataclasses.replace(engine, throws=engine.throws[:2], cylinders=engine.cylinders[:2])
    g2 = dataclasses.replace(g, throws=g.throws[:2])
    wide = engine_shaft_layout(g2, _spaced(two, 0.15), geometry_file="g", engine_file="e")
    step = layout_step(wide, tmp_path / "two.step", nose=(0.04, 0.03), flange=(0.1, 0.012))
    cad = CadInput(step, density=g.density)
    f = recognise(cad)
    with pytest.raises(InputError) as e:
        engine_keys(f, cad, _spaced(two, 0.092), **KW)
    assert "are 150 mm apart" in str(e.value) and "the engine's 92 mm" in str(e.value), str(e.value)
    assert engine_keys(f, cad, _spaced(two, 0.15), **KW) == {"1": "1", "2": "2"}
