"""VDI 2230 Part 1 (2015), "Systematic calculation of highly stressed bolted joints", for one
bolt, concentrically or eccentrically clamped and loaded: the formulas, SI in and out.

* Thread (ISO 68-1, ISO 724): d_2 = d - 0.64952 P, d_3 = d - 1.22687 P, stress area
  A_s = pi/4 ((d_2 + d_3)/2)^2, A_d3 = pi/4 d_3^2, A_N = pi/4 d^2 (VDI 2230 5.1.1, 5.5.1).
* Elastic resilience of the bolt (5.1.1): delta_S = delta_SK + delta_shank + delta_Gew +
  delta_G + delta_M, head l_SK = 0.5 d over A_N, free loaded thread over A_d3, engaged thread
  l_G = 0.5 d over A_d3, nut l_M = 0.4 d (through-bolted, DSV) or tapped thread
  l_M = 0.33 d (ESV) over A_N with the nut's (the tapped part's) modulus.
* Elastic resilience of the clamped parts (5.1.2, deformation cone and sleeve):
  tan(phi) = 0.362 + 0.032 ln(beta_L/2) + 0.153 ln(y) (DSV) or 0.348 + 0.013 ln(beta_L) +
  0.193 ln(y) (ESV), beta_L = l_K/d_W, y = D_A/d_W; D_A,Gr = d_W + w l_K tan(phi), w = 1 DSV,
  2 ESV; with D_A >= D_A,Gr the cones alone (eq. 5.1/50), d_W < D_A < D_A,Gr cones and a
  sleeve (5.1/55), D_A <= d_W a sleeve.
* Load factor Phi_K = delta_P / (delta_S + delta_P) (5.3.1), Phi_n = n Phi_K.
* Amount of embedding f_Z (table 5.4/1) and the preload loss F_Z = f_Z / (delta_S + delta_P).
* Permissible assembly preload (R7, 5.5.1): F_M,zul = A_0 nu R_p0.2 / sqrt(1 + 3 [3/2
  d_2/d_0 (P/(pi d_2) + 1.155 mu_G)]^2), A_0 = A_s, d_0 = d_s, nu = 0.9; the assembly
  stresses sigma_M = F_M/A_0, tau_M = M_G/W_p, M_G = F_M d_2/2 (P/(pi d_2) + 1.155 mu_G), with
  the fully plastic W_p = pi d_0^3/12 that the factor 3/2 of F_M,zul stands for (so a bolt
  tightened to F_M,zul is at nu exactly); tightening torque
  M_A = F_M (0.16 P + 0.58 d_2 mu_G + D_Km/2 mu_K).
* Working stress (R8, 5.5.2): sigma_red,B = sqrt(sigma_z^2 + 3 (k_tau tau)^2), k_tau = 0.5,
  tau = M_G/W_p with the elastic W_p = pi d_0^3/16.
* Fatigue (R9, 5.5.3): sigma_ASV = 0.85 (150/d + 45) N/mm^2 (d in mm, d <= 40 mm; rolled
  before heat treatment), rolled after: sigma_ASG = (2 - F_Sm/F_0.2min) sigma_ASV.

Eccentric clamping and loading (5.1.2 and 5.3: R2, R3, R5, R9; ``Eccentric``).  In the plane of
the eccentricity a coordinate xi runs across the interface from the axis O-O of the
substitutional deformation body (the interface's centroid axis); the bolt axis lies at
xi = s_sym, the working load F_A acts at xi = a, a working moment M_B counts positive when it
opens the edge at xi = +u (the same sense as F_A a).  Then (VDI 2230's own signs: s_sym, a, u
positive on the side of the edge U that opens first):
* delta_P* = delta_P + s_sym^2 l_K / (E_P I_Bers), delta_P** = delta_P + a s_sym l_K / (E_P I_Bers)
  (R3: the clamped parts' resilience under the bolt's eccentric clamp load and under the
  eccentric working load);
* Phi_en* = n delta_P** / (delta_S + delta_P*) (R3), Phi_m* = n s_sym l_K /
  (E_P I_Bers (delta_S + delta_P*)) for the moment (R3); the additional bolt load
  F_SA = Phi_en* F_A + Phi_m* M_B;
* opening limit (R2, F_KA = F_Kab): F_Kab = (F_A (a u - s_sym u) + M_B u) / (I_BT/A_D + s_sym u);
  the joint does not open while the residual clamp load exceeds it (R5: F_M,min >= F_Kerf +
  (1 - Phi_en*) F_A + F_Z);
* bolt bending (R9, eccentric loading): sigma_SAb = F_SA/A_S + (l_K/l_ers) (E_S/E_P) (d_S/(2 I_Bers))
  (F_A a + M_B - F_SA s_sym), which for M_B = 0 is VDI 2230's
  [1 + (1/Phi_en* - s_sym/a) (l_K/l_ers) (E_S/E_P) pi a d_S^3/(8 I_Bers)] Phi_en* F_A/A_S
  (with A_S = pi d_S^2/4): the clamped parts turn by (F_A a + M_B - F_SA s_sym) l_K/(E_P I_Bers)
  and the bolt, of bending length l_ers, turns with them;
* the substitutional moment of inertia of a prismatic deformation body as wide as the
  interface (R3): I_Bers = I_BT = b_T c_T^3/12 - pi d_h^4/64, A_D = b_T c_T - pi d_h^2/4.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fe_crank.geometry.spec import COARSE_PITCH_MM

#: ISO 898-1 lower yield strength R_p0.2 (Pa) of the property classes (8.8: d <= 16 / > 16 mm)
PROPERTY_CLASS_RP02 = {"8.8": (640e6, 660e6), "10.9": (940e6, 940e6), "12.9": (1100e6, 1100e6)}
#: VDI 2230 table 5.4/1: amounts of embedding (um) per thread, per head or nut bearing, per
#: inner interface, for mean roughness Rz classes, loaded in tension / in shear
EMBEDDING_UM = {
    "below_10": {"tension": (3.0, 2.5, 1.5), "shear": (3.0, 3.0, 2.0)},
    "10_to_40": {"tension": (3.0, 3.0, 2.0), "shear": (3.0, 4.5, 2.5)},
    "40_to_160": {"tension": (3.0, 4.0, 3.0), "shear": (3.0, 6.5, 3.5)},
}
NU_ASSEMBLY = 0.9  # VDI 2230 R7: utilisation of the yield point in assembly
K_TAU = 0.5  # VDI 2230 R8: reduction of the torsional stress in service


def thread(d: float, pitch: float) -> dict[str, float]:
    """d_2, d_3, d_s (= d_0), A_s, A_d3, A_N of an ISO metric thread (m, m^2)."""
    d2, d3 = d - 0.64952 * pitch, d - 1.22687 * pitch
    ds = 0.5 * (d2 + d3)
    return {
        "d2": d2,
        "d3": d3,
        "ds": ds,
        "As": math.pi / 4 * ds**2,
        "Ad3": math.pi / 4 * d3**2,
        "AN": math.pi / 4 * d**2,
    }


def bolt_resilience(
    d: float,
    pitch: float,
    clamp_length: float,
    e_bolt: float,
    e_nut: float,
    *,
    tapped: bool,
    shank_length: float = 0.0,
    shank_diameter: float | None = None,
) -> float:
    """delta_S (m/N), VDI 2230 5.1.1: hexagon head, an unthreaded shank of ``shank_length``
    (diameter ``shank_diameter``, default d) inside the clamp length, the rest free loaded
    thread, the engaged thread and the nut or tapped thread (``tapped``: ESV)."""
    t = thread(d, pitch)
    a_shank = math.pi / 4 * (shank_diameter or d) ** 2
    l_gew = clamp_length - shank_length
    d_sk = 0.5 * d / (e_bolt * t["AN"])
    d_shank = shank_length / (e_bolt * a_shank)
    d_gew = l_gew / (e_bolt * t["Ad3"])
    d_g = 0.5 * d / (e_bolt * t["Ad3"])
    d_m = (0.33 if tapped else 0.4) * d / (e_nut * t["AN"])
    return d_sk + d_shank + d_gew + d_g + d_m


def cone_tangent(clamp_length: float, bearing_diameter: float, outer_diameter: float, *, tapped: bool) -> float:
    """tan(phi) of the deformation cone, VDI 2230 5.1.2.2 (DSV or ESV)."""
    beta_l, y = clamp_length / bearing_diameter, outer_diameter / bearing_diameter
    if tapped:
        return 0.348 + 0.013 * math.log(beta_l) + 0.193 * math.log(y)
    return 0.362 + 0.032 * math.log(beta_l / 2) + 0.153 * math.log(y)


def plate_resilience(
    clamp_length: float,
    bearing_diameter: float,
    hole_diameter: float,
    outer_diameter: float,
    e_plate: float,
    *,
    tapped: bool,
) -> float:
    """delta_P (m/N) of the clamped parts, VDI 2230 5.1.2.2 (cones, cones and sleeve, sleeve)."""
    lk, dw, dh, da = clamp_length, bearing_diameter, hole_diameter, outer_diameter
    if not dh < dw:
        raise ValueError("the hole must be smaller than the head bearing diameter")
    if da <= dw:
        return 4.0 * lk / (e_plate * math.pi * (da**2 - dh**2))
    w = 2.0 if tapped else 1.0
    tphi = cone_tangent(lk, dw, da, tapped=tapped)
    d_gr = dw + w * lk * tphi
    if da >= d_gr:
        arg = (dw + dh) * (d_gr - dh) / ((dw - dh) * (d_gr + dh))
        return 2.0 * math.log(arg) / (w * e_plate * math.pi * dh * tphi)
    cones = 2.0 / (w * dh * tphi) * math.log((dw + dh) * (da - dh) / ((dw - dh) * (da + dh)))
    sleeve = 4.0 / (da**2 - dh**2) * (lk - (da - dw) / (w * tphi))
    return (cones + sleeve) / (e_plate * math.pi)


def embedding(roughness: str, loading: str, *, tapped: bool, inner_interfaces: int = 1) -> float:
    """f_Z (m): one thread, the head bearing (and the nut bearing, through-bolted), the inner
    interfaces, VDI 2230 table 5.4/1."""
    th, bearing, inner = EMBEDDING_UM[roughness][loading]
    return 1e-6 * (th + bearing * (1 if tapped else 2) + inner * inner_interfaces)


def thread_torque_lever(d: float, pitch: float, mu_g: float) -> float:
    """M_G / F_M = d_2/2 (P/(pi d_2) + 1.155 mu_G) (m), VDI 2230 5.4.2."""
    d2 = thread(d, pitch)["d2"]
    return 0.5 * d2 * (pitch / (math.pi * d2) + 1.155 * mu_g)


def permissible_preload(d: float, pitch: float, rp02: float, mu_g: float, nu: float = NU_ASSEMBLY) -> float:
    """F_M,zul (N), VDI 2230 R7 (5.5.1): the preload whose equivalent assembly stress is
    nu R_p0.2 at the thread friction mu_G (its smallest value)."""
    t = thread(d, pitch)
    k = 1.5 * t["d2"] / t["ds"] * (pitch / (math.pi * t["d2"]) + 1.155 * mu_g)
    return t["As"] * nu * rp02 / math.sqrt(1.0 + 3.0 * k**2)


def assembly_stress(d: float, pitch: float, preload: float, mu_g: float) -> tuple[float, float, float]:
    """(sigma_M, tau_M, sigma_red,M) (Pa) of an assembly preload, VDI 2230 5.5.1 (R7: the
    fully plastic W_p = pi d_0^3/12)."""
    t = thread(d, pitch)
    sigma = preload / t["As"]
    tau = preload * thread_torque_lever(d, pitch, mu_g) / (math.pi * t["ds"] ** 3 / 12.0)
    return sigma, tau, math.hypot(sigma, math.sqrt(3.0) * tau)


def working_torsion(d: float, pitch: float, preload: float, mu_g: float) -> float:
    """tau (Pa) of the thread torque in service, M_G / W_p with the elastic W_p = pi d_0^3/16
    (VDI 2230 R8, reduced there by k_tau)."""
    t = thread(d, pitch)
    return preload * thread_torque_lever(d, pitch, mu_g) / (math.pi * t["ds"] ** 3 / 16.0)


def tightening_torque(d: float, pitch: float, preload: float, mu_g: float, mu_k: float, d_km: float) -> float:
    """M_A = F_M (0.16 P + 0.58 d_2 mu_G + D_Km/2 mu_K) (N m), VDI 2230 5.4.3."""
    d2 = thread(d, pitch)["d2"]
    return preload * (0.16 * pitch + 0.58 * d2 * mu_g + 0.5 * d_km * mu_k)


def endurance_limit(d: float, *, rolled_after_heat_treatment: bool, mean_over_yield_load: float = 0.0) -> float:
    """sigma_AS (Pa), VDI 2230 R9: sigma_ASV = 0.85 (150/d + 45) N/mm^2 (d in mm) for a thread
    rolled before heat treatment; rolled after: (2 - F_Sm/F_0.2min) sigma_ASV."""
    dmm = d * 1e3
    if not dmm <= 40.0 + 1e-9:
        raise ValueError(f"VDI 2230's endurance limit holds up to M40, not d = {dmm:g} mm")
    sv = 0.85 * (150.0 / dmm + 45.0) * 1e6
    return (2.0 - mean_over_yield_load) * sv if rolled_after_heat_treatment else sv


@dataclass(frozen=True)
class Eccentric:
    """One bolt's joint in the plane of its eccentricity (module docstring; SI, m):
    the interface's width c_T (in the plane) and length b_T, the bolt's offset s_sym and the
    working load's a from the interface's centroid axis, positive towards the edge at +c_T/2."""

    width: float  # c_T
    length: float  # b_T
    s_sym: float = 0.0
    a: float = 0.0

    @property
    def centric(self) -> bool:
        return self.s_sym == 0.0 and self.a == 0.0


def interface_section(ecc: Eccentric, hole_diameter: float) -> tuple[float, float]:
    """(I_BT = I_Bers, A_D) of the interface less the bolt hole (m^4, m^2), VDI 2230 5.1.2.3."""
    c, b, dh = ecc.width, ecc.length, hole_diameter
    return b * c**3 / 12.0 - math.pi * dh**4 / 64.0, b * c - math.pi * dh**2 / 4.0


def eccentric_resiliences(
    delta_p: float, ecc: Eccentric, clamp_length: float, e_plate: float, i_bers: float
) -> tuple[float, float]:
    """(delta_P*, delta_P**) (m/N), VDI 2230 R3 (eccentric clamping and loading)."""
    k = clamp_length / (e_plate * i_bers)
    return delta_p + ecc.s_sym**2 * k, delta_p + ecc.a * ecc.s_sym * k


def eccentric_load_factors(
    delta_s: float, delta_p: float, ecc: Eccentric, clamp_length: float, e_plate: float, i_bers: float, n: float
) -> tuple[float, float]:
    """(Phi_en*, Phi_m* in 1/m) of VDI 2230 R3: the share of F_A and the
    force per unit moment M_B that the bolt takes."""
    dps, dpss = eccentric_resiliences(delta_p, ecc, clamp_length, e_plate, i_bers)
    phi_en = n * dpss / (delta_s + dps)
    phi_m = n * ecc.s_sym * clamp_length / (e_plate * i_bers * (delta_s + dps))
    return phi_en, phi_m


def opening_limit(f_a: float, m_b: float, ecc: Eccentric, u: float, i_bt: float, a_d: float) -> float:
    """F_Kab (N), VDI 2230 R2 (opening limit): the clamp load below which the edge at xi = +u
    opens under F_A at a and M_B (inf: the bolt's own eccentric clamp load lifts that edge)."""
    den = i_bt / a_d + ecc.s_sym * u
    if not den > 0:
        return math.inf
    return (f_a * (ecc.a - ecc.s_sym) * u + m_b * u) / den


def opening_limit_both_edges(f_a: float, m_b: float, ecc: Eccentric, i_bt: float, a_d: float) -> float:
    """The larger F_Kab of the interface's two edges (+c_T/2 and, mirrored, -c_T/2), >= 0."""
    u = 0.5 * ecc.width
    mirrored = Eccentric(ecc.width, ecc.length, -ecc.s_sym, -ecc.a)
    return max(0.0, opening_limit(f_a, m_b, ecc, u, i_bt, a_d), opening_limit(f_a, -m_b, mirrored, u, i_bt, a_d))


def bending_length(
    d: float, pitch: float, clamp_length: float, shank_length: float = 0.0, shank_diameter: float | None = None
) -> float:
    """l_ers (m): the bolt's substitutional bending length within the clamp length, referred
    to the stress diameter d_S (VDI 2230 5.5.3: sum of l_i (d_S/d_i)^4; the free thread at d_3,
    the shank at its diameter; the head and the engaged thread left out, which shortens l_ers
    and so raises the bending stress)."""
    t = thread(d, pitch)
    ds = t["ds"]
    return (clamp_length - shank_length) * (ds / t["d3"]) ** 4 + shank_length * (ds / (shank_diameter or d)) ** 4


def bending_stress_coefficients(
    ecc: Eccentric,
    phi_en: float,
    phi_m: float,
    d: float,
    pitch: float,
    clamp_length: float,
    l_ers: float,
    e_bolt: float,
    e_plate: float,
    i_bers: float,
) -> tuple[float, float, float, float]:
    """(k_F, k_M) of the bolt's axial stress F_SA/A_S and (b_F, b_M) of its bending stress at
    the fibre towards +xi, both linear in (F_A, M_B), VDI 2230 R9 for eccentric loading (module
    docstring): sigma_SAb = (k_F + b_F) F_A + (k_M + b_M) M_B."""
    t = thread(d, pitch)
    c = clamp_length / l_ers * e_bolt / e_plate * t["ds"] / (2.0 * i_bers)
    k_f, k_m = phi_en / t["As"], phi_m / t["As"]
    return k_f, k_m, c * (ecc.a - phi_en * ecc.s_sym), c * (1.0 - phi_m * ecc.s_sym)


__all__ = [
    "Eccentric",
    "interface_section",
    "eccentric_resiliences",
    "eccentric_load_factors",
    "opening_limit",
    "opening_limit_both_edges",
    "bending_length",
    "bending_stress_coefficients",
    "COARSE_PITCH_MM",
    "PROPERTY_CLASS_RP02",
    "EMBEDDING_UM",
    "NU_ASSEMBLY",
    "K_TAU",
    "thread",
    "bolt_resilience",
    "cone_tangent",
    "plate_resilience",
    "embedding",
    "thread_torque_lever",
    "permissible_preload",
    "assembly_stress",
    "working_torsion",
    "tightening_torque",
    "endurance_limit",
]
