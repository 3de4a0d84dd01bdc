"""Hodograph of a harmonic plane vector: ellipse, tilt, co- and counter-rotating parts.

A resultant of order ``k`` written as (Liventsev, engines with complex kinematic schemes, eqs. 152-157 and 112-117)::

    Fx = a cos k theta + b sin k theta
    Fy = c cos k theta + d sin k theta

traces an ellipse.  With ``B = ac + bd``, ``C = a^2 + b^2``, ``A = c^2 + d^2`` the
principal axes are tilted from ``+x`` (towards ``+y``) by ``delta`` with
``tan 2 delta = 2 B / (C - A)`` (Liventsev, eqs. 112-114, 125; the tests use it as the
independent check).  The package takes the other route: the vector is the sum of a
co-rotating vector (turning with the reference shaft, i.e. in the positive angle sense of
``fe_crank.model``) and a counter-rotating one; their lengths ``p`` and ``q`` give the
semi-axes ``p + q`` and ``|p - q|`` and their directions the major axis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

#: the shape of a hodograph: a point at the origin, a line through it, a circle, an ellipse
HodographKind = Literal["zero", "line", "circle", "ellipse"]

#: relative size below which an axis is taken as zero (degenerate ellipse)
DEGENERATE_RTOL = 1e-9


@dataclass(frozen=True)
class Hodograph:
    """Ellipse traced by ``(a cos k t + b sin k t, c cos k t + d sin k t)``.

    ``kind`` is ``"zero"`` (no resultant), ``"line"`` (a straight-line oscillation,
    minor axis zero), ``"circle"`` (a pure rotating vector) or ``"ellipse"``.
    ``tilt`` is the angle of the major axis from ``+x`` towards ``+y`` (rad, in
    ``(-pi/2, pi/2]``), i.e. Liventsev's delta.  ``co_magnitude`` / ``counter_magnitude``
    are the lengths of the co- and counter-rotating vectors and ``co_angle`` /
    ``counter_angle`` their directions at ``theta = 0`` in the engine's angle
    convention (from ``+y`` towards ``+x``).
    """

    a: float
    b: float
    c: float
    d: float
    major: float
    minor: float
    tilt: float
    co_magnitude: float
    co_angle: float
    counter_magnitude: float
    counter_angle: float
    kind: HodographKind

    def as_dict(self) -> dict:
        return {
            "coefficients": {"a": self.a, "b": self.b, "c": self.c, "d": self.d},
            "kind": self.kind,
            "semi_major": self.major,
            "semi_minor": self.minor,
            "tilt_deg": math.degrees(self.tilt),
            "co_rotating": {"magnitude": self.co_magnitude, "angle_deg": math.degrees(self.co_angle)},
            "counter_rotating": {"magnitude": self.counter_magnitude, "angle_deg": math.degrees(self.counter_angle)},
        }


def rotating_parts(a: float, b: float, c: float, d: float) -> tuple[complex, complex]:
    """Split into co- and counter-rotating vectors.

    With ``w = Fy + i Fx`` (so that a direction at angle ``psi`` from ``+y`` towards ``+x``
    is ``exp(i psi)``), ``w = P exp(i k theta) + Q exp(-i k theta)`` and

    ``P = ((c + b) + i (a - d)) / 2``,  ``Q = ((c - b) + i (a + d)) / 2``.
    """
    p = complex(c + b, a - d) / 2.0
    q = complex(c - b, a + d) / 2.0
    return p, q


def hodograph(a: float, b: float, c: float, d: float) -> Hodograph:
    """Describe the ellipse of one order's resultant (see module docstring)."""
    a, b, c, d = float(a), float(b), float(c), float(d)
    p, q = rotating_parts(a, b, c, d)
    pm, qm = abs(p), abs(q)
    major, minor = pm + qm, abs(pm - qm)
    scale = max(major, 1e-300)
    # |a|, |b|, |c|, |d| <= p + q = major, so only an exactly zero resultant is "zero"
    # (fe_crank.balance.forces clears round-off to exact zeros before this)
    kind: HodographKind
    if major <= 1e-300:
        kind = "zero"
    elif minor <= DEGENERATE_RTOL * scale:
        kind = "line"
    elif min(pm, qm) <= DEGENERATE_RTOL * scale:
        kind = "circle"
    else:
        kind = "ellipse"
    # major axis direction: where P e^{ikt} and Q e^{-ikt} line up, angle (arg P + arg Q)/2
    # measured from +y towards +x; convert to Liventsev's angle from +x towards +y.
    if kind in ("zero", "circle"):
        tilt = 0.0
    else:
        # here both p and q are non-zero (a zero one makes the kind "circle")
        psi = 0.5 * (math.atan2(p.imag, p.real) + math.atan2(q.imag, q.real))
        tilt = math.pi / 2.0 - psi
        tilt = (tilt + math.pi / 2.0) % math.pi - math.pi / 2.0
        if tilt <= -math.pi / 2.0 + 1e-15:
            tilt += math.pi
    return Hodograph(
        a,
        b,
        c,
        d,
        major,
        minor,
        tilt,
        pm,
        math.atan2(p.imag, p.real),
        qm,
        math.atan2(q.imag, q.real),
        kind,
    )
