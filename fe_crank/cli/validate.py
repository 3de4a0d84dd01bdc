"""``fe-crank validate FILE...``: check input files, print one line per file."""

from __future__ import annotations

import sys
from pathlib import Path

from fe_crank.errors import FeCrankError
from fe_crank.io.base import read_toml


def add_arguments(p) -> None:
    p.add_argument(
        "files", nargs="+", type=Path, help="load-case, engine, geometry or CAD geometry ([cad]) .toml files"
    )
    p.add_argument(
        "--allow-outside-paths",
        action="store_true",
        help="let engine/geometry/CSV paths leave the load case's folder tree (refused by default)",
    )


def _kind(data: dict) -> str:
    if "operating" in data:
        return "loadcase"
    if "cad" in data:
        return "cad"
    if "cylinders" in data:
        return "engine"
    if "throws" in data or "journal" in data or "crankpin" in data:
        return "geometry"
    return "loadcase"


def _recognised(features) -> str:
    t = features.throws
    return (
        f"{features.source.format} file {features.source.file}: {len(t)} throw(s) recognised, crank radius "
        + ", ".join(f"{x.crank_radius * 1e3:.6g} mm" for x in t)
    )


def validate_file(path: Path, allow_outside_paths: bool = False) -> str:
    """Validate one file of any kind; return a one-line summary.  Raises InputError.
    A CAD geometry (a ``[cad]`` file, or a load case's) is read and recognised, and a
    load case's checked against its engine, as the check's geometry stage does."""
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
    if kind == "cad":
        from fe_crank.cad import recognise
        from fe_crank.io.cad import load_cad
        from fe_crank.io.includes import input_root

        with input_root(path, allow_outside_paths or None):
            cad = load_cad(path)
        return "CAD geometry: " + _recognised(recognise(cad))
    from fe_crank.cad.config import CadInput
    from fe_crank.io.loadcase import load_loadcase

    lc = load_loadcase(path, allow_outside_paths=allow_outside_paths or None)
    text = f"load case '{lc.name}': engine '{lc.engine.name}', {lc.operating.speed * 30 / 3.141592653589793:.0f} rpm"
    if isinstance(lc.geometry, CadInput):
        from fe_crank.pipeline.cad_geometry import cad_layout, recognise_case

        features = recognise_case(lc, lc.geometry)[0]
        text += "; " + _recognised(features)
        layout = cad_layout(lc, lc.geometry, features)  # the whole shaft's refusals, before any meshing
        if layout is not None:
            text += f"; whole shaft on {len(layout.bearings)} main bearings"
    return text


def run(args) -> int:
    bad = 0
    for path in args.files:
        try:
            print(f"ok    {path}: {validate_file(path, getattr(args, 'allow_outside_paths', False))}")
        except FeCrankError as exc:
            bad += 1
            print(f"error {exc}", file=sys.stderr)
    return 2 if bad else 0
