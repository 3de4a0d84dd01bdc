"""The ``[cad]`` section: what it states, and every wrong entry refused with the file,
the key and the reason (``fe_crank.io.cad``)."""

from __future__ import annotations

import pytest

from fe_crank.errors import InputError
from fe_crank.io.cad import cad_from_dict, load_cad


@pytest.fixture
def folder(tmp_path):
    d = tmp_path / "geometry"
    d.mkdir()
    return d


def section(**kw):
    base = {"file": "crank.step", "density": "7850 kg/m^3"}
    base.update(kw)
    return {k: v for k, v in base.items() if v is not None}


def parse(folder, **kw):
    return cad_from_dict(section(**kw), folder / "crank.toml")


def test_a_full_section(folder):
    cad = parse(
        folder,
        length_unit="in",
        axis="-y",
        throws=["1", "2"],
        bodies="fuse",
        counterweight_radius="40 mm",
        pin_recess="0.5 mm",
        journal_recess="0 mm",
        bearing_width="16 mm",
        faces={"axis": [3, 4], "2": {"crankpin": [7], "oil_bore": []}},
    )
    assert cad.file == folder / "crank.step"
    assert cad.length_unit == pytest.approx(0.0254, rel=1e-15)
    assert cad.length_unit_text == "in"
    assert cad.axis == (0.0, -1.0, 0.0)
    assert cad.throws == ("1", "2") and cad.bodies == "fuse"
    assert cad.counterweight_radius == pytest.approx(0.04)
    assert (cad.pin_recess, cad.journal_recess) == (pytest.approx(5e-4), 0.0)
    assert cad.bearing_width == pytest.approx(0.016)
    assert cad.override("axis").faces == (3, 4)
    assert cad.override("crankpin", "2").faces == (7,)
    assert cad.override("oil_bore", "2").faces == ()
    assert cad.override("crankpin", "1") is None
    assert cad.override("crankpin", "2").key == 'cad.faces."2".crankpin'


def test_density_from_the_material_library(folder):
    cad = parse(folder, density=None, material="42CrMo4")
    assert cad.density == pytest.approx(7850.0) and cad.material == "42CrMo4"


def test_axis_as_a_vector_is_normalised(folder):
    cad = parse(folder, axis=[0, 3, 4])
    assert cad.axis == pytest.approx((0.0, 0.6, 0.8), rel=1e-15)


@pytest.mark.parametrize(
    ("kw", "key", "words"),
    [
        ({"density": None}, "cad", "exactly one of density and material"),
        ({"material": "42CrMo4"}, "cad", "exactly one of density and material"),
        ({"density": None, "material": "unobtainium"}, "cad.material", "not in the material library"),
        ({"density": "7850"}, "cad.density", "has no unit"),
        ({"length_unit": "kg"}, "cad.length_unit", "not a length"),
        ({"length_unit": "furlongs per fortnight"}, "cad.length_unit", "unit"),
        ({"axis": "z"}, "cad.axis", '"+x"'),
        ({"axis": [0, 0, 0]}, "cad.axis", "not all zero"),
        ({"axis": [0, 1]}, "cad.axis", "three numbers"),
        ({"throws": ["1", "1"]}, "cad.throws", "different"),
        ({"bodies": "glued"}, "cad.bodies", "one"),
        ({"counterweight_radius": "-4 mm"}, "cad.counterweight_radius", "positive"),
        ({"pin_recess": "-1 mm"}, "cad.pin_recess", "negative"),
        ({"bearing_width": "0 mm"}, "cad.bearing_width", "positive"),
        ({"faces": {"crankpn": [3]}}, "cad.faces.crankpn", "unknown feature"),
        ({"faces": {"crankpin": [0]}}, "cad.faces.crankpin", "positive"),
        ({"faces": {"crankpin": []}}, "cad.faces.crankpin", "at least one"),
        ({"faces": {"9": {"crankpin": [3]}}}, "cad.faces.9", "named after a throw"),
        ({"throws": ["1", "2"], "faces": {"crankpin": [3]}}, "cad.faces.crankpin", "name the throw"),
        ({"shape": "round"}, "cad.shape", "unknown key"),
    ],
)
def test_wrong_entries(folder, kw, key, words):
    with pytest.raises(InputError) as e:
        parse(folder, **kw)
    assert e.value.key == key
    assert e.value.file == str(folder / "crank.toml")
    assert words in str(e.value)


def test_a_file_outside_the_folder_tree_is_refused(tmp_path, folder):
    with pytest.raises(InputError) as e:
        parse(folder, file="../../elsewhere/crank.step")
    assert e.value.key == "cad.file" and "outside" in str(e.value)


def test_load_cad_needs_the_section(folder):
    p = folder / "crank.toml"
    p.write_text('[geometry]\nfile = "crank.step"\n')
    with pytest.raises(InputError) as e:
        load_cad(p)
    assert e.value.key == "cad" and "no [cad] section" in str(e.value)
    p.write_text('[cad]\nfile = "crank.step"\nlength_unit = "mm"\nmaterial = "C45"\n')
    cad = load_cad(p)
    assert cad.file == folder / "crank.step" and cad.toml == str(p) and cad.length_unit == pytest.approx(1e-3)
