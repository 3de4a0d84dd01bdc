"""``fe-crank validate FILE...``: check input files, print one line per file."""

from __future__ import annotations

import sys
from pathlib import Path

from fe_crank.errors import FeCrankError
from fe_crank.io.base import read_toml


def add_arguments(p) -> None:
    p.add_argument(
        "files",
        nargs="+",
        type=Path,
        help="load-case, engine, geometry, CAD geometry ([cad]) or study ([study]) .toml files",
    )
    p.add_argument(
        "--loadcase",
        type=Path,
        default=None,
        metavar="FILE",
        help="the load case a study file is checked against (default: the load cases among FILES)",
    )
    p.add_argument(
        "--allow-outside-paths",
        action="store_true",
        help="let engine/geometry/CSV paths leave the load case's folder tree (refused by default)",
    )


def _kind(data: dict) -> str:
    if "study" in data:
        return "study"
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


def validate_study(path: Path, loadcases: list[Path], allow_outside_paths: bool = False) -> str:
    """A study file alone, then against each load case: every refusal of ``fe-crank
    study`` before meshing (rates, limits, placements, the drawn counterweights against
    the envelope and the crankpin, the candidates' shapes).  Candidates that cannot be
    built inside a valid range are counted, not refused (the study reports them)."""
    from fe_crank.io.loadcase import load_loadcase
    from fe_crank.study.run import prepare
    from fe_crank.study.spec import parse_study

    spec = parse_study(path)
    if not loadcases:
        return (
            f"study '{spec.name}': read alone (give --loadcase, or its load case among the files, "
            "to check its webs and shapes)"
        )
    parts = []
    for lcp in loadcases:
        lc = load_loadcase(lcp, allow_outside_paths=allow_outside_paths or None)
        _, _, cands = prepare(lc, spec)
        bad = [c for c in cands if not c.buildable]
        text = f"{len(cands)} candidates on {lcp}"
        if bad:
            text += f", {len(bad)} cannot be built (#{', #'.join(str(c.index) for c in bad)}: the study reports why)"
        parts.append(text)
    return f"study '{spec.name}': " + "; ".join(parts)


def validate_file(path: Path, allow_outside_paths: bool = False) -> str:
    """Validate one file of any kind; return a one-line summary.  Raises InputError.
    A CAD geometry (a ``[cad]`` file, or a load case's) is read and recognised, and a
    load case's checked against its engine, as the check's geometry stage does."""
    data = read_toml(path)
    kind = _kind(data)
    if kind == "study":
        return validate_study(path, [], allow_outside_paths)
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
    outside = getattr(args, "allow_outside_paths", False)
    loadcases = [args.loadcase] if getattr(args, "loadcase", None) else None
    for path in args.files:
        try:
            if loadcases is None and _is_study(path):
                loadcases = [p for p in args.files if _kind_or_none(p) == "loadcase"]
            if _is_study(path):
                print(f"ok    {path}: {validate_study(path, loadcases or [], outside)}")
                continue
            print(f"ok    {path}: {validate_file(path, outside)}")
        except FeCrankError as exc:
            bad += 1
            print(f"error {exc}", file=sys.stderr)
    return 2 if bad else 0


def _kind_or_none(path: Path) -> str | None:
    try:
        return _kind(read_toml(path))
    except FeCrankError:
        return None


def _is_study(path: Path) -> bool:
    return _kind_or_none(path) == "study"
