"""Faults of the machine, not of the input: a mesh cache the process may not write and
a file the file system will not let grow are named as such, with the path, exit 2 and
no traceback."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from fe_crank.cli import main

ROOT = Path(__file__).resolve().parents[2]
GEOMETRY = ROOT / "geometry" / "single_cylinder.toml"
CASE = ROOT / "loadcases" / "single_cylinder.toml"
#: a folder no process may create (sysfs is not writable, not even by root)
FORBIDDEN = "/sys/fe-crank-cache"


def test_mesh_cache_without_write_permission(tmp_path, capsys):
    argv = ["mesh", GEOMETRY, "--mesh-size", "test", "--cache-dir", FORBIDDEN, "-o", tmp_path / "o", "--no-render"]
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert rc == 2
    assert "Traceback" not in err
    assert "environment fault: operation not permitted while creating the mesh cache at " + FORBIDDEN in err


def test_check_names_the_cache_fault(tmp_path, capsys):
    argv = ["check", CASE, "-o", tmp_path / "out", "--mesh-size", "test", "--cache-dir", FORBIDDEN]
    rc = main([str(a) for a in argv])
    out = capsys.readouterr()
    text = out.out + out.err
    assert rc == 2
    assert "Traceback" not in text and "internal error" not in text
    assert "environment fault" in text and FORBIDDEN in text


def test_a_file_that_cannot_grow_is_an_environment_fault(tmp_path):
    """A file-size limit of 64 kB (``RLIMIT_FSIZE``, its signal ignored: the write fails
    with EFBIG as a full disk fails with ENOSPC) stops the mesh cache's first large file."""
    cache = tmp_path / "cache"
    code = (
        "import resource, signal, sys\n"
        "signal.signal(signal.SIGXFSZ, signal.SIG_IGN)\n"
        "resource.setrlimit(resource.RLIMIT_FSIZE, (65536, 65536))\n"
        "from fe_crank.cli import main\n"
        "sys.exit(main(sys.argv[1:]))\n"
    )
    argv = ["mesh", str(GEOMETRY), "--mesh-size", "test", "--cache-dir", str(cache), "-o", str(tmp_path / "o")]
    env = dict(os.environ, PYTHONPATH=str(ROOT), OPENBLAS_NUM_THREADS="1")
    res = subprocess.run(
        [sys.executable, "-c", code, *argv, "--no-render"], capture_output=True, text=True, env=env, timeout=600
    )
    assert res.returncode == 2, res.stderr
    assert "Traceback" not in res.stderr
    assert "environment fault: file too large" in res.stderr
    assert str(cache) in res.stderr
    assert not [p for p in cache.iterdir() if not p.name.startswith(".")]  # no entry left half written
