"""``fe-crank validate FILE...``: check input files, print one line per file."""

from __future__ import annotations

import sys
from pathlib import Path

from fe_crank.errors import FeCrankError
from fe_crank.io.base import read_toml


def add_arguments(p) -> None:
    p.add_argument("files", nargs="+", type=Path, help="load-case, engine or geometry .toml files")
    p.add_argument(
        "--allow-outside-paths",
        action="store_true",
        help="let engine/geometry/CSV paths leave the load case's folder tree (refused by default)",
    )


def _kind(data: dict) -> str:
    if "operating" in data:
        return "loadcase"
    if "cylinders" in data:
        return "engine"
    if "throws" in data or "journal" in data or "crankpin" in data:
        return "geometry"
    return "loadcase"


def validate_file(path: Path, allow_outside_paths: bool = False) -> str:
    """Validate one file of any kind; return a one-line summary.  Raises InputError."""
    data = read_toml(path)
    kind = _kind(data)
    if kind == "engine":
        from fe_crank.io.engine import load_engine

        e = load_engine(path)
        return f"engine '{e.name}': {len(e.cylinders)} cylinder(s), {len(e.throws)} throw(s), {len(e.shafts)} shaft(s)"
    if kind == "geometry":
        from fe_crank.io import geometry as geo  # provided by the geometry stage

        g = geo.load_geometry(path)
        return f"geometry '{getattr(g, 'name', path.stem)}'"
    from fe_crank.io.loadcase import load_loadcase

    lc = load_loadcase(path, allow_outside_paths=allow_outside_paths or None)
    return f"load case '{lc.name}': engine '{lc.engine.name}', {lc.operating.speed * 30 / 3.141592653589793:.0f} rpm"


def run(args) -> int:
    bad = 0
    for path in args.files:
        try:
            print(f"ok    {path}: {validate_file(path, getattr(args, 'allow_outside_paths', False))}")
        except FeCrankError as exc:
            bad += 1
            print(f"error {exc}", file=sys.stderr)
    return 2 if bad else 0
