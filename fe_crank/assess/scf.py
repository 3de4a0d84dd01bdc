"""SCF mode: stress concentration factors of the crank throw fillets by FE (IACS UR M53, FE appendix).

Load cases on one throw whose journal end faces ``end_1``/``end_2`` are coupled rigidly to
reference points on the crank axis (as the UR M53 FE guidance prescribes):

* pure bending: ``end_1`` held, a moment M_B about x (bending in the crank plane) at ``end_2``;
* pure torsion: the same support, a torque T about z at ``end_2`` (same factorisation);
* three-point bending: both reference points held in translation (``end_1`` also in
  rotation about z), the crankpin loaded by a radial force F as a cosine pressure.

Factors, with the nominal stresses of UR M53 section 2 (web section for bending and shear):
alpha_B = sigma_max(pin fillet) / sigma_N, beta_B = sigma_max(journal fillet) / sigma_N,
sigma_N = M_B / (B W^2 / 6);  alpha_T = tau_max(pin fillet) / (T / W_P,pin),
beta_T = tau_max(journal fillet) / (T / W_P,journal), W_P = pi/16 (D^4 - D_B^4) / D;
beta_Q = (sigma_3P - beta_B sigma_N3P) / sigma_Q3P with sigma_N3P = Q L / (B W^2 / 6),
sigma_Q3P = Q / (B W), Q the support reaction and L the axial distance from the support
point to the web centre line (UR M53 FE appendix, three-point bending).
sigma_max is the principal stress of largest magnitude (a pure moment puts the pin fillets
in compression where the journal fillets are in tension: the factor is a magnitude) and
tau_max = (sigma_1 - sigma_3)/2, both from averaged nodal stresses on the fillet surface.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from fe_crank.assess import m53
from fe_crank.errors import InputError
from fe_crank.fe.loads import pin_pressure_load
from fe_crank.fe.stress import averaging_indicator, max_shear, principal, stress_at_nodes
from fe_crank.fe.supports import Coupling, boundary_facets
from fe_crank.fe.system import EQUILIBRIUM_TOL, build_system
from fe_crank.errors import SolverError

ALL6 = ("ux", "uy", "uz", "rx", "ry", "rz")
PIN_FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2")
JOURNAL_FILLETS = ("journal_fillet_1", "journal_fillet_2")


@dataclass(frozen=True)
class ScfResult:
    """FE stress concentration factors beside the UR M53 empirical ones (None: out of range)."""

    fe: dict[str, float]                     # alpha_B, alpha_T, beta_B, beta_T, beta_Q
    empirical: dict[str, float | None]
    out_of_range: dict[str, tuple[str, ...]]  # "pin"/"journal" -> violated validity limits
    averaging: dict[str, dict[str, float]]   # case -> fillet group -> M53 indicator
    equilibrium_error: dict[str, float]
    n_dof: int
    details: dict = field(default_factory=dict)

    def for_assessment(self) -> dict[str, dict[str, float]]:
        """The ``fe_scf`` dictionaries that ``fe_crank.assess.m53.assess_fillet`` takes."""
        return {"pin": {"bending": self.fe["alpha_B"], "shear": 0.0, "torsion": self.fe["alpha_T"]},
                "journal": {"bending": self.fe["beta_B"], "shear": self.fe["beta_Q"], "torsion": self.fe["beta_T"]}}


def _abs_principal(s):
    """Magnitude of the principal stress of largest magnitude, max(|sigma_1|, |sigma_3|)."""
    p = principal(s)
    return np.maximum(np.abs(p[0]), np.abs(p[2]))


def _group_max(mesh, basis, field_, groups):
    vals = []
    for g in groups:
        nodes = basis.get_dofs(boundary_facets(mesh, g, "the SCF evaluation")).all()
        vals.append(field_[nodes].max())
    return float(max(vals)), vals


def compute_scf(throw_mesh, material, geometry, *, solver: str = "auto", pin_fillets=PIN_FILLETS,
                journal_fillets=JOURNAL_FILLETS) -> ScfResult:
    """UR M53 FE-appendix SCFs of one throw (see module docstring).

    ``geometry``: an ``fe_crank.assess.m53.M53Geometry`` (pin_diameter, journal_diameter,
    web_thickness, web_width, pin_bore, journal_bore, ...), SI.
    """
    mesh = getattr(throw_mesh, "mesh", throw_mesh)
    E, nu = material.youngs_modulus, material.poisson_ratio
    B, W = geometry.web_width, geometry.web_thickness
    if not (B > 0 and W > 0):
        raise InputError("web width and thickness must be > 0 for the SCF nominal stresses", key="geometry")
    w_eq = B * W**2 / 6.0
    area = B * W
    wp_pin = np.pi / 16 * (geometry.pin_diameter**4 - geometry.pin_bore**4) / geometry.pin_diameter
    wp_jou = np.pi / 16 * (geometry.journal_diameter**4 - geometry.journal_bore**4) / geometry.journal_diameter
    for g in (*pin_fillets, *journal_fillets, "end_1", "end_2", "crankpin"):
        boundary_facets(mesh, g, "the SCF mode")
    groups = [*pin_fillets, *journal_fillets]

    # bending and torsion: one system, two right-hand sides
    sys1 = build_system(mesh, E, nu, couplings=[Coupling("end_1", fixed=ALL6), Coupling("end_2")], solver=solver)
    zero = np.zeros(3 * sys1.basis.N)
    loads = [{"end_2": np.array([0, 0, 0, 1.0, 0, 0])}, {"end_2": np.array([0, 0, 0, 0, 0, 1.0])}]
    U = sys1.solve(np.column_stack([zero, zero]), loads)
    eq = {}
    for k, name in enumerate(("bending", "torsion")):
        eq[name], _ = sys1.equilibrium_error(U[:, k], zero, loads[k])
    s_b = stress_at_nodes(mesh, U[:, 0], E, nu)
    s_t = stress_at_nodes(mesh, U[:, 1], E, nu)
    sig1_b = _abs_principal(s_b)
    tau_t = max_shear(s_t)
    sigma_n = 1.0 / w_eq
    fe = {}
    fe["alpha_B"], _ = _group_max(mesh, sys1.basis, sig1_b, pin_fillets)
    fe["beta_B"], beta_b_side = _group_max(mesh, sys1.basis, sig1_b, journal_fillets)
    beta_b_side = [v / (1.0 / w_eq) for v in beta_b_side]
    fe["alpha_B"] /= sigma_n
    fe["beta_B"] /= sigma_n
    fe["alpha_T"] = _group_max(mesh, sys1.basis, tau_t, pin_fillets)[0] / (1.0 / wp_pin)
    fe["beta_T"] = _group_max(mesh, sys1.basis, tau_t, journal_fillets)[0] / (1.0 / wp_jou)
    averaging = {"bending": averaging_indicator(mesh, U[:, 0], E, nu, groups),
                 "torsion": averaging_indicator(mesh, U[:, 1], E, nu, groups)}

    # three-point bending
    sys2 = build_system(mesh, E, nu, solver=solver, couplings=[
        Coupling("end_1", fixed=("ux", "uy", "uz", "rz")), Coupling("end_2", fixed=("ux", "uy"))])
    f, _ = pin_pressure_load(sys2.basis, (0.0, -1.0))
    u3 = sys2.solve(f)
    eq["three_point"], reac = sys2.equilibrium_error(u3, f)
    if max(eq.values()) >= EQUILIBRIUM_TOL:
        raise SolverError(f"SCF mode: reactions do not balance the loads ({max(eq.values()):.2e})")
    s3 = _abs_principal(stress_at_nodes(mesh, u3, E, nu))
    x = sys2.points
    beta_q = []
    for side, fil, bb in zip(("end_1", "end_2"), journal_fillets, beta_b_side):
        q = abs(reac[side][1])
        nodes = sys2.basis.get_dofs(boundary_facets(mesh, fil, "the SCF mode")).all()
        z_support = sys2.ref_points[side][2]
        # web centre line: the journal fillet's web-side edge plus half the web thickness
        z_fillet = x[2, nodes].max() if side == "end_1" else x[2, nodes].min()
        z_web = z_fillet + (W / 2 if side == "end_1" else -W / 2)
        L = abs(z_web - z_support)
        sigma_n3 = q * L / w_eq
        sigma_q3 = q / area
        # each side with its own beta_B: beta_Q is a small difference of two large stresses
        beta_q.append((s3[nodes].max() - bb * sigma_n3) / sigma_q3)
    fe["beta_Q"] = float(max(beta_q))
    averaging["three_point"] = averaging_indicator(mesh, u3, E, nu, groups)

    empirical, bad = _empirical(geometry)
    return ScfResult(fe=fe, empirical=empirical, out_of_range=bad, averaging=averaging, equilibrium_error=eq,
                     n_dof=sys1.n_dof, details={"beta_Q_per_side": beta_q, "beta_B_per_side": beta_b_side})


def _empirical(geometry):
    """UR M53 empirical SCFs for the same geometry (``fe_crank.assess.m53``), None out of range."""
    rel_p, rel_j = geometry.related("pin"), geometry.related("journal")
    bad_p, bad_j = tuple(m53.out_of_range(rel_p)), tuple(m53.out_of_range(rel_j))
    emp = {"alpha_B": None if bad_p else m53.alpha_b(rel_p), "alpha_T": None if bad_p else m53.alpha_t(rel_p),
           "beta_B": None if bad_j else m53.beta_b(rel_j), "beta_T": None if bad_j else m53.alpha_t(rel_j),
           "beta_Q": None if bad_j else m53.beta_q(rel_j)}
    return emp, {"pin": bad_p, "journal": bad_j}
