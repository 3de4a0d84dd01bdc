"""A counterweight turned from opposite its pin (``counterweight.offset``, docs/geometry.md):
its exact mass properties against the closed form of the annular sector turned by the
offset, the throw's m r vector, the mirror planes the turned throw keeps and the mesh it
is built with, and the refusals of bad input through ``fe-crank validate``."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.geometry import base_throw

from fe_crank.assess.adapters import counterweights_of
from fe_crank.cli import main
from fe_crank.geometry import mass_properties
from fe_crank.geometry.checks import distance_to_sector
from fe_crank.io.geometry import geometry_from_dict
from fe_crank.mesh.planes import mesh_planes, symmetry_planes

RHO = 7800.0  # kg/m^3, base_throw's density
R1, R2, ANGLE, T = 0.075, 0.020, math.radians(100.0), 0.015  # the sector; as thick as the web
CW = {"outer_radius": "75 mm", "inner_radius": "20 mm", "angle": "100 deg", "webs": [1, 2]}


def _sector(offset_deg: float) -> tuple[float, np.ndarray]:
    """Mass (kg) and m r vector (kg m, throw frame) of the annular sector turned by the
    offset from -y towards +x, in closed form: m = rho b (a/2)(r1^2 - r2^2), its centroid at
    r_c = 2 (r1^3 - r2^3) sin(a/2) / (3 (r1^2 - r2^2)(a/2)) along (sin d, -cos d)."""
    half = ANGLE / 2
    m = RHO * T * half * (R1**2 - R2**2)
    rc = 2 * (R1**3 - R2**3) * math.sin(half) / (3 * (R1**2 - R2**2) * half)
    d = math.radians(offset_deg)
    return m, m * rc * np.array([math.sin(d), -math.cos(d)])


@pytest.mark.parametrize("offset", [25.0, -40.0])
def test_turned_sector_mass_properties_are_the_closed_form_turned(offset):
    """The counterweight part (the whole sector prism, fillet-less) against the closed
    form turned by the offset, and the built m r the assessment takes from them
    (``assess.adapters.counterweights_of``; the whole shaft's cycle, ``fe.shaft.cycle``,
    takes the parts' m r vectors as they are)."""
    g = geometry_from_dict(base_throw(counterweight={**CW, "offset": f"{offset} deg"}))
    assert g.throws[0].counterweights[0].offset == pytest.approx(math.radians(offset), rel=1e-15)
    mp = mass_properties(g)
    m, u = _sector(offset)
    for web in (1, 2):
        p = mp.parts[f"counterweight_{web}"]
        assert p.mass == pytest.approx(m, rel=1e-6)
        assert np.asarray(p.unbalance_vector) == pytest.approx(u, rel=1e-6, abs=1e-9 * m)
        turn = math.degrees(math.atan2(p.unbalance_vector[0], -p.unbalance_vector[1]))  # from -y towards +x
        assert turn == pytest.approx(offset, abs=1e-6)
        z = p.centroid[2]
        assert (z < 0) == (web == 1) and abs(abs(z) - (0.015 + 0.0075)) < 1e-9
    # the assessment's built m r (its balance input): the vector sum's length over the mass
    cws = counterweights_of(g.throws[0], mp, 0.0, "main", None, g)
    assert [c.name for c in cws] == ["counterweight_1", "counterweight_2"]
    for c in cws:
        assert c.mass * c.centroid_radius == pytest.approx(float(np.hypot(*u)), rel=1e-6)


def test_pin_clearance_of_a_turned_sector_is_the_rotated_distance():
    """``distance_to_sector`` of a turned sector: that of the point turned back by the offset
    to the sector opposite the pin (hand calculation: the pin centre (0, R) and the edge
    nearer to it)."""
    g = geometry_from_dict(base_throw(counterweight={**CW, "offset": "30 deg"}))
    cw = g.throws[0].counterweights[0]
    # the edge at 30 + 50 = 80 deg from -y, i.e. 100 deg from +y: the pin centre (0, 40 mm)
    # projects onto its line at 40 cos(100 deg) < 0, behind the axis: its nearest point is the
    # edge's inner end at r2 = 20 mm, 100 deg from +y
    e = (R2 * math.sin(math.radians(100)), R2 * math.cos(math.radians(100)))
    assert distance_to_sector((0.0, 0.040), cw) == pytest.approx(math.hypot(e[0], e[1] - 0.040), rel=1e-12)
    unturned = dataclasses.replace(cw, offset=0.0)
    c, s = math.cos(-0.5), math.sin(-0.5)
    for p in ((0.01, -0.05), (0.06, 0.02), (-0.03, 0.0)):
        q = (c * p[0] + s * p[1], -s * p[0] + c * p[1])  # p turned by +0.5 rad (from -y towards +x)
        turned = dataclasses.replace(cw, offset=0.5)
        assert distance_to_sector(q, turned) == pytest.approx(distance_to_sector(p, unturned), abs=1e-15)


@pytest.fixture
def every_plane(monkeypatch):
    """Let the mesher mirror across every exact plane, x = 0 included (by default only the
    mid-plane, ``fe_crank.mesh.planes.MESH_PLANES``)."""
    monkeypatch.setattr("fe_crank.mesh.planes.MESH_PLANES", (0, 2))


def test_turned_throw_keeps_the_mid_plane_only_and_its_fillets_turn_with_it(every_plane):
    """A turned sector is not its own image across the crank plane x = 0: the throw keeps
    z = 0 (both webs turned alike) and loses x = 0, for the mesher (``mesh_planes``, what
    ``mesh_throw`` cuts and mirrors across) as for the solid; webs turned differently lose
    z = 0 too.  The built throw's transition fillets (``counterweight_fillet_1``, the
    group the mesh sizing and the hot-spot search take) lie round the turned sector's
    edges, 30 -+ 50 deg from opposite the pin, where the unturned sector's reach +-50 deg."""
    import gmsh

    from fe_crank.geometry.throw import add_throw
    from fe_crank.gmsh_io import gmsh_session

    fillets = {"crankpin": {"fillet_radius": "2 mm"}, "journal": {"fillet_radius": "2 mm"}}
    g = geometry_from_dict(base_throw(counterweight={**CW, "fillet_radius": "3 mm", "offset": "30 deg"}, **fillets))
    plain = geometry_from_dict(base_throw(counterweight={**CW, "fillet_radius": "3 mm"}, **fillets))
    assert symmetry_planes(plain) == (0, 2) and mesh_planes(plain) == (0, 2)
    assert symmetry_planes(g) == (2,) and mesh_planes(g) == (2,)
    spec = g.throws[0]
    other = dataclasses.replace(spec.counterweights[1], offset=-spec.counterweights[1].offset)
    assert symmetry_planes(g, dataclasses.replace(spec, counterweights=(spec.counterweights[0], other))) == ()
    with gmsh_session():
        model = add_throw(g, cut=mesh_planes(g))
        faces = model.surfaces["counterweight_fillet_1"]
        ang = []
        for f in faces:
            x, y, _ = gmsh.model.occ.getCenterOfMass(2, f)
            ang.append(math.degrees(math.atan2(x, -y)))  # from -y towards +x
    assert "counterweight_fillet_2" not in model.surfaces  # cut at z = 0: web 2 is web 1's image
    near = sorted({round(a / 10) * 10 for a in ang})
    assert min(ang) > -30 and max(ang) < 90 and any(a < -10 for a in ang) and any(a > 70 for a in ang), near


BAD = [
    ('offset = "10"', "counterweight.offset", "no unit"),
    ('offset = "200 deg"', "counterweight.offset", "between -180 and 180 deg"),
    ('offset = "120 deg"', "counterweight", "overlaps the crankpin"),
]


@pytest.mark.parametrize("line, key, why", BAD)
def test_bad_offset_refused_by_validate_with_file_and_key(tmp_path, capsys, line, key, why):
    f = tmp_path / "turned.toml"
    f.write_text(
        'name = "turned"\ndensity = "7800 kg/m^3"\ncrank_radius = "40 mm"\n'
        '[journal]\ndiameter = "50 mm"\nlength = "20 mm"\n'
        '[crankpin]\ndiameter = "40 mm"\nlength = "30 mm"\n'
        '[web]\nthickness = "15 mm"\noutline = "stadium"\nwidth = "60 mm"\n'
        '[counterweight]\nouter_radius = "75 mm"\ninner_radius = "20 mm"\nangle = "100 deg"\n' + line + "\n"
    )
    assert main(["validate", str(f)]) == 2
    err = capsys.readouterr().err
    assert str(f) in err and f"{key}:" in err and why in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1


def test_bolted_joint_section_of_a_turned_counterweight_turns_with_it():
    """The radial joint's section (``assess.joint_loads.fe_section_loads``): nodes and nodal
    stresses of a counterweight centred opposite the pin, and the same turned by 35 deg as a
    rigid body (points turned, stress tensors Q S Q^T), give the same joint loads with the
    joint's ``offset``; the bolts' positions across the joint (``bolt_offsets``) are in its
    own frame and do not change."""
    from fe_crank.assess.counterweight import JointGeometry
    from fe_crank.assess.joint_loads import bolt_offsets, fe_section_loads
    from fe_crank.assess.superpose import UnitStresses
    from fe_crank.geometry.spec import BoltedJoint

    rng = np.random.default_rng(7)
    n = 400
    pts = np.stack([rng.uniform(-0.03, 0.03, n), rng.uniform(-0.034, -0.026, n), rng.uniform(-0.03, -0.015, n)])
    s = rng.normal(size=(2, 6, n)) * 1e6
    geo = JointGeometry(0.03, 0.015, 0.015, 0.02, 0.075, ANGLE, 0.0275, 0.1, 1)
    joint = BoltedJoint(count=2, diameter=0.006, pitch_radius=0.05, clamped_diameter=0.012)
    d = math.radians(35.0)
    c, sn = math.cos(d), math.sin(d)
    q = np.array([[c, -sn, 0.0], [sn, c, 0.0], [0.0, 0.0, 1.0]])  # -y turned by d towards +x
    voigt = ((0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (2, 0))
    full = np.zeros((2, 3, 3, n))
    for k, (i, j) in enumerate(voigt):
        full[:, i, j] = full[:, j, i] = s[:, k]
    turned = np.einsum("ia,cabn,jb->cijn", q, full, q)
    s_t = np.stack([turned[:, i, j] for i, j in voigt], axis=1)
    cases = ("pin_x", "pin_y")
    coeffs = rng.normal(size=(5, 2))
    a = fe_section_loads(UnitStresses(s, pts, {"cw": np.arange(n)}, cases=cases), "cw", geo, joint, coeffs)
    b = fe_section_loads(
        UnitStresses(s_t, q @ pts, {"cw": np.arange(n)}, cases=cases),
        "cw",
        dataclasses.replace(geo, offset=d),
        joint,
        coeffs,
    )
    assert a is not None and b is not None and a.nodes == b.nodes > 12
    assert b.moment == pytest.approx(a.moment, rel=1e-9, abs=1e-12 * np.abs(a.moment).max())
    assert b.force == pytest.approx(a.force, rel=1e-9, abs=1e-12 * np.abs(a.force).max())
    assert bolt_offsets(joint, dataclasses.replace(geo, offset=d)) == pytest.approx(bolt_offsets(joint, geo))
