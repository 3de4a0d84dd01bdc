"""The bolted counterweights' VDI 2230 results in the case report (formatting only: the
joint checks are the assessment's, ``ThrowAssessment.joints``, ``fe_crank.assess.cw_joint``)."""

from __future__ import annotations

import math

from fe_crank.report.html import table

#: (header, JointCheck field, format, scale)
_COLUMNS = (
    ("preload F_M,max / F_M,min [kN]", None, "", 1.0),
    ("load factor Phi_K / Phi_en* (R3)", None, "", 1.0),
    ("eccentricity s_sym / a, interface c_T x b_T [mm]", None, "", 1.0),
    ("friction mu_G / mu_K / mu_T", None, "", 1.0),
    ("embedding loss F_Z [kN]", "embedding_loss", "{:.2f}", 1e-3),
    ("tightening torque M_A [N m]", "tightening_torque", "{:.1f}", 1.0),
    ("axial load F_A max / overspeed [kN]", None, "", 1.0),
    ("transverse load F_Q [kN]", None, "", 1.0),
    ("web's deformation onto the joint: model", None, "", 1.0),
    ("web's moment per bolt, largest [N m]", None, "", 1.0),
    ("moment M_B min / max / overspeed [N m]", None, "", 1.0),
    ("opening limit F_Kab [kN] (R2)", "opening_limit", "{:.2f}", 1e-3),
    ("R7 assembly utilisation nu", "assembly_utilisation", "{:.3f}", 1.0),
    ("R8 working safety S_F (overspeed)", "working_safety", "{:.3f}", 1.0),
    ("R9 fatigue: sigma_a (bending part) / sigma_AS [MPa]", None, "", 1.0),
    ("R9 fatigue safety S_D", "fatigue_safety", "{:.3f}", 1.0),
    ("residual clamp load F_KR,min [kN]", "residual_clamp", "{:.2f}", 1e-3),
    ("opening safety S_sep (R2/R5)", "separation_safety", "{:.3f}", 1.0),
    ("R12 slip safety S_G", "slip_safety", "{:.3f}", 1.0),
)


def _fmt(x: float, fmt: str, scale: float = 1.0) -> str:
    return "unbounded (no load)" if not math.isfinite(x) else fmt.format(x * scale)


def _cell(j, header: str, attr: str | None, fmt: str, scale: float) -> str:
    if attr is not None:
        return _fmt(float(getattr(j, attr)), fmt, scale)
    ld = j.loads
    if header.startswith("preload"):
        return f"{j.preload_max / 1e3:.2f} / {j.preload_min / 1e3:.2f}"
    if header.startswith("axial"):
        return f"{ld.axial_max / 1e3:.3f} / {ld.axial_overspeed / 1e3:.3f}"
    if header.startswith("transverse"):
        return f"{ld.transverse_max / 1e3:.3f}"
    if header.startswith("load factor"):
        return f"{j.load_factor:.3f} / {j.eccentric_load_factor:.3f}"
    if header.startswith("eccentricity"):
        e = ld.eccentric
        if e is None:
            return "centric"
        return f"{e.s_sym * 1e3:.1f} / {e.a * 1e3:.1f}, {e.width * 1e3:.1f} x {e.length * 1e3:.1f}"
    if header.startswith("friction"):
        return " / ".join(f"{mu:.2f}" for mu in j.friction)
    if header.endswith("model"):
        return ld.web_model or "none"
    if header.startswith("web's moment"):
        return f"{ld.web_moment:.3g}"
    if header.startswith("moment"):
        return f"{ld.moment_min:.3g} / {ld.moment_max:.3g} / {ld.moment_overspeed:.3g}"
    return f"{j.fatigue_amplitude / 1e6:.2f} ({j.bending_amplitude / 1e6:.2f}) / {j.endurance_limit / 1e6:.2f}"


def joint_table(throws) -> str:
    """One column per bolted counterweight (per bolt, VDI 2230 Part 1); "" without any."""
    joints = [(t.name, j) for t in throws for j in t.joints]
    if not joints:
        return ""
    header = ["VDI 2230, per bolt"] + [f"throw {t}: {j.name}" for t, j in joints]
    rows = [[h] + [_cell(j, h, attr, fmt, scale) for _, j in joints] for h, attr, fmt, scale in _COLUMNS]
    return (
        "<h3>bolted joints (VDI 2230 Part 1)</h3>"
        + table(header, rows, num_cols=set(range(1, len(header))))
        + '<p class="note">Loads per bolt, shared equally: centrifugal m r_c omega^2 over the working '
        "cycle's speed band and at the overspeed, tangential m r_c alpha with its prying lever to the joint "
        "plane; the web's deformation under the pin force and torque from the FE model's stress across the "
        "joint plane (or, where it cannot be fitted, the web's moment R (L_j + t/2) whole: an upper bound); "
        "VDI 2230's eccentric clamping and loading (Phi_en*, F_Kab, "
        "the bolt's bending in sigma_a); without a stated load introduction factor n the bounds n = 1 "
        "(bolt) and n = 0 (clamp). docs/assessment.md.</p>"
    )


__all__ = ["joint_table"]
