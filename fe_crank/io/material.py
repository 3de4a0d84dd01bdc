"""The load case's ``[material]`` section -> frozen ``Material`` (SI floats).

::

    [material]
    name = "42CrMo4"                 # an entry of fe_crank/data/materials.toml
    yield_strength = "700 MPa"        # any property may be overridden, with its unit
    surface_finish = "ground"         # the shaft fillets: ground | machined (default) | hot_rolled | as_forged
    [material.surface]                # per location, a finish or { factor = 0.9, reason = "..." }:
    crankpin_fillet = "ground"        # crankpin_fillet, journal_fillet (default: the above),
    oil_bore = "drilled"              # oil_bore (default drilled), counterweight_fillet (as_forged)
    reliability = 0.99                # of the fatigue limits (default 0.99)
    size_factor = 0.85                # optional: else from each section's diameter
    forging = "drop_forged"           # UR M53 6 factor K: drop_forged | continuous_grain_flow
                                      # (K = 1.05) | free_form (1.0, also the default when not stated)

Without ``name`` every property the assessment needs must be given inline.  The
library itself is read with the same model, so a library entry with a bare number
where a unit is needed is as much an error as one in a load case.
"""

from __future__ import annotations

import importlib.resources
from dataclasses import dataclass, fields
from functools import lru_cache
from pathlib import Path
from typing import Any, Literal, get_args

from pydantic import Field

from fe_crank.errors import InputError
from fe_crank.io.base import Strict, read_toml, validate
from fe_crank.io.units import Density, Pressure

LIBRARY_NAME = "materials.toml"


#: the assessed locations that may state their own surface ([material.surface])
SurfaceLocation = Literal["crankpin_fillet", "journal_fillet", "oil_bore", "counterweight_fillet"]
SURFACE_LOCATIONS: tuple[str, ...] = get_args(SurfaceLocation)
#: a location's finish when the load case states none for it: the oil bore is drilled (not
#: ground with the fillets); an integral counterweight's transition fillet is left as forged
#: unless stated otherwise (the lowest factor of Shigley's table: on the safe side)
DEFAULT_FINISH = {"oil_bore": "drilled", "counterweight_fillet": "as_forged"}


@dataclass(frozen=True)
class Surface:
    """The surface of one assessed location: a finish of Shigley's table 6-2 (k_a = a R_m^b)
    or a given k_a with the reason the load case states for it."""

    location: str
    finish: str | None = None
    factor: float | None = None
    reason: str = ""


@dataclass(frozen=True)
class Material:
    """Material properties, SI.  ``None`` marks a property the source does not give.

    The specimen fatigue limits are multiplied by the part's factors
    (``fe_crank.assess.factors``, Shigley eq. 6-18): surface (``surface_factor``, or
    from ``surface_finish`` and R_m), size (``size_factor``, or from the section
    diameter), reliability (from ``reliability``), treatment and notch support.  The
    defaults are on the safe side: machined surface, size from the diameter, 99 %
    reliability, no treatment and no notch-support credit.
    """

    name: str
    youngs_modulus: float  # Pa
    poisson_ratio: float
    density: float  # kg/m^3
    yield_strength: float | None = None  # Pa
    tensile_strength: float | None = None  # Pa
    fatigue_limit_bending: float | None = None  # Pa, fully reversed
    fatigue_limit_torsion: float | None = None  # Pa, fully reversed
    surface_factor: float | None = None  # None: from surface_finish (Shigley eq. 6-19)
    surface_finish: str = "machined"
    size_factor: float | None = None  # None: from the section diameter (Shigley eq. 6-20)
    reliability: float = 0.99  # -> k_e (Shigley table 6-5)
    treatment_factor: float = 1.0
    notch_support_factor: float = 1.0  # FKM n_sigma, FE route only; 1 = no credit
    m53_k: float | None = None  # IACS UR M53 factor K (section 6), see ``forging``
    kind: str | None = None  # "steel" | "cast_iron" (library); UR M53 covers steel only
    forging: str | None = None  # the process stated for UR M53's K (``FORGING_K``); None: not stated
    surfaces: tuple[Surface, ...] = ()  # per-location surfaces stated in [material.surface]
    description: str = ""
    source: str = ""

    def surface(self, location: str | None) -> Surface:
        """The surface of ``location`` (``SURFACE_LOCATIONS``; None: the shaft fillets' common
        one): its own entry, else the oil bore drilled and the counterweight fillet as forged
        (``DEFAULT_FINISH``), else the common ``surface_factor`` / ``surface_finish``."""
        own = next((x for x in self.surfaces if x.location == location), None)
        if own is not None:
            return own
        if location in DEFAULT_FINISH:
            return Surface(location, DEFAULT_FINISH[location])
        if self.surface_factor is not None:
            return Surface(location or "", None, self.surface_factor, "material.surface_factor, every shaft fillet")
        return Surface(location or "", self.surface_finish)

    def missing(self, names: tuple[str, ...] | list[str]) -> list[str]:
        """The properties among ``names`` that this material does not give."""
        return [n for n in names if getattr(self, n) is None]


PROPERTY_NAMES = tuple(f.name for f in fields(Material) if f.name not in ("name", "description", "source", "surfaces"))

#: UR M53 section 6, factor K of the fatigue strength by manufacturing process: "1.05 for
#: continuous grain flow forged or drop-forged crankshafts, 1.0 for free form forged
#: crankshafts (without continuous grain flow)"; values above 1 for the fillets only
FORGING_K = {"drop_forged": 1.05, "continuous_grain_flow": 1.05, "free_form": 1.0}
#: K of a steel crank whose load case does not state the process: the free-form value
DEFAULT_FORGING_K = 1.0


FINISHES = Literal["ground", "machined", "drilled", "hot_rolled", "as_forged"]


class GivenSurfaceInput(Strict):
    factor: float = Field(gt=0.0, le=1.0)  # k_a
    reason: str = Field(min_length=3)  # why this value (measured roughness, a test, ...)


class MaterialInput(Strict):
    name: str | None = Field(default=None, min_length=1)
    description: str | None = None
    youngs_modulus: Pressure | None = None
    poisson_ratio: float | None = Field(default=None, gt=-1.0, lt=0.5)
    density: Density | None = None
    yield_strength: Pressure | None = None
    tensile_strength: Pressure | None = None
    fatigue_limit_bending: Pressure | None = None
    fatigue_limit_torsion: Pressure | None = None
    surface_factor: float | None = Field(default=None, gt=0.0, le=1.0)
    surface_finish: FINISHES | None = None
    size_factor: float | None = Field(default=None, gt=0.0, le=1.0)
    reliability: float | None = Field(default=None, ge=0.5, lt=1.0)
    treatment_factor: float | None = Field(default=None, gt=0.0, le=3.0)
    notch_support_factor: float | None = Field(default=None, ge=1.0, le=2.0)
    m53_k: float | None = Field(default=None, gt=0.0, le=2.0)
    surface: dict[SurfaceLocation, FINISHES | GivenSurfaceInput] | None = None
    kind: Literal["steel", "cast_iron"] | None = None
    forging: Literal["drop_forged", "continuous_grain_flow", "free_form"] | None = None
    source: str | None = None

    def given(self) -> dict:
        return {k: v for k, v in self.model_dump().items() if v is not None and k not in ("name", "surface")}

    def surfaces(self) -> tuple[Surface, ...]:
        out = []
        for loc, v in (self.surface or {}).items():
            out.append(Surface(loc, v) if isinstance(v, str) else Surface(loc, None, v.factor, v.reason))
        return tuple(out)


def library_path() -> Path:
    return Path(str(importlib.resources.files("fe_crank") / "data" / LIBRARY_NAME))


@lru_cache(maxsize=4)
def _library(path: str) -> dict[str, dict]:
    data = read_toml(path, record=False)  # package data, traced by the package version
    out = {}
    for name, entry in data.items():
        if not isinstance(entry, dict):
            raise InputError("each material must be a table", file=path, key=name)
        out[name] = validate(MaterialInput, entry, path, name).given()
    return out


def library() -> dict[str, dict]:
    """Name -> validated properties (SI) of every material in the library."""
    return dict(_library(str(library_path())))


def _check_positive(props: dict, file, key: str) -> None:
    for k in (
        "youngs_modulus",
        "density",
        "yield_strength",
        "tensile_strength",
        "fatigue_limit_bending",
        "fatigue_limit_torsion",
    ):
        v = props.get(k)
        if v is not None and not v > 0:
            raise InputError(f"must be positive (got {v:g} SI)", file=str(file), key=f"{key}.{k}")
    ys, ts = props.get("yield_strength"), props.get("tensile_strength")
    if ys is not None and ts is not None and ys > ts:
        raise InputError(
            f"yield strength {ys / 1e6:g} MPa exceeds tensile strength {ts / 1e6:g} MPa",
            file=str(file),
            key=f"{key}.yield_strength",
        )


def parse_material(value: object, file: str | Path, key: str = "material") -> Material:
    """Section parser of the load case's ``[material]`` section (``fe_crank.io.sections``)."""
    if isinstance(value, str):
        value = {"name": value}
    if not isinstance(value, dict):
        raise InputError('must be a table, e.g. [material] name = "42CrMo4"', file=str(file), key=key)
    raw = validate(MaterialInput, value, file, key)
    props: dict = {}
    source_parts = []
    if raw.name is not None:
        lib = library()
        if raw.name not in lib:
            raise InputError(
                f"unknown material {raw.name!r}; the library ({library_path().name}) has {sorted(lib)}",
                file=str(file),
                key=f"{key}.name",
            )
        props.update(lib[raw.name])
        source_parts.append(props.pop("source", ""))
    overrides = raw.given()
    overrides.pop("source", None)
    props.update(overrides)
    if raw.source:
        source_parts.append(raw.source)
    changed = sorted(k for k in overrides if k != "description")
    if raw.name is not None and changed:
        source_parts.append(f"overridden in {Path(file).name}: {', '.join(changed)}")
    for k in ("youngs_modulus", "poisson_ratio", "density"):
        if props.get(k) is None:
            raise InputError(
                "required (give name = a library material, or the value with its unit)",
                file=str(file),
                key=f"{key}.{k}",
            )
    _check_positive(props, file, key)
    _forging_factor(props, raw, file, key)
    given: dict[str, Any] = {k: props.get(k) for k in PROPERTY_NAMES if props.get(k) is not None}
    return Material(
        name=raw.name or "custom",
        surfaces=raw.surfaces(),
        description=props.pop("description", ""),
        source="; ".join(p for p in source_parts if p),
        **given,
    )


def _forging_factor(props: dict, raw: MaterialInput, file, key: str) -> None:
    """UR M53's K into ``props["m53_k"]``: a K given in the load case wins (with a stated
    reason, e.g. 0.93 for cold-rolled cast steel), else the stated ``forging`` process
    (``FORGING_K``), else 1.0 for a steel (free-form forged: the lower value, since the
    process is not stated), else none (UR M53 covers steel only)."""
    if raw.m53_k is not None and raw.forging is not None:
        raise InputError(
            "give either forging (the process, from which UR M53 section 6 sets K) or m53_k, not both",
            file=str(file),
            key=f"{key}.m53_k",
        )
    forging = props.get("forging")
    if forging is not None and props.get("kind") != "steel":
        raise InputError(
            f"forging = {forging!r} applies to a forged steel; material {raw.name or 'custom'!r} is "
            f'{props.get("kind") or "of no stated kind"} (set kind = "steel" for a custom steel)',
            file=str(file),
            key=f"{key}.forging",
        )
    if raw.m53_k is not None:
        return
    if forging is not None:
        props["m53_k"] = FORGING_K[forging]
    elif props.get("m53_k") is None and props.get("kind") == "steel":
        props["m53_k"] = DEFAULT_FORGING_K


def load_material(name: str, **overrides: object) -> Material:
    """A library material by name, overrides given as input strings (``"700 MPa"``)."""
    return parse_material({"name": name, **overrides}, library_path(), "material")


__all__ = [
    "Material",
    "parse_material",
    "load_material",
    "library",
    "library_path",
    "PROPERTY_NAMES",
    "FORGING_K",
    "DEFAULT_FORGING_K",
]
