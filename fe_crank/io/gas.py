"""Gas-pressure input: a p(phi) table inline, or a CSV file beside the input file.

Three forms (``model`` key): ``"table"`` (default, inline points), ``"csv"`` (a file
beside the input file) and ``"wiebe"`` (the parametric cycle of ``fe_crank.mechanism.gas``).
Units are explicit: the table states its angle and pressure units
(``angle_unit = "deg"``, ``pressure_unit = "MPa"``); a CSV states them in its
header (``angle [deg], pressure [MPa]``).  Pressures are absolute.

The motored curve (no combustion, the overspeed check's ``overspeed_gas = "motored"``,
``fe_crank.mechanism.gas.motored_cycle``) needs the compression ratio and the intake/boost
pressure: the ``wiebe`` model has them (its ``k`` is the exponent); a ``table`` or
``csv`` may state them with the optional keys ``compression_ratio`` and
``intake_pressure`` (both or neither) and ``polytropic_exponent`` (default 1.35).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any, Literal

import numpy as np
from pydantic import Field, ValidationError, model_validator

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.io.base import Strict, read_text, validate, validation_to_input_error
from fe_crank.io.includes import resolve_reference
from fe_crank.io.units import Angle, Energy, Pressure, parse_unit, ureg


class MotoredKeys(Strict):
    """Optional data for the motored curve of a table or CSV gas model."""

    compression_ratio: float | None = Field(default=None, gt=1.0)
    intake_pressure: Pressure | None = None
    polytropic_exponent: float = Field(default=1.35, gt=1.0, lt=2.0)

    @model_validator(mode="after")
    def _pair(self) -> MotoredKeys:
        if (self.compression_ratio is None) != (self.intake_pressure is None):
            raise ValueError("compression_ratio and intake_pressure go together (the motored compression curve)")
        if self.intake_pressure is not None and not self.intake_pressure > 0:
            raise ValueError("intake_pressure must be a positive absolute pressure")
        return self


class GasTableInput(MotoredKeys):
    model: Literal["table"] = "table"
    angle_unit: str = Field(description="unit of the first column, e.g. 'deg'")
    pressure_unit: str = Field(description="unit of the second column, e.g. 'MPa' (absolute)")
    points: list[tuple[float, float]] = Field(min_length=2)
    crankcase_pressure: Pressure = 101325.0
    source: str = ""

    @model_validator(mode="after")
    def _check(self) -> GasTableInput:
        try:
            a = ureg.Quantity(1.0, parse_unit(self.angle_unit))
        except ValueError as exc:
            raise ValueError(f"angle_unit: {exc}") from None
        if not a.dimensionless or a.unitless:
            raise ValueError(f"angle_unit {self.angle_unit!r} is not an angle unit (deg or rad)")
        try:
            p = ureg.Quantity(1.0, parse_unit(self.pressure_unit))
        except ValueError as exc:
            raise ValueError(f"pressure_unit: {exc}") from None
        if not p.check("[pressure]"):
            raise ValueError(f"pressure_unit {self.pressure_unit!r} is not a pressure unit (Pa, kPa, MPa, bar)")
        ang = np.array([pt[0] for pt in self.points])
        if np.any(np.diff(ang) <= 0):
            raise ValueError("points: angles must increase strictly")
        if any(pt[1] < 0 for pt in self.points):
            raise ValueError("points: absolute pressure cannot be negative")
        return self

    def arrays_si(self) -> tuple[np.ndarray, np.ndarray]:
        ang = np.array([pt[0] for pt in self.points], dtype=float)
        prs = np.array([pt[1] for pt in self.points], dtype=float)
        ang = ureg.Quantity(ang, parse_unit(self.angle_unit)).to("rad").magnitude
        prs = ureg.Quantity(prs, parse_unit(self.pressure_unit)).to("Pa").magnitude
        return np.asarray(ang, float), np.asarray(prs, float)


class GasCsvInput(MotoredKeys):
    """``model = "csv"``: a CSV file beside the input file, header ``angle [deg], pressure [MPa]``."""

    model: Literal["csv"]
    file: str = Field(min_length=1)
    crankcase_pressure: Pressure = 101325.0
    source: str = ""


class GasWiebeInput(Strict):
    """``model = "wiebe"``: closed-cycle polytropes with Wiebe heat release (fe_crank.mechanism.gas.wiebe_cycle)."""

    model: Literal["wiebe"]
    compression_ratio: float = Field(gt=1.0)
    intake_pressure: Pressure
    exhaust_pressure: Pressure
    heat_released: Energy
    combustion_start: Angle
    combustion_duration: Angle
    k: float = Field(default=1.35, gt=1.0, lt=2.0)
    wiebe_a: float = Field(default=5.0, gt=0)
    wiebe_m: float = Field(default=2.0, ge=0)
    crankcase_pressure: Pressure = 101325.0
    source: str = ""

    @model_validator(mode="after")
    def _check(self) -> GasWiebeInput:
        for key in ("intake_pressure", "exhaust_pressure"):
            if not getattr(self, key) > 0:
                raise ValueError(f"{key} must be a positive absolute pressure")
        if self.heat_released < 0:
            raise ValueError("heat_released cannot be negative")
        if not self.combustion_duration > 0:
            raise ValueError("combustion_duration must be positive")
        return self


def _split_header(cell: str, file: str | Path, key: str) -> str:
    cell = cell.strip()
    if "[" not in cell or not cell.endswith("]"):
        raise InputError(
            f"CSV header cell {cell!r} must state its unit as 'name [unit]', e.g. 'angle [deg], pressure [MPa]'",
            file=str(file),
            key=key,
        )
    return cell[cell.index("[") + 1 : -1].strip()


def read_gas_csv(path: str | Path, *, crankcase_pressure: float = 101325.0, source: str = "") -> model.GasPressure:
    """Read ``angle [unit], pressure [unit]`` CSV (absolute pressure) into a table."""
    path = Path(path)
    lines = read_text(path, "gas pressure CSV").splitlines()
    rows = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith("#")]
    if len(rows) < 3:
        raise InputError("needs a header and at least two rows", file=str(path))
    head = rows[0].split(",")
    if len(head) != 2:
        raise InputError("header must have two columns: 'angle [deg], pressure [MPa]'", file=str(path), key="header")
    au, pu = _split_header(head[0], path, "header"), _split_header(head[1], path, "header")
    points = []
    for i, ln in enumerate(rows[1:], start=2):
        cells = ln.split(",")
        try:
            if len(cells) != 2:
                raise IndexError
            pt = (float(cells[0]), float(cells[1]))
        except (ValueError, IndexError):
            raise InputError("is not two numbers", file=str(path), key=f"row {i}") from None
        if not all(np.isfinite(pt)):
            raise InputError(
                "must be two finite numbers (inf and nan are not accepted)", file=str(path), key=f"row {i}"
            )
        points.append(pt)
    try:
        table = GasTableInput(angle_unit=au, pressure_unit=pu, points=points, source=source or str(path.name))
    except ValidationError as exc:
        raise validation_to_input_error(exc, path) from None
    ang, prs = table.arrays_si()
    return model.GasPressure(ang, prs, crankcase_pressure, table.source)


def _with_motored(
    gas: model.GasPressure, raw: MotoredKeys, *, bore: float, crank_radius: float, rod_length: float, strokes: int
) -> model.GasPressure:
    """``gas`` with its motored curve when the input states compression ratio and intake pressure
    (both or neither: ``MotoredKeys``)."""
    if raw.compression_ratio is None or raw.intake_pressure is None:
        return gas
    from dataclasses import replace

    from fe_crank.mechanism.gas import motored_cycle

    m = motored_cycle(
        compression_ratio=raw.compression_ratio,
        intake_pressure=raw.intake_pressure,
        n_poly=raw.polytropic_exponent,
        crankcase_pressure=gas.crankcase_pressure,
        bore=bore,
        r=crank_radius,
        l=rod_length,
        strokes=strokes,
    )
    return replace(gas, motored=m)


def build_gas(
    data: Any, file: str | Path, key: str, *, strokes: int, bore: float, crank_radius: float, rod_length: float
) -> model.GasPressure:
    """Validate a ``[gas]`` table (``model`` = table | csv | wiebe) and return the p(phi) table.

    The Wiebe model needs the cylinder geometry (first cylinder of the engine)."""
    if not isinstance(data, dict):
        raise InputError("must be a table", file=str(file), key=key)
    kind = data.get("model", "table")
    if kind == "table":
        table = validate(GasTableInput, data, file, key)
        ang, prs = table.arrays_si()
        cycle = 4.0 * np.pi if strokes == 4 else 2.0 * np.pi
        if ang[0] < -1e-9 or ang[-1] > cycle + 1e-9:
            raise InputError(
                f"angles must lie within one cycle, 0 .. {np.degrees(cycle):.0f} deg from TDC firing",
                file=str(file),
                key=f"{key}.points",
            )
        return _with_motored(
            model.GasPressure(ang, prs, table.crankcase_pressure, table.source),
            table,
            bore=bore,
            crank_radius=crank_radius,
            rod_length=rod_length,
            strokes=strokes,
        )
    if kind == "csv":
        ref = validate(GasCsvInput, data, file, key)
        csv = resolve_reference(ref.file, file, key=f"{key}.file")
        if not csv.is_file():
            state = "is a folder" if csv.is_dir() else "not found"
            raise InputError(f"the gas pressure CSV {ref.file!r} {state}", file=str(file), key=f"{key}.file")
        try:
            return _with_motored(
                read_gas_csv(csv, crankcase_pressure=ref.crankcase_pressure, source=ref.source),
                ref,
                bore=bore,
                crank_radius=crank_radius,
                rod_length=rod_length,
                strokes=strokes,
            )
        except InputError as exc:
            if exc.key is None:  # the file as a whole: name the key that referenced it
                raise InputError(
                    f"the gas pressure CSV {ref.file!r}: {exc.reason}", file=str(file), key=f"{key}.file"
                ) from None
            raise
    if kind == "wiebe":
        from fe_crank.mechanism.gas import motored_cycle, wiebe_cycle

        raw = validate(GasWiebeInput, data, file, key)
        g = wiebe_cycle(
            bore=bore,
            r=crank_radius,
            l=rod_length,
            compression_ratio=raw.compression_ratio,
            intake_pressure=raw.intake_pressure,
            exhaust_pressure=raw.exhaust_pressure,
            heat_released=raw.heat_released,
            combustion_start=raw.combustion_start,
            combustion_duration=raw.combustion_duration,
            k=raw.k,
            wiebe_a=raw.wiebe_a,
            wiebe_m=raw.wiebe_m,
            strokes=strokes,
            crankcase_pressure=raw.crankcase_pressure,
        )
        motored = motored_cycle(
            bore=bore,
            r=crank_radius,
            l=rod_length,
            compression_ratio=raw.compression_ratio,
            intake_pressure=raw.intake_pressure,
            exhaust_pressure=raw.exhaust_pressure,
            n_poly=raw.k,
            strokes=strokes,
            crankcase_pressure=raw.crankcase_pressure,
        )
        return model.GasPressure(g.angle, g.pressure, g.crankcase_pressure, raw.source or g.source, motored)
    raise InputError(f"unknown gas model {kind!r}; use 'table', 'csv' or 'wiebe'", file=str(file), key=f"{key}.model")
