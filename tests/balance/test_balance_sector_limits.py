"""Annular-sector counterweight (fe_crank.balance.sector): the limits of its input and of
the inverse design, each on both sides, and every refusal's message and key in full.

Hand values use density 1.5 kg/m^3, for which (2/3) rho = 1 exactly, thickness 1 m and a
180 deg sector (sin(a/2) = 1): the unbalance of a sector is then ``r1^3 - r2^3`` (kg m).
"""

import math

import pytest

from fe_crank.balance.sector import annular_sector, solve_sector
from fe_crank.errors import InputError

PI = math.pi


def _refused(fn, *args, **kw):
    with pytest.raises(InputError) as err:
        fn(*args, **kw)
    return err.value


def test_a_full_disc_sector_by_hand():
    """r2 = 0 (a disc sector): r1 = 0.07 m, b = 0.02 m, 180 deg, 7800 kg/m^3:
    m = 7800 * 0.02 * (pi/2) * 0.07^2 = 156 * 1.570796 * 0.0049 = 1.200717 kg,
    U = (2/3) 7800 * 0.02 * 1 * 0.07^3 = 104 * 0.000343 = 0.035672 kg m,
    r_c = U/m = 4 r1 / (3 pi) = 0.0297089 m."""
    s = annular_sector(0.07, 0.0, 0.02, PI, 7800.0)
    assert s.mass == pytest.approx(1.200717, rel=1e-6)
    assert s.unbalance == pytest.approx(0.035672, rel=1e-6)
    assert s.centroid_radius == pytest.approx(4 * 0.07 / (3 * PI), rel=1e-12)
    assert (s.r_outer, s.r_inner, s.thickness, s.angle, s.density) == (0.07, 0.0, 0.02, PI, 7800.0)


def test_narrow_and_full_angles_and_light_materials_are_accepted():
    """0.5 rad (below 1 rad): m = 1.5 * 1 * 0.25 * 0.25 = 0.09375 kg for r1 = 0.5, r2 = 0;
    exactly 360 deg (+ the 1e-12 rad allowance) is accepted; a density of 0.5 kg/m^3 is
    valid (m = 0.5 * 1 * (pi/2) * 0.25 = 0.19635 kg)."""
    assert annular_sector(0.5, 0.0, 1.0, 0.5, 1.5).mass == pytest.approx(0.09375, rel=1e-14)
    full = annular_sector(0.5, 0.0, 1.0, 2.0 * math.pi + 1e-12, 1.5)
    assert full.mass == pytest.approx(1.5 * PI * 0.25, rel=1e-12)
    assert annular_sector(0.5, 0.0, 1.0, PI, 0.5).mass == pytest.approx(0.5 * PI / 2 * 0.25, rel=1e-14)


@pytest.mark.parametrize(
    "args, reason",
    [
        ((0.07, -0.01, 0.02, PI, 7800.0), "outer radius 70 mm must exceed inner radius -10 mm >= 0"),
        ((0.05, 0.05, 0.02, PI, 7800.0), "outer radius 50 mm must exceed inner radius 50 mm >= 0"),
        ((0.07, 0.03, 0.0, PI, 7800.0), "thickness must be positive (got 0 mm)"),
        ((0.07, 0.03, -0.002, PI, 7800.0), "thickness must be positive (got -2 mm)"),
        ((0.07, 0.03, 0.02, 0.0, 7800.0), "included angle must lie in (0, 360] deg (got 0 deg)"),
        ((0.07, 0.03, 0.02, 7.0, 7800.0), "included angle must lie in (0, 360] deg (got 401.07 deg)"),
        ((0.07, 0.03, 0.02, PI, 0.0), "density must be positive (got 0.0)"),
    ],
)
def test_sector_refusals_in_full(args, reason):
    """Lengths are reported in mm (x 1e3), angles in degrees (7 rad = 401.07 deg)."""
    err = _refused(annular_sector, *args)
    assert (err.key, err.reason) == ("counterweight", reason)


def test_inverse_design_at_its_limits_by_hand():
    """rho = 1.5, b = 1 m, 180 deg: U = r1^3 - r2^3.
    * r_inner free, U = r1^3 = 0.125 kg m with r1 = 0.5 m: r2^3 = 0.125 - 0.125 = 0 ->
      r2 = 0 (a disc sector, accepted);
    * angle free, r1 = 0.5, r2 = 0, U = 0.125: sin(a/2) = 0.125 / 0.125 = 1 -> a = 180 deg
      (the largest unbalance, accepted);
    * thickness free at exactly 360 deg: accepted by the angle check (b = U / (sin(pi) *
      0.125), the ring's round-off unbalance);
    * r_outer exactly at the envelope, r_inner exactly at the journal radius, and each at
      the 1e-12 relative allowance: accepted."""
    s = solve_sector(0.125, free="r_inner", r_outer=0.5, thickness=1.0, angle=PI, density=1.5)
    assert s.r_inner == 0.0
    s = solve_sector(0.125, free="angle", r_outer=0.5, r_inner=0.0, thickness=1.0, density=1.5)
    assert s.angle == pytest.approx(PI, rel=1e-15)
    s = solve_sector(0.125, free="thickness", r_outer=0.5, r_inner=0.0, angle=2.0 * PI, density=1.5)
    assert s.angle == 2.0 * PI
    assert s.thickness == pytest.approx(0.125 / (math.sin(PI) * 0.125), rel=1e-12)
    for r1, env in ((0.5, 0.5), (0.5 * (1.0 + 1e-12), 0.5)):
        s = solve_sector(0.1, free="thickness", r_outer=r1, r_inner=0.0, angle=PI, density=1.5, envelope=env)
        assert s.thickness == pytest.approx(0.1 / 0.125, rel=1e-9)
    for r2, jr in ((0.2, 0.2), (0.2 * (1.0 - 1e-12), 0.2)):
        s = solve_sector(0.1, free="thickness", r_outer=0.5, r_inner=r2, angle=PI, density=1.5, journal_radius=jr)
        assert s.thickness == pytest.approx(0.1 / (0.125 - 0.008), rel=1e-9)
    # a light material (0.5 kg/m^3: (2/3) rho = 1/3) is valid: b = 0.1 / (0.125 / 3) = 2.4 m
    s = solve_sector(0.1, free="thickness", r_outer=0.5, r_inner=0.0, angle=PI, density=0.5)
    assert s.thickness == pytest.approx(2.4, rel=1e-12)


G = dict(r_outer=0.5, r_inner=0.0, thickness=1.0, angle=PI, density=1.5)


@pytest.mark.parametrize(
    "call, reason",
    [
        (
            dict(unbalance=0.1, free="diameter", **G),
            "free dimension 'diameter' is not one of ('r_outer', 'r_inner', 'thickness', 'angle')",
        ),
        (dict(unbalance=0.0, free="thickness", **G), "required unbalance must be positive (got 0.0 kg m)"),
        (dict(unbalance=0.1, free="thickness", r_outer=0.5, density=1.5), "to solve for thickness give r_inner, angle"),
        (dict(unbalance=0.1, free="thickness", **{**G, "density": 0.0}), "density must be positive (got 0.0)"),
        # U > 0.125: even r2 = 0 gives only (2/3) 1.5 * 1 * 1 * 0.5^3 = 0.125 kg m
        (
            dict(unbalance=0.2, free="r_inner", **{k: v for k, v in G.items() if k != "r_inner"}),
            "even a full sector out to r_outer = 500 mm gives only 0.125 kg m, 0.2 kg m required",
        ),
        # b = 0.5 m, 60 deg (sin 30 deg = 0.5): 1 * 0.5 * 0.5 * 0.125 = 0.03125 kg m
        (
            dict(unbalance=0.05, free="r_inner", r_outer=0.5, thickness=0.5, angle=PI / 3, density=1.5),
            "even a full sector out to r_outer = 500 mm gives only 0.03125 kg m, 0.05 kg m required",
        ),
        # sin(a/2) = 0.2 / 0.125 = 1.6 > 1: the half ring gives 0.2 / 1.6 = 0.125 kg m
        (
            dict(unbalance=0.2, free="angle", **{k: v for k, v in G.items() if k != "angle"}),
            "needs 0.2 kg m but a 180 deg sector of these radii and thickness gives only 0.125 kg m "
            "(a wider angle gives less): the counterweight cannot fit",
        ),
        (
            dict(unbalance=0.1, free="thickness", **{**G, "angle": 7.0}),
            "needs an included angle of 401.1 deg > 360 deg",
        ),
        (
            dict(unbalance=0.1, free="thickness", envelope=0.4, **G),
            "needs an outer radius of 500 mm, beyond the envelope of 400 mm: the counterweight cannot provide the "
            "required unbalance; widen, thicken or use a denser material",
        ),
        (
            dict(unbalance=0.1, free="thickness", journal_radius=0.032, **{**G, "r_inner": 0.03}),
            "needs an inner radius of 30 mm, inside the journal radius 32 mm",
        ),
    ],
)
def test_inverse_design_refusals_in_full(call, reason):
    call = dict(call)  # the parameter is shared between runs: leave it intact
    u = call.pop("unbalance")
    err = _refused(solve_sector, u, **call)
    assert (err.key, err.reason) == ("counterweight", reason)
    err = _refused(solve_sector, u, key="counterweights.web_2", **call)
    assert err.key == "counterweights.web_2"


def test_sector_record_in_report_units():
    """Lengths in mm, the angle in degrees, the rest in SI: Seed 003's sector (r1 = 71,
    r2 = 32, b = 19 mm, 180 deg, 7400 kg/m^3) by the module's closed forms:
    m = 7400 * 0.019 * (pi/2) * (0.071^2 - 0.032^2) = 140.6 * 1.5707963 * 0.004017 = 0.887170 kg,
    U = (2/3) 7400 * 0.019 * (0.071^3 - 0.032^3) = 93.733333 * 0.000325143 = 0.03047674 kg m,
    r_c = U / m = 34.353 mm."""
    d = annular_sector(0.071, 0.032, 0.019, PI, 7400.0).as_dict()
    assert set(d) == {
        "r_outer_mm",
        "r_inner_mm",
        "thickness_mm",
        "angle_deg",
        "density_kg_m3",
        "mass_kg",
        "centroid_radius_mm",
        "unbalance_kg_m",
    }
    assert (d["r_outer_mm"], d["r_inner_mm"], d["thickness_mm"]) == pytest.approx((71.0, 32.0, 19.0), rel=1e-12)
    assert d["angle_deg"] == pytest.approx(180.0, rel=1e-12)
    assert d["density_kg_m3"] == 7400.0
    assert d["mass_kg"] == pytest.approx(0.887170, rel=1e-6)
    assert d["unbalance_kg_m"] == pytest.approx(0.03047674, rel=1e-6)
    assert d["centroid_radius_mm"] == pytest.approx(34.353, rel=1e-4)
