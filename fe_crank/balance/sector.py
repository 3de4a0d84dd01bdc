"""Annular-sector counterweight: closed-form properties and the inverse design problem.

A sector of a flat ring (outer radius ``r1``, inner ``r2``, thickness ``b``, included
angle ``a``, density ``rho``), symmetric about its mid-line:

* mass ``m = rho b (a/2) (r1^2 - r2^2)``;
* centroid radius ``r_c = (2 sin(a/2) / (3 a/2)) (r1^3 - r2^3)/(r1^2 - r2^2)``
  (for ``a = 180 deg`` this is ``4/(3 pi) (r1^3 - r2^3)/(r1^2 - r2^2)``; Voronkov, fig. 4);
* unbalance ``U = m r_c = (2/3) rho b sin(a/2) (r1^3 - r2^3)``.

Voronkov's V4-90 pneumatic engine: ``r1 = 71``, ``r2 = 32 mm``, ``b = 19 mm``, 180 deg, 7400 kg/m^3 ->
``m = 0.887 kg`` at ``r_c = 34.3 mm``.

The inverse (``solve_sector``) solves ``U`` for one free dimension in closed form:
``b`` linearly; ``r1 = (r2^3 + U/K)^(1/3)`` and ``r2 = (r1^3 - U/K)^(1/3)`` with
``K = (2/3) rho b sin(a/2)``; the angle from ``sin(a/2) = U / ((2/3) rho b (r1^3 - r2^3))``
on the branch ``a <= 180 deg`` (``U`` is largest at 180 deg; a wider sector only adds mass).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fe_crank.errors import InputError

FREE_DIMENSIONS = ("r_outer", "r_inner", "thickness", "angle")


@dataclass(frozen=True)
class SectorProperties:
    r_outer: float
    r_inner: float
    thickness: float
    angle: float  # rad
    density: float
    mass: float  # kg
    centroid_radius: float  # m
    unbalance: float  # kg m

    def as_dict(self) -> dict:
        return {
            "r_outer_mm": self.r_outer * 1e3,
            "r_inner_mm": self.r_inner * 1e3,
            "thickness_mm": self.thickness * 1e3,
            "angle_deg": math.degrees(self.angle),
            "density_kg_m3": self.density,
            "mass_kg": self.mass,
            "centroid_radius_mm": self.centroid_radius * 1e3,
            "unbalance_kg_m": self.unbalance,
        }


def _check(r_outer, r_inner, thickness, angle, density, key="counterweight"):
    if not (r_inner >= 0.0 and r_outer > r_inner):
        raise InputError(
            f"outer radius {r_outer * 1e3:.4g} mm must exceed inner radius {r_inner * 1e3:.4g} mm >= 0", key=key
        )
    if not thickness > 0.0:
        raise InputError(f"thickness must be positive (got {thickness * 1e3:.4g} mm)", key=key)
    if not 0.0 < angle <= 2.0 * math.pi + 1e-12:
        raise InputError(f"included angle must lie in (0, 360] deg (got {math.degrees(angle):.6g} deg)", key=key)
    if not density > 0.0:
        raise InputError(f"density must be positive (got {density})", key=key)


def annular_sector(r_outer: float, r_inner: float, thickness: float, angle: float, density: float) -> SectorProperties:
    """Mass, centroid radius and unbalance of an annular-sector counterweight (module doc)."""
    _check(r_outer, r_inner, thickness, angle, density)
    half = angle / 2.0
    mass = density * thickness * half * (r_outer**2 - r_inner**2)
    unbalance = 2.0 / 3.0 * density * thickness * math.sin(half) * (r_outer**3 - r_inner**3)
    rc = unbalance / mass
    return SectorProperties(r_outer, r_inner, thickness, angle, density, mass, rc, unbalance)


def solve_sector(
    unbalance: float,
    *,
    free: str,
    r_outer: float | None = None,
    r_inner: float | None = None,
    thickness: float | None = None,
    angle: float | None = None,
    density: float,
    envelope: float | None = None,
    journal_radius: float | None = None,
    key: str = "counterweight",
) -> SectorProperties:
    """Find the ``free`` dimension giving ``unbalance`` (kg m); the others are given.

    Refuses (``InputError``) a design whose outer radius exceeds ``envelope``, whose
    inner radius lies inside ``journal_radius``, or that needs more than 360 deg (or more
    unbalance than a half ring can give).
    """
    if free not in FREE_DIMENSIONS:
        raise InputError(f"free dimension {free!r} is not one of {FREE_DIMENSIONS}", key=key)
    if not unbalance > 0.0:
        raise InputError(f"required unbalance must be positive (got {unbalance} kg m)", key=key)
    given = {"r_outer": r_outer, "r_inner": r_inner, "thickness": thickness, "angle": angle}
    missing = [k for k, v in given.items() if k != free and v is None]
    if missing:
        raise InputError(f"to solve for {free} give {', '.join(missing)}", key=key)
    if not density > 0.0:
        raise InputError(f"density must be positive (got {density})", key=key)
    # the given dimensions (checked above); the free one is nan until solved for below
    ro, ri, t, phi = (math.nan if v is None else v for v in (r_outer, r_inner, thickness, angle))
    k3 = 2.0 / 3.0 * density
    if free == "thickness":
        t = unbalance / (k3 * math.sin(phi / 2.0) * (ro**3 - ri**3))
    elif free == "r_outer":
        ro = (ri**3 + unbalance / (k3 * t * math.sin(phi / 2.0))) ** (1.0 / 3.0)
    elif free == "r_inner":
        rest = ro**3 - unbalance / (k3 * t * math.sin(phi / 2.0))
        if rest < 0.0:
            raise InputError(
                f"even a full sector out to r_outer = {ro * 1e3:.4g} mm gives only "
                f"{k3 * t * math.sin(phi / 2) * ro**3:.4g} kg m, {unbalance:.4g} kg m required",
                key=key,
            )
        ri = rest ** (1.0 / 3.0)
    else:
        s = unbalance / (k3 * t * (ro**3 - ri**3))
        if s > 1.0:
            raise InputError(
                f"needs {unbalance:.4g} kg m but a 180 deg sector of these radii and thickness gives only "
                f"{unbalance / s:.4g} kg m (a wider angle gives less): the counterweight cannot fit",
                key=key,
            )
        phi = 2.0 * math.asin(s)
    if phi > 2.0 * math.pi + 1e-12:
        raise InputError(f"needs an included angle of {math.degrees(phi):.4g} deg > 360 deg", key=key)
    if envelope is not None and ro > envelope * (1.0 + 1e-12):
        raise InputError(
            f"needs an outer radius of {ro * 1e3:.4g} mm, beyond the envelope of {envelope * 1e3:.4g} mm: "
            "the counterweight cannot provide the required unbalance; widen, thicken or use a denser material",
            key=key,
        )
    if journal_radius is not None and ri < journal_radius * (1.0 - 1e-12):
        raise InputError(
            f"needs an inner radius of {ri * 1e3:.4g} mm, inside the journal radius {journal_radius * 1e3:.4g} mm",
            key=key,
        )
    return annular_sector(ro, ri, t, phi, density)
