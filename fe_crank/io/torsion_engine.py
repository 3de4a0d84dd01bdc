"""Cross-checks of ``[torsion]`` against the rest of the load case: the lumped model's
stations against the engine's cylinders, the speed range against the full-load curve."""

from __future__ import annotations

import math
from pathlib import Path

from fe_crank.errors import InputError
from fe_crank.io.torsion import TorsionSettings
from fe_crank.io.torsion_lumped import check_stations


def check_torsion_engine(
    settings: TorsionSettings, engine, file: str | Path, key: str = "torsion", *, full_load=None
) -> None:
    """Cross-checks of ``[torsion]`` against the load case's engine and full-load curve
    (the speed range within the per-speed diagrams: never extrapolated; every speed of
    the sweep within the speed range, where the forced response is known).  InputError."""
    if settings.model == "lumped":
        check_stations(settings.stations, engine, str(file), f"{key}.stations")
    w = full_load.gas_speeds if full_load is not None else ()
    lo, hi = settings.speed_range
    if w and not (w[0] * (1 - 1e-12) <= lo and hi <= w[-1] * (1 + 1e-12)):
        raise InputError(
            f"the speed range {lo * 30 / math.pi:.6g}-{hi * 30 / math.pi:.6g} rpm reaches beyond the full-load "
            f"diagrams ([[operating.gas]], {w[0] * 30 / math.pi:.6g}-{w[-1] * 30 / math.pi:.6g} rpm), which are "
            "never extrapolated",
            file=str(file),
            key=f"{key}.speed_range",
        )
    sweep = full_load.speeds if full_load is not None else ()
    out = [x for x in sweep if not lo * (1 - 1e-12) <= x <= hi * (1 + 1e-12)]
    if out:
        raise InputError(
            f"the full-load curve's speed {out[0] * 30 / math.pi:.6g} rpm lies outside the speed range "
            f"{lo * 30 / math.pi:.6g}-{hi * 30 / math.pi:.6g} rpm: every speed of the sweep takes its torsional "
            "vibration from this range",
            file=str(file),
            key=f"{key}.speed_range",
        )
