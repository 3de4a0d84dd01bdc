"""Cylinder gas pressure: evaluation of the p(phi) table and a parametric model.

The core always works on a :class:`fe_crank.model.GasPressure` table (absolute
pressure against the cylinder's crank angle from TDC firing).  For engines whose
sources give no indicator diagram, :func:`wiebe_cycle` builds such a table from a
closed single-zone cycle:

* intake stroke at the intake pressure, exhaust stroke at the exhaust pressure;
* from BDC (intake valve closing idealised at BDC) to BDC after firing (exhaust
  opening idealised at BDC) the first law for a closed ideal-gas system with a
  constant ratio of specific heats ``k`` (used as the polytropic exponent),
  Heywood, *Internal Combustion Engine Fundamentals* (1988), eq. 9.25::

      dp/dphi = (k - 1)/V dQ/dphi - k p/V dV/dphi

* heat release by Wiebe's function (Wiebe 1956; Heywood eq. 9.23)::

      x_b = 1 - exp(-a ((phi - phi_0)/dphi)^(m + 1)),  Q = Q_total x_b

  Without heat release the equation reduces to the polytrope ``p V^k = const``
  (compression and expansion lines).

Pneumatic engines (seed 003) give their own table: compressed-air admission and
exhaust are a p(phi) table like any other.

:func:`motored_cycle` is the same closed cycle without combustion (the overspeed check's
"motored" gas): the charge trapped at BDC (inlet valve closure idealised at BDC) at the
intake/boost pressure p_0 is compressed and re-expanded along one polytrope,
``p = p_0 (V_BDC / V(phi))^n``, so ``p_TDC = p_0 eps^n``.  n = 1.35 unless the gas data
state their own exponent: Heywood (1988), sec. 9.2, fits the compression and expansion
lines of real engines with polytropes of n = 1.3 +- 0.05; the upper end is taken so
the compression load at the firing TDC is not under-estimated.
"""

from __future__ import annotations

import numpy as np

from fe_crank import model
from fe_crank.errors import InputError
from fe_crank.mechanism.kinematics import piston_motion

__all__ = ["pressure_at", "cylinder_volume", "wiebe_cycle", "motored_cycle", "MOTORED_EXPONENT"]

#: polytropic exponent of the motored curve, Heywood (1988) sec. 9.2: n = 1.3 +- 0.05 (upper end)
MOTORED_EXPONENT = 1.35


def pressure_at(gas: model.GasPressure, angle, cycle: float) -> np.ndarray:
    """Absolute cylinder pressure at crank angles ``angle`` (rad from TDC firing).

    Linear interpolation in the table, periodic with the cycle angle ``cycle``
    (4 pi for a four-stroke, 2 pi for a two-stroke).
    """
    ang = np.mod(np.asarray(angle, dtype=float), cycle)
    return np.interp(ang, gas.angle, gas.pressure, period=cycle)


def cylinder_volume(phi, bore: float, r: float, l: float, compression_ratio: float, *, offset: float = 0.0):
    """Cylinder volume ``V = V_c + A s(phi)`` with ``V_c = V_s / (eps - 1)`` and swept
    volume ``V_s = A * stroke`` (exact slider-crank ``s``)."""
    area = np.pi * bore**2 / 4.0
    s = piston_motion(phi, r, l, 1.0, offset=offset).s
    stroke = np.sqrt((l + r) ** 2 - offset**2) - np.sqrt((l - r) ** 2 - offset**2)
    vc = area * stroke / (compression_ratio - 1.0)
    return vc + area * s


def wiebe_cycle(
    *,
    bore: float,
    r: float,
    l: float,
    compression_ratio: float,
    intake_pressure: float,
    exhaust_pressure: float,
    heat_released: float,
    combustion_start: float,
    combustion_duration: float,
    k: float = 1.35,
    wiebe_a: float = 5.0,
    wiebe_m: float = 2.0,
    strokes: int = 4,
    n: int = 1441,
    crankcase_pressure: float = 101325.0,
) -> model.GasPressure:
    """Four- or two-stroke pressure table from polytropes and Wiebe heat release.

    Parameters
    ----------
    bore, r, l : float
        Cylinder bore, crank radius, rod length, m.
    compression_ratio : float
        Geometric compression ratio ``eps > 1``.
    intake_pressure, exhaust_pressure : float
        Absolute pressures of the gas-exchange strokes, Pa; the closed cycle starts
        at BDC with the intake pressure.
    heat_released : float
        Heat released to the gas per cycle, J.
    combustion_start : float
        Start of heat release, rad relative to TDC firing (negative = before TDC).
    combustion_duration : float
        Wiebe duration ``dphi``, rad.
    k : float
        Ratio of specific heats / polytropic exponent.
    wiebe_a, wiebe_m : float
        Wiebe efficiency and form parameters (5 and 2 are Heywood's typical values).
    strokes : {2, 4}
        Two-stroke: the closed part spans BDC..BDC through TDC, gas exchange is
        idealised at BDC (exhaust pressure).

    Returns
    -------
    GasPressure
        Table over ``0 .. cycle`` (angle from TDC firing), RK4 integration of the
        first-law equation on ``n`` points.
    """
    if compression_ratio <= 1.0:
        raise InputError(f"compression_ratio must exceed 1 (got {compression_ratio})", key="gas.compression_ratio")
    if k <= 1.0:
        raise InputError(f"k must exceed 1 (got {k})", key="gas.k")
    if combustion_duration <= 0:
        raise InputError("combustion_duration must be positive", key="gas.combustion_duration")
    cycle = 4.0 * np.pi if strokes == 4 else 2.0 * np.pi

    def volume(p):
        return cylinder_volume(p, bore, r, l, compression_ratio)

    def dqdphi(p):
        x = (p - combustion_start) / combustion_duration
        x = np.clip(x, 0.0, None)
        return (
            heat_released
            * wiebe_a
            * (wiebe_m + 1.0)
            / combustion_duration
            * x**wiebe_m
            * np.exp(-wiebe_a * x ** (wiebe_m + 1.0))
        )

    # closed part: -pi .. +pi around TDC firing.  The first law's terms that depend on the
    # angle alone (the volume, its central difference, the heat release) at every RK4 node
    # (the step's start, middle and end) in one vectorised evaluation
    m = (n - 1) // 2 + 1
    phis = np.linspace(-np.pi, np.pi, m)
    steps = phis[1:] - phis[:-1]
    nodes = np.stack([phis[:-1], phis[:-1] + steps / 2, phis[1:]])  # (3, m - 1)
    dphi = 1e-6
    v = volume(nodes)
    dv = (volume(nodes + dphi) - volume(nodes - dphi)) / (2 * dphi)
    heat = (k - 1.0) / v * dqdphi(nodes)  # the heat-release term of dp/dphi
    work = k / v * dv  # dp/dphi = heat - work p
    pr = np.empty(m)
    pr[0] = intake_pressure
    for i in range(m - 1):
        h = steps[i]
        q0, q1, q2 = heat[0, i], heat[1, i], heat[2, i]
        w0, w1, w2 = work[0, i], work[1, i], work[2, i]
        k1 = q0 - w0 * pr[i]
        k2 = q1 - w1 * (pr[i] + h / 2 * k1)
        k3 = q1 - w1 * (pr[i] + h / 2 * k2)
        k4 = q2 - w2 * (pr[i] + h * k3)
        pr[i + 1] = pr[i] + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)
    # table on 0 .. cycle from TDC firing
    ang = np.linspace(0.0, cycle, n)
    closed_phi = np.where(ang <= np.pi, ang, ang - cycle)  # to -pi..pi where closed
    p = np.interp(closed_phi, phis, pr)
    if strokes == 4:
        exhaust = (ang > np.pi) & (ang <= 2 * np.pi)
        intake = (ang > 2 * np.pi) & (ang < 3 * np.pi)
        p = np.where(exhaust, exhaust_pressure, np.where(intake, intake_pressure, p))
    return model.GasPressure(
        ang, p, crankcase_pressure, source="Wiebe heat release with polytropes (fe_crank.mechanism.gas.wiebe_cycle)"
    )


def motored_cycle(
    *,
    bore: float,
    r: float,
    l: float,
    compression_ratio: float,
    intake_pressure: float,
    exhaust_pressure: float | None = None,
    n_poly: float = MOTORED_EXPONENT,
    strokes: int = 4,
    n: int = 1441,
    crankcase_pressure: float = 101325.0,
) -> model.GasPressure:
    """Pressure table of a motored cylinder (no combustion), angle from TDC firing.

    Closed part, BDC .. TDC firing .. BDC (-pi .. pi): ``p = p_0 (V(-pi)/V(phi))^n`` with
    ``p_0`` = ``intake_pressure`` (the intake/boost pressure at inlet valve closure,
    idealised at BDC) and ``V`` from :func:`cylinder_volume`; at TDC ``V(-pi)/V(0) = eps``,
    so ``p_TDC = p_0 eps^n``.  Four-stroke: exhaust stroke at ``exhaust_pressure``
    (default ``p_0``), intake stroke at ``p_0``; two-stroke: the closed part is the
    whole cycle (scavenging idealised at BDC).  ``n_poly``: polytropic exponent
    (:data:`MOTORED_EXPONENT` = 1.35, Heywood 1988 sec. 9.2).
    """
    if compression_ratio <= 1.0:
        raise InputError(f"compression_ratio must exceed 1 (got {compression_ratio})", key="gas.compression_ratio")
    if not 1.0 < n_poly < 2.0:
        raise InputError(f"the polytropic exponent must lie in (1, 2) (got {n_poly})", key="gas.k")
    if not intake_pressure > 0:
        raise InputError("intake_pressure must be a positive absolute pressure", key="gas.intake_pressure")
    p_ex = intake_pressure if exhaust_pressure is None else exhaust_pressure
    cycle = 4.0 * np.pi if strokes == 4 else 2.0 * np.pi
    ang = np.linspace(0.0, cycle, n)
    closed_phi = np.where(ang <= np.pi, ang, ang - cycle)  # -pi .. pi around TDC firing
    v_bdc = cylinder_volume(-np.pi, bore, r, l, compression_ratio)
    p = intake_pressure * (v_bdc / cylinder_volume(closed_phi, bore, r, l, compression_ratio)) ** n_poly
    if strokes == 4:
        exhaust = (ang > np.pi) & (ang <= 2 * np.pi)
        intake = (ang > 2 * np.pi) & (ang < 3 * np.pi)
        p = np.where(exhaust, p_ex, np.where(intake, intake_pressure, p))
    src = (
        f"motored: polytrope p = p_0 (V_BDC/V)^n, eps = {compression_ratio:g}, "
        f"p_0 = {intake_pressure / 1e6:.4g} MPa, n = {n_poly:g} (fe_crank.mechanism.gas.motored_cycle)"
    )
    return model.GasPressure(ang, np.asarray(p, float), crankcase_pressure, source=src)
