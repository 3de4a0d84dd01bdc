"""UR M53's machine- and process-dependent inputs: the forging factor K (section 6) from the
stated process (1.0 when not stated), sigma_add (section 4) from the engine's construction
(10 MPa trunk piston, 30 MPa crosshead) in both routes, and K_e (2.1.2.1) only for
internal-combustion engines -- by hand."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank import model
from fe_crank.assess import ThrowContext, assess_throw
from fe_crank.assess.superpose import UnitStresses
from fe_crank.errors import InputError
from fe_crank.io.engine import build_engine
from fe_crank.io.material import load_material, parse_material
from fe_crank.rules.m53.basis import additional_bending, m53_basis

D = 0.05
M_A, T_M = 2000.0, 3000.0  # N m


def _bar_units(group="journal_fillet_1", n=36):
    """Surface nodes of a round bar (diameter D): 'pin_x' = 1 N m of bending about x
    (sigma_zz = M y / I), 'torque' = 1 N m (tau_theta_z = T r / J), as in test_assess_fatigue.py."""
    a = D / 2
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    I, J = np.pi * D**4 / 64, np.pi * D**4 / 32
    s = np.zeros((3, 6, n))
    s[0, 2] = a * np.sin(phi) / I
    s[2, 5] = -a / J * np.sin(phi)
    s[2, 4] = a / J * np.cos(phi)
    pts = np.vstack([a * np.cos(phi), a * np.sin(phi), np.zeros(n)])
    return UnitStresses(s, pts, {group: np.arange(n)}, np.arange(n) + 100, ("pin_x", "pin_y", "torque"), 1.0)


def test_forging_factor_from_the_stated_process_default_one():
    """UR M53 6: K = 1.05 continuous grain flow or drop-forged, 1.0 free-form forged; the
    library no longer attaches 1.05 to every steel: not stated -> 1.0."""
    assert load_material("C45").m53_k == 1.0
    assert load_material("42CrMo4").m53_k == 1.0
    assert load_material("C45", forging="drop_forged").m53_k == 1.05
    assert load_material("38MnVS6", forging="continuous_grain_flow").m53_k == 1.05
    assert load_material("42CrMo4", forging="free_form").m53_k == 1.0
    assert load_material("EN-GJS-700-2").m53_k is None  # UR M53 covers steel only
    assert load_material("C45", m53_k=0.93).m53_k == 0.93  # e.g. cold-rolled cast steel, given


@pytest.mark.parametrize(
    ("extra", "key", "words"),
    [
        ({"name": "EN-GJS-700-2", "forging": "drop_forged"}, "material.forging", "applies to a forged steel"),
        ({"name": "C45", "forging": "drop_forged", "m53_k": 1.05}, "material.m53_k", "not both"),
        ({"name": "C45", "forging": "hammered"}, "material.forging", "drop_forged"),
        ({"name": "C45", "forging": 1.05}, "material.forging", ""),
    ],
)
def test_forging_input_errors(tmp_path, extra, key, words):
    with pytest.raises(InputError) as e:
        parse_material(extra, tmp_path / "case.toml")
    assert e.value.key == key and words in str(e.value)


def _engine(strokes=4, **top):
    data = {
        "name": "one",
        "strokes": strokes,
        "throws": [{"name": "1", "stroke": "100 mm"}],
        "cylinders": [
            {
                "name": "1",
                "throw": "1",
                "bore": "90 mm",
                "rod_length": "200 mm",
                "rod_mass": "1 kg",
                "rod_cg_from_big_end": "50 mm",
                "piston_mass": "1 kg",
            }
        ],
        **top,
    }
    return build_engine(data, "engine.toml")


def test_additional_bending_by_construction_and_stated():
    """UR M53 4: +-10 N/mm^2 trunk piston, +-30 N/mm^2 crosshead; a stated value may be larger."""
    assert _engine().construction == "trunk_piston" and _engine().internal_combustion is True
    assert additional_bending("trunk_piston", None)[0] == 10e6
    assert additional_bending("crosshead", None)[0] == 30e6
    assert additional_bending("trunk_piston", 20e6)[0] == 20e6
    with pytest.raises(InputError) as e:
        additional_bending("crosshead", 10e6, file="case.toml")
    assert e.value.key == "criteria.m53_additional_bending" and "30 MPa" in str(e.value)
    b = m53_basis(_engine(construction="crosshead"), load_material("C45"), None)
    assert b.additional == 30e6 and b.ke == 1.0 and not b.analogy
    with pytest.raises(InputError):
        _engine(construction="diesel")
    with pytest.raises(InputError):
        _engine(internal_combustion="no")


def test_ke_only_for_internal_combustion_engines_and_the_analogy_flag():
    """K_e = 0.8 (2.1.2.1) for an I.C. two-stroke; an air motor's M53 route is an analogy,
    K_e = 1, and says so."""
    ic = m53_basis(_engine(strokes=2), load_material("C45", forging="drop_forged"), None)
    assert (ic.ke, ic.analogy, ic.forging_k) == (0.8, False, 1.05)
    air = m53_basis(_engine(strokes=2, internal_combustion=False), load_material("C45"), None)
    assert (air.ke, air.analogy, air.forging_k) == (1.0, True, 1.0)
    assert any("analogy" in n for n in air.notes) and any("not stated" in n for n in air.notes)


def test_shipped_air_motor_is_not_an_ic_engine():
    from fe_crank.io.loadcase import load_loadcase

    lc = load_loadcase("loadcases/v4_90_pneumatic_operating.toml")
    assert lc.engine.internal_combustion is False
    assert m53_basis(lc.engine, lc.material, None).analogy


def test_fe_route_adds_sigma_add_to_the_fillet_bending_amplitude():
    """The round bar of test_assess_fatigue.py as a journal fillet, sigma_add = 30 MPa (UR M53 4,
    crosshead): Goodman 1/n = (sigma_a + 30 MPa)/(k sigma_W) + sqrt(3) tau_m / R_m, Gough-Pollard
    n = k sigma_W / (sigma_a + 30 MPa); the same bar as an oil bore gets none (5.2)."""
    mat = load_material("42CrMo4", surface_factor=0.9, size_factor=0.95, reliability=0.5)
    k = 0.9 * 0.95
    theta = np.deg2rad(np.arange(720.0))
    pin = np.column_stack([M_A * np.sin(theta), np.zeros_like(theta)])
    kw = dict(omega=0.0, sense=-1, overspeed=None, material=mat, crank_radius=0.0)
    t = assess_throw(ThrowContext("1", _bar_units(), theta, pin, np.full(theta.size, T_M), m53_additional=30e6, **kw))
    g = t.groups[0]
    sa = 32 * M_A / (np.pi * D**3)  # 162.97 MPa
    tm = 16 * T_M / (np.pi * D**3)
    assert g.additional_bending == 30e6
    assert g.fatigue_safety.value == pytest.approx(1 / ((sa + 30e6) / (k * 450e6) + np.sqrt(3) * tm / 900e6), rel=1e-12)
    assert g.gough_pollard_safety.value == pytest.approx(k * 450e6 / (sa + 30e6), rel=1e-12)
    o = assess_throw(
        ThrowContext("1", _bar_units("oil_bore"), theta, pin, np.full(theta.size, T_M), m53_additional=30e6, **kw)
    ).groups[0]
    assert o.additional_bending == 0.0
    k_bore = 4.51 * 900.0**-0.265 * 0.95  # the drilled outlet's own surface (test_assess_surfaces.py)
    assert o.fatigue_safety.value == pytest.approx(1 / (sa / (k_bore * 450e6) + np.sqrt(3) * tm / 900e6), rel=1e-12)


def test_model_engine_defaults():
    e = model.Engine("x", 4, (), (), ())
    assert (e.construction, e.internal_combustion) == ("trunk_piston", True)
