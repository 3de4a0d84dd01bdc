"""CAD route, whole shaft: a parametric two-throw shaft written to STEP by fe-crank itself
(gmsh's OpenCASCADE writer, ``tests/cad_files.layout_step``), read back and modelled as a
whole shaft gives the parametric layout's dimensions to 1e-6 m and its main-bearing loads
within the test mesh's noise; the drawn throws' end faces join node to node.

Reference: the parametric whole-shaft model of the same shaft (``geometry.shaft``,
``mesh.shaft``), an independent construction of the same solid (the parametric route
builds it from its dimensions, the CAD route from the file's faces)."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from helpers.cad_files import layout_step
from helpers.shaft import Steel, small_engine, small_geometry

from fe_crank import model
from fe_crank.cad import CadInput, recognise
from fe_crank.cad.engine import engine_keys
from fe_crank.cad.source import mesh_source_shaft
from fe_crank.cad.whole import cad_shaft_layout, cad_throw_masses
from fe_crank.errors import InputError
from fe_crank.fe.shaft.whole_shaft import analyse_whole_shaft, throw_masses
from fe_crank.geometry.shaft import shaft_layout
from fe_crank.mechanism.dynamics import analyse
from fe_crank.mesh.shaft import joints

pytestmark = pytest.mark.heavy
POS = 1e-6  # m
SPEED = 4000 * 2 * np.pi / 60
#: the two routes' test meshes differ (the CAD route meshes the whole throw from the
#: file's faces, the parametric one its mirrored quarter): bearing loads within this
LOAD_NOISE = 2e-3


@pytest.fixture(scope="module")
def shaft(tmp_path_factory):
    angles = [0.0, np.pi]
    g, e = small_geometry(angles), small_engine(angles, pitch=0.066)
    par = shaft_layout(g, e, geometry_file="g.toml", engine_file="e.toml")
    folder = tmp_path_factory.mktemp("cad")
    # a nose and a flange: the end journals end in shoulders, their bearings at their middles
    step = layout_step(par, folder / "shaft.step", nose=(0.024, 0.02), flange=(0.05, 0.01))
    cad = CadInput(step, density=g.density)
    features = recognise(cad)
    engine_keys(features, cad, e, engine_file="e.toml", loadcase="case.toml")
    return g, e, par, cad, features, cad_shaft_layout(features, cad, e, engine_file="e.toml"), folder


def test_the_drawn_layout_is_the_parametric_one(shaft):
    g, e, par, cad, features, drawn, _ = shaft
    for name in ("crank_radius", "journal_diameter", "journal_length", "crankpin_diameter", "crankpin_length"):
        assert getattr(drawn.geometry, name) == pytest.approx(getattr(par.geometry, name), abs=POS), name
    assert drawn.geometry.web_thickness == pytest.approx(g.web_thickness, abs=POS)
    assert [t.z for t in drawn.throws] == pytest.approx([t.z for t in par.throws], abs=POS)
    assert [t.angle for t in drawn.throws] == [t.angle for t in par.throws]
    for a, b in zip(drawn.journals, par.journals, strict=True):
        assert (a.z0, a.z1, a.centre) == pytest.approx((b.z0, b.z1, b.centre), abs=POS)
    assert [(b.name, b.z) for b in drawn.bearings] == [(b.name, pytest.approx(b.z, abs=POS)) for b in par.bearings]
    # a drawing states no bearing shell: each bearing's width the journal's flat between its fillets
    flat = (par.journals[1].z1 - par.journals[1].z0) - 2 * g.journal_fillet
    assert [b.width for b in drawn.bearings] == pytest.approx([flat] * 3, abs=POS)
    assert not any(b.width_stated for b in drawn.bearings)
    # the shells' width stated in [cad], as [shaft] bearing_width states it for the parametric shaft
    stated = cad_shaft_layout(features, dataclasses.replace(cad, bearing_width=0.016), e, engine_file="e.toml")
    assert [(b.width, b.width_stated) for b in stated.bearings] == [(b.width, True) for b in par.bearings]


def test_main_bearing_loads_equal_the_parametric_models(shaft):
    _, e, par, cad, features, drawn, folder = shaft
    dyn = analyse(e, model.OperatingPoint(speed=SPEED))
    cache = folder / "cache"
    ref_mesh = mesh_source_shaft(par.geometry, par, size="test", cache_dir=cache)
    ref, ref_cases = analyse_whole_shaft(ref_mesh, Steel(), dyn, mass=throw_masses(par))
    ref_cases.model.free_factors()
    drawn_mesh = mesh_source_shaft(cad, drawn, size="test", cache_dir=cache, features=features)
    got, cases = analyse_whole_shaft(drawn_mesh, Steel(), dyn, mass=cad_throw_masses(features, drawn))
    cases.model.free_factors()
    sm = cases.model.mesh
    # one drawn throw mesh for both throws, turned by 180 deg: the end faces meet node to node
    assert len(sm.throw_meshes) == 1 and sm.sectors == 2
    # the drawn throw is its own mirror image across z = 0: meshed as its half and mirrored
    assert next(iter(sm.throw_meshes.values())).stats.symmetry == (2,)
    for (na, nb), k in zip(joints(sm), range(len(sm.pieces) - 1), strict=True):
        xa, xb = sm.placed_points(k)[:, na], sm.placed_points(k + 1)[:, nb]
        assert np.abs(xa - xb).max() < 1e-12
    for a, b in zip(got.bearings, ref.bearings, strict=True):
        assert a.name == b.name
        peak = a.with_counterweights.peak_n
        assert peak == pytest.approx(b.with_counterweights.peak_n, rel=LOAD_NOISE)
        scale = np.abs(b.with_counterweights.load_n).max()
        assert np.abs(a.with_counterweights.load_n - b.with_counterweights.load_n).max() < LOAD_NOISE * scale
        # without counterweights the routes take off different material (the parametric
        # route its counterweight sector, the drawn one all beyond the web's rounded end,
        # docs/geometry.md): no comparison


def test_throws_of_other_journals_or_webs_are_refused(shaft):
    _, e, _, cad, features, _, _ = shaft
    t = features.throws[1]
    other = dataclasses.replace(t, crank_radius=t.crank_radius * (1 + 1e-6))
    bad = dataclasses.replace(features, throws=(features.throws[0], other))
    with pytest.raises(InputError, match="differs from throw 1 in its crank radius"):
        cad_shaft_layout(bad, cad, e, engine_file="e.toml")


TWO_THROWS = """name = "two throws from CAD"
geometry = "shaft.step"

[operating]
speed = "4000 rpm"

[engine]
name = "small twin"
strokes = 4

[[engine.throws]]
name = "1"
crank_radius = "20 mm"
angle = "0 deg"
axial_position = "-33 mm"

[[engine.throws]]
name = "2"
crank_radius = "20 mm"
angle = "180 deg"
axial_position = "33 mm"

[engine.cylinder_defaults]
bore = "50 mm"
rod_length = "80 mm"
rod_mass = "0.20 kg"
rod_cg_from_big_end = "22 mm"
piston_mass = "0.15 kg"

[[engine.cylinders]]
name = "1"
throw = "1"
firing_offset = "0 deg"

[[engine.cylinders]]
name = "2"
throw = "2"
firing_offset = "360 deg"

[cad]
density = "7850 kg/m^3"

[material]
name = "42CrMo4"

[criteria]
max_main_bearing_load = "20 kN"
"""


def test_validate_refuses_the_bearing_specific_load_of_a_drawn_shaft(shaft, capsys):
    """A drawing holds no bearing shell: ``validate`` takes the specific-load criterion with
    ``[cad] bearing_width`` and refuses it without, before any meshing, naming the load
    case and the key."""
    from fe_crank.cli import main

    folder = shaft[-1]
    case = folder / "case.toml"
    specific = 'max_main_bearing_specific_load = "40 MPa"\n'
    case.write_text(TWO_THROWS.replace("[material]", 'bearing_width = "16 mm"\n\n[material]') + specific)
    assert main(["validate", str(case)]) == 0
    assert "whole shaft on 3 main bearings" in capsys.readouterr().out
    case.write_text(TWO_THROWS + specific)
    assert main(["validate", str(case)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"error {case}: criteria.max_main_bearing_specific_load: "), err
    assert "draws the journals, not the bearing shells" in err
    assert not (folder / ".cache").exists()


def test_validate_refuses_an_oil_film_criterion_on_a_drawn_shaft(shaft, capsys):
    """A drawn shaft's bearings are rigid: an oil-film criterion is refused by ``validate``."""
    from fe_crank.cli import main

    folder = shaft[-1]
    case = folder / "film.toml"
    case.write_text(TWO_THROWS + 'min_oil_film_thickness = "1 um"\n')
    assert main(["validate", str(case)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"error {case}: criteria.min_oil_film_thickness: "), err
    assert "rigid" in err


def test_validate_refuses_a_bolt_criterion_on_a_drawing(shaft, capsys):
    """No bolt data in a drawing: a bolt criterion is refused before recognition."""
    from fe_crank.cli import main

    folder = shaft[-1]
    case = folder / "bolts.toml"
    case.write_text(TWO_THROWS + "min_bolt_working_safety = 1.0\n")
    assert main(["validate", str(case)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith(f"error {case}: criteria.min_bolt_working_safety: "), err
    assert "no bolt data" in err


def test_a_journal_that_is_no_plain_round_bar_at_its_bearing_centre_is_refused(shaft):
    """The whole-shaft model joins the throws on whole round end faces at the bearing
    centres: an oil bore opening there, or an axial bore, is refused before meshing."""
    from fe_crank.cad.features import OilBore

    _, e, _, cad, features, _, _ = shaft
    t = features.throws[0]
    b2 = t.bearings[1].z
    bore = OilBore((), 0.003, ("journal_2",), (0.0, 0.0, b2 + 0.002), (1.0, 0.0, 0.0), math.pi / 2)
    drilled = dataclasses.replace(features, throws=(dataclasses.replace(t, oil_bores=(bore,)), *features.throws[1:]))
    with pytest.raises(InputError, match="an oil bore \\(3 mm\\) opens on its journal_2 0.5 mm from the bearing"):
        cad_shaft_layout(drilled, cad, e, engine_file="e.toml")
    far = dataclasses.replace(bore, point=(0.0, 0.0, t.webs[1].z_outer))  # at the web: outside the redrawn bar
    drilled = dataclasses.replace(features, throws=(dataclasses.replace(t, oil_bores=(far,)), *features.throws[1:]))
    cad_shaft_layout(drilled, cad, e, engine_file="e.toml")
    hollow = dataclasses.replace(t.journals[0], bore_diameter=0.01)
    bored = dataclasses.replace(t, journals=(hollow, t.journals[1]))
    with pytest.raises(InputError, match="journal_1 is bored along the axis \\(10 mm\\)"):
        cad_shaft_layout(dataclasses.replace(features, throws=(bored, *features.throws[1:])), cad, e, engine_file="e")


def test_throw_angles_the_joined_meshes_cannot_take_are_refused(shaft):
    _, e, _, cad, features, _, _ = shaft
    turned = dataclasses.replace(
        e, throws=tuple(dataclasses.replace(t, angle=math.radians(170)) if t.name == "2" else t for t in e.throws)
    )
    with pytest.raises(InputError, match=r"\(170 deg\) are not multiples of 360/24 deg") as err:
        cad_shaft_layout(features, cad, turned, engine_file="e.toml")
    assert err.value.key == "cad.throws"
