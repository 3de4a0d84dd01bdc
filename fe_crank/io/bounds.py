"""The physical range of an engine fe-crank accepts: speeds and strokes (docs/limits.md,
"Physical range").

The bounds are wide enough for every reciprocating engine from a model engine to a
large two-stroke and stop slips of the unit or the exponent (``"1e6 rpm"``, a stroke of
``"1 um"``), which would otherwise be computed as if they were real:

* **speed** 1 rpm ... 60 000 rpm: the slowest large two-strokes run at 20-30 rpm at
  dead-slow ahead, the fastest model engines at 30 000-40 000 rpm;
* **crank radius** 1 mm ... 2.5 m (stroke 2 mm ... 5 m): the smallest commercial model
  engine (0.16 cm^3) has a stroke of about 5.7 mm, the largest two-strokes 2.5-3.5 m;
* **mean piston speed** ``2 s n`` at most 50 m/s at any speed of the case: the fastest
  racing engines reach 25-27 m/s at their rated speed.
"""

from __future__ import annotations

import math

from fe_crank.errors import InputError

#: rad/s: the slowest and fastest accepted speed (1 rpm, 60 000 rpm)
MIN_SPEED = 1.0 * math.pi / 30.0
MAX_SPEED = 60_000.0 * math.pi / 30.0
#: m: the smallest and largest accepted crank radius (stroke 2 mm ... 5 m)
MIN_CRANK_RADIUS = 1e-3
MAX_CRANK_RADIUS = 2.5
#: m/s: the largest accepted mean piston speed 2 s n at any speed of a case
MAX_PISTON_SPEED = 50.0


def check_speed(w: float, file: str, key: str) -> None:
    """Refuse a speed (rad/s) outside ``MIN_SPEED ... MAX_SPEED``."""
    if not MIN_SPEED <= w <= MAX_SPEED:
        raise InputError(
            f"{w * 30 / math.pi:.6g} rpm lies outside the accepted range of engine speeds, 1-60 000 rpm "
            "(docs/limits.md, physical range): check the number and its unit",
            file=file,
            key=key,
        )


def check_crank_radius(r: float, file: str, key: str) -> None:
    """Refuse a crank radius (m) outside ``MIN_CRANK_RADIUS ... MAX_CRANK_RADIUS``."""
    if not MIN_CRANK_RADIUS <= r <= MAX_CRANK_RADIUS:
        raise InputError(
            f"a stroke of {2 * r * 1e3:.6g} mm lies outside the accepted range of strokes, 2 mm to 5 m "
            "(docs/limits.md, physical range): check the number and its unit",
            file=file,
            key=key,
        )


def check_piston_speed(w: float, r: float, file: str, key: str) -> None:
    """Refuse a speed (rad/s) at which the mean piston speed ``2 s n = 2 w r / pi`` of a
    crank radius ``r`` exceeds ``MAX_PISTON_SPEED``."""
    c = 2.0 * w * r / math.pi
    if c > MAX_PISTON_SPEED:
        raise InputError(
            f"at {w * 30 / math.pi:.6g} rpm a stroke of {2 * r * 1e3:.6g} mm gives a mean piston speed of "
            f"{c:.4g} m/s, beyond the accepted {MAX_PISTON_SPEED:g} m/s (docs/limits.md, physical range): "
            "check the speed and the stroke",
            file=file,
            key=key,
        )
