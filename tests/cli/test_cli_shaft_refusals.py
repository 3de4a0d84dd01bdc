"""A geometry that contradicts its engine, and a [shaft] section that cannot be built, are
refused when the load case is read: `fe-crank validate` and `fe-crank check` exit 2 with
one message naming the file and the key, in the per-throw and the whole-shaft model alike."""

from __future__ import annotations

import shutil
from pathlib import Path

import numpy as np
import pytest

from fe_crank.cli import main

ROOT = Path(__file__).resolve().parents[2]


def without_shaft(text: str) -> str:
    """A geometry file's text without its ``[shaft]`` tables (the section and its
    ``[shaft.*]`` / ``[[shaft.*]]`` tables, up to the next other table)."""
    out, skip = [], False
    for line in text.splitlines(keepends=True):
        s = line.strip()
        if s.startswith("["):
            skip = s.strip("[]").split(".")[0].strip() == "shaft"
        if not skip:
            out.append(line)
    return "".join(out)


def _tree(tmp_path: Path, case: str, engine: str | None = None, geometry_edit=None) -> tuple[Path, Path]:
    """A copy of the shipped loadcases/, engines/ and geometry/ with ``case`` pointing at
    ``engine`` and its geometry file edited by ``geometry_edit(text) -> text``, applied to
    the geometry without its shipped ``[shaft]`` section (the edits state their own), and
    the case without its oil-film criteria (they need the shipped section's film)."""
    for d in ("engines", "geometry"):
        shutil.copytree(ROOT / d, tmp_path / d)
    (tmp_path / "loadcases").mkdir()
    text = "".join(
        line
        for line in (ROOT / "loadcases" / case).read_text().splitlines(keepends=True)
        if not line.startswith(("min_oil_film_thickness", "max_oil_film_pressure"))
    )
    if engine is not None:
        old = next(line for line in text.splitlines() if line.startswith("engine = "))
        text = text.replace(old, f'engine = "../engines/{engine}"')
    p = tmp_path / "loadcases" / case
    p.write_text(text)
    gname = next(line for line in text.splitlines() if line.startswith("geometry = ")).split('"')[1]
    g = (p.parent / gname).resolve()
    g.write_text((geometry_edit or (lambda s: s))(without_shaft(g.read_text())))
    return p, g


def _refused(capsys, path: Path, *words: str) -> str:
    assert main(["validate", str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0, err  # one message
    for w in words:
        assert w in err, (w, err)
    return err


def test_single_throw_geometry_of_another_stroke_is_refused(tmp_path, capsys):
    """The example of a V6 engine (stroke 86 mm) checked on the single cylinder's throw
    (crank radius 64 mm): refused in the per-throw model, naming both files."""
    p, g = _tree(tmp_path, "single_cylinder.toml", engine="v6_90.toml")
    err = _refused(capsys, p, str(g.name), "v6_90.toml", ": stroke:", "stroke 128 mm", "stroke 86 mm")
    assert err.startswith("error ") and "single_cylinder.toml" in err


def test_four_throws_on_a_six_throw_engine_are_refused(tmp_path, capsys):
    p, _ = _tree(tmp_path, "inline4_rated.toml", engine="inline6.toml")
    _refused(capsys, p, "inline4.toml", ": throws:", "4 throw(s) here, 6 in the engine", "inline6.toml")


@pytest.mark.parametrize(
    "old, new, words",
    [
        ('name = "2"', 'name = "X"', (": throws[1].name:", "'X' here", "'2' in the engine")),
        (
            'angle = "180 deg"\n\n[[throws]]\nname = "3"',
            'angle = "90 deg"\n\n[[throws]]\nname = "3"',
            (": throws[1].angle:", "90 deg here"),
        ),
        ('stroke = "86 mm"', 'stroke = "90 mm"', (": stroke:", "stroke 90 mm", "stroke 86 mm")),
        ('thickness = "17 mm"', 'thickness = "40 mm"', (": web.thickness:", "no room")),
        (
            "require_overlap = true",
            'require_overlap = true\n[shaft]\npitch = "90 mm"',
            (": shaft.pitch:", "pitch 90 mm", "92 mm"),
        ),
    ],
)
def test_multi_throw_geometry_against_its_engine(tmp_path, capsys, old, new, words):
    p, _ = _tree(tmp_path, "inline4_rated.toml", geometry_edit=lambda t: t.replace(old, new, 1))
    _refused(capsys, p, "inline4.toml", *words)


@pytest.mark.parametrize(
    "section, words",
    [
        (
            '[[shaft.bearings]]\nname = "A"\njournal = 0\n[[shaft.bearings]]\nname = "B"\njournal = 7',
            (": shaft.bearings[1].journal:", "journal 7", "inline4.toml"),
        ),
        ('[shaft]\nthrust_bearing = "9"', (": shaft.thrust_bearing:", "'9' is none of the main bearings")),
        ('[shaft]\nbearing = { model = "spring", stiffness = "-1e9 N/m" }', (": shaft.bearing", "greater than 0")),
        (
            '[shaft]\nbearing = { model = "clearance", clearance = "-40 um", stiffness = "1e9 N/m" }',
            (": shaft.bearing", "greater than or equal to 0"),
        ),
    ],
)
def test_a_shaft_section_that_cannot_be_built(tmp_path, capsys, section, words):
    p, _ = _tree(tmp_path, "inline4_rated.toml", geometry_edit=lambda t: t + "\n" + section + "\n")
    _refused(capsys, p, "inline4.toml", *words)


def test_check_exits_2_on_a_mismatch(tmp_path, capsys):
    p, _ = _tree(tmp_path, "inline4_rated.toml", engine="inline6.toml")
    assert main(["check", str(p), "-o", str(tmp_path / "out"), "--no-render", "--no-vtu"]) == 2
    out = capsys.readouterr()
    assert "4 throw(s) here, 6 in the engine" in out.out + out.err


def test_a_cad_shaft_keeps_its_recognised_journals(tmp_path):
    """A CAD file of the whole inline-4 shaft on its engine: the load case reads (the
    bearing centres stay the journals' middles the CAD route recognises, no parametric
    stubs to move) and the whole-shaft stage, which builds its shaft from a parametric
    geometry, does not run: the per-throw model alone, without a crash."""
    from helpers.cad_files import shaft_step

    from fe_crank.cad.config import CadInput
    from fe_crank.io.geometry import load_geometry
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.pipeline.stages import shaft_layout

    p, _ = _tree(tmp_path, "inline4_rated.toml")
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    shaft_step(g, tmp_path / "geometry" / "shaft.step")
    text = p.read_text().replace('geometry = "../geometry/inline4.toml"', 'geometry = "../geometry/shaft.step"')
    p.write_text(text + '\n[cad]\ndensity = "7850 kg/m^3"\n')
    lc = load_loadcase(p)
    assert isinstance(lc.geometry, CadInput) and len(lc.engine.throws) == 4
    assert shaft_layout(lc) is None


_FILM = 'clearance = "25 um", groove = "full", groove_width = "3 mm"'


@pytest.mark.parametrize(
    "bearing, words",
    [
        ('{ model = "hydrodynamic", clearance = "0 um", viscosity = "8 mPa*s" }', ("shaft.bearing", "clearance")),
        ('{ model = "hydrodynamic", clearance = "-5 um", viscosity = "8 mPa*s" }', ("shaft.bearing", "clearance")),
        ('{ model = "hydrodynamic", clearance = "25 um" }', ("shaft.bearing", "needs its oil")),
        (
            f'{{ model = "hydrodynamic", {_FILM}, viscosity = "0 mPa*s" }}',
            ("shaft.bearing.viscosity", "greater than 0"),
        ),
        (
            f'{{ model = "hydrodynamic", {_FILM}, viscosity = "-8 mPa*s" }}',
            ("shaft.bearing.viscosity", "greater than 0"),
        ),
        (
            '{ model = "hydrodynamic", clearance = "30 mm", viscosity = "8 mPa*s", groove = "full", groove_width = "3 mm" }',
            ("shaft.bearing.clearance", "not smaller than the journal's radius 28 mm"),
        ),
        (
            '{ model = "hydrodynamic", clearance = "25 um", viscosity = "8 mPa*s", groove = "half" }',
            ("shaft.bearing.groove", "'none' or 'full'"),
        ),
        (f'{{ model = "hydrodynamic", {_FILM}, viscosity = "8 mPa" }}', ("shaft.bearing.viscosity", "not a viscosity")),
        (
            '{ model = "hydrodynamic", clearance = "25 um", viscosity = "8 mPa*s" }',
            ("shaft.bearing", "oil film model's range"),
        ),
        (
            f'{{ model = "hydrodynamic", {_FILM}, viscosity = "8 mPa*s", '
            'oil = { nu40 = "65 mm^2/s", nu100 = "11 mm^2/s", density = "850 kg/m^3", temperature = "120 degC" } }',
            ("shaft.bearing", "not both"),
        ),
        ('{ model = "rigid", viscosity = "8 mPa*s" }', ("shaft.bearing", 'only a "hydrodynamic" bearing')),
    ],
)
def test_a_hydrodynamic_bearing_that_cannot_be_built(tmp_path, capsys, bearing, words):
    p, _ = _tree(tmp_path, "inline4_rated.toml", geometry_edit=lambda t: t + f"\n[shaft]\nbearing = {bearing}\n")
    _refused(capsys, p, "inline4.toml", *words)


def test_an_oil_film_criterion_without_a_film_is_refused(tmp_path, capsys):
    p, _ = _tree(tmp_path, "inline4_rated.toml")
    p.write_text(p.read_text().replace("[criteria]\n", '[criteria]\nmin_oil_film_thickness = "1 um"\n'))
    _refused(capsys, p, "inline4_rated.toml", "criteria.min_oil_film_thickness", "no main bearing has an oil film")


def test_a_hydrodynamic_bearing_reads(tmp_path):
    """A valid film: the oil by Walther's equation, the structural law rigid."""
    from fe_crank.geometry.oil import walther_viscosity
    from fe_crank.io.geometry import load_geometry

    oil = 'oil = { nu40 = "65 mm^2/s", nu100 = "11 mm^2/s", density = "850 kg/m^3", temperature = "120 degC" }'
    _, g = _tree(
        tmp_path,
        "inline4_rated.toml",
        geometry_edit=lambda t: t + f'\n[shaft]\nbearing = {{ model = "hydrodynamic", {_FILM}, {oil} }}\n',
    )
    law = load_geometry(g).shaft.bearing_law
    assert law.model == "rigid" and law.film is not None
    assert law.film.viscosity == pytest.approx(walther_viscosity(65e-6, 11e-6, 850.0, 393.15))
    assert law.film.groove == "full" and law.film.groove_width == pytest.approx(3e-3)


def test_an_oil_film_criterion_without_the_whole_shaft_is_refused(tmp_path, capsys):
    p, _ = _tree(tmp_path, "single_cylinder.toml")
    text = p.read_text()
    text = (
        text.replace("[criteria]\n", '[criteria]\nmax_oil_film_pressure = "150 MPa"\n')
        if "[criteria]" in text
        else (text + '\n[criteria]\nmax_oil_film_pressure = "150 MPa"\n')
    )
    p.write_text(text)
    _refused(capsys, p, "single_cylinder.toml", "criteria.max_oil_film_pressure", "whole-shaft model")


def test_a_specific_load_criterion_without_a_bearing_width_is_refused(tmp_path, capsys):
    """tests/data/small_shaft.toml limits the specific load: with the [shaft] section's
    bearing width taken out of its geometry, `validate` refuses it (the journal's flat
    is no bearing width), naming the geometry file and the key; a width stated per
    bearing is enough, and without the criterion the same geometry is accepted."""
    data = ROOT / "tests" / "data"
    for f in ("small_shaft.toml", "geometry_small_shaft.toml"):
        shutil.copy(data / f, tmp_path / f)
    g = tmp_path / "geometry_small_shaft.toml"
    text = g.read_text()
    cut = text[: text.index("[shaft]")]
    g.write_text(cut)
    err = _refused(
        capsys, tmp_path / "small_shaft.toml", "geometry_small_shaft.toml", "shaft.bearing_width", "19 mm", "1, 2"
    )
    assert "max_main_bearing_specific_load" in err
    per_bearing = "".join(f'\n[[shaft.bearings]]\nname = "{j + 1}"\njournal = {j}\nwidth = "16 mm"\n' for j in range(5))
    g.write_text(cut + per_bearing)
    assert main(["validate", str(tmp_path / "small_shaft.toml")]) == 0
    g.write_text(cut)
    case = tmp_path / "small_shaft.toml"
    case.write_text(case.read_text().replace('max_main_bearing_specific_load = "40 MPa"\n', ""))
    assert main(["validate", str(case)]) == 0


@pytest.mark.parametrize(
    "line, ok",
    [
        ('stiffness_range = ["5e8 N/m", "2e9 N/m"]', True),
        ('stiffness_range = ["3e9 N/m", "3e8 N/m"]', False),
        ('stiffness_range = ["3e8 N/m"]', False),
        ('stiffness_range = ["3e8 N/m", "3e9 N/mm"]', True),
    ],
)
def test_the_stiffness_range_is_read_or_refused(tmp_path, capsys, line, ok):
    """[shaft] stiffness_range: two positive stiffnesses, the lower first, with units;
    read into the layout, or refused with the file and the key."""
    from fe_crank.io.loadcase import load_loadcase

    data = ROOT / "tests" / "data"
    for f in ("small_shaft.toml", "geometry_small_shaft.toml"):
        shutil.copy(data / f, tmp_path / f)
    g = tmp_path / "geometry_small_shaft.toml"
    g.write_text(g.read_text().replace("[shaft]\n", f"[shaft]\n{line}\n"))
    if not ok:
        err = _refused(capsys, tmp_path / "small_shaft.toml", "geometry_small_shaft.toml", "stiffness_range")
        assert "literal" not in err and "Input should" not in err
        return
    assert main(["validate", str(tmp_path / "small_shaft.toml")]) == 0
    lc = load_loadcase(tmp_path / "small_shaft.toml")
    lo, hi = (5e8, 2e9) if "2e9" in line else (3e8, 3e12)
    assert lc.geometry.shaft.stiffness_range == pytest.approx((lo, hi))


def test_flywheel_and_pulley_are_read_with_their_units_or_refused(tmp_path, capsys):
    """[shaft] flywheel (at the power take-off's end, rear by default) and pulley (the other
    end): SI values from their units; a flywheel without its mass is refused with the key."""
    from fe_crank.io.loadcase import load_loadcase

    data = ROOT / "tests" / "data"
    for f in ("small_shaft.toml", "geometry_small_shaft.toml"):
        shutil.copy(data / f, tmp_path / f)
    g = tmp_path / "geometry_small_shaft.toml"
    text = g.read_text()
    lines = (
        'flywheel = { mass = "12 kg", offset = "40 mm", eccentricity = "0.1 mm", unbalance_angle = "30 deg" }\n'
        'pulley = { mass = "1500 g", offset = "3.5 cm", belt_pull = "1.2 kN", belt_angle = "90 deg" }\n'
    )
    g.write_text(text.replace("[shaft]\n", "[shaft]\n" + lines))
    lc = load_loadcase(tmp_path / "small_shaft.toml")
    pulley, flywheel = lc.geometry.shaft.end_loads
    assert (pulley.name, pulley.end, flywheel.name, flywheel.end) == ("pulley", "front", "flywheel", "rear")
    assert flywheel.unbalance == pytest.approx(12 * 1e-4)
    assert flywheel.unbalance_angle == pytest.approx(np.pi / 6)
    assert (pulley.mass, pulley.offset, pulley.belt_pull) == pytest.approx((1.5, 0.035, 1200.0))
    assert pulley.belt_angle == pytest.approx(np.pi / 2) and pulley.eccentricity == 0.0
    g.write_text(text.replace("[shaft]\n", '[shaft]\nflywheel = { offset = "40 mm" }\n'))
    _refused(capsys, tmp_path / "small_shaft.toml", "geometry_small_shaft.toml", "shaft.flywheel.mass")
