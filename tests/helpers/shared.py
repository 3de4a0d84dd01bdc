"""Files and meshes shared by the test files of one run, across its processes.

``make test`` hands whole files to two processes (``--dist loadfile``): a session
fixture is built once per process, not once per run.  What several files build the same
way (a CAD file written from a shipped geometry, its mesh at ``test``) is kept here in
one folder of the run, built under a lock by the first process that needs it and read
by the others.  The folder is the run's own (``--basetemp`` or ``pytest-N``, beside the
processes' folders under ``pytest-xdist``), so nothing outlives the run.

A STEP file's header holds the time it was written: two exports of one solid differ in
their bytes and hence in their mesh cache keys (``fe_crank.cad.mesh.cad_cache_key``
hashes the file).  One export, copied where a test needs it (the key holds the bytes,
not the path), lets the files that mesh it share the mesh through ``shared_mesh_cache``.
The mesh cache itself takes concurrent writers (``fe_crank.mesh.cache``: each entry is
built in a folder of its own and renamed into place); the lock only keeps two processes
from building the same entry at the same time.
"""

from __future__ import annotations

import fcntl
import os
import pickle
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import TypeVar

import pytest

T = TypeVar("T")


def shared_dir(factory: pytest.TempPathFactory) -> Path:
    """The run's folder shared by its processes (module doc)."""
    base = factory.getbasetemp()
    root = base.parent if os.environ.get("PYTEST_XDIST_WORKER") else base
    folder = root / "shared"
    folder.mkdir(exist_ok=True)
    return folder


@contextmanager
def locked(factory: pytest.TempPathFactory, name: str) -> Iterator[None]:
    """Hold the run's lock ``name`` (an exclusive ``flock`` on a file of the shared folder)."""
    with open(shared_dir(factory) / f"{name}.lock", "a") as fh:
        fcntl.flock(fh, fcntl.LOCK_EX)
        try:
            yield
        finally:
            fcntl.flock(fh, fcntl.LOCK_UN)


def shared_file(factory: pytest.TempPathFactory, name: str, build: Callable[[Path], object]) -> Path:
    """The shared file ``name``, written once in the run by ``build(path)`` (into a
    temporary name with the same suffix, then renamed: a reader never sees half a file)."""
    path = shared_dir(factory) / name
    with locked(factory, name):
        if not path.exists():
            tmp = path.with_name(f".{os.getpid()}-{name}")
            build(tmp)
            os.replace(tmp, path)
    return path


def copy_of(shared: Path, dest: Path) -> Path:
    """``shared``'s bytes at ``dest`` (a file a test names or places itself)."""
    dest.write_bytes(shared.read_bytes())
    return dest


def shared_mesh_cache(factory: pytest.TempPathFactory) -> Path:
    """The run's mesh cache shared by its processes."""
    folder = shared_dir(factory) / "mesh_cache"
    folder.mkdir(exist_ok=True)
    return folder


def shared_value(factory: pytest.TempPathFactory, name: str, compute: Callable[[], T]) -> T:
    """``compute()``'s value, computed once in the run and kept in the shared folder as the
    pickle ``name`` (``shared_file``): every process reads the same value back, bit for bit."""
    path = shared_file(factory, name, lambda p: p.write_bytes(pickle.dumps(compute())))
    return pickle.loads(path.read_bytes())
