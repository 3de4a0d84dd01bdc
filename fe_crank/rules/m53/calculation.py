"""IACS UR M53 "Calculation of crankshafts for I.C. engines", Rev.1 (Dec 2004).

The empirical route beside the FE one: nominal alternating stresses from the statically
determinate model of one throw (supports at the main-bearing centres), empirical stress
concentration factors (section 3, valid inside a stated range), the equivalent
alternating stress (section 5), the fatigue strength (section 6) and the acceptability
factor Q (section 7, Q >= 1.15).  The empirical formulas are unchanged in Rev.2
(Jan 2011), which only adds the FE alternative for the SCFs (its Appendix III); that is
what ``fe_crank`` uses outside the validity range.

The formulas are in the rule's units: lengths in mm, stresses in N/mm^2 (MPa).  The
public functions here take and return SI (m, Pa) and convert inside.  Checked against
the rule text as the Korean Register reproduces it clause by clause (Rules for the
Classification of Steel Ships, Pt 5, Annex 5-3, 2025), which also gives K_e (2.1.2.1,
``ke_factor``).  The SCFs of section 3 and their validity range are in ``m53_scf`` (and
re-exported here).

Related dimensions (section 3.1, all divided by the crankpin diameter D):
r = R_H/D (pin fillet) or R_G/D (journal fillet), s = S/D (S: pin/journal overlap,
S = (D + D_G)/2 - crank radius), w = W/D (web thickness), b = B/D (web width),
d_G = D_BG/D, d_H = D_BH/D (bores), t_H = T_H/D, t_G = T_G/D (fillet recesses).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from typing import Protocol

import numpy as np
from numpy.typing import ArrayLike

from fe_crank.rules.m53.scf_empirical import (  # noqa: F401  (re-exported: the rule's SCFs)
    F_B_CUBIC,
    VALIDITY,
    alpha_b,
    alpha_t,
    beta_b,
    beta_q,
    beta_t,
    out_of_range,
)

#: the rods' loads on one crankpin: (force (n, 2) N over the cycle, place on the pin m) per
#: rod (``fe.throw.pin_patches``)
RodLoads = Sequence[tuple[ArrayLike, float]]


class M53Material(Protocol):
    """What UR M53 reads from a material (``io.material.Material``; SI)."""

    @property
    def tensile_strength(self) -> float | None: ...
    @property
    def m53_k(self) -> float | None: ...
    @property
    def forging(self) -> str | None: ...
    @property
    def kind(self) -> str | None: ...


@dataclass(frozen=True)
class M53Geometry:
    """Throw dimensions for UR M53, SI (m).  ``bearing_to_web`` is the axial distance
    from a main-bearing centre to the web centre line (for the web bending moment)."""

    pin_diameter: float  # D
    journal_diameter: float  # D_G
    crank_radius: float
    web_thickness: float  # W (axial)
    web_width: float  # B (at the pin/journal overlap)
    pin_fillet_radius: float  # R_H
    journal_fillet_radius: float  # R_G
    bearing_to_web: float
    pin_bore: float = 0.0  # D_BH
    journal_bore: float = 0.0  # D_BG
    pin_recess: float = 0.0  # T_H
    journal_recess: float = 0.0  # T_G
    pin_length: float = 0.0  # L_pin, axial (for the oil-bore outlet's bending arm)
    oil_bore_diameter: float = 0.0  # D_O (0: no oil bore)
    oil_bore_angle: float = 0.0  # rad, from the radial (+y) towards the tangential (+x) direction

    @property
    def overlap(self) -> float:
        """S = (D + D_G)/2 - R (UR M53 3.1)."""
        return 0.5 * (self.pin_diameter + self.journal_diameter) - self.crank_radius

    def related(self, fillet: str) -> dict[str, float]:
        """Related dimensions of UR M53 3.1 for ``fillet`` in ("pin", "journal")."""
        d = self.pin_diameter
        rad = self.pin_fillet_radius if fillet == "pin" else self.journal_fillet_radius
        return {
            "r": rad / d,
            "s": max(self.overlap / d, -0.5),
            "w": self.web_thickness / d,
            "b": self.web_width / d,
            "dG": self.journal_bore / d,
            "dH": self.pin_bore / d,
            "tH": self.pin_recess / d,
            "tG": self.journal_recess / d,
        }


def fatigue_strength(tensile: float, diameter: float, fillet_radius: float, k: float) -> float:
    """sigma_DW = K (0.42 R_m + 39.3) [0.264 + 1.073 D^-0.2 + (785 - R_m)/4900 + (196/R_m) sqrt(1/R_X)].

    UR M53 Rev.1 section 6, fillets: D the pin (or journal) diameter, R_X the fillet
    radius (not taken below 2 mm), R_m in MPa, lengths in mm inside.  SI in and out.
    """
    rm = tensile / 1e6
    d = diameter * 1e3
    rx = max(fillet_radius * 1e3, 2.0)
    value: float = (
        1e6
        * k
        * (0.42 * rm + 39.3)
        * (0.264 + 1.073 * d**-0.2 + (785.0 - rm) / 4900.0 + (196.0 / rm) * math.sqrt(1.0 / rx))
    )
    return value


def equivalent_stress(bending: float, torsion: float, additional: float) -> float:
    """sigma_V = sqrt((sigma_B + sigma_add)^2 + 3 tau^2) (UR M53 Rev.1 section 5.2)."""
    return math.sqrt((abs(bending) + additional) ** 2 + 3.0 * torsion**2)


#: K_e of UR M53 2.1.2.1: "empirical factor considering to some extent the influence of
#: adjacent crank and bearing restraint", on the web's nominal bending and compressive
#: stresses only (not on the oil-bore outlet's sigma_BON of 2.1.2.2, nor on torsion)
KE = {2: 0.8, 4: 1.0}


def ke_factor(strokes: int) -> float:
    """K_e = 0.8 for two-stroke, 1.0 for four-stroke engines (UR M53 2.1.2.1)."""
    try:
        return KE[int(strokes)]
    except (KeyError, ValueError, TypeError):
        raise ValueError(f"UR M53 K_e is defined for 2- and 4-stroke engines, not strokes = {strokes!r}") from None


@dataclass(frozen=True)
class NominalStresses:
    """Nominal alternating stresses (amplitudes, Pa) of UR M53 section 2; ``bending`` and
    ``shear`` include K_e (``ke``, 2.1.2.1)."""

    bending: float  # sigma_BFN = K_e M_BRFN / W_eqw, web section W_eqw = B W^2 / 6
    shear: float  # sigma_QFN = K_e Q_RFN / F, web section F = B W
    torsion_pin: float  # tau_N = M_TN / W_P, W_P = pi/16 (D^4 - D_BH^4)/D
    torsion_journal: float  # same with D_G, D_BG
    ke: float = 1.0  # K_e of 2.1.2.1 (0.8 two-stroke, 1.0 four-stroke)


def half_range(x: ArrayLike) -> float:
    x = np.asarray(x, float)
    return 0.5 * float(x.max() - x.min())


def nominal_stresses(
    geo: M53Geometry, radial_force: ArrayLike, torque: ArrayLike, *, ke: float = 1.0
) -> NominalStresses:
    """Nominal alternating stresses from the cycle of the radial pin force and the torque.

    Statically determinate throw (UR M53 2.1.1): supports at the main-bearing centres,
    each carries half of the radial force; the web bending moment at the web centre
    line is M_BR = (F_R/2) a (a = ``bearing_to_web``) and the web shear force
    Q_R = F_R/2.  Amplitudes are half the range over the cycle (2.1.2.1):
    sigma_BFN = K_e M_BRFN / (B W^2/6), sigma_QFN = K_e Q_RFN / (B W), K_e = 0.8 for
    two-stroke and 1.0 for four-stroke engines (``ke_factor``); tau_N = M_TN / W_P (2.2.2).
    The torque is a journal torque from the dynamics stage (``assess_throw`` passes the
    side with the larger alternating part); torsional
    vibration is NOT included (UR M53 asks for it from a forced-vibration calculation).
    """
    a = geo.bearing_to_web
    m_bn = half_range(0.5 * a * np.asarray(radial_force, float))
    q_n = half_range(0.5 * np.asarray(radial_force, float))
    m_tn = half_range(torque)
    w_eq = geo.web_width * geo.web_thickness**2 / 6.0
    area = geo.web_width * geo.web_thickness
    wp_pin = math.pi / 16.0 * (geo.pin_diameter**4 - geo.pin_bore**4) / geo.pin_diameter
    wp_jou = math.pi / 16.0 * (geo.journal_diameter**4 - geo.journal_bore**4) / geo.journal_diameter
    return NominalStresses(ke * m_bn / w_eq, ke * q_n / area, m_tn / wp_pin, m_tn / wp_jou, ke)


@dataclass(frozen=True)
class M53Fillet:
    """UR M53 result for one fillet."""

    fillet: str  # "pin" or "journal"
    scf_source: str  # "empirical (UR M53 3.2/3.3)" or "FE (...)"
    scf_bending: float
    scf_shear: float  # journal only (beta_Q); 0 for the pin
    scf_torsion: float
    bending: float  # Pa, alternating
    torsion: float  # Pa, alternating
    equivalent: float  # sigma_V, Pa
    fatigue_strength: float  # sigma_DW, Pa
    acceptability: float  # Q
    out_of_range: tuple[str, ...] = ()
    scf_accepted: bool = True  # False: FE SCFs of a mesh UR M53 App. III does not accept (no verdict)


def assess_fillet(
    geo: M53Geometry,
    nominal: NominalStresses,
    fillet: str,
    *,
    tensile: float,
    k: float,
    additional: float = 10e6,
    fe_scf: dict[str, float] | None = None,
) -> M53Fillet:
    """UR M53 for one fillet.  Outside the validity range the FE SCFs ``fe_scf``
    (keys ``bending``, ``shear``, ``torsion``) are used and the result says so; if they
    are not given either, a ValueError names the out-of-range dimensions."""
    rel = geo.related(fillet)
    bad = out_of_range(rel)
    if not bad:
        if fillet == "pin":
            scf = {"bending": alpha_b(rel), "shear": 0.0, "torsion": alpha_t(rel)}
        else:
            r_g = geo.journal_fillet_radius / geo.journal_diameter  # beta_T: r = R_G/D_G (3.3)
            scf = {"bending": beta_b(rel), "shear": beta_q(rel), "torsion": beta_t(rel, r_g)}
        source = f"empirical, UR M53 Rev.1 {'3.2' if fillet == 'pin' else '3.3'}"
    elif fe_scf is not None:
        scf = {"bending": fe_scf["bending"], "shear": fe_scf.get("shear", 0.0), "torsion": fe_scf["torsion"]}
        source = "FE (geometry outside the UR M53 validity range: " + "; ".join(bad) + ")"
    else:
        raise ValueError(
            f"{fillet} fillet outside the UR M53 validity range ({'; '.join(bad)}) "
            "and no FE stress concentration factors given"
        )
    tau_n = nominal.torsion_pin if fillet == "pin" else nominal.torsion_journal
    bending = scf["bending"] * nominal.bending + scf["shear"] * nominal.shear
    torsion = scf["torsion"] * tau_n
    sv = equivalent_stress(bending, torsion, additional)
    diameter = geo.pin_diameter if fillet == "pin" else geo.journal_diameter
    radius = geo.pin_fillet_radius if fillet == "pin" else geo.journal_fillet_radius
    sdw = fatigue_strength(tensile, diameter, radius, k)
    return M53Fillet(
        fillet,
        source,
        scf["bending"],
        scf["shear"],
        scf["torsion"],
        bending,
        torsion,
        sv,
        sdw,
        sdw / sv if sv > 0 else math.inf,
        tuple(bad),
    )


def web_section_modulus(geo: M53Geometry) -> float:
    """W_eqw = B W^2 / 6, the web section for the nominal bending stress (UR M53 2.1.2.1), m^3."""
    return geo.web_width * geo.web_thickness**2 / 6.0


def web_area(geo: M53Geometry) -> float:
    """F = B W, the web section for the nominal shear stress (UR M53 2.1.2.2), m^2."""
    return geo.web_width * geo.web_thickness


def polar_section_modulus(geo: M53Geometry, fillet: str) -> float:
    """W_P = pi/16 (D^4 - D_BH^4)/D (pin) or pi/16 (D_G^4 - D_BG^4)/D_G (journal) (UR M53 2.2.2), m^3."""
    d, bore = (geo.pin_diameter, geo.pin_bore) if fillet == "pin" else (geo.journal_diameter, geo.journal_bore)
    return math.pi / 16.0 * (d**4 - bore**4) / d


def scf_mode_needed(material: M53Material | None, geometries: Iterable[M53Geometry | None]) -> bool:
    """Whether UR M53's empirical SCFs are outside their validity range (3.2, 3.3) for the
    pin or journal fillet of one of ``geometries`` (``M53Geometry`` or None, one per throw
    model), with UR M53 run at all (``material``: a ``Material`` with a tensile strength and
    the rule's k): the SCF mode of the FE appendix (App. III) then gives the factors
    (``rules.m53.scf_mode``)."""
    if material is None or material.tensile_strength is None or material.m53_k is None:
        return False
    return any(out_of_range(g.related(f)) for g in geometries if g is not None for f in ("pin", "journal"))
