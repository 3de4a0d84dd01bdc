"""One pint registry for the whole application; quantities only at the edges.

Every dimensional input is a string with its unit ("66 mm", "2800 rpm", "5 MPa").
It is parsed once, here, to a plain SI float.  A bare number where a unit is
required, or a unit of the wrong dimension, is an error, never a guess.
"""

from __future__ import annotations

import math
from typing import Annotated

import pint
from pydantic import BeforeValidator

ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
ureg.define("rpm = revolution / minute")  # pint's 'rpm' is already this; keep explicit

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
}


def _describe_dimension(q: pint.Quantity) -> str:
    dims = q.dimensionality
    for kind, (dim, _, _) in KINDS.items():
        try:
            if dim and dims == ureg.get_dimensionality(dim):
                return kind
        except Exception:  # pragma: no cover - defensive only
            continue
    return str(dims) if str(dims) != "dimensionless" else "a pure number"


def to_si(value: object, kind: str) -> float:
    """Parse ``value`` (a string with a unit) as a quantity of ``kind`` and return SI.

    Raises ``ValueError`` with a message that says what was expected.  Angles may be
    given in deg or rad (a bare number is refused: degrees or radians would be a guess).
    Speeds accept rpm, rad/s, Hz (revolutions per second).
    """
    dim, si_unit, example = KINDS[kind]
    if isinstance(value, bool) or not isinstance(value, str):
        raise ValueError(
            f"expected a {kind} with its unit as a string, e.g. \"{example}\"; got {value!r} without a unit"
        )
    text = value.strip()
    try:
        q = ureg.Quantity(text)
    except Exception as exc:  # pint raises several unrelated classes
        raise ValueError(f"cannot read {value!r} as a {kind} (e.g. \"{example}\"): {exc}") from None
    if not isinstance(q, pint.Quantity) or q.unitless:
        raise ValueError(f"{value!r} has no unit; write a {kind} with its unit, e.g. \"{example}\"")
    if kind == "angle":
        if not q.dimensionless:
            raise ValueError(f"{value!r} is not an angle (e.g. \"{example}\")")
        out = float(q.to("rad").magnitude)
    elif kind == "speed":
        if q.check("1/[time]"):
            out = float(q.to("rad/s").magnitude) if str(q.units) not in ("hertz",) else 2 * math.pi * float(q.to("Hz").magnitude)
        else:
            raise ValueError(
                f"{value!r} is a {_describe_dimension(q)}, not a rotational speed (e.g. \"{example}\")"
            )
    else:
        if not q.check(dim):
            raise ValueError(f"{value!r} is a {_describe_dimension(q)}, not a {kind} (e.g. \"{example}\")")
        out = float(q.to(si_unit).magnitude)
    if not math.isfinite(out):
        raise ValueError(f"{value!r} is not a finite {kind}")
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
