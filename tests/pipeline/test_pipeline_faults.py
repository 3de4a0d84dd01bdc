"""Faults a CI runner meets: kill -9 at each stage, a damaged mesh cache, two writers
to one output folder, outputs that cannot be written.  Each ends in a complete,
correct report or a clear error (exit 2, file and option named), and leaves no
temporary folders behind.  Real processes, real gmsh meshes, real solves.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
CASE = ROOT / "tests" / "data" / "small_pass.toml"
GEOM = ROOT / "tests" / "data" / "geometry_small.toml"
FE_CRANK = [str(Path(sys.executable).parent / "fe-crank")]
ENV = {**os.environ, "OPENBLAS_NUM_THREADS": "1", "PYVISTA_OFF_SCREEN": "true"}


def check_cmd(out: Path, cache: Path, *extra) -> list[str]:
    return FE_CRANK + [
        "check",
        str(CASE),
        "-o",
        str(out),
        "--cache-dir",
        str(cache),
        "--mesh-size",
        "test",
        "--no-render",
        "--no-vtu",
        *map(str, extra),
    ]


def leftovers(out: Path, cache: Path) -> list[str]:
    found = [p.name for p in out.iterdir() if ".partial-" in p.name or ".old-" in p.name] if out.exists() else []
    found += [p.name for p in cache.iterdir() if p.name.startswith(".")] if cache.exists() else []
    return found


def assert_complete(out: Path) -> dict:
    folder = out / "small_pass"
    case = json.loads((folder / "case.json").read_text())
    assert case["status"] == "pass", case
    assert (folder / "report.html").stat().st_size > 0
    results = json.loads((folder / "results.json").read_text())  # strict JSON: no NaN tokens
    assert results["passed"] is True
    return case


def kill_when(cmd, ready, timeout=600.0) -> bool:
    """Start ``cmd``; SIGKILL it as soon as ``ready()`` is true.  False if it ended first."""
    proc = subprocess.Popen(cmd, env=ENV, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    t0 = time.monotonic()
    try:
        while proc.poll() is None and time.monotonic() - t0 < timeout:
            if ready():
                proc.send_signal(signal.SIGKILL)
                proc.wait()
                return True
            time.sleep(0.02)
        return False
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()


def test_kill_at_each_stage_then_rerun(tmp_path):
    """SIGKILL while loading, while meshing (a temporary cache folder exists), while
    solving (the mesh entry is complete, no report yet) and while writing the report
    (the case's temporary folder has files); then a clean run gives the complete
    report and no temporary folder of the killed runs survives."""
    out, cache = tmp_path / "out", tmp_path / "cache"

    def partial_files():
        return out.exists() and any(p.is_dir() and ".partial-" in p.name and any(p.iterdir()) for p in out.iterdir())

    def meshing():
        return cache.exists() and any(p.name.startswith(".") for p in cache.iterdir())

    def meshed():
        return cache.exists() and any((p / "complete").exists() for p in cache.iterdir())

    t_start = time.monotonic()
    assert kill_when(check_cmd(out, cache), lambda: time.monotonic() - t_start > 0.5)  # load / imports
    assert kill_when(check_cmd(out, cache), meshing)
    assert any(p.name.startswith(".") for p in cache.iterdir())  # the killed run's temporary entry
    assert kill_when(check_cmd(out, cache), meshed)  # FE stage (mesh just cached)
    killed_in_report = kill_when(check_cmd(out, cache), partial_files)
    assert not (out / "small_pass").exists()  # nothing published by a killed run
    r = subprocess.run(check_cmd(out, cache), env=ENV, capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    assert_complete(out)
    assert leftovers(out, cache) == [], killed_in_report


def test_damaged_cache_entry_is_rebuilt(tmp_path, mesh_cache):
    """A truncated mesh.npz, then a garbled stats.json: each is discarded and the
    mesh rebuilt with the same element count (gmsh is deterministic for one input).
    The first mesh is the run's (``helpers.seeded_cache``): both rebuilds are gmsh's."""
    from helpers.seeded_cache import seed

    from fe_crank.geometry.estimate import estimate_elements
    from fe_crank.io.geometry import load_geometry
    from fe_crank.mesh import mesh_throw, resolve_options

    g = load_geometry(GEOM)
    key = seed(tmp_path, mesh_cache, g)
    first = mesh_throw(g, size="test", cache_dir=tmp_path)
    assert first.stats.from_cache and first.key == key
    # the pre-meshing estimate against gmsh's real count (independent): within a factor
    # 3, the accuracy docs/limits.md states (the limit must not let a 10x mesh through)
    ratio = estimate_elements(g, g.throw(None), resolve_options("test")) / first.stats.elements
    assert 1 / 3 < ratio < 3, ratio
    entry = tmp_path / first.key
    npz = entry / "mesh.npz"
    npz.write_bytes(npz.read_bytes()[: npz.stat().st_size // 2])
    again = mesh_throw(g, size="test", cache_dir=tmp_path)
    assert not again.stats.from_cache and again.stats.elements == first.stats.elements
    (entry / "stats.json").write_text("{not json")
    third = mesh_throw(g, size="test", cache_dir=tmp_path)
    assert not third.stats.from_cache and third.stats.elements == first.stats.elements
    hit = mesh_throw(g, size="test", cache_dir=tmp_path)
    assert hit.stats.from_cache and hit.stats.elements == first.stats.elements


@pytest.fixture(scope="module")
def shared_cache(tmp_path_factory) -> Path:
    return tmp_path_factory.mktemp("cache")


def test_two_writers_to_one_output_folder(tmp_path, shared_cache):
    """Two `fe-crank check` processes on the same case and output folder at once:
    both finish, the report is one complete run's, nothing temporary is left."""
    out, cache = tmp_path / "out", shared_cache
    procs = [
        subprocess.Popen(check_cmd(out, cache), env=ENV, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        for _ in range(2)
    ]
    for p in procs:
        _, err = p.communicate(timeout=900)
        assert p.returncode == 0, err
        assert "Traceback" not in err
    assert_complete(out)
    assert leftovers(out, cache) == []


@pytest.mark.parametrize(
    "args, words",
    [
        (["-o", "/sys/fe-crank-reports"], ["--output", "cannot write"]),
        (["--junit", "/sys/fe-crank-junit.xml"], ["--junit", "cannot write"]),
    ],
)
def test_read_only_outputs_refused_before_work(tmp_path, args, words):
    if not Path("/sys").is_dir():
        pytest.skip("needs a read-only file system")
    cmd = FE_CRANK + [
        "check",
        str(CASE),
        "--cache-dir",
        str(tmp_path / "c"),
        "--mesh-size",
        "test",
        "-o",
        str(tmp_path / "out"),
        *args,
    ]
    t0 = time.monotonic()
    r = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=300)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    for w in words:
        assert w in r.stderr
    assert not (tmp_path / "c").exists()  # refused before any meshing
    assert time.monotonic() - t0 < 60


def test_hostile_files_in_a_folder_do_not_stop_the_valid_case(tmp_path, shared_cache):
    """A folder scan meets a nested-array bomb, a symbolic-link loop, a binary file
    and a load case with "9**9**9 rpm": each is an error case naming its file, the
    valid case beside them gets its complete report; exit 2."""
    d = tmp_path / "cases"
    d.mkdir()
    (d / "small_pass.toml").write_text(CASE.read_text())
    (d / "geometry_small.toml").write_text(GEOM.read_text())
    (d / "bomb.toml").write_text("x = " + "[" * 5000 + "]" * 5000 + "\n")
    os.symlink("loop.toml", d / "loop.toml")
    (d / "binary.toml").write_bytes(bytes(range(256)))
    (d / "hang.toml").write_text(CASE.read_text().replace('speed = "3000 rpm"', 'speed = "9**9**9 rpm"'))
    out = tmp_path / "out"
    cmd = FE_CRANK + [
        "check",
        str(d),
        "-o",
        str(out),
        "--cache-dir",
        str(shared_cache),
        "--mesh-size",
        "test",
        "--no-render",
        "--no-vtu",
    ]
    r = subprocess.run(cmd, env=ENV, capture_output=True, text=True, timeout=900)
    assert r.returncode == 2, r.stderr
    assert "Traceback" not in r.stderr + r.stdout
    for name, words in (
        ("bomb.toml", "nested deeper"),
        ("loop.toml", "symbolic-link loop"),
        ("binary.toml", "binary"),
        ("hang.toml", "operating.speed"),
    ):
        line = next(ln for ln in r.stderr.splitlines() if name in ln)
        assert words in line, line
    assert_complete(out)
