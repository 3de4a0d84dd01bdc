"""Which mirror planes a throw gets (``fe_crank.mesh.planes.symmetry_planes``): one test
per rule of its docstring, and the shipped geometries."""

from __future__ import annotations

import dataclasses
import math
from pathlib import Path

import pytest
from helpers.geometry import base_throw as _base

from fe_crank.io.geometry import geometry_from_dict, load_geometry
from fe_crank.mesh.planes import bore_axis_aligned, symmetry_planes

ROOT = Path(__file__).resolve().parents[2]
CW = {"outer_radius": "70 mm", "inner_radius": "20 mm", "angle": "120 deg"}


def test_plain_throw_is_symmetric_about_both_planes():
    assert symmetry_planes(geometry_from_dict(_base())) == (0, 2)


def test_equal_counterweights_on_both_webs_keep_both_planes():
    assert symmetry_planes(geometry_from_dict(_base(counterweight={**CW, "webs": [1, 2]}))) == (0, 2)


def test_counterweight_on_one_web_breaks_z():
    for webs in ([1], [2]):
        assert symmetry_planes(geometry_from_dict(_base(counterweight={**CW, "webs": webs}))) == (0,)


def test_different_counterweights_break_z():
    g = geometry_from_dict(_base(counterweight={**CW, "webs": [1, 2]}))
    t = g.throws[0]
    cw1, cw2 = t.counterweights
    for field, value in (
        ("outer_radius", cw2.outer_radius + 1e-3),
        ("inner_radius", cw2.inner_radius - 1e-3),
        ("angle", cw2.angle + 1e-6),
        ("thickness", cw2.thickness - 1e-4),
    ):
        other = dataclasses.replace(t, counterweights=(cw1, dataclasses.replace(cw2, **{field: value})))
        assert symmetry_planes(g, other) == (0,), field


def test_two_counterweights_on_one_web_break_z():
    g = geometry_from_dict(_base(counterweight={**CW, "webs": [1, 2]}))
    cw1 = g.throws[0].counterweights[0]
    assert symmetry_planes(g, dataclasses.replace(g.throws[0], counterweights=(cw1, cw1))) == (0,)


def test_bolt_data_do_not_change_the_solid():
    g = geometry_from_dict(_base(counterweight={**CW, "webs": [1, 2]}))
    t = g.throws[0]
    cw1, cw2 = t.counterweights
    bolted = dataclasses.replace(
        cw1,
        bolted=dataclasses.replace(
            load_geometry(ROOT / "geometry" / "inline4.toml").throws[0].counterweights[0].bolted
        ),
    )
    assert symmetry_planes(g, dataclasses.replace(t, counterweights=(bolted, cw2))) == (0, 2)


@pytest.mark.parametrize(
    "deg, x_sym",
    [
        (0, True),
        (90, True),
        (180, True),
        (270, True),
        (-90, True),
        (45, False),
        (30, False),
        (135, False),
        (89.9, False),
    ],
)
def test_oil_bore_along_x_or_y_keeps_x_oblique_breaks_it(deg, x_sym):
    g = geometry_from_dict(_base(crankpin={"oil_bore": {"diameter": "5 mm", "angle": f"{deg} deg"}}))
    assert symmetry_planes(g) == ((0, 2) if x_sym else (2,))


def test_bore_angle_tolerance_is_round_off_only():
    """pi/2 as parsed is exact to 1 ulp; 1e-9 rad off (a bore end 1e-11 m off the plane) is not symmetric."""
    assert bore_axis_aligned(math.pi / 2) == 1 and bore_axis_aligned(math.pi) == 0
    assert bore_axis_aligned(math.pi / 2 + 1e-9) is None


def test_oblique_bore_and_one_sided_counterweight_leave_no_plane():
    g = geometry_from_dict(
        _base(crankpin={"oil_bore": {"diameter": "5 mm", "angle": "45 deg"}}, counterweight={**CW, "webs": [1]})
    )
    assert symmetry_planes(g) == ()


@pytest.mark.parametrize(
    "name, planes",
    [
        # bore at 90 deg (along x), equal counterweights on both webs of every throw
        ("single_cylinder.toml", {"1": (0, 2)}),
        # no bore, four equal 180-deg counterweights
        ("v4_90_pneumatic.toml", {"A": (0, 2), "B": (0, 2)}),
        # bore at 90 deg; bolted counterweights on both webs of throws 1 and 4, the shaft-wide ones on 2 and 3
        ("inline4.toml", {"1": (0, 2), "2": (0, 2), "3": (0, 2), "4": (0, 2)}),
    ],
)
def test_shipped_geometries(name, planes):
    g = load_geometry(ROOT / "geometry" / name)
    assert {t.name: symmetry_planes(g, t) for t in g.throws} == planes


def test_mesh_section_symmetric_key():
    from fe_crank.errors import InputError
    from fe_crank.io.mesh import parse_mesh_section

    assert parse_mesh_section({}, "lc.toml").symmetric is True
    assert parse_mesh_section({"symmetric": False}, "lc.toml").symmetric is False
    with pytest.raises(InputError, match="mesh.symmetric.*true or false"):
        parse_mesh_section({"symmetric": "no"}, "lc.toml")


def test_meshes_are_mirrored_across_the_mid_plane_only():
    """The shipped single cylinder is symmetric about x = 0 and z = 0; the mesh is mirrored
    across z = 0 alone (``MESH_PLANES``: a cut along the crank plane runs through the
    fillets' hot spots)."""
    from fe_crank.mesh.planes import mesh_planes

    g = load_geometry(ROOT / "geometry" / "single_cylinder.toml")
    assert symmetry_planes(g) == (0, 2)
    assert mesh_planes(g) == (2,)
