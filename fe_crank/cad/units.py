"""The length unit a CAD file states, read from its text (no geometry kernel).

* STEP (ISO 10303-21): the ``LENGTH_UNIT`` of the context the B-rep shape
  representations are given in (``GLOBAL_UNIT_ASSIGNED_CONTEXT``), either an SI
  unit with its prefix (``( LENGTH_UNIT() NAMED_UNIT(*) SI_UNIT(.MILLI.,.METRE.) )``,
  ISO 10303-41 ``si_unit``) or a conversion-based unit (``CONVERSION_BASED_UNIT('INCH',
  #9)`` whose ``LENGTH_MEASURE_WITH_UNIT(LENGTH_MEASURE(25.4), #10)`` gives its size in
  another unit).  Several different length units in one file: ambiguous.
* IGES 5.3 (section 2.2.4.3): the global section's unit flag (parameter 14: 1 inch,
  2 mm, 4 ft, 5 mile, 6 m, 7 km, 8 mil, 9 micron, 10 cm, 11 microinch; 3: the unit named
  in parameter 15).
* BREP (OpenCASCADE's own format) states no unit.

``declared_unit(path, kind) -> StatedUnit | None``: None when the file states no unit.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from pathlib import Path

#: ISO 10303-41 SI prefixes that make sense for a length
_PREFIX = {
    "": 1.0,
    "KILO": 1e3,
    "HECTO": 1e2,
    "DECA": 1e1,
    "DECI": 1e-1,
    "CENTI": 1e-2,
    "MILLI": 1e-3,
    "MICRO": 1e-6,
    "NANO": 1e-9,
}
#: names of conversion-based units whose size the file does not resolve (m)
_NAMED = {"INCH": 0.0254, "FOOT": 0.3048, "MIL": 2.54e-5, "YARD": 0.9144, "MILE": 1609.344}
_IGES_FLAG = {1: 0.0254, 2: 1e-3, 4: 0.3048, 5: 1609.344, 6: 1.0, 7: 1e3, 8: 2.54e-5, 9: 1e-6, 10: 1e-2, 11: 2.54e-8}
_IGES_NAME = {"IN": 0.0254, "INCH": 0.0254, "MM": 1e-3, "FT": 0.3048, "MI": 1609.344, "M": 1.0, "KM": 1e3}
_IGES_NAME.update({"MIL": 2.54e-5, "UM": 1e-6, "CM": 1e-2, "UIN": 2.54e-8})
_HEAD = 4_000_000  # bytes of a STEP file searched for its units (the units come before the geometry in most files)


@dataclass(frozen=True)
class StatedUnit:
    """A length unit stated by a file: its name as written and its size in metres."""

    name: str
    metres: float


class AmbiguousUnit(ValueError):
    """The file states more than one length unit."""


def _step_instances(text: str) -> dict[str, str]:
    """``#id -> instance text`` (whitespace removed) of the data section's instances."""
    out = {}
    for m in re.finditer(r"#(\d+)\s*=\s*(.*?);", text, re.S):
        out[m.group(1)] = re.sub(r"\s+", "", m.group(2))
    return out


def _step_size(inst: dict[str, str], ref: str, depth: int = 0) -> tuple[str, float] | None:
    """(name, metres) of the length unit instance ``#ref``; None when it is none."""
    body = inst.get(ref, "")
    if "LENGTH_UNIT()" not in body or depth > 4:
        return None
    si = re.search(r"SI_UNIT\((?:\*,)?(\$|\.(\w+)\.),\.METRE\.\)", body)
    if si:
        prefix = si.group(2) or ""
        if prefix not in _PREFIX:
            return None
        return (prefix.lower() + "metre"), _PREFIX[prefix]
    cb = re.search(r"CONVERSION_BASED_UNIT\('([^']*)',#(\d+)\)", body)
    if cb:
        name = cb.group(1).strip().upper()
        measure = inst.get(cb.group(2), "")
        mm = re.search(r"LENGTH_MEASURE_WITH_UNIT\(LENGTH_MEASURE\(([-+0-9.Ee]+)\),#(\d+)\)", measure)
        if mm:
            base = _step_size(inst, mm.group(2), depth + 1)
            if base is not None:
                return name.lower(), float(mm.group(1)) * base[1]
        if name in _NAMED:
            return name.lower(), _NAMED[name]
    return None


def _solid_contexts(inst: dict[str, str]) -> list[str]:
    """Length units of the contexts the B-rep shape representations are given in."""
    units = []
    for body in inst.values():
        if re.match(r"^\(?\w*BREP_SHAPE_REPRESENTATION\(|^\(?MANIFOLD_SURFACE_SHAPE_REPRESENTATION\(", body):
            ctx = re.search(r"#(\d+)\)$", body)
            refs = (
                re.search(r"GLOBAL_UNIT_ASSIGNED_CONTEXT\(\(([#\d,]*)\)\)", inst.get(ctx.group(1), "")) if ctx else None
            )
            if refs:
                units += [
                    r.strip("#") for r in refs.group(1).split(",") if "LENGTH_UNIT()" in inst.get(r.strip("#"), "")
                ]
    return units


def step_unit(text: str) -> StatedUnit | None:
    """The length unit a STEP file's text states for its solids (None: none;
    ``AmbiguousUnit``: several).  The unit of the context of the B-rep shape
    representations; a file without one: every length unit it declares (other than the
    units that only size a conversion-based unit)."""
    inst = _step_instances(text)
    refs = _solid_contexts(inst)
    if not refs:
        bases = set()  # units that only give the size of a conversion-based unit
        for body in inst.values():
            for cb in re.finditer(r"CONVERSION_BASED_UNIT\('[^']*',#(\d+)\)", body):
                m = re.search(
                    r"LENGTH_MEASURE_WITH_UNIT\(LENGTH_MEASURE\([-+0-9.Ee]+\),#(\d+)\)", inst.get(cb.group(1), "")
                )
                if m:
                    bases.add(m.group(1))
        refs = [r for r, body in inst.items() if "LENGTH_UNIT()" in body and r not in bases]
    found = {}
    for ref in refs:
        got = _step_size(inst, ref)
        if got is not None:
            found[round(got[1], 15)] = got
    if len(found) > 1:
        raise AmbiguousUnit(", ".join(sorted(n for n, _ in found.values())))
    if not found:
        return None
    name, metres = next(iter(found.values()))
    return StatedUnit(name, metres)


def _iges_global(text: str) -> list[str]:
    """Parameters of an IGES global section (Hollerith strings decoded)."""
    lines = [ln for ln in text.splitlines() if len(ln) >= 73 and ln[72] == "G"]
    g = "".join(ln[:72] for ln in lines)
    delim, end = ",", ";"
    if g.startswith("1H"):
        delim = g[2]
    params, pos, cur = [], 0, ""
    while pos < len(g):
        m = re.match(r"\s*(\d+)H", g[pos:])
        if m and not cur.strip():
            n = int(m.group(1))
            start = pos + m.end()
            cur = g[start : start + n]
            pos = start + n
            continue
        c = g[pos]
        if c in (delim, end):
            params.append(cur.strip())
            cur = ""
            if c == end:
                break
            if len(params) == 1 and params[0] and params[0] != delim:
                delim = params[0]
        else:
            cur += c
        pos += 1
    return params


def iges_unit(text: str) -> StatedUnit | None:
    """The length unit an IGES file's global section states (None: none readable)."""
    p = _iges_global(text)
    if len(p) < 14:
        return None
    try:
        flag = int(float(p[13]))
    except ValueError:
        return None
    if flag == 3:
        name = p[14].strip().upper() if len(p) > 14 else ""
        return StatedUnit(name.lower(), _IGES_NAME[name]) if name in _IGES_NAME else None
    if flag in _IGES_FLAG:
        names = {1: "inch", 2: "mm", 4: "ft", 5: "mile", 6: "m", 7: "km", 8: "mil", 9: "micron", 10: "cm"}
        return StatedUnit(names.get(flag, "microinch"), _IGES_FLAG[flag])
    return None


def declared_unit(path: Path, kind: str) -> StatedUnit | None:
    """The length unit ``path`` (of ``kind`` "step", "iges" or "brep") states."""
    if kind == "brep":
        return None
    with open(path, "rb") as fh:
        text = fh.read(_HEAD).decode("latin-1")
    return step_unit(text) if kind == "step" else iges_unit(text)
