"""One pint registry for the whole application; quantities only at the edges.

Every dimensional input is a string with its unit ("66 mm", "2800 rpm", "5 MPa").
It is parsed once, here, to a plain SI float.  A bare number where a unit is
required, a unit without a number, a unit of the wrong dimension, a non-finite
or absurdly large value are errors, never guesses.

The text is checked by a small tokenizer *before* pint sees it (pint evaluates
``**`` exponents, so ``"9**9**9 rpm"`` would never return): one decimal number,
then a unit expression of names, ``*``, ``/``, ``^``/``**`` with a one-digit
integer exponent and at most ``MAX_PAREN_DEPTH`` nested parentheses, all within
``MAX_TEXT`` characters (docs/limits.md).

Rotational speeds are read from an explicit table (``SPEED_UNITS``), not through
pint's dimensional analysis, which takes ``1/min`` as 1/60 s^-1 and would turn it
into 1/60 rad/s (``"2800 1/min"`` would become 446 rpm).  ``1/s`` and ``s^-1`` are
refused: for a shaft they may mean rev/s or rad/s.
"""

from __future__ import annotations

import functools
import math
import re
from typing import Annotated

import numpy as np
import pint
from pydantic import BeforeValidator

ureg: pint.UnitRegistry[float | np.ndarray] = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
ureg.define("rpm = revolution / minute")  # pint's 'rpm' is already this; keep explicit

#: longest accepted quantity or unit text (characters)
MAX_TEXT = 64
#: deepest accepted parenthesis nesting in a unit expression
MAX_PAREN_DEPTH = 2
#: largest accepted absolute exponent in a unit expression (m^3, kg*m**2, s^-2 ...)
MAX_EXPONENT = 4

#: kind name -> (pint dimensionality, SI unit to convert to, example for messages)
KINDS: dict[str, tuple[str, str, str]] = {
    "length": ("[length]", "m", "66 mm"),
    "mass": ("[mass]", "kg", "0.62 kg"),
    "angle": ("", "rad", "90 deg"),
    "speed": ("1/[time]", "rad/s", "3000 rpm"),
    "pressure": ("[mass]/[length]/[time]**2", "Pa", "5 MPa"),
    "force": ("[mass]*[length]/[time]**2", "N", "12 kN"),
    "moment": ("[mass]*[length]**2/[time]**2", "N*m", "300 N*m"),
    "inertia": ("[mass]*[length]**2", "kg*m**2", "0.002 kg*m**2"),
    "density": ("[mass]/[length]**3", "kg/m**3", "7850 kg/m^3"),
    "stiffness_per_area": ("[mass]/[length]**2/[time]**2", "N/m**3", "1e12 N/m^3"),
    "energy": ("[mass]*[length]**2/[time]**2", "J", "500 J"),
    "unbalance": ("[mass]*[length]", "kg*m", "0.03 kg*m"),
    "time": ("[time]", "s", "0.1 s"),
    "area": ("[length]**2", "m**2", "12 mm^2"),
    "stiffness": ("[mass]/[time]**2", "N/m", "5e8 N/m"),
    "viscosity": ("[mass]/[length]/[time]", "Pa*s", "8 mPa*s"),
    "kinematic_viscosity": ("[length]**2/[time]", "m**2/s", "68 mm^2/s"),
    "temperature": ("[temperature]", "K", "110 degC"),
}

#: kind -> largest accepted absolute SI value.  Far beyond any crankshaft (a 1 km
#: length, 1e6 rad/s ...): they only stop typing slips such as "1e30 mm" from
#: reaching the geometry kernel or the solver.  docs/limits.md lists them.
MAX_ABS: dict[str, float] = {
    "length": 1e3,
    "mass": 1e7,
    "angle": 1e3,
    "speed": 1e6,
    "pressure": 1e13,
    "force": 1e10,
    "moment": 1e10,
    "inertia": 1e7,
    "density": 1e6,
    "stiffness_per_area": 1e20,
    "energy": 1e10,
    "unbalance": 1e5,
    "time": 1e7,
    "area": 1e6,
    "stiffness": 1e16,
    "viscosity": 1e6,
    "kinematic_viscosity": 1e3,
    "temperature": 1e4,
}

_TAU = 2.0 * math.pi
#: rotational-speed spelling (spaces removed, lower case) -> rad/s per unit.
#: rpm = rev/min = r/min = 1/min = min^-1: 2 pi / 60;  Hz = rev/s = rps: 2 pi;  rad/s: 1.
SPEED_UNITS: dict[str, float] = {
    **dict.fromkeys(
        ("rpm", "1/min", "min^-1", "min**-1", "min-1", "rev/min", "r/min", "revolution/minute"), _TAU / 60.0
    ),
    **dict.fromkeys(("hz", "rev/s", "r/s", "rps", "revolution/second"), _TAU),
    **dict.fromkeys(("rad/s", "rad*s^-1", "rad*s**-1", "radian/second"), 1.0),
    "deg/s": math.pi / 180.0,
}
_AMBIGUOUS_SPEED = ("1/s", "s^-1", "s**-1", "s-1", "1/second")

_NUMBER = re.compile(r"[+-]?(?:\d+(?:\.\d*)?|\.\d+)(?:[eE][+-]?\d{1,3})?")
_UNIT_TOKEN = re.compile(
    r"\s*(?:(?P<name>[A-Za-z_°µμΩ%][A-Za-z0-9_°µμΩ]*)|(?P<pow>\*\*|\^)\s*(?P<exp>[+-]?\d+)"
    r"|(?P<op>[*/·])|(?P<one>1)(?=\s*/)|(?P<lp>\()|(?P<rp>\)))"
)


def _clip(value: object) -> str:
    """``repr`` of a value for a message, cut to a few dozen characters."""
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "...'"


def check_unit_expression(text: str) -> str:
    """Refuse a unit expression pint could not evaluate quickly; return it stripped.

    Allowed: unit names, ``*``, ``/``, ``^``/``**`` followed by an integer with
    ``|n| <= MAX_EXPONENT``, a leading ``1/``, parentheses nested at most
    ``MAX_PAREN_DEPTH`` deep, ``MAX_TEXT`` characters.  Raises ValueError.
    """
    text = text.strip()
    if not text:
        raise ValueError("the unit is missing")
    if len(text) > MAX_TEXT:
        raise ValueError(f"unit text longer than {MAX_TEXT} characters")
    pos, depth = 0, 0
    while pos < len(text):
        m = _UNIT_TOKEN.match(text, pos)
        if not m or m.end() == pos:
            raise ValueError(f"unexpected character {text[pos]!r} in the unit")
        if m.group("exp") is not None and abs(int(m.group("exp"))) > MAX_EXPONENT:
            raise ValueError(f"unit exponent beyond +-{MAX_EXPONENT}")
        if m.group("lp"):
            depth += 1
            if depth > MAX_PAREN_DEPTH:
                raise ValueError(f"parentheses nested deeper than {MAX_PAREN_DEPTH} in the unit")
        if m.group("rp"):
            depth -= 1
            if depth < 0:
                raise ValueError("unbalanced parentheses in the unit")
        pos = m.end()
        while pos < len(text) and text[pos].isspace():
            pos += 1
    if depth:
        raise ValueError("unbalanced parentheses in the unit")
    return text


def parse_unit(text: str) -> pint.Unit:
    """A unit string (``"MPa"``, ``"deg"``) checked by ``check_unit_expression``, then pint."""
    checked = check_unit_expression(text)
    try:
        return ureg.parse_units(checked)
    except Exception:  # pint raises several unrelated classes
        raise ValueError(f"{_clip(text)} is not a known unit") from None


def _a(kind: str) -> str:
    """``kind`` with its indefinite article ("a length", "an angle")."""
    return f"{'an' if kind[:1] in 'aeiou' else 'a'} {kind}"


def _split(value: str, kind: str, example: str) -> tuple[float, str]:
    text = value.strip()
    if len(text) > MAX_TEXT:
        raise ValueError(f'{_a(kind)} is at most {MAX_TEXT} characters, e.g. "{example}"')
    m = _NUMBER.match(text)
    if not m:
        raise ValueError(f'cannot read {_clip(value)} as {_a(kind)}: it must start with a number, e.g. "{example}"')
    number = float(m.group(0))
    unit = text[m.end() :].strip()
    if not unit:
        raise ValueError(f'{_clip(value)} has no unit; write {_a(kind)} with its unit, e.g. "{example}"')
    return number, unit


def _describe_dimension(q: pint.Quantity) -> str:
    dims = q.dimensionality
    for kind, (dim, _, _) in KINDS.items():
        try:
            if dim and dims == ureg.get_dimensionality(dim):
                return kind
        except Exception:  # pragma: no cover - defensive only
            continue
    return str(dims) if str(dims) != "dimensionless" else "a pure number"


def _article(word: str) -> str:
    return ("an " if word[:1] in "aeiou" else "a ") + word


def _speed(number: float, unit: str, value: str, example: str) -> float:
    key = re.sub(r"\s+", "", unit).lower()
    if key in SPEED_UNITS:
        return number * SPEED_UNITS[key]
    if key in _AMBIGUOUS_SPEED:
        raise ValueError(
            f"{_clip(value)}: 1/s is ambiguous for a shaft speed (rev/s or rad/s?); write rpm, Hz (rev/s) or rad/s"
        )
    try:
        q = ureg.Quantity(1.0, parse_unit(unit))
    except ValueError as exc:
        raise ValueError(f'cannot read {_clip(value)} as a speed (e.g. "{example}"): {exc}') from None
    if q.check("1/[time]"):
        raise ValueError(f"{_clip(value)}: write a rotational speed in rpm, 1/min, rev/min, Hz (rev/s) or rad/s")
    raise ValueError(f'{_clip(value)} is {_article(_describe_dimension(q))}, not a rotational speed (e.g. "{example}")')


def to_si(value: object, kind: str) -> float:
    """Parse ``value`` (a string with a unit) as a quantity of ``kind`` and return SI.

    Raises ``ValueError`` with a message that says what was expected.  Angles may be
    given in deg or rad (a bare number is refused: degrees or radians would be a guess).
    Speeds: ``SPEED_UNITS`` (rpm, 1/min, min^-1, rev/min, r/min -> 2 pi/60 rad/s;
    Hz, rev/s -> 2 pi rad/s; rad/s); ``1/s`` is refused as ambiguous.
    """
    example = KINDS[kind][2]
    if isinstance(value, bool) or not isinstance(value, str):
        shown = _clip(value) if isinstance(value, (int, float)) else type(value).__name__
        raise ValueError(f'expected a {kind} with its unit as a string, e.g. "{example}"; got {shown} without a unit')
    return _text_to_si(str(value), kind)


@functools.lru_cache(maxsize=4096)
def _text_to_si(value: str, kind: str) -> float:
    """``to_si`` of a string: a pure function of (text, kind), remembered (a refusal is not)."""
    dim, si_unit, example = KINDS[kind]
    number, unit = _split(value, kind, example)
    if not math.isfinite(number):
        raise ValueError(f"{_clip(value)} is not a finite {kind}")
    if kind == "speed":
        out = _speed(number, unit, value, example)
    else:
        try:
            u = parse_unit(unit)
        except ValueError as exc:
            raise ValueError(f'cannot read {_clip(value)} as a {kind} (e.g. "{example}"): {exc}') from None
        q = ureg.Quantity(number, u)
        if kind == "angle":
            if not q.dimensionless or q.unitless:
                raise ValueError(f'{_clip(value)} is not an angle (e.g. "{example}")')
            out = float(q.to("rad").magnitude)
        else:
            if not q.check(dim):
                raise ValueError(
                    f'{_clip(value)} is {_article(_describe_dimension(q))}, not a {kind} (e.g. "{example}")'
                )
            out = float(q.to(si_unit).magnitude)
    if not math.isfinite(out):
        raise ValueError(f"{_clip(value)} is not a finite {kind}")
    if abs(out) > MAX_ABS[kind]:
        raise ValueError(
            f"{_clip(value)} is beyond the largest accepted {kind}, {MAX_ABS[kind]:g} {si_unit} (docs/limits.md)"
        )
    return out


def _validator(kind: str):
    def parse(v: object) -> float:
        return to_si(v, kind)

    return BeforeValidator(parse)


# Annotated float types for pydantic models: the string is parsed, the model holds SI.
Length = Annotated[float, _validator("length")]
Mass = Annotated[float, _validator("mass")]
Angle = Annotated[float, _validator("angle")]
Speed = Annotated[float, _validator("speed")]
Pressure = Annotated[float, _validator("pressure")]
Force = Annotated[float, _validator("force")]
Moment = Annotated[float, _validator("moment")]
Inertia = Annotated[float, _validator("inertia")]
Density = Annotated[float, _validator("density")]
StiffnessPerArea = Annotated[float, _validator("stiffness_per_area")]
Energy = Annotated[float, _validator("energy")]
Unbalance = Annotated[float, _validator("unbalance")]
Area = Annotated[float, _validator("area")]
Stiffness = Annotated[float, _validator("stiffness")]
Viscosity = Annotated[float, _validator("viscosity")]
KinematicViscosity = Annotated[float, _validator("kinematic_viscosity")]
Temperature = Annotated[float, _validator("temperature")]
