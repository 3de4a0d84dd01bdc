"""UR M53 stress concentration factors by FE (SCF mode), beside the empirical ones.

The FE stage (``fe_crank.rules.m53.fe_cases.scf_stresses``) solves the three load cases of the UR M53
FE appendix (Rev.2 and later, Appendix III; clause numbers below are the appendix's)
for unit loads; here its stress measures are divided by the nominal stresses of UR M53:

* alpha_B = sigma_equiv,alpha / sigma_N, beta_B = sigma_equiv,beta / sigma_N,
  sigma_N = M / W_eqw, W_eqw = B W^2 / 6 (3.2.3; UR M53 2.1.2.1);
  sigma_equiv the largest von Mises stress over the pin (alpha) or journal (beta) fillets;
* alpha_T = tau_equiv,alpha / tau_N, beta_T = tau_equiv,beta / tau_N, tau_N = T / W_P with
  W_P of the crankpin resp. journal (3.1.3; UR M53 2.2.2);
* 3-point bending (3.3.3), method 1: sigma_3P = sigma_N3P beta_B + sigma_Q3P beta_Q, i.e.
  beta_Q = (sigma_3P - sigma_N3P beta_B) / sigma_Q3P with sigma_N3P = Q_3P L / W_eqw (the
  bending moment at the web centre, L from the support to the web centre) and
  sigma_Q3P = Q_3P / (B W); method 2: beta_BQ = sigma_3P / sigma_N3P (reported).
  Each web with its own reaction, lever and journal-fillet peak; the larger factor is kept.

The assessment uses method 1 (beta_B and beta_Q separately, as in UR M53 5.1's
sigma_BG = beta_B sigma_BN + beta_Q sigma_QN).  Mesh checks (2.1-2.3): fillet elements
<= r/4, at least 6 elements across the web thickness (``rules.m53.web_mesh``) and, at each peak,
the principal-stress (< 3 %) or the averaged/unaveraged (< 5 %) criterion;
``ScfResult.mesh_ok`` says whether the appendix would accept the mesh.  The check's SCF
stage refines until it does (``rules.m53.scf_refine``); factors of a mesh the appendix does not
accept never enter a verdict (the M53 criterion is refused, ``assess.criteria.judge``).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

from fe_crank.cad.config import CadInput
from fe_crank.cad.source import mesh_source_throw
from fe_crank.fe.throw.options import Material
from fe_crank.geometry.spec import CrankGeometry
from fe_crank.mesh.options import MeshOptions
from fe_crank.mesh.types import ThrowMesh
from fe_crank.rules.m53 import calculation as m53
from fe_crank.rules.m53 import scf_empirical
from fe_crank.rules.m53.fe_cases import (
    JOURNAL_FILLETS,
    PIN_FILLETS,
    Peak,
    ScfStresses,
    scf_stresses,
    web_centres_from_mesh,
)
from fe_crank.rules.m53.web_mesh import MIN_ELEMENTS_ACROSS, WebElements, web_elements_across, web_groups

ELEMENT_SIZE_LIMIT = 0.25  # fillet element edge / r, UR M53 App. III 2.1


@dataclass(frozen=True)
class ScfResult:
    """FE SCFs (``fe``: alpha_B, alpha_T, beta_B, beta_T, beta_Q, beta_BQ), the empirical ones
    of UR M53 3.2/3.3 (``empirical``, None out of range), the appendix's mesh checks at each
    factor's peak (``quality``) and the FE stress measures they come from (``stresses``)."""

    fe: dict[str, float]
    empirical: dict[str, float | None]
    out_of_range: dict[str, tuple[str, ...]]
    quality: dict[str, dict[str, Any]]
    element_size: dict[str, float]  # fillet group -> longest element edge / r
    stresses: ScfStresses
    details: dict[str, Any] = field(default_factory=dict)
    web_elements: tuple[WebElements, ...] = ()  # App. III 2.2, per web (meshes with web subdomains)
    refinement: tuple[str, ...] = ()  # the meshes tried before this one and why each was refined

    @property
    def web_ok(self) -> bool:
        """At least 6 elements across each web's thickness (where measured)."""
        return all(w.ok for w in self.web_elements)

    @property
    def equilibrium_error(self) -> dict[str, float]:
        return self.stresses.equilibrium_error

    @property
    def mesh_ok(self) -> bool:
        """Fillet elements <= r/4 (where known), >= 6 elements across the webs (where
        measured) and every peak meets a 2.3 criterion."""
        return self.size_ok and self.web_ok and all(q["mesh_ok"] for q in self.quality.values())

    @property
    def size_ok(self) -> bool:
        """Fillet elements <= r/4 (where known)."""
        return all(v <= ELEMENT_SIZE_LIMIT * (1 + 1e-9) for v in self.element_size.values())

    def for_assessment(self) -> dict[str, dict[str, float]]:
        """The ``fe_scf`` dictionaries that ``fe_crank.rules.m53.calculation.assess_fillet`` takes."""
        f = self.fe
        return {
            "pin": {"bending": f["alpha_B"], "shear": 0.0, "torsion": f["alpha_T"]},
            "journal": {"bending": f["beta_B"], "shear": f["beta_Q"], "torsion": f["beta_T"]},
        }

    def summary(self) -> str:
        """One line for ``scf_source``: the appendix, the mesh verdict and the worst checks."""
        worst_p = max(q["principal_ratio"] for q in self.quality.values())
        worst_a = max(q["averaging"] for q in self.quality.values())
        size = max(self.element_size.values()) if self.element_size else None
        parts = [
            f"principal criterion max {100 * worst_p:.1f} % (< 3 %)",
            f"averaging max {100 * worst_a:.1f} % (< 5 %)",
        ]
        if size is not None:
            parts.append(f"fillet elements <= r/{1 / size:.1f} (r/4 required)")
        if self.web_elements:
            across = min(w.across for w in self.web_elements)
            parts.append(f"{across:.1f} elements across the web (>= {MIN_ELEMENTS_ACROSS} required)")
        if self.refinement:
            parts.append(f"after {len(self.refinement)} refinement(s)")
        verdict = "mesh accepted" if self.mesh_ok else "mesh NOT accepted, refine"
        return f"FE, UR M53 App. III SCF mode ({verdict}: {'; '.join(parts)})"


def _quality(peak: Peak) -> dict[str, Any]:
    return {
        "group": peak.group,
        "point": peak.point,
        "principal_ratio": peak.principal_ratio,
        "averaging": peak.averaging,
        "principal_ok": peak.principal_ok,
        "averaging_ok": peak.averaging_ok,
        "mesh_ok": peak.mesh_ok,
    }


def _worst(peaks: dict[str, Peak], groups: Iterable[str]) -> Peak:
    return max((peaks[g] for g in groups), key=lambda p: p.value)


def factors(
    st: ScfStresses, geo: m53.M53Geometry
) -> tuple[dict[str, float], dict[str, dict[str, Any]], dict[str, Any]]:
    """SCFs of UR M53 App. III from unit-load stress measures (module docstring)."""
    w_eq, area = m53.web_section_modulus(geo), m53.web_area(geo)
    wp = {"pin": m53.polar_section_modulus(geo, "pin"), "journal": m53.polar_section_modulus(geo, "journal")}
    sigma_n, tau_n = 1.0 / w_eq, {k: 1.0 / v for k, v in wp.items()}  # M = T = 1 N m
    pb, jb = _worst(st.bending, PIN_FILLETS), _worst(st.bending, JOURNAL_FILLETS)
    pt, jt = _worst(st.torsion, PIN_FILLETS), _worst(st.torsion, JOURNAL_FILLETS)
    fe = {
        "alpha_B": pb.value / sigma_n,
        "beta_B": jb.value / sigma_n,
        "alpha_T": pt.value / tau_n["pin"],
        "beta_T": jt.value / tau_n["journal"],
    }
    per_side: list[dict[str, Any]] = []
    for side, g in zip(("end_1", "end_2"), JOURNAL_FILLETS):
        q, lever = st.reaction[side], st.lever[side]
        s3p = st.three_point[g].value
        s_n3p, s_q3p = q * lever / w_eq, q / area
        per_side.append(
            {
                "side": side,
                "group": g,
                "sigma_3P": s3p,
                "Q_3P": q,
                "L": lever,
                "sigma_N3P": s_n3p,
                "sigma_Q3P": s_q3p,
                "beta_Q": (s3p - s_n3p * fe["beta_B"]) / s_q3p,
                "beta_BQ": s3p / s_n3p,
            }
        )
    fe["beta_Q"] = max(s["beta_Q"] for s in per_side)
    fe["beta_BQ"] = max(s["beta_BQ"] for s in per_side)
    q3 = max(st.three_point.values(), key=lambda p: p.value)
    quality = {
        "alpha_B": _quality(pb),
        "beta_B": _quality(jb),
        "alpha_T": _quality(pt),
        "beta_T": _quality(jt),
        "beta_Q": _quality(q3),
    }
    return fe, quality, {"three_point": per_side}


def empirical(geo: m53.M53Geometry) -> tuple[dict[str, float | None], dict[str, tuple[str, ...]]]:
    """UR M53 3.2/3.3 empirical SCFs of the same throw, None outside the validity range (3.1)."""
    rel_p, rel_j = geo.related("pin"), geo.related("journal")
    bad_p, bad_j = tuple(scf_empirical.out_of_range(rel_p)), tuple(scf_empirical.out_of_range(rel_j))
    emp = {
        "alpha_B": None if bad_p else scf_empirical.alpha_b(rel_p),
        "alpha_T": None if bad_p else scf_empirical.alpha_t(rel_p),
        "beta_B": None if bad_j else scf_empirical.beta_b(rel_j),
        "beta_T": None if bad_j else scf_empirical.beta_t(rel_j, geo.journal_fillet_radius / geo.journal_diameter),
        "beta_Q": None if bad_j else scf_empirical.beta_q(rel_j),
    }
    return emp, {"pin": bad_p, "journal": bad_j}


def web_centres_of(geometry: CrankGeometry) -> tuple[float, float]:
    """Web centre planes z = -+(L_pin/2 + W/2) of a ``CrankGeometry`` (docs/contracts.md axial layout)."""
    z = 0.5 * geometry.crankpin_length + 0.5 * geometry.web_thickness
    return (-z, z)


def _element_size(throw_mesh: ThrowMesh) -> dict[str, float]:
    stats = throw_mesh.stats
    return {
        g: h / stats.fillet_radii[g]
        for g, h in stats.fillet_max_edge.items()
        if g in (*PIN_FILLETS, *JOURNAL_FILLETS) and stats.fillet_radii.get(g)
    }


def compute_scf(
    throw_mesh: ThrowMesh,
    material: Material,
    geo: m53.M53Geometry,
    *,
    web_centres: tuple[float, float] | None = None,
    solver: str = "auto",
) -> ScfResult:
    """SCF mode on one throw mesh (UR M53 App. III), SCFs beside the empirical ones.

    ``throw_mesh``: a ``fe_crank.mesh.ThrowMesh`` (from ``mesh_throw``: its fillet element
    size is checked too); its end faces must be the main-bearing centre
    planes.  ``web_centres``: axial positions of the two web centre planes (default: from
    the journal fillets' web-side edges and W, ``rules.m53.fe_cases.web_centres_from_mesh``).
    """
    if web_centres is None:
        web_centres = web_centres_from_mesh(throw_mesh, geo.web_thickness)
    st = scf_stresses(throw_mesh, material, web_centres=web_centres, solver=solver)
    fe, quality, details = factors(st, geo)
    emp, bad = empirical(geo)
    mesh = throw_mesh.mesh
    webs = web_groups(mesh)
    return ScfResult(
        fe=fe,
        empirical=emp,
        out_of_range=bad,
        quality=quality,
        element_size=_element_size(throw_mesh),
        stresses=st,
        details=details,
        web_elements=web_elements_across(mesh, webs, geo.web_thickness) if webs else (),
    )


def scf_mesh_options(options: MeshOptions | None) -> MeshOptions | None:
    """Mesh options for the SCF mode: the load case's own when its fillet elements are at most
    r/4 (UR M53 App. III 2.1), else the same options with ``fillet_divisions = 4``."""
    if options is None or options.fillet_divisions >= 4.0:
        return options
    return dataclasses.replace(options, fillet_divisions=4.0)


def scf_mesh(throw_mesh: ThrowMesh, geometry: object) -> ThrowMesh:
    """The throw mesh the SCF mode runs on: the load case's mesh, or, when that mesh is
    coarser than r/4 in the fillets (e.g. the ``test`` preset), the same throw of
    ``geometry`` (a ``CrankGeometry`` or a CAD file's ``CadInput``) meshed again with
    ``scf_mesh_options`` (same cache).  A geometry that cannot be meshed here leaves the
    mesh as it is (its ``mesh_ok`` says whether the appendix accepts it)."""
    opt = throw_mesh.options
    want = scf_mesh_options(opt)
    if want is None or want is opt or not isinstance(geometry, CrankGeometry | CadInput):
        return throw_mesh
    return mesh_source_throw(geometry, throw_mesh.throw, size=want, cache_dir=throw_mesh.cache_dir)
