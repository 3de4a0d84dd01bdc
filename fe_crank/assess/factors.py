"""Endurance-limit modifying factors of the part (Marin factors), after Shigley.

Source: Budynas & Nisbett, *Shigley's Mechanical Engineering Design*, 10th ed. (2015),
section 6-9, eq. 6-18: S_e = k_a k_b k_c k_d k_e k_f S'_e.  Here:

* k_a, surface (eq. 6-19, table 6-2): k_a = a R_m^b, R_m in MPa, with
  ground a = 1.58, b = -0.085; machined or cold-drawn 4.51, -0.265 (also a drilled hole);
  hot-rolled 57.7, -0.718; as-forged 272, -0.995.  Capped at 1 (a polished specimen).
  Per assessed location (``Material.surface``): the shaft fillets take the load case's
  common finish (default machined), the oil-bore outlet is drilled and the counterweight's
  transition fillet as forged unless the load case states otherwise ([material.surface]).
* k_b, size (eq. 6-20, rotating round section of diameter d):
  k_b = 1.24 d^-0.107 for 2.79 <= d <= 51 mm, 1.51 d^-0.157 for 51 < d <= 254 mm,
  1 below 2.79 mm; above 254 mm the 254-mm value.  The crank's sections are loaded
  in a direction fixed to the throw: the full diameter is used (not Shigley's
  non-rotating equivalent 0.370 d, eq. 6-24, which would give a larger, less
  conservative k_b).  Without a diameter: the 254-mm value, 0.633 (lowest of the range).
* k_e, reliability (table 6-5): k_e = 1 - 0.08 z_a, z_a the standard normal quantile
  of the reliability (0.50 -> 1.000, 0.90 -> 0.897, 0.99 -> 0.814, 0.999 -> 0.753);
  the library fatigue limits (0.5 R_m, eq. 6-8) are mean values.
* k_treatment: surface treatment (rolling, induction hardening), given by the user.
* notch support n (FKM guideline, 6th ed. 2012, section 4.3.1.3.2, n_sigma >= 1 from
  the relative stress gradient): given by the user, default 1 (no credit).  It applies
  to the FE route, whose peak stresses carry the full elastic K_t.
"""

from __future__ import annotations

from dataclasses import dataclass
from statistics import NormalDist

from fe_crank.io.material import Material

#: Shigley table 6-2: surface finish -> (a [MPa], b)
SURFACE = {
    "ground": (1.58, -0.085),
    "machined": (4.51, -0.265),
    "hot_rolled": (57.7, -0.718),
    "as_forged": (272.0, -0.995),
    "drilled": (4.51, -0.265),  # a drilled hole: table 6-2's machined
}
#: size factor used when the section diameter is unknown (eq. 6-20 at 254 mm)
SIZE_FALLBACK_DIAMETER = 0.254


def surface_factor(finish: str, tensile: float) -> float:
    """k_a = a R_m^b (Shigley eq. 6-19, table 6-2), R_m in Pa, not above 1."""
    a, b = SURFACE[finish]
    return min(1.0, float(a * (tensile / 1e6) ** b))


def size_factor(diameter: float | None) -> float:
    """k_b (Shigley eq. 6-20) for a round section of ``diameter`` m (None: 254 mm)."""
    d = (SIZE_FALLBACK_DIAMETER if diameter is None else diameter) * 1e3
    d = min(d, 254.0)
    if d < 2.79:
        return 1.0
    if d <= 51.0:
        return float(1.24 * d**-0.107)
    return float(1.51 * d**-0.157)


def reliability_factor(reliability: float) -> float:
    """k_e = 1 - 0.08 z_a (Shigley table 6-5), z_a the normal quantile of ``reliability``."""
    if not 0.5 <= reliability < 1.0:
        raise ValueError(f"reliability must be in [0.5, 1), got {reliability}")
    return 1.0 - 0.08 * NormalDist().inv_cdf(reliability)


@dataclass(frozen=True)
class FatigueFactors:
    """The factors applied to the specimen fatigue limits of one section."""

    surface: float
    size: float
    reliability: float
    treatment: float
    notch_support: float
    diameter: float | None  # m, section diameter the size factor was taken for
    surface_basis: str = ""  # the finish, or "given: <reason>"

    @property
    def product(self) -> float:
        return self.surface * self.size * self.reliability * self.treatment * self.notch_support


def location_of(group: str) -> str | None:
    """The surface location of an assessed group: ``crankpin_fillet_2`` -> ``crankpin_fillet``,
    ``oil_bore`` -> ``oil_bore``; None for a group without a surface of its own (a subdomain)."""
    for loc in ("crankpin_fillet", "journal_fillet", "oil_bore", "counterweight_fillet"):
        if group == loc or group.startswith(loc + "_"):
            return loc
    return None


def factors(material: Material, diameter: float | None = None, location: str | None = None) -> FatigueFactors:
    """The factors of ``material`` (``fe_crank.io.material.Material``) for a section of
    ``diameter`` at ``location`` (``location_of``; None: the shaft fillets' common surface):
    given values win over the computed ones (surface from the location's finish and R_m,
    size from the diameter)."""
    surf = material.surface(location)
    if surf.factor is not None:
        ks, basis = surf.factor, f"given {surf.factor:g}: {surf.reason}"
    elif material.tensile_strength is not None:
        if surf.finish is None:  # a Surface gives a finish or a factor (io.material)
            raise ValueError(f"material {material.name}: the surface at {location} gives neither a finish nor a factor")
        ks, basis = surface_factor(surf.finish, material.tensile_strength), surf.finish
    else:
        ks, basis = 1.0, "no tensile strength: none"
    kb = material.size_factor if material.size_factor is not None else size_factor(diameter)
    return FatigueFactors(
        ks,
        kb,
        reliability_factor(material.reliability),
        material.treatment_factor,
        material.notch_support_factor,
        None if material.size_factor is not None else diameter,
        basis,
    )


__all__ = [
    "SURFACE",
    "surface_factor",
    "size_factor",
    "reliability_factor",
    "FatigueFactors",
    "factors",
    "location_of",
    "material_rows",
]


def material_rows(material: object) -> list[list[str]]:
    """Rows (name, value and source) of the factors for the report's material table (none
    for anything but a ``Material``)."""
    if not isinstance(material, Material):
        return []
    ff = factors(material, None)
    ka = []
    for loc in ("crankpin_fillet", "journal_fillet", "oil_bore", "counterweight_fillet"):
        f = factors(material, None, loc)
        how = f.surface_basis if f.surface_basis.startswith("given") else f"{f.surface_basis}, Shigley eq. 6-19"
        ka.append([f"surface factor k_a, {loc.replace('_', ' ')}", f"{f.surface:.3f} ({how})"])
    kb = (
        f"{material.size_factor:.3f} (given)"
        if material.size_factor is not None
        else "per section from its diameter (Shigley eq. 6-20; see the fatigue table)"
    )
    return ka + [
        ["size factor k_b", kb],
        ["reliability factor k_e", f"{ff.reliability:.3f} ({material.reliability:.4g}, Shigley table 6-5)"],
        ["treatment factor", f"{ff.treatment:.3f}"],
        ["notch support factor", f"{ff.notch_support:.3f} (FE route; 1 = no credit)"],
    ]
