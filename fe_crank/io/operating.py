"""The load case's ``[operating]`` section -> ``fe_crank.model.OperatingPoint``.

::

    [operating]
    speed = "2800 rpm"                        # the operating (rated) speed
    overspeed = "3360 rpm"                    # optional
    overspeed_gas = "motored"                 # or "as_operating"

    # optional: the full-load curve, evaluated at every speed
    speeds = ["1000 rpm", "1600 rpm", "2200 rpm", "2800 rpm"]   # increasing
    # or: speed_range = ["1000 rpm", "2800 rpm"] and speed_step = "200 rpm"

    [[operating.gas]]                         # optional: the full-load diagram per speed
    speed = "1000 rpm"
    model = "wiebe"                           # the keys of the engine's [gas]: table | csv | wiebe
    ...

    misfire = "each"                          # optional: each cylinder cut out in turn, or ["3", "5"]

The sweep's speeds are those given plus the operating speed.  Per-speed diagrams are
interpolated linearly in speed between the two that bracket a speed and never
extrapolated: every speed of the sweep (and the operating speed) must lie between the
first and the last diagram; they replace the engine file's diagram (the engine's gas is
then the diagram at the operating speed).  Without ``[[operating.gas]]`` the engine's
diagram serves every speed.  A misfiring cylinder is motored (``fe_crank.mechanism.misfire``).
"""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import Field, model_validator

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.io.base import Strict, validate
from fe_crank.io.bounds import check_piston_speed, check_speed
from fe_crank.io.gas import build_gas
from fe_crank.io.units import Speed, to_si

#: the most speeds a sweep may have (each is a dynamics run and an assessment)
MAX_SPEEDS = 200


class OperatingInput(Strict):
    speed: Speed
    overspeed: Speed | None = None
    overspeed_gas: Literal["motored", "as_operating"] = "motored"  # gas load at the overspeed
    speeds: list[Speed] | None = Field(default=None, min_length=1, max_length=MAX_SPEEDS)
    speed_range: tuple[Speed, Speed] | None = None
    speed_step: Speed | None = None
    gas: list | None = Field(default=None, min_length=1, max_length=MAX_SPEEDS)
    misfire: Any = None  # "each" or a list of cylinder names (checked in _misfire, with its own message)

    @model_validator(mode="after")
    def _check(self):
        if not self.speed > 0:
            raise ValueError(f"speed must be positive (got {self.speed} rad/s)")
        if self.overspeed is not None and self.overspeed < self.speed:
            raise ValueError("overspeed must not be below the operating speed")
        if self.speeds is not None and self.speed_range is not None:
            raise ValueError("give speeds or speed_range (with speed_step), not both")
        if (self.speed_range is None) != (self.speed_step is None):
            raise ValueError("speed_range and speed_step go together")
        return self


def _check_speeds(raw: OperatingInput, engine: model.Engine, file: str, key: str) -> None:
    """Every speed of the section within the physical range (``io.bounds``), the mean
    piston speed of each throw too."""
    given = [(raw.speed, f"{key}.speed")]
    if raw.overspeed is not None:
        given.append((raw.overspeed, f"{key}.overspeed"))
    given += [(w, f"{key}.speeds[{i}]") for i, w in enumerate(raw.speeds or ())]
    given += [(w, f"{key}.speed_range[{i}]") for i, w in enumerate(raw.speed_range or ())]
    for w, k in given:
        check_speed(w, file, k)
    w, k = max(given)
    for t in engine.throws:
        shaft = next((s for s in engine.shafts if s.name == t.shaft), None)
        check_piston_speed(w * (abs(shaft.speed_ratio) if shaft is not None else 1.0), t.crank_radius, file, k)


def _sweep(raw: OperatingInput, file: str, key: str) -> tuple[float, ...] | None:
    if raw.speeds is not None:
        w = np.array(raw.speeds)
        if not np.all(w > 0):
            raise InputError("speeds must be positive", file=file, key=f"{key}.speeds")
        bad = np.nonzero(np.diff(w) <= 0)[0]
        if bad.size:
            raise InputError(
                f"speeds must increase: entry {bad[0] + 1} ({w[bad[0] + 1] * 30 / np.pi:.6g} rpm) does not "
                f"exceed the one before it ({w[bad[0]] * 30 / np.pi:.6g} rpm)",
                file=file,
                key=f"{key}.speeds",
            )
    elif raw.speed_range is not None:
        lo, hi = raw.speed_range
        if not 0 < lo < hi:
            raise InputError("speed_range must be two increasing positive speeds", file=file, key=f"{key}.speed_range")
        step = raw.speed_step
        if step is None or not step > 0:
            raise InputError("speed_step must be positive", file=file, key=f"{key}.speed_step")
        count = int(np.floor((hi - lo) / step * (1 + 1e-12))) + 1
        if count > MAX_SPEEDS:
            raise InputError(f"gives {count} speeds, more than {MAX_SPEEDS}", file=file, key=f"{key}.speed_step")
        w = lo + step * np.arange(count)
        w = np.append(w, hi) if hi - w[-1] > 1e-9 * hi else w
    else:
        return None
    return _merged([float(x) for x in w], raw.speed)


def _merged(speeds: list[float], operating: float) -> tuple[float, ...]:
    """``speeds`` and the operating speed in increasing order, speeds within a relative
    1e-9 of each other (the same speed written twice, or reached by the step to within
    rounding) taken once, as the operating speed where it is one of them."""
    out: list[float] = []
    for x in sorted([*speeds, operating]):
        if out and x - out[-1] <= 1e-9 * x:
            if x == operating:
                out[-1] = x
            continue
        out.append(x)
    return tuple(out)


def _diagrams(raw: OperatingInput, engine: model.Engine, file: str, key: str):
    speeds: list[float] = []
    tables = []
    c0 = engine.cylinders[0]
    geom: dict[str, Any] = {
        "strokes": engine.strokes,
        "bore": c0.bore,
        "crank_radius": engine.throw(c0.throw).crank_radius,
        "rod_length": c0.rod.length,
    }
    for i, item in enumerate(raw.gas or ()):
        k = f"{key}.gas[{i}]"
        if not isinstance(item, dict) or "speed" not in item:
            raise InputError("each [[operating.gas]] entry is a gas table with its speed", file=file, key=f"{k}.speed")
        try:
            w = to_si(item["speed"], "speed")
        except ValueError as exc:
            raise InputError(str(exc), file=file, key=f"{k}.speed") from None
        check_speed(w, file, f"{k}.speed")
        if speeds and not w > speeds[-1]:
            raise InputError("the diagrams' speeds must increase", file=file, key=f"{k}.speed")
        speeds.append(w)
        tables.append(build_gas({a: b for a, b in item.items() if a != "speed"}, file, k, **geom))
    return tuple(speeds), tuple(tables)


def _misfire(raw: OperatingInput, engine: model.Engine, file: str, key: str) -> tuple[str, ...]:
    names = [c.name for c in engine.cylinders]
    value = raw.misfire
    if value is None:
        return ()
    if engine.gas is None and not raw.gas:
        raise InputError("a misfire needs the engine's gas pressure (the firing cylinders)", file=file, key=key)
    usage = 'write misfire = "each" or a list of cylinder names, e.g. ["3"]'
    if isinstance(value, str):
        if value.strip() != "each":
            raise InputError(usage, file=file, key=key)
        return tuple(names)
    if not (isinstance(value, list) and all(isinstance(n, str) for n in value)):
        raise InputError(usage, file=file, key=key)
    given = [n.strip() for n in value]
    if not given:
        raise InputError('name the misfiring cylinders, or write misfire = "each"', file=file, key=key)
    for j, n in enumerate(given):
        if n not in names:
            raise InputError(
                f"names cylinder {n!r}, which the engine does not have ({names})", file=file, key=f"{key}[{j}]"
            )
        if n in given[:j]:
            raise InputError(f"cylinder {n!r} is named twice", file=file, key=f"{key}[{j}]")
    return tuple(given)


def parse_operating(
    value: object, engine: model.Engine, file: str | Path, key: str = "operating"
) -> tuple[model.Engine, model.OperatingPoint]:
    """Validate ``[operating]`` against the load case's engine.  Raises InputError.

    Returns the engine (with per-speed diagrams: its gas replaced by the diagram at the
    operating speed, so that the operating point's dynamics use it) and the operating
    point."""
    file = str(file)
    raw = validate(OperatingInput, value, file, key)
    _check_speeds(raw, engine, file, key)
    sweep = _sweep(raw, file, key)
    gas_speeds, diagrams = _diagrams(raw, engine, file, key)
    full = None
    if sweep is not None or diagrams:
        speeds = sweep if sweep is not None else tuple(sorted({raw.speed, *gas_speeds}))
        if diagrams:
            for w, what in [(raw.speed, "the operating speed")] + [(x, "of the sweep") for x in speeds]:
                if not gas_speeds[0] * (1 - 1e-12) <= w <= gas_speeds[-1] * (1 + 1e-12):
                    raise InputError(
                        f"no gas pressure for {w * 30 / np.pi:.6g} rpm ({what}): the diagrams cover "
                        f"{gas_speeds[0] * 30 / np.pi:.6g}-{gas_speeds[-1] * 30 / np.pi:.6g} rpm and are "
                        "never extrapolated",
                        file=file,
                        key=f"{key}.gas",
                    )
        full = model.FullLoadCurve(speeds, gas_speeds, diagrams, engine.gas, engine.cycle_angle)
    misfire = _misfire(raw, engine, file, f"{key}.misfire")
    if full is not None and diagrams:
        engine = replace(engine, gas=full.gas_at(raw.speed))
    return engine, model.OperatingPoint(raw.speed, raw.overspeed, raw.overspeed_gas, full_load=full, misfire=misfire)


__all__ = ["OperatingInput", "parse_operating", "MAX_SPEEDS"]
