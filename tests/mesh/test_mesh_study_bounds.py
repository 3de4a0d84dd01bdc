"""A fillet too small for the hot-spot convergence study's finest level, refused by
``fe-crank validate`` and by ``check`` before anything is meshed: one line naming the
geometry file and the key, exit 2 (``fe_crank.mesh.study_bounds``).

The shipped single-cylinder case with its crankpin fillet at 0.1 mm: at ``coarse`` the
study's finest level is r/8, the size field's target 0.65 x 0.1 mm / 8 = 8.1 um, below
the 10 um bound; at ``test`` the study does not run, so the case is valid.
"""

from __future__ import annotations

import math
import shutil
from pathlib import Path

import pytest
from helpers.paths import ROOT

from fe_crank.cli import main
from fe_crank.io.geometry import load_geometry
from fe_crank.mesh.options import PRESETS
from fe_crank.mesh.study_bounds import MIN_EDGE, study_edges


def case(tmp_path: Path, fillet: str, size: str) -> tuple[Path, Path]:
    """The single-cylinder case copied with its crankpin fillet ``fillet`` and mesh ``size``."""
    for d in ("loadcases", "engines", "geometry"):
        (tmp_path / d).mkdir()
    shutil.copy(ROOT / "engines" / "single_cylinder.toml", tmp_path / "engines")
    geo = (ROOT / "geometry" / "single_cylinder.toml").read_text()
    lines = geo.splitlines()
    pin = lines.index("[crankpin]")
    at = next(i for i in range(pin, len(lines)) if lines[i].startswith("fillet_radius"))
    lines[at] = f'fillet_radius = "{fillet}"'
    gfile = tmp_path / "geometry" / "single_cylinder.toml"
    gfile.write_text("\n".join(lines) + "\n")
    lc = (ROOT / "loadcases" / "single_cylinder.toml").read_text().replace('size = "test"', f'size = "{size}"')
    lfile = tmp_path / "loadcases" / "case.toml"
    lfile.write_text(lc)
    return lfile, gfile


def test_the_finest_level_edges_by_hand():
    g = load_geometry(ROOT / "geometry" / "single_cylinder.toml")
    got = {k: (size, edge) for k, size, edge in study_edges(g, PRESETS["coarse"], 2.0)}
    assert got["crankpin.fillet_radius"] == pytest.approx((4e-3, 0.65 * 4e-3 / 8))
    assert got["counterweight.fillet_radius"] == pytest.approx((5e-3, 0.65 * 5e-3 / 8))
    m = PRESETS["coarse"].bore_divisions * 2
    assert got["oil_bore.diameter"] == pytest.approx((6e-3, math.pi * 6e-3 / (2 * m)))
    assert min(e for _, e in got.values()) > MIN_EDGE


def test_a_fillet_too_small_for_the_study_is_refused(tmp_path, capsys):
    lfile, gfile = case(tmp_path, "0.1 mm", "coarse")
    assert main(["validate", str(lfile)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    named, key = err.removeprefix("error ").split(": ")[:2]
    assert Path(named).resolve() == gfile.resolve() and key == "crankpin.fillet_radius", err
    assert "8.13 um" in err and "at least 0.123 mm" in err, err


def test_valid_without_the_study_and_refused_by_check_at_a_finer_size(tmp_path, capsys):
    lfile, gfile = case(tmp_path, "0.1 mm", "test")
    assert main(["validate", str(lfile)]) == 0
    capsys.readouterr()
    out = tmp_path / "report"
    code = main(["check", str(lfile), "--mesh-size", "coarse", "-o", str(out), "--cache-dir", str(tmp_path / "m")])
    assert code == 2
    err = capsys.readouterr().err
    assert "single_cylinder.toml: crankpin.fillet_radius: " in err and "too small" in err, err
    assert not (tmp_path / "m").exists() or not any((tmp_path / "m").iterdir())  # nothing meshed
