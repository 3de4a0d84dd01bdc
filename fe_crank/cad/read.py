"""A CAD file into the current gmsh model (OpenCASCADE), in metres, as one solid.

Checked before gmsh reads anything: the file exists, is not empty, not larger than
``MAX_CAD_BYTES``, has a known extension and starts as its format must (STEP:
``ISO-10303-21;``; IGES: an 80-column start section; BREP: OpenCASCADE's header).
Units: the file's numbers are in the unit ``[cad] length_unit`` states, else in the unit
the file states (``fe_crank.cad.units``); a file stating none needs ``length_unit``.
OpenCASCADE converts a stated unit to metres (gmsh option ``Geometry.OCCTargetUnit =
"M"``); ``length_unit`` (and IGES's millimetres) are applied while the file is imported
(gmsh option ``Geometry.OCCScaling``: a similarity transformation, ``gp_Trsf``, that keeps
planes, cylinders and tori analytic, so that mass properties stay exact; ``occ.dilate``
would rebuild every face as a B-spline and its integrals would drift, by 0.16 % in
volume on a test throw).  Bodies: one solid, or several
fused into one (``bodies = "fuse"``: each must touch the rest), or the largest taken as
the shaft and the others kept out of the model as bolted parts (``bodies = "bolted"``).

Call :func:`read_cad` inside :func:`fe_crank.gmsh_io.gmsh_session`.
"""

from __future__ import annotations

import contextlib
import hashlib
import os
from dataclasses import dataclass
from pathlib import Path

from fe_crank.cad.config import CadInput
from fe_crank.cad.units import AmbiguousUnit, declared_unit
from fe_crank.errors import InputError

#: largest CAD file read (bytes)
MAX_CAD_BYTES = 200_000_000
#: most faces a model may have (recognition visits every face)
MAX_FACES = 20_000
_KINDS = {".step": "step", ".stp": "step", ".brep": "brep", ".brp": "brep", ".iges": "iges", ".igs": "iges"}
_NAMES = {"step": "STEP", "brep": "BREP", "iges": "IGES"}
#: triangulated-surface formats: no exact faces to recognise features on
_MESH_FORMATS = {".stl": "STL", ".obj": "OBJ", ".ply": "PLY", ".off": "OFF", ".3mf": "3MF", ".vtk": "VTK"}
_OCC_DEFAULT_UNIT = 1e-3  # m: OpenCASCADE's unit of imported STEP and IGES without a target unit


@dataclass(frozen=True)
class CadUnit:
    """The length unit the file's numbers were taken in."""

    name: str  # as stated ("mm", "inch", "millimetre")
    metres: float  # size of one unit in m
    stated_by: str  # "file" or "cad.length_unit"
    file_states: str | None  # what the file itself states (None: nothing)


@dataclass(frozen=True)
class ReadResult:
    """Internal: the model after reading (gmsh volume tags)."""

    kind: str  # "step", "brep", "iges"
    sha256: str
    unit: CadUnit
    solids: int  # solids in the file
    shaft: int  # volume tag of the (fused) shaft
    bolted: tuple[int, ...]  # volume tags of bodies kept out of the shaft


def _fail(cad: CadInput, reason: str, key: str | None = None) -> InputError:
    return InputError(reason, file=str(cad.file), key=key or cad.file_key)


def unsupported_format(path: str | Path) -> str | None:
    """Why a geometry file of a triangulated-surface format (STL, OBJ, ...) cannot be
    read; None for any other file."""
    name = _MESH_FORMATS.get(Path(path).suffix.lower())
    if name is None:
        return None
    return (
        f"{name} is not supported (a CAD solid is needed: STEP, BREP or IGES): a triangulated surface has no exact "
        "cylinders, fillets and planes to recognise the crankshaft's features on; export the solid from the CAD "
        "system as STEP"
    )


def file_kind(cad: CadInput) -> str:
    kind = _KINDS.get(cad.file.suffix.lower())
    if kind is None:
        why = unsupported_format(cad.file)
        raise _fail(
            cad, why or "not a CAD file fe-crank reads: give a STEP (.step, .stp), BREP (.brep) or IGES (.iges) file"
        )
    return kind


def file_digest(cad: CadInput) -> str:
    """SHA-256 of the file's bytes, after the checks of size and header."""
    p = cad.file
    if not p.is_file():
        raise _fail(cad, "the CAD file is a folder" if p.is_dir() else "the CAD file is not found")
    size = p.stat().st_size
    if size == 0:
        raise _fail(cad, "the CAD file is empty")
    if size > MAX_CAD_BYTES:
        raise _fail(cad, f"the CAD file is larger than {MAX_CAD_BYTES // 1_000_000} MB, the limit")
    kind = file_kind(cad)
    with open(p, "rb") as fh:
        head = fh.read(512)
    text = head.lstrip(b"\xef\xbb\xbf \t\r\n")
    ok = {
        "step": text.startswith(b"ISO-10303-21"),
        "iges": len(head) > 72 and head[72:73] == b"S",
        "brep": b"CASCADE Topology" in head or text.startswith(b"DBRep_DrawableShape"),
    }[kind]
    if not ok:
        raise _fail(cad, f"not a {_NAMES[kind]} file (its first line is not a {_NAMES[kind]} header)")
    h = hashlib.sha256()
    with open(p, "rb") as fh:
        for block in iter(lambda: fh.read(1 << 20), b""):
            h.update(block)
    return h.hexdigest()


def _unit(cad: CadInput, kind: str) -> tuple[CadUnit, float]:
    """The unit of the numbers and the factor to apply after OpenCASCADE's conversion."""
    try:
        stated = declared_unit(cad.file, kind)
    except AmbiguousUnit as exc:
        raise _fail(
            cad, f"the file states several length units ({exc}), so which its geometry uses is unclear: export it again"
        ) from None
    if cad.length_unit is not None:
        # OpenCASCADE has scaled the numbers by the stated unit (or by 1 without one)
        factor = cad.length_unit / (stated.metres if stated is not None else 1.0)
        unit = CadUnit(cad.length_unit_text or f"{cad.length_unit:g} m", cad.length_unit, "cad.length_unit", None)
        return (unit if stated is None else CadUnit(unit.name, unit.metres, unit.stated_by, stated.name)), factor
    if stated is None:
        raise _fail(
            cad,
            f'the {_NAMES[kind]} file states no length unit; set length_unit (e.g. "mm") in {cad.where}',
            "cad.length_unit",
        )
    return CadUnit(stated.name, stated.metres, "file", stated.name), 1.0


@contextlib.contextmanager
def _quiet_stdout():
    """OpenCASCADE prints some readers' statistics on the process's stdout: silence it."""
    try:
        fd = os.dup(1)
    except OSError:
        yield
        return
    try:
        with open(os.devnull, "wb") as null:
            os.dup2(null.fileno(), 1)
            try:
                yield
            finally:
                os.dup2(fd, 1)
    finally:
        os.close(fd)


def _import(gmsh, path: Path, unit: str, scale: float) -> None:
    gmsh.option.setString("Geometry.OCCTargetUnit", unit)
    gmsh.option.setNumber("Geometry.OCCScaling", scale)
    try:
        try:
            gmsh.model.occ.importShapes(str(path))
        except Exception as exc:
            if "target unit" not in str(exc) or unit != "MM":
                raise
            gmsh.option.setString("Geometry.OCCTargetUnit", "")  # the default: millimetres
            gmsh.model.occ.importShapes(str(path))
    finally:
        gmsh.option.setNumber("Geometry.OCCScaling", 1.0)


def read_cad(gmsh, cad: CadInput) -> ReadResult:
    """Read ``cad.file`` into the current (empty) gmsh model; see the module docstring."""
    digest = file_digest(cad)
    kind = file_kind(cad)
    occ = gmsh.model.occ
    # the unit is settled from the file's text before the import (the scale is applied
    # by the importer); a missing unit is reported after the file is known to hold a solid
    try:
        unit, factor = _unit(cad, kind)
        missing: InputError | None = None
    except InputError as exc:
        unit, factor, missing = CadUnit("", 1.0, "file", None), 1.0, exc
    # STEP: OpenCASCADE converts the stated unit to metres.  IGES: in millimetres, scaled
    # here; its reader refuses a target unit before a translator has run in the process
    # (OpenCASCADE's unit setting is global), and then reads in its default, millimetres
    if kind == "iges":  # IGES carries faces; sew them into solids
        gmsh.option.setNumber("Geometry.OCCSewFaces", 1)
        gmsh.option.setNumber("Geometry.OCCMakeSolids", 1)
        factor *= _OCC_DEFAULT_UNIT
    try:
        with _quiet_stdout():
            _import(gmsh, cad.file, "M" if kind != "iges" else "MM", factor)
        occ.synchronize()
    except Exception as exc:  # gmsh raises a bare Exception
        raise _fail(cad, f"OpenCASCADE could not read the {_NAMES[kind]} file: {exc}") from None
    volumes = [t for _, t in gmsh.model.getEntities(3)]
    if not volumes:
        n = len(gmsh.model.getEntities(2))
        what = f"only {n} loose faces" if n else "no geometry at all"
        raise _fail(cad, f"the file holds no solid ({what}): export the crankshaft as a solid body")
    if missing is not None:
        raise missing
    if len(gmsh.model.getEntities(2)) > MAX_FACES:
        raise _fail(cad, f"the model has more than {MAX_FACES} faces, the limit")
    shaft, bolted = _bodies(gmsh, cad, volumes)
    return ReadResult(kind, digest, unit, len(volumes), shaft, bolted)


def _bodies(gmsh, cad: CadInput, volumes: list[int]) -> tuple[int, tuple[int, ...]]:
    occ = gmsh.model.occ
    if len(volumes) == 1:
        return volumes[0], ()
    sizes = {v: occ.getMass(3, v) for v in volumes}
    listing = ", ".join(f"{sizes[v] * 1e6:.4g} cm^3" for v in volumes)
    if cad.bodies == "one":
        raise _fail(
            cad,
            f'the file holds {len(volumes)} solids ({listing}); a crankshaft is one: set bodies = "fuse" in '
            f'{cad.where} to join bodies that touch (counterweights drawn as bodies), or bodies = "bolted" to '
            "keep all but the largest out of the FE model as bolted parts",
            "cad.bodies",
        )
    if cad.bodies == "bolted":
        shaft = max(volumes, key=lambda v: sizes[v])
        return shaft, tuple(v for v in volumes if v != shaft)
    out, _ = occ.fuse([(3, volumes[0])], [(3, v) for v in volumes[1:]])
    occ.synchronize()
    if len(out) != 1:
        raise _fail(
            cad,
            f"the file's {len(volumes)} solids ({listing}) do not form one solid when fused ({len(out)} pieces "
            'remain): they do not touch; join them in the CAD system, or set bodies = "bolted" for parts that '
            "are bolted on",
            "cad.bodies",
        )
    return out[0][1], ()
