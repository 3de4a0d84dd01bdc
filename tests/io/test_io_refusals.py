"""Designs that cannot exist and inputs outside the physical range of an engine are
refused by ``fe-crank validate`` and by ``fe-crank check`` before any meshing, each with
one message naming the file and the key (docs/limits.md, "Physical range" and
"Refusals").  Each case is a shipped input with one value changed."""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.io.bounds import MAX_PISTON_SPEED

ROOT = Path(__file__).resolve().parents[2]


def _tree(tmp_path: Path) -> Path:
    for d in ("engines", "geometry", "loadcases"):
        shutil.copytree(ROOT / d, tmp_path / d)
    return tmp_path


def _edit(path: Path, old: str, new: str, count: int = 1) -> None:
    text = path.read_text()
    assert old in text, old
    path.write_text(text.replace(old, new, count))


def _refused(capsys, tmp_path: Path, case: str, file: str, *words: str) -> None:
    """validate and check both refuse, naming the file and the words; check meshes nothing."""
    path = tmp_path / "loadcases" / case
    for argv in (
        ["validate", path],
        ["check", path, "-o", tmp_path / "out", "--cache-dir", tmp_path / "cache", "--mesh-size", "test"],
    ):
        rc = main([str(a) for a in argv])
        err = capsys.readouterr().err
        assert rc == 2, err
        assert "Traceback" not in err
        for w in (file, *words):
            assert w in err, (w, err)
        assert not (tmp_path / "cache").exists() or not any((tmp_path / "cache").iterdir())


INLINE4 = "inline4_rated.toml"


@pytest.mark.parametrize(
    ("file", "old", "new", "case", "words"),
    [
        # bolts at a 500 mm pitch radius on an 80 mm counterweight
        ("geometry/inline4.toml", 'pitch_radius = "58 mm"', 'pitch_radius = "500 mm"', INLINE4,
         ["inline4.toml", "throws[0].counterweight.bolted.pitch_radius", "within the counterweight"]),
        # bolts 5 mm from the axis: inside the 54 mm journal
        ("geometry/inline4.toml", 'pitch_radius = "58 mm"', 'pitch_radius = "5 mm"', INLINE4,
         ["throws[0].counterweight.bolted.pitch_radius", "into the journal"]),
        # a 600 mm counterweight on a 43 mm crank radius with 143.5 mm rods: hits the piston pin at BDC
        ("geometry/inline4.toml", 'outer_radius = "80 mm"', 'outer_radius = "600 mm"', INLINE4,
         ["counterweight.outer_radius", "100.5 mm", "cannot turn"]),
        # a 150 mm bore on a 92 mm cylinder pitch
        ("engines/inline4.toml", 'bore = "86 mm"', 'bore = "150 mm"', INLINE4,
         ["inline4.toml", "cylinders[1].bore", "overlap"]),
        # 1e6 rpm
        ("loadcases/inline4_rated.toml", 'speed = "6000 rpm"\noverspeed = "7200 rpm"',
         'speed = "1e6 rpm"\noverspeed = "1.2e6 rpm"', INLINE4,
         ["operating.speed", "1-60 000 rpm"]),
        # a 1 um stroke
        ("engines/inline4.toml", 'stroke = "86 mm"', 'stroke = "0.001 mm"', INLINE4,
         ["engines/inline4.toml", "throws[0].stroke", "2 mm to 5 m"]),
        # the torsional sweep 800-2000 rpm excludes the operating 3000 rpm (and the full-load curve's 2200 rpm)
        ("loadcases/inline4_genset_torsion.toml", '"800 rpm", "3600 rpm"', '"800 rpm", "2000 rpm"',
         "inline4_genset_torsion.toml", ["torsion.speed_range", "outside the speed range 800-2000 rpm"]),
        # a main-bearing criterion on the single throw without [shaft]
        ("loadcases/single_cylinder.toml", "[criteria]\n", '[criteria]\nmax_main_bearing_load = "100 kN"\n',
         "single_cylinder.toml", ["single_cylinder.toml: criteria.max_main_bearing_load: needs the whole-shaft", "[shaft]"]),
    ],
    ids=["bolts-outside", "bolts-in-journal", "counterweight-600mm", "bores-overlap", "1e6rpm", "1um-stroke",
         "torsion-range", "main-bearing-single"],
)  # fmt: skip
def test_impossible_inputs_refused_before_meshing(tmp_path, capsys, file, old, new, case, words):
    root = _tree(tmp_path)
    _edit(root / file, old, new)
    _refused(capsys, root, case, *words)


def test_mean_piston_speed_bound(tmp_path, capsys):
    """86 mm stroke: 2 s n = 50 m/s at 17 442 rpm; 18 000 rpm (overspeed) is refused."""
    root = _tree(tmp_path)
    s = 0.086
    n_limit = MAX_PISTON_SPEED / (2 * s) * 60  # rpm at 50 m/s, hand formula c_m = 2 s n
    assert math.isclose(n_limit, 17441.86, rel_tol=1e-6)
    _edit(root / "loadcases" / INLINE4, 'overspeed = "7200 rpm"', 'overspeed = "18000 rpm"')
    _refused(capsys, root, INLINE4, "operating.overspeed", "mean piston speed of 51.6 m/s")


def test_shipped_inputs_lie_within_the_bounds():
    for path in sorted((ROOT / "loadcases").glob("*.toml")):
        assert main(["validate", str(path)]) == 0, path


def test_main_bearing_criterion_on_a_cad_geometry_refused_before_recognition(tmp_path, capsys):
    from helpers.cad_files import cad_loadcase, parametric_step

    from fe_crank.io.geometry import load_geometry

    parametric_step(load_geometry(ROOT / "tests" / "data" / "geometry_small.toml"), tmp_path / "throw.step")
    lc = cad_loadcase(tmp_path, "throw.step", criteria='max_main_bearing_load = "100 kN"')
    assert main(["validate", str(lc)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert err.startswith(f"error {lc}: criteria.max_main_bearing_load: "), err
    assert "CAD file" in err
