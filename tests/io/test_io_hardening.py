"""Hostile and careless inputs: each refused with exit 2 and one message naming the
file, the key and the reason; no traceback, no hang, no value echoed from a file.

Each test writes real files and runs the real command line (``fe_crank.cli.main``)
or the input layer; the categories follow docs/limits.md.
"""

from __future__ import annotations

import math
import os
import time
from pathlib import Path

import pytest

from fe_crank.cli import main
from fe_crank.errors import InputError
from fe_crank.io.loadcase import load_loadcase

ROOT = Path(__file__).resolve().parents[2]
SMALL = (ROOT / "tests" / "data" / "small_pass.toml").read_text()
GEOM = (ROOT / "tests" / "data" / "geometry_small.toml").read_text()


def case_dir(tmp_path: Path, text: str = SMALL, name: str = "case.toml") -> Path:
    """A load case in tmp/cases/ with its geometry beside it (the folder tree is tmp/)."""
    d = tmp_path / "cases"
    d.mkdir(exist_ok=True)
    (d / "geometry_small.toml").write_text(GEOM)
    p = d / name
    p.write_text(text)
    return p


def refused(capsys, argv, *words, code=2) -> str:
    """Run the CLI; assert the exit code, no traceback, and each word in stderr."""
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert rc == code, err
    assert "Traceback" not in err
    for w in words:
        assert str(w) in err, (w, err)
    return err


def validate_refuses(capsys, path, *words) -> str:
    return refused(capsys, ["validate", path], str(path), *words)


# ---------------------------------------------------------------- parsing


@pytest.mark.parametrize(
    "deep",
    [
        "x = " + "[" * 5000 + "]" * 5000,  # arrays
        "x = " + "{a = " * 3000 + "1" + "}" * 3000,  # inline tables
        "[" + ".".join(["a"] * 3000) + "]\nb = 1",  # dotted tables
    ],
)
def test_deep_nesting_refused(tmp_path, capsys, deep):
    p = case_dir(tmp_path, SMALL + "\n" + deep + "\n")
    validate_refuses(capsys, p, "nested deeper than 12")


def test_deep_nesting_in_a_folder_scan_does_not_stop_the_batch(tmp_path, capsys):
    """A nested-array bomb among the load cases of a folder: the folder scan reports it
    as an error case (exit 2) and does not crash while looking for [operating]."""
    from fe_crank.pipeline import find_loadcases

    d = tmp_path / "cases"
    d.mkdir()
    (d / "bomb.toml").write_text("x = " + "[" * 5000 + "]" * 5000 + "\n")
    (d / "fine.toml").write_text('name = "x"\n[operating]\nspeed = "1 rpm"\n')
    found = [p.name for p in find_loadcases([d])]
    assert found == ["bomb.toml", "fine.toml"]


def test_unknown_key_deeply_nested_message_is_short(tmp_path, capsys):
    p = case_dir(tmp_path, SMALL.replace("[operating]", 'extra = {a = {b = "secret-token"}}\n[operating]'))
    err = validate_refuses(capsys, p, "extra", "unknown key")
    assert "secret-token" not in err


def test_bom_is_accepted(tmp_path, capsys):
    """A UTF-8 byte-order mark (Windows editors) is not an 'Invalid statement'."""
    p = case_dir(tmp_path)
    p.write_bytes(b"\xef\xbb\xbf" + SMALL.encode())
    assert main(["validate", str(p)]) == 0


# ---------------------------------------------------------------- numbers


@pytest.mark.parametrize(
    "old, new, key",
    [
        ("min_static_safety = 1.5", "min_static_safety = nan", "criteria.min_static_safety"),
        ("min_static_safety = 1.5", "min_static_safety = inf", "criteria.min_static_safety"),
        ('speed = "3000 rpm"', 'speed = "rpm"', "operating.speed"),
        ('speed = "3000 rpm"', 'speed = "9**9**9 rpm"', "operating.speed"),
        ('speed = "3000 rpm"', 'speed = "2**2**20 rpm"', "operating.speed"),
        ('speed = "3000 rpm"', 'speed = "1e999 rpm"', "operating.speed"),
        ('speed = "3000 rpm"', 'speed = "3000 1/s"', "operating.speed"),
        ('bore = "50 mm"', 'bore = "1e30 mm"', "bore"),
        ('bore = "50 mm"', 'bore = "nan mm"', "bore"),
        ('bore = "50 mm"', 'bore = "50 m**999"', "bore"),
        ('bore = "50 mm"', 'bore = "50 ((((mm))))"', "bore"),
        ('bore = "50 mm"', "bore = " + '"' + "5" * 80 + ' mm"', "bore"),
    ],
)
def test_bad_numbers_refused_quickly(tmp_path, capsys, old, new, key):
    assert old in SMALL
    p = case_dir(tmp_path, SMALL.replace(old, new))
    t0 = time.perf_counter()
    err = validate_refuses(capsys, p, key)
    assert time.perf_counter() - t0 < 10.0  # "9**9**9" used to run for ever
    assert "must not be negative" not in err


@pytest.mark.parametrize(
    "table",
    [
        "points = [[0.0, 0.1], [360.0, nan], [720.0, 0.1]]",
        "points = [[0.0, 0.1], [360.0, inf], [720.0, 0.1]]",
    ],
)
def test_non_finite_gas_table_refused(tmp_path, capsys, table):
    gas = f'\n[engine.gas]\nangle_unit = "deg"\npressure_unit = "MPa"\n{table}\n'
    p = case_dir(tmp_path, SMALL.replace("[material]", gas + "\n[material]"))
    validate_refuses(capsys, p, "engine.gas.points", "finite")


@pytest.mark.parametrize(
    "key, value", [("wiebe_a", "inf"), ("wiebe_m", "nan"), ("compression_ratio", "inf"), ("k", "nan")]
)
def test_non_finite_wiebe_refused(tmp_path, capsys, key, value):
    gas = {
        "model": '"wiebe"',
        "compression_ratio": "9.0",
        "intake_pressure": '"1 bar"',
        "exhaust_pressure": '"1.1 bar"',
        "heat_released": '"500 J"',
        "combustion_start": '"-10 deg"',
        "combustion_duration": '"60 deg"',
        key: value,
    }
    body = "\n".join(f"{k} = {v}" for k, v in gas.items())
    p = case_dir(tmp_path, SMALL.replace("[material]", f"\n[engine.gas]\n{body}\n\n[material]"))
    validate_refuses(capsys, p, f"engine.gas.{key}", "finite")


# ---------------------------------------------------------------- units

RPM = 2 * math.pi / 60


@pytest.mark.parametrize(
    "text, rad_s",
    [
        ("2800 rpm", 2800 * RPM),
        ("2800 1/min", 2800 * RPM),
        ("2800 min^-1", 2800 * RPM),
        ("2800 rev/min", 2800 * RPM),
        ("2800 r/min", 2800 * RPM),
        ("50 Hz", 50 * 2 * math.pi),  # Hz of a shaft: revolutions per second
        ("293.2 rad/s", 293.2),
    ],
)
def test_rotational_speed_spellings(text, rad_s):
    """2800 rpm = 2800 * 2 pi / 60 = 293.215 rad/s by hand; '1/min' used to give 1/60 of
    it in rad/s (446 rpm).  Relative 1e-12: only rounding may differ."""
    from fe_crank.io.units import to_si

    assert to_si(text, "speed") == pytest.approx(rad_s, rel=1e-12)


@pytest.mark.parametrize("text", ["2800 1/s", "2800 s^-1"])
def test_ambiguous_speed_refused(text):
    from fe_crank.io.units import to_si

    with pytest.raises(ValueError, match="ambiguous.*rpm.*rad/s"):
        to_si(text, "speed")


# ---------------------------------------------------------------- files


def _csv_case(tmp_path: Path, csv_name: str) -> Path:
    gas = f'\n[engine.gas]\nmodel = "csv"\nfile = "{csv_name}"\n'
    return case_dir(tmp_path, SMALL.replace("[material]", gas + "\n[material]"))


def test_gas_csv_binary(tmp_path, capsys):
    p = _csv_case(tmp_path, "p.csv")
    (p.parent / "p.csv").write_bytes(bytes(range(256)) * 4)
    validate_refuses(capsys, p, "p.csv", "binary")


def test_gas_csv_folder(tmp_path, capsys):
    p = _csv_case(tmp_path, "sub")
    (p.parent / "sub").mkdir()
    validate_refuses(capsys, p, "engine.gas.file", "is a folder")


def test_gas_csv_symlink_loop(tmp_path, capsys):
    p = _csv_case(tmp_path, "loop.csv")
    os.symlink("loop.csv", p.parent / "loop.csv")
    validate_refuses(capsys, p, "engine.gas.file")


def test_gas_csv_non_finite_row(tmp_path, capsys):
    p = _csv_case(tmp_path, "p.csv")
    (p.parent / "p.csv").write_text("angle [deg], pressure [MPa]\n0, 0.1\n360, nan\n720, 0.1\n")
    refused(capsys, ["validate", p], p.parent / "p.csv", "row 3", "finite")  # the CSV's own file and row


@pytest.mark.skipif(os.geteuid() == 0, reason="root reads files whatever their mode")
def test_unreadable_loadcase(tmp_path, capsys):
    p = case_dir(tmp_path)
    p.chmod(0)
    validate_refuses(capsys, p, "permission denied")


def test_symlink_loop_loadcase_in_folder_scan(tmp_path):
    """A self-referencing link among the load cases becomes an error case; the valid
    case of the folder is still found."""
    from fe_crank.pipeline import find_loadcases

    d = tmp_path / "cases"
    d.mkdir()
    os.symlink("loop.toml", d / "loop.toml")
    (d / "fine.toml").write_text('name = "x"\n[operating]\nspeed = "1 rpm"\n')
    assert [p.name for p in find_loadcases([d])] == ["fine.toml", "loop.toml"]


def test_oversized_file_refused(tmp_path, capsys, monkeypatch):
    monkeypatch.setenv("FE_CRANK_MAX_FILE_BYTES", "1000")
    p = case_dir(tmp_path, SMALL + "#" * 2000 + "\n")
    validate_refuses(capsys, p, "larger than 1000 bytes")


# ---------------------------------------------------------------- includes and security


def test_missing_include_names_the_key(tmp_path, capsys):
    p = case_dir(tmp_path, SMALL.replace('geometry = "geometry_small.toml"', 'geometry = "nope.toml"'))
    validate_refuses(capsys, p, "geometry", "nope.toml", "not found")


@pytest.mark.parametrize("target", ["/etc/passwd", "../../../../../../etc/hostname", "/no/such/file.toml"])
def test_paths_outside_the_tree_refused_alike(tmp_path, capsys, target):
    """Existing or not, a path outside the folder tree gets the same refusal and
    nothing is read from it."""
    p = case_dir(tmp_path, SMALL.replace('geometry = "geometry_small.toml"', f'geometry = "{target}"'))
    err = validate_refuses(capsys, p, "geometry", "outside the load case's folder tree", "--allow-outside-paths")
    assert "not found" not in err and "root:" not in err


def test_outside_path_allowed_with_the_option(tmp_path, capsys):
    other = tmp_path / "elsewhere" / "deep"
    other.mkdir(parents=True)
    (other / "g.toml").write_text(GEOM)
    lc = tmp_path / "a" / "b" / "case.toml"
    lc.parent.mkdir(parents=True)
    lc.write_text(SMALL.replace('geometry = "geometry_small.toml"', f'geometry = "{other / "g.toml"}"'))
    refused(capsys, ["validate", lc], "outside")
    assert main(["validate", str(lc), "--allow-outside-paths"]) == 0


def test_secret_values_of_an_included_file_are_not_echoed(tmp_path, capsys):
    """An include that is a TOML file with other keys (a credentials file): the
    message names the keys' file, never the values."""
    p = case_dir(tmp_path, SMALL.replace('geometry = "geometry_small.toml"', 'geometry = "creds.toml"'))
    (p.parent / "creds.toml").write_text('token = "ghp_SECRET123"\npassword = "hunter2"\n')
    err = refused(capsys, ["validate", p], "creds.toml")
    assert "ghp_SECRET123" not in err and "hunter2" not in err


# ---------------------------------------------------------------- outputs (checked before any work)


def test_output_is_an_existing_file(tmp_path, capsys):
    f = tmp_path / "reports"
    f.write_text("x")
    t0 = time.perf_counter()
    refused(capsys, ["check", ROOT / "tests" / "data" / "small_pass.toml", "-o", f], "--output", "existing file")
    assert time.perf_counter() - t0 < 20.0  # refused before the case runs


def test_junit_is_a_folder(tmp_path, capsys):
    refused(
        capsys,
        ["check", ROOT / "tests" / "data" / "small_pass.toml", "-o", tmp_path / "r", "--junit", tmp_path],
        "--junit",
        "is a folder",
    )


@pytest.mark.skipif(not Path("/sys").is_dir(), reason="needs a read-only file system")
def test_output_in_a_read_only_place(tmp_path, capsys):
    refused(
        capsys,
        ["check", ROOT / "tests" / "data" / "small_pass.toml", "-o", "/sys/fe-crank-reports"],
        "--output",
        "cannot write",
    )


# ---------------------------------------------------------------- geometry


def test_counterweight_inside_the_web_refused():
    """A 60-deg sector r 10..18 mm on a 40 mm stadium web (journal-end radius 20 mm):
    every point within 18 mm of the axis lies in the web, so it adds nothing."""
    import tomllib

    from fe_crank.errors import GeometryError
    from fe_crank.io.geometry import geometry_from_dict

    d = tomllib.loads(GEOM)
    d["counterweight"] = {
        "webs": [1],
        "outer_radius": "18 mm",
        "inner_radius": "10 mm",
        "angle": "60 deg",
        "thickness": "12 mm",
    }
    with pytest.raises(GeometryError, match="wholly inside the web") as e:
        geometry_from_dict(d, "g.toml")
    assert e.value.key == "counterweight"
    d["counterweight"]["outer_radius"] = "30 mm"  # reaches beyond the web: material added
    geometry_from_dict(d, "g.toml")


def test_tiny_fillet_refused_before_meshing(tmp_path):
    """A 1 um fillet: the estimate (fillet layers ~ 1/r_f^2) exceeds the limit and
    mesh_throw refuses within a second instead of meshing for minutes."""
    import tomllib

    from fe_crank.errors import GeometryError
    from fe_crank.io.geometry import geometry_from_dict
    from fe_crank.mesh import mesh_throw

    d = tomllib.loads(GEOM)
    d["crankpin"]["fillet_radius"] = "0.001 mm"
    g = geometry_from_dict(d, "g.toml")
    t0 = time.perf_counter()
    with pytest.raises(GeometryError, match="--max-elements") as e:
        mesh_throw(g, size="coarse", cache_dir=tmp_path)
    assert time.perf_counter() - t0 < 5.0
    assert e.value.key == "crankpin.fillet_radius"


def test_mesh_section_max_elements(tmp_path):
    p = case_dir(tmp_path, SMALL + '\n[mesh]\nsize = "test"\nmax_elements = 10\n')
    assert load_loadcase(p).mesh.max_elements == 10
    p.write_text(SMALL + "\n[mesh]\nmax_elements = -1\n")
    with pytest.raises(InputError, match="positive whole number") as e:
        load_loadcase(p)
    assert e.value.key == "mesh.max_elements"


def test_error_inside_an_included_file_names_the_including_key(tmp_path, capsys):
    p = case_dir(tmp_path)
    (p.parent / "geometry_small.toml").write_text(GEOM.replace('crank_radius = "20 mm"', 'crank_radius = "20"'))
    err = validate_refuses(
        capsys, p, "geometry_small.toml", "crank_radius", "has no unit", f"(included by {p}: geometry)"
    )
    assert err.count("\n") == 1  # one message


@pytest.mark.parametrize("geometry", sorted((ROOT / "geometry").glob("*.toml")), ids=lambda p: p.stem)
def test_shipped_throws_pass_the_element_budget_at_every_preset(geometry):
    """The limit must not refuse a real design: the `fine` preset of each shipped throw
    (the V4 throw's fine mesh has 0.58 M tetrahedra, docs/performance.md) stays below it."""
    from fe_crank.geometry.estimate import MAX_ELEMENTS, check_element_budget
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import resolve_options

    g = load_geometry(geometry)
    for t in g.throws:
        for preset in ("test", "coarse", "medium", "fine"):
            assert check_element_budget(g, t, resolve_options(preset)) < MAX_ELEMENTS
