"""Torsional stiffness and damping with their units, parsed at the edge.

Torsional stiffness is written per angle (``N*m/rad``, ``kN*m/deg``) and damping per
angular speed (``N*m*s/rad``): a bare ``N*m`` could be a torque, so it is refused.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Annotated

import pint
from pydantic import BeforeValidator

from fe_crank.errors import InputError
from fe_crank.io.units import ureg

_PER_ANGLE = {
    "stiffness": ("[mass]*[length]**2/[time]**2", "N*m/rad", "2e5 N*m/rad"),
    "damping": ("[mass]*[length]**2/[time]", "N*m*s/rad", "5 N*m*s/rad"),
}


def _parse_per_angle(value: object, kind: str) -> float:
    """A torsional stiffness or damping with its unit (module docstring); ValueError."""
    dims, si, example = _PER_ANGLE[kind]
    if isinstance(value, bool) or not isinstance(value, str):
        raise ValueError(
            f'expected a torsional {kind} with its unit as a string, e.g. "{example}"; got a value without a unit'
        )
    try:
        q: pint.Quantity[float] = ureg.Quantity(value.strip())  # a parsed number: int or float
    except Exception:  # pint raises several unrelated classes
        raise ValueError(f'cannot read this as a torsional {kind} (e.g. "{example}")') from None
    units = dict(getattr(q, "_units", {}) or {})
    per_angle = any(u in ("radian", "degree", "revolution", "turn") and e < 0 for u, e in units.items())
    if not per_angle:
        raise ValueError(
            f'a torsional {kind} is written per angle, e.g. "{example}" (without /rad it could be a torque)'
        )
    if not q.check(dims):
        raise ValueError(f'not a torsional {kind} (e.g. "{example}")')
    out = float(q.to(si).magnitude)
    if not math.isfinite(out):
        raise ValueError(f"not a finite torsional {kind}")
    return out


def parse_per_angle(value: object, kind: str, file: str | Path, key: str) -> float:
    """``_parse_per_angle`` for a key read outside a pydantic model: InputError."""
    try:
        return _parse_per_angle(value, kind)
    except ValueError as exc:
        raise InputError(str(exc), file=str(file), key=key) from None


def _per_angle(kind: str):
    return BeforeValidator(lambda value: _parse_per_angle(value, kind))


Stiffness = Annotated[float, _per_angle("stiffness")]
Damping = Annotated[float, _per_angle("damping")]

__all__ = ["Stiffness", "Damping", "parse_per_angle"]
