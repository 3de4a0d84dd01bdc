"""A surface factor per assessed location (Shigley eq. 6-19, table 6-2, k_a = a R_m^b):
the shaft fillets take the load case's common finish, the drilled oil-bore outlet its own
(table 6-2's machined constants), the counterweight's transition fillet as forged unless
stated; [material.surface] states any of them, a given factor only with its reason."""

from __future__ import annotations

import numpy as np
import pytest

from fe_crank.assess import ThrowContext, assess_throw
from fe_crank.assess.factors import factors, location_of
from fe_crank.assess.superpose import UnitStresses
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase
from fe_crank.io.material import load_material, parse_material

MACHINED_C45 = 4.51 * 580.0**-0.265  # 0.83475
GROUND_C45 = 1.58 * 580.0**-0.085  # 0.91993
AS_FORGED_C45 = 272.0 * 580.0**-0.995  # 0.48376


def test_locations_of_groups():
    assert location_of("crankpin_fillet_2") == "crankpin_fillet"
    assert location_of("journal_fillet_1") == "journal_fillet"
    assert location_of("oil_bore") == "oil_bore"
    assert location_of("counterweight_fillet_1") == "counterweight_fillet"
    assert location_of("counterweight_1") is None and location_of("junction_2") is None


def test_oil_bore_is_drilled_whatever_the_fillets():
    """Ground fillets (0.920 at R_m = 580 MPa) do not make the drilled outlet ground: its k_a
    is table 6-2's machined value, 0.835; a given common surface_factor applies to the
    shaft fillets only."""
    mat = load_material("C45", surface_finish="ground")
    assert factors(mat, 0.05, "crankpin_fillet").surface == pytest.approx(GROUND_C45, rel=1e-12)
    assert factors(mat, 0.05, "oil_bore").surface == pytest.approx(MACHINED_C45, rel=1e-12)
    assert factors(mat, 0.05, "oil_bore").surface_basis == "drilled"
    assert factors(mat, None, "counterweight_fillet").surface == pytest.approx(AS_FORGED_C45, rel=1e-12)
    given = load_material("C45", surface_factor=0.9)
    assert factors(given, 0.05, "journal_fillet").surface == 0.9
    assert factors(given, 0.05, "oil_bore").surface == pytest.approx(MACHINED_C45, rel=1e-12)


def test_surface_per_location_input(tmp_path):
    f = tmp_path / "case.toml"
    m = parse_material(
        {
            "name": "C45",
            "surface": {
                "crankpin_fillet": "ground",
                "journal_fillet": "machined",
                "oil_bore": {"factor": 0.7, "reason": "measured Ra 3.2 um, rough reamed"},
                "counterweight_fillet": "machined",
            },
        },
        f,
    )
    assert factors(m, 0.05, "crankpin_fillet").surface == pytest.approx(GROUND_C45, rel=1e-12)
    assert factors(m, 0.05, "journal_fillet").surface == pytest.approx(MACHINED_C45, rel=1e-12)
    assert factors(m, 0.05, "oil_bore").surface == 0.7
    assert factors(m, 0.05, "oil_bore").surface_basis == "given 0.7: measured Ra 3.2 um, rough reamed"
    assert factors(m, None, "counterweight_fillet").surface == pytest.approx(MACHINED_C45, rel=1e-12)
    for bad, key in [
        ({"oil_bore": {"factor": 0.7}}, "material.surface.oil_bore"),  # no reason
        ({"oil_bore": {"factor": 1.3, "reason": "polished"}}, "material.surface.oil_bore"),
        ({"web": "ground"}, "material.surface"),
        ({"oil_bore": "polished"}, "material.surface.oil_bore"),
    ]:
        with pytest.raises(InputError) as e:
            parse_material({"name": "C45", "surface": bad}, f)
        assert e.value.key.startswith(key), (bad, e.value.key)


def test_shipped_v4_fillets_take_the_library_machined_value():
    """The V4 case declares machined fillets: k_a = 4.51 x 580^-0.265 = 0.835, not the 0.9 it gave."""
    mat = load_loadcase("loadcases/v4_90_pneumatic_operating.toml").material
    for loc in ("crankpin_fillet", "journal_fillet", "oil_bore"):
        assert factors(mat, 0.045, loc).surface == pytest.approx(MACHINED_C45, rel=1e-12), loc


def test_oil_bore_group_assessed_with_its_own_surface():
    """Fully reversed bending of a round bar (sigma_a = 32 M / (pi d^3)) as the oil-bore group
    of a crank with ground fillets: Goodman n = k_a(drilled) k_b k_e sigma_W / sigma_a."""
    d, n = 0.05, 36
    phi = np.linspace(0, 2 * np.pi, n, endpoint=False)
    s = np.zeros((2, 6, n))
    s[0, 2] = (d / 2) * np.sin(phi) / (np.pi * d**4 / 64)
    unit = UnitStresses(
        s, np.vstack([np.cos(phi), np.sin(phi), 0 * phi]) * d / 2, {"oil_bore": np.arange(n)}, None, ("pin_x", "pin_y")
    )
    mat = load_material("C45", surface_finish="ground", size_factor=1.0, reliability=0.5)
    theta = np.deg2rad(np.arange(360.0))
    pin = np.column_stack([1000.0 * np.sin(theta), np.zeros_like(theta)])
    g = assess_throw(
        ThrowContext("1", unit, theta, pin, np.zeros(360), omega=0.0, overspeed=None, material=mat, crank_radius=0.0)
    )
    sa = 32 * 1000.0 / (np.pi * d**3)
    assert g.groups[0].fatigue_factors.surface == pytest.approx(MACHINED_C45, rel=1e-12)
    assert g.groups[0].fatigue_safety.value == pytest.approx(MACHINED_C45 * 290e6 / sa, rel=1e-9)
