"""A geometry that contradicts its engine, and a [shaft] section that cannot be built, are
refused when the load case is read: `fe-crank validate` and `fe-crank check` exit 2 with
one message naming the file and the key, in the per-throw and the whole-shaft model alike."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from fe_crank.cli import main

ROOT = Path(__file__).resolve().parents[1]


def _tree(tmp_path: Path, case: str, engine: str | None = None, geometry_edit=None) -> tuple[Path, Path]:
    """A copy of the shipped loadcases/, engines/ and geometry/ with ``case`` pointing at
    ``engine`` and its geometry file edited by ``geometry_edit(text) -> text``."""
    for d in ("engines", "geometry"):
        shutil.copytree(ROOT / d, tmp_path / d)
    (tmp_path / "loadcases").mkdir()
    text = (ROOT / "loadcases" / case).read_text()
    if engine is not None:
        old = next(line for line in text.splitlines() if line.startswith("engine = "))
        text = text.replace(old, f'engine = "../engines/{engine}"')
    p = tmp_path / "loadcases" / case
    p.write_text(text)
    gname = next(line for line in text.splitlines() if line.startswith("geometry = ")).split('"')[1]
    g = (p.parent / gname).resolve()
    if geometry_edit is not None:
        g.write_text(geometry_edit(g.read_text()))
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
    from cad_files import shaft_step

    from fe_crank.cad.config import CadInput
    from fe_crank.check.stages import shaft_layout
    from fe_crank.io.geometry import load_geometry
    from fe_crank.io.loadcase import load_loadcase

    p, _ = _tree(tmp_path, "inline4_rated.toml")
    g = load_geometry(ROOT / "geometry" / "inline4.toml")
    shaft_step(g, tmp_path / "geometry" / "shaft.step")
    text = p.read_text().replace('geometry = "../geometry/inline4.toml"', 'geometry = "../geometry/shaft.step"')
    p.write_text(text + '\n[cad]\ndensity = "7850 kg/m^3"\n')
    lc = load_loadcase(p)
    assert isinstance(lc.geometry, CadInput) and len(lc.engine.throws) == 4
    assert shaft_layout(lc) is None
