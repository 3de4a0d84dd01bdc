"""[material] and [criteria] sections: library, overrides, units, clear errors, exit 2."""

from __future__ import annotations

import textwrap

import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.criteria import build_criteria
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.material import library, load_material, parse_material

ENGINE = """
[engine]
name = "test single"
strokes = 4
[[engine.throws]]
name = "1"
crank_radius = "64 mm"
[[engine.cylinders]]
name = "1"
throw = "1"
bore = "92 mm"
rod_length = "307 mm"
rod_mass = "1.2 kg"
rod_cg_from_big_end = "80 mm"
piston_mass = "0.9 kg"
"""


def _case(tmp_path, body: str):
    p = tmp_path / "case.toml"
    p.write_text('name = "t"\n[operating]\nspeed = "2800 rpm"\n' + textwrap.dedent(body) + ENGINE)
    return p


def test_library_values_in_si_with_sources():
    m = load_material("42CrMo4")
    assert m.yield_strength == pytest.approx(650e6) and m.tensile_strength == pytest.approx(900e6)
    assert m.youngs_modulus == pytest.approx(210e9) and m.density == pytest.approx(7850.0)
    assert "EN 10083-3" in m.source
    for name, props in library().items():
        for key in (
            "youngs_modulus",
            "poisson_ratio",
            "density",
            "yield_strength",
            "tensile_strength",
            "fatigue_limit_bending",
            "fatigue_limit_torsion",
            "source",
        ):
            assert key in props, (name, key)
        # the header's convention: tau_W = 0.577 sigma_W for steels, 0.65 for nodular iron
        ratio = props["fatigue_limit_torsion"] / props["fatigue_limit_bending"]
        assert ratio == pytest.approx(0.65 if "GJS" in name else 0.577, abs=0.003)


def test_override_with_units_and_recorded_in_source(tmp_path):
    m = parse_material({"name": "C45", "yield_strength": "0.35 GPa", "surface_factor": 0.9}, tmp_path / "x.toml")
    assert m.yield_strength == pytest.approx(350e6) and m.surface_factor == pytest.approx(0.9)
    assert "overridden in x.toml: surface_factor, yield_strength" in m.source


@pytest.mark.parametrize(
    "value, key, words",
    [
        ({"name": "Unobtainium"}, "material.name", "unknown material"),
        ({"name": "C45", "yield_strength": "300"}, "material.yield_strength", "no unit"),
        ({"name": "C45", "yield_strength": "300 mm"}, "material.yield_strength", "not a pressure"),
        ({"name": "C45", "yield_strength": "900 MPa"}, "material.yield_strength", "exceeds tensile"),
        ({"name": "C45", "hardness": "200 HB"}, "material.hardness", "unknown key"),
        ({"poisson_ratio": 0.3, "density": "7850 kg/m^3"}, "material.youngs_modulus", "required"),
    ],
)
def test_material_errors_name_key(value, key, words):
    with pytest.raises(InputError) as e:
        parse_material(value, "case.toml", "material")
    assert e.value.key == key and words in str(e.value) and "case.toml" in str(e.value)


def test_criteria_parse_units():
    c = build_criteria(
        {"min_static_safety": 1.5, "max_counterweight_stress": "150 MPa", "m53_additional_bending": "30 MPa"}, "f.toml"
    )
    assert c.limit("static_safety").value == 1.5
    assert c.limit("counterweight_stress").value == pytest.approx(150e6)
    assert c.m53_additional_bending == pytest.approx(30e6)


@pytest.mark.parametrize(
    "value, key, words",
    [
        ({"min_fatigue_safty": 1.3}, "criteria.min_fatigue_safty", "unknown quantity 'fatigue_safty'"),
        ({"max_static_safety": 1.3}, "criteria.max_static_safety", "takes a minimum"),
        ({"limit_static_safety": 1.3}, "criteria.limit_static_safety", "not a criterion"),
        ({"max_counterweight_stress": 150}, "criteria.max_counterweight_stress", "without a unit"),
        ({"min_static_safety": "1.5"}, "criteria.min_static_safety", "pure number"),
    ],
)
def test_criteria_errors_name_key(value, key, words):
    with pytest.raises(InputError) as e:
        build_criteria(value, "f.toml")
    assert e.value.key == key and words in str(e.value)


def test_loadcase_with_material_and_criteria(tmp_path):
    p = _case(
        tmp_path,
        """
        [material]
        name = "42CrMo4"
        [criteria]
        min_static_safety = 1.5
        min_m53_acceptability = 1.15
        m53_quasi_static_torque = true
        """,
    )
    lc = load_loadcase(p)
    assert lc.material.name == "42CrMo4" and lc.criteria.limit("m53_acceptability").value == 1.15
    assert main(["validate", str(p)]) == 0


def test_material_missing_property_a_criterion_needs(tmp_path, capsys):
    p = _case(
        tmp_path,
        """
        [material]
        name = "EN-GJS-700-2"
        [criteria]
        min_m53_acceptability = 1.15
        """,
    )
    with pytest.raises(InputError) as e:
        load_loadcase(p)
    assert e.value.key == "criteria.min_m53_acceptability" and "m53_k" in str(e.value)
    assert main(["validate", str(p)]) == 2
    assert "m53_k" in capsys.readouterr().err


def test_unknown_quantity_exit_2(tmp_path, capsys):
    p = _case(
        tmp_path,
        """
        [material]
        name = "C45"
        [criteria]
        min_bending_safety = 1.2
        """,
    )
    assert main(["validate", str(p)]) == 2
    err = capsys.readouterr().err
    assert "criteria.min_bending_safety" in err and "unknown quantity" in err and "Traceback" not in err


def test_criterion_without_material_section(tmp_path):
    p = _case(
        tmp_path,
        """
        [criteria]
        min_fatigue_safety = 1.2
        """,
    )
    with pytest.raises(InputError, match="needs a \\[material\\] section"):
        load_loadcase(p)
