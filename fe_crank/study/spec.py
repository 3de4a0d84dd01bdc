"""The study file: which counterweight candidates to screen and how to choose one.

A study TOML beside the load case (``fe-crank study LOADCASE STUDY``)::

    [study]
    name = "inline-4: 4 or 8 counterweights"
    rotating_rate_percent = [0, 20, 40, 60, 80, 100]  # of each throw's rotating m r, 0-120
    reciprocating_share_percent = [0]                  # of its first-order reciprocating m r, 0-100
    offset = ["0 deg", "15 deg"]                       # counterweights turned from opposite the pin
                                                       # towards +x (throw frame); default: as drawn
    free = ["thickness", "angle", "r_outer"]           # sector dimension solved for each mass, in order
    envelope = "95 mm"                                 # largest outer radius a counterweight may have
    rule = "least_mass"                                # or "least_bearing_load"
    stresses = "fatigue"                               # or "static", "off": the stress screening

    [study.limits]                                     # all optional
    max_main_bearing_load = "25 kN"
    max_main_bearing_specific_load = "30 MPa"
    max_web_bending_moment = "1.5 kN*m"
    max_free_force = "100 N"                           # first-order resultant, amplitude
    max_free_moment = "200 N*m"                        # first-order couple, amplitude
    max_counterweight_mass = "6 kg"                    # the shaft's counterweights together
    min_oil_film = "1 um"                              # hydrodynamic bearings only
    max_film_pressure = "300 MPa"                      # hydrodynamic bearings only
    max_fillet_stress = "400 MPa"                      # the fillets' peak von Mises
    min_fillet_static_safety = 2.0                     # a plain number
    min_fillet_fatigue_safety = 1.5                    # a plain number
    min_overspeed_safety = 1.5                         # a plain number: yield over the overspeed peak
    max_counterweight_overspeed_stress = "150 MPa"     # counterweight fillets and junctions
    min_bolt_working_safety = 1.0                      # bolted counterweights, VDI 2230 (plain numbers):
    min_bolt_fatigue_safety = 1.2                      # also max_bolt_assembly_utilisation,
    min_bolt_separation_safety = 1.0                   # min_bolt_slip_safety; none named: the load
                                                       # case's joint criteria (``study.joints``)

    [[study.placements]]
    name = "8 counterweights"
    webs = "all"                                       # every web that carries one as drawn
    [[study.placements]]
    name = "4 counterweights"
    webs = ["1.1", "2.2", "3.1", "4.2"]                # "<throw>.<web>", web 1 front, 2 rear

``parse_study`` checks the file alone; ``check_against`` the webs and the envelope
against the load case's shaft.  Every refusal is one ``InputError`` naming the file and
the key.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path

from fe_crank.assess.joint_criteria import JOINT_QUANTITIES
from fe_crank.errors import InputError
from fe_crank.io.base import read_toml
from fe_crank.io.units import to_si

RULES = ("least_mass", "least_bearing_load")
#: what the stress screening evaluates (docs/study.md): the static peaks and the least
#: Goodman safety, the static peaks alone, nothing
STRESSES = ("fatigue", "static", "off")
FREE = ("thickness", "angle", "r_outer", "r_inner")
MAX_ROTATING_PERCENT = 120.0
LIMITS = {
    "max_main_bearing_load": "force",
    "max_main_bearing_specific_load": "pressure",
    "max_web_bending_moment": "moment",
    "max_free_force": "force",
    "max_free_moment": "moment",
    "max_counterweight_mass": "mass",
    "min_oil_film": "length",  # hydrodynamic bearings: the least h_min (docs/study.md)
    "max_film_pressure": "pressure",  # hydrodynamic bearings: the peak film pressure
    "max_fillet_stress": "pressure",  # the fillets' screened peak von Mises (docs/study.md)
    "min_fillet_static_safety": "number",  # yield over that peak
    "min_fillet_fatigue_safety": "number",  # the fillets' least screened Goodman safety
    "min_overspeed_safety": "number",  # yield over the screened overspeed peak, any group
    "max_counterweight_overspeed_stress": "pressure",  # the counterweights' fillets and junctions
    "max_counterweight_stress": "pressure",  # the per-throw model's counterweight groups (``study.bodies``)
    "min_m53_acceptability": "number",  # UR M53's Q, the load case's criterion (``study.m53``)
}
#: the bolted joints' VDI 2230 limits (``study.joints``): the check's criterion keys, plain numbers
JOINT_LIMITS = tuple(f"{sense}_{q}" for q, (_, sense) in JOINT_QUANTITIES.items())
LIMITS.update(dict.fromkeys(JOINT_LIMITS, "number"))
KEYS = (
    "name",
    "rotating_rate_percent",
    "reciprocating_share_percent",
    "offset",
    "free",
    "envelope",
    "rule",
    "stresses",
    "limits",
    "placements",
)


@dataclass(frozen=True)
class Placement:
    name: str
    webs: tuple[tuple[str, int], ...] | None  # (throw, web); None: every web drawn with one


@dataclass(frozen=True)
class StudySpec:
    file: str
    name: str
    rotating: tuple[float, ...]  # fractions of the rotating m r
    reciprocating: tuple[float, ...]  # fractions of the first-order reciprocating m r
    offsets: tuple[float, ...] | None  # rad, from opposite the pin towards +x; None: as drawn
    free: tuple[str, ...]
    envelope: float | None  # m
    rule: str
    limits: dict[str, float]  # SI
    placements: tuple[Placement, ...]
    stresses: str = "fatigue"  # one of STRESSES


def _numbers(value, file: str, key: str, lo: float, hi: float) -> tuple[float, ...]:
    if not isinstance(value, list):
        raise InputError("must be a list of numbers (percent)", file=file, key=key)
    if not value:
        raise InputError("is empty: the study has no candidates", file=file, key=key)
    out = []
    for i, v in enumerate(value):
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            raise InputError(f"{v!r} is not a number (percent)", file=file, key=f"{key}[{i}]")
        if not lo <= v <= hi:
            raise InputError(f"{v:g} % is outside {lo:g}-{hi:g} %", file=file, key=f"{key}[{i}]")
        out.append(float(v) / 100.0)
    return tuple(out)


def _quantity(value, kind: str, file: str, key: str) -> float:
    try:
        return to_si(value, kind)
    except ValueError as exc:
        raise InputError(str(exc), file=file, key=key) from None


def _web(value, file: str, key: str) -> tuple[str, int]:
    if not isinstance(value, str) or value.count(".") < 1:
        raise InputError(f'{value!r} is not a web "<throw>.<web>", e.g. "1.2"', file=file, key=key)
    throw, _, web = value.rpartition(".")
    if web not in ("1", "2") or not throw:
        raise InputError(f"{value!r}: the web after the dot is 1 (front) or 2 (rear)", file=file, key=key)
    return throw, int(web)


def _placements(value, file: str) -> tuple[Placement, ...]:
    key = "study.placements"
    if value is None:
        return (Placement("as drawn", None),)
    if not isinstance(value, list) or not value:
        raise InputError("must be a non-empty list of tables [[study.placements]]", file=file, key=key)
    out, names = [], set()
    for i, p in enumerate(value):
        k = f"{key}[{i}]"
        if not isinstance(p, dict):
            raise InputError("must be a table with name and webs", file=file, key=k)
        extra = sorted(set(p) - {"name", "webs"})
        if extra:
            raise InputError(f"unknown key {extra[0]!r}; a placement takes name and webs", file=file, key=k)
        name = p.get("name", f"placement {i + 1}")
        if not isinstance(name, str) or not name or name in names:
            raise InputError(f"{name!r}: give each placement a name of its own", file=file, key=f"{k}.name")
        names.add(name)
        webs = p.get("webs", "all")
        if webs == "all":
            out.append(Placement(name, None))
            continue
        if not isinstance(webs, list) or not webs:
            raise InputError('must be "all" or a non-empty list of webs "<throw>.<web>"', file=file, key=f"{k}.webs")
        parsed = tuple(_web(w, file, f"{k}.webs[{j}]") for j, w in enumerate(webs))
        if len(set(parsed)) != len(parsed):
            raise InputError("names a web twice", file=file, key=f"{k}.webs")
        out.append(Placement(name, parsed))
    return tuple(out)


def parse_study(path: str | Path) -> StudySpec:
    """Read and check a study file (module doc)."""
    file = str(path)
    data = read_toml(path)
    st = data.get("study")
    if not isinstance(st, dict):
        raise InputError("has no [study] table", file=file, key="study")
    extra = sorted(set(data) - {"study"})
    if extra:
        raise InputError("unknown table; a study file has one table, [study]", file=file, key=extra[0])
    unknown = sorted(set(st) - set(KEYS))
    if unknown:
        raise InputError(f"unknown key; [study] takes {', '.join(KEYS)}", file=file, key=f"study.{unknown[0]}")
    if "rotating_rate_percent" not in st:
        raise InputError("is missing: the balance rates to screen", file=file, key="study.rotating_rate_percent")
    rot = _numbers(st["rotating_rate_percent"], file, "study.rotating_rate_percent", 0.0, MAX_ROTATING_PERCENT)
    rec = _numbers(st.get("reciprocating_share_percent", [0]), file, "study.reciprocating_share_percent", 0.0, 100.0)
    offsets = None
    if "offset" in st:
        offsets_raw = st["offset"]
        if not isinstance(offsets_raw, list) or not offsets_raw:
            raise InputError('must be a non-empty list of angles, e.g. ["0 deg"]', file=file, key="study.offset")
        offsets = tuple(_quantity(v, "angle", file, f"study.offset[{i}]") for i, v in enumerate(offsets_raw))
        for i, o in enumerate(offsets):
            if not abs(o) < math.pi:
                raise InputError(
                    f"the turn from opposite the pin must lie between -180 and 180 deg (got {math.degrees(o):g} deg)",
                    file=file,
                    key=f"study.offset[{i}]",
                )
        if len(set(offsets)) != len(offsets):
            raise InputError("names an offset twice", file=file, key="study.offset")
    free_raw = st.get("free", ["thickness", "angle", "r_outer"])
    if isinstance(free_raw, str):
        free_raw = [free_raw]
    if not isinstance(free_raw, list) or not free_raw or any(f not in FREE for f in free_raw):
        raise InputError(f"must list sector dimensions from {', '.join(FREE)}", file=file, key="study.free")
    envelope = None
    if "envelope" in st:
        envelope = _quantity(st["envelope"], "length", file, "study.envelope")
        if not envelope > 0.0:
            raise InputError("must be a positive radius", file=file, key="study.envelope")
    rule = st.get("rule", "least_mass")
    if rule not in RULES:
        raise InputError(f"{rule!r} is not one of {', '.join(RULES)}", file=file, key="study.rule")
    limits_raw = st.get("limits", {})
    if not isinstance(limits_raw, dict):
        raise InputError("must be a table", file=file, key="study.limits")
    limits = {}
    for k, v in limits_raw.items():
        if k not in LIMITS:
            raise InputError(f"unknown limit; pick from {', '.join(LIMITS)}", file=file, key=f"study.limits.{k}")
        if LIMITS[k] == "number":
            if isinstance(v, bool) or not isinstance(v, (int, float)):
                raise InputError(f"must be a plain number (got {v!r})", file=file, key=f"study.limits.{k}")
            x = float(v)
        else:
            x = _quantity(v, LIMITS[k], file, f"study.limits.{k}")
        if not x > 0.0:
            raise InputError(f"must be positive (got {v})", file=file, key=f"study.limits.{k}")
        limits[k] = x
    stresses = st.get("stresses", "fatigue")
    if stresses not in STRESSES:
        raise InputError(f"{stresses!r} is not one of {', '.join(STRESSES)}", file=file, key="study.stresses")
    wants = {"min_fillet_fatigue_safety": ("fatigue",), "min_fillet_static_safety": ("fatigue", "static")}
    wants["max_fillet_stress"] = wants["min_fillet_static_safety"]
    wants["min_overspeed_safety"] = wants["min_fillet_static_safety"]
    wants["max_counterweight_overspeed_stress"] = wants["min_fillet_static_safety"]
    wants["max_counterweight_stress"] = wants["min_fillet_static_safety"]
    # the joints take the web's deformation from the per-throw model's stresses (``study.joints``)
    wants.update(dict.fromkeys(JOINT_LIMITS, wants["min_fillet_static_safety"]))
    for k, modes in wants.items():
        if k in limits and stresses not in modes:
            raise InputError(
                f'the limit needs stresses = "{modes[0]}" (the study says "{stresses}")',
                file=file,
                key=f"study.limits.{k}",
            )
    name = st.get("name", Path(file).stem)
    if not isinstance(name, str):
        raise InputError("must be a string", file=file, key="study.name")
    return StudySpec(
        file,
        name,
        rot,
        rec,
        offsets,
        tuple(free_raw),
        envelope,
        rule,
        limits,
        _placements(st.get("placements"), file),
        stresses,
    )
