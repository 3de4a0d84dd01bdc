"""The ``[cad]`` section (a CAD file as the crank geometry) -> frozen ``CadInput`` (SI).

The keys and their meaning: ``fe_crank.cad.config``.  The CAD file's path is relative
to the TOML file and must stay in the load case's folder tree (``io.base``).  Exactly
one of ``density`` and ``material`` (a name of the material library, whose density is
taken).  ``length_unit`` is a unit of length (``"mm"``, ``"in"``); ``axis`` one of
``"+x"`` ... ``"-z"`` or three numbers; ``[cad.faces]`` maps the feature names of
``fe_crank.cad.config.THROW_FACE_GROUPS`` and ``axis`` to lists of face numbers, in
one table per throw name for a file with several throws.  ``[cad.shaft]``: a drawn whole
shaft's main bearings, parsed as a geometry's ``[shaft]`` (``fe_crank.io.shaft``), the keys
the drawing gives (``DRAWN_SHAFT_KEYS``) refused, and ``bearing_width`` in ``[cad]`` or
there, not both.

In a load case (``parse_geometry_source``): ``geometry = "crank.step"`` (a file with a
CAD extension) is read as the load case's ``[cad]`` section says, ``file`` then being
the ``geometry`` key's; ``geometry = "x.toml"`` is a CAD geometry when that file holds a
``[cad]`` section (and nothing else), else a parametric geometry file
(``fe_crank.io.geometry``).  The CAD file is checked (found, not empty, its format's
header) and recorded with the load case's inputs when the load case is read; it is
recognised by the check's geometry stage.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Literal

from pydantic import Field, field_validator, model_validator

from fe_crank.cad.config import THROW_FACE_GROUPS, CadInput, FaceOverride
from fe_crank.errors import InputError
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.io.base import Strict, read_toml, record_file, validate
from fe_crank.io.geometry import geometry_from_dict, parse_geometry
from fe_crank.io.includes import read_included, resolve_reference, with_include_context
from fe_crank.io.shaft import ShaftInput, shaft_spec
from fe_crank.io.units import Density, Length, to_si

_AXES = {f"{s}{a}": (s, a) for s in "+-" for a in "xyz"}
FaceList = list[int]


#: the ``[shaft]`` keys a drawing gives itself (refused in ``[cad.shaft]``)
DRAWN_SHAFT_KEYS = ("pitch", "end_journal_length", "nose", "flange")


class CadSection(Strict):
    file: str = Field(min_length=1, max_length=4096)
    length_unit: str | None = Field(default=None, min_length=1, max_length=40)
    density: Density | None = None
    material: str | None = Field(default=None, min_length=1, max_length=200)
    axis: str | list[float] | None = None
    throws: list[str] | None = Field(default=None, min_length=1, max_length=64)
    bodies: Literal["one", "fuse", "bolted"] = "one"  # fe_crank.cad.config.BODIES
    counterweight_radius: Length | None = None
    pin_recess: Length | None = None
    journal_recess: Length | None = None
    bearing_width: Length | None = None
    shaft: ShaftInput | None = None  # the main bearings of a drawn whole shaft (``DRAWN_SHAFT_KEYS`` refused)
    faces: dict[str, FaceList | dict[str, FaceList]] = Field(default_factory=dict, max_length=256)

    @field_validator("length_unit")
    @classmethod
    def _unit(cls, v):
        if v is not None:
            to_si(f"1 {v}", "length")  # ValueError with the reason
        return v

    @field_validator("axis")
    @classmethod
    def _axis(cls, v):
        if isinstance(v, str) and v not in _AXES:
            raise ValueError('must be one of "+x", "-x", "+y", "-y", "+z", "-z" or [x, y, z]')
        if isinstance(v, list) and (len(v) != 3 or not 0 < math.hypot(*v) < math.inf):
            raise ValueError("must be three numbers, not all zero: the direction from the front to the flywheel")
        return v

    @field_validator("throws")
    @classmethod
    def _throws(cls, v):
        if v is not None and (len(set(v)) != len(v) or not all(v)):
            raise ValueError("throw names must be different and not empty")
        return v

    @field_validator("counterweight_radius", "pin_recess", "journal_recess", "bearing_width")
    @classmethod
    def _sizes(cls, v, info):
        positive = info.field_name in ("counterweight_radius", "bearing_width")
        if v is not None and (v < 0 or (v == 0 and positive)):
            raise ValueError("must be positive" if positive else "must not be negative")
        return v

    @field_validator("shaft")
    @classmethod
    def _drawn_keys(cls, v):
        drawn = [] if v is None else [k for k in DRAWN_SHAFT_KEYS if getattr(v, k) is not None]
        if drawn:
            raise ValueError(
                f"{drawn[0]}: the drawing gives the shaft's pitch, end journals, nose and flange; "
                "[cad.shaft] takes the main bearings and what acts on the shaft's ends only"
            )
        return v

    @model_validator(mode="after")
    def _drawn(self):
        if self.shaft is not None:
            if self.bearing_width is not None and self.shaft.bearing_width is not None:
                raise ValueError("bearing_width: give it once, in [cad] or in [cad.shaft]")
        return self

    @model_validator(mode="after")
    def _density(self):
        if (self.density is None) == (self.material is None):
            raise ValueError("give exactly one of density and material")
        if self.density is not None and not self.density > 0:
            raise ValueError("density must be positive")
        return self


def _faces(raw: dict, throws: list[str] | None, file: str, prefix: str) -> tuple[FaceOverride, ...]:
    out = []
    for key, value in raw.items():
        where = f"{prefix}.faces.{key}"
        if isinstance(value, dict):
            if throws is None or key not in throws:
                raise InputError("a table of faces must be named after a throw of throws = [...]", file=file, key=where)
            items = [(g, ids, key) for g, ids in value.items()]
        else:
            items = [(key, value, None)]
        for group, ids, throw in items:
            k = f"{where}.{group}" if throw is not None else where
            allowed = THROW_FACE_GROUPS + (("axis",) if throw is None else ())
            if group not in allowed:
                raise InputError(f"unknown feature; one of {', '.join(allowed)}", file=file, key=k)
            if throw is None and group != "axis" and throws is not None and len(throws) > 1:
                raise InputError(
                    f'in a file with several throws, name the throw: [{prefix}.faces."<throw>"]', file=file, key=k
                )
            if any(i <= 0 for i in ids) or len(set(ids)) != len(ids):
                raise InputError("face numbers must be positive and different", file=file, key=k)
            if group != "oil_bore" and not ids:
                raise InputError("give at least one face number", file=file, key=k)
            out.append(FaceOverride(group, tuple(ids), throw))
    return tuple(out)


def _axis_vector(v) -> tuple[float, float, float] | None:
    if v is None:
        return None
    if isinstance(v, str):
        sign, a = _AXES[v]
        out = [0.0, 0.0, 0.0]
        out["xyz".index(a)] = 1.0 if sign == "+" else -1.0
        return (out[0], out[1], out[2])
    n = math.hypot(*v)
    return (v[0] / n, v[1] / n, v[2] / n)


def cad_from_dict(data: dict, file: str | Path, prefix: str = "cad", *, file_key: str | None = None) -> CadInput:
    """Validate a ``[cad]`` table (already read from TOML) into a ``CadInput``;
    ``file_key``: the key that named the CAD file (default ``<prefix>.file``)."""
    raw = validate(CadSection, data, file, prefix)
    density, material = raw.density, raw.material
    if material is not None:
        from fe_crank.io.material import library

        lib = library()
        if material not in lib:
            raise InputError(
                f"not in the material library ({', '.join(sorted(lib))})", file=str(file), key=f"{prefix}.material"
            )
        density = lib[material].get("density")
        if density is None:
            raise InputError("the library entry gives no density", file=str(file), key=f"{prefix}.material")
    if density is None:  # the section's validator asks for density or material
        raise InputError("give density or material", file=str(file), key=f"{prefix}.density")
    file_key = file_key or f"{prefix}.file"
    path = resolve_reference(raw.file, file, key=file_key)
    return CadInput(
        file=path,
        density=float(density),
        length_unit=to_si(f"1 {raw.length_unit}", "length") if raw.length_unit is not None else None,
        length_unit_text=raw.length_unit,
        material=material,
        axis=_axis_vector(raw.axis),
        throws=tuple(raw.throws) if raw.throws is not None else None,
        bodies=raw.bodies,
        counterweight_radius=raw.counterweight_radius,
        pin_recess=raw.pin_recess,
        journal_recess=raw.journal_recess,
        bearing_width=raw.bearing_width,
        shaft=shaft_spec(raw.shaft),
        faces=_faces(raw.faces, raw.throws, str(file), prefix),
        toml=str(file),
        file_key=file_key,
    )


def load_cad(path: str | Path) -> CadInput:
    """Read the ``[cad]`` section of a TOML file (the file's other tables are not read)."""
    data = read_toml(path)
    if "cad" not in data or not isinstance(data["cad"], dict):
        raise InputError("no [cad] section", file=str(path), key="cad")
    return cad_from_dict(data["cad"], path)


#: extensions of the CAD files ``fe_crank.cad`` reads
CAD_SUFFIXES = (".step", ".stp", ".brep", ".brp", ".iges", ".igs")


def _checked(cad: CadInput) -> CadInput:
    """The CAD file found, not empty, its format's header (``cad.read.file_digest``), and
    recorded with the load case's inputs."""
    from fe_crank.cad.read import file_digest

    file_digest(cad)
    record_file(cad.file)
    return cad


def parse_geometry_source(data: dict, file: str | Path) -> CrankGeometry | CadInput | None:
    """The load case's geometry (its ``geometry`` key and ``[cad]`` section, module
    docstring): a parametric ``CrankGeometry``, a ``CadInput``, or None without one."""
    value, section = data.get("geometry"), data.get("cad")
    if value is None:
        if section is not None:
            raise InputError(
                'a [cad] section says how to read the CAD file geometry names: add geometry = "<file>.step"',
                file=str(file),
                key="geometry",
            )
        return None
    if isinstance(value, str):
        from fe_crank.cad.read import unsupported_format

        why = unsupported_format(value)
        if why is not None:
            raise InputError(why, file=str(file), key="geometry")
    if isinstance(value, str) and Path(value).suffix.lower() in CAD_SUFFIXES:
        if not isinstance(section, dict):
            raise InputError(
                "a CAD file as the geometry needs a [cad] table beside it: its density (or material) and, when the "
                'file states none, its length unit (e.g. length_unit = "mm")',
                file=str(file),
                key="cad",
            )
        if "file" in section:
            raise InputError(
                "geometry names the CAD file; remove cad.file (or name a TOML file holding [cad] in geometry)",
                file=str(file),
                key="cad.file",
            )
        return _checked(cad_from_dict({**section, "file": value}, file, "cad", file_key="geometry"))
    if section is not None:
        raise InputError(
            'a [cad] section goes with a CAD file as the geometry (geometry = "<file>.step"); a geometry TOML '
            "file holds its own [cad]",
            file=str(file),
            key="cad",
        )
    if not isinstance(value, str):
        return parse_geometry(value, file, "geometry")
    p, included = read_included(value, file, "geometry", "geometry file")
    try:
        if "cad" not in included:
            return geometry_from_dict(included, p)
        others = sorted(k for k in included if k != "cad")
        if others:
            raise InputError(
                "a CAD geometry file holds the [cad] section only (the parametric keys go in a geometry file "
                "of their own)",
                file=str(p),
                key=str(others[0])[:40],
            )
        if not isinstance(included["cad"], dict):
            raise InputError("must be a table", file=str(p), key="cad")
        return _checked(cad_from_dict(included["cad"], p))
    except InputError as exc:
        raise with_include_context(exc, file, "geometry") from None
