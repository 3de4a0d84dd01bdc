"""SCF mode, FE part: the load cases and stress measures of the IACS UR M53 FE appendix.

The appendix ("Guidance for calculation of stress concentration factors in the web
fillet radii of crankshafts by utilizing finite element method", UR M53 Rev.2 and later,
Appendix III; the clause numbers below are its own) defines, for one crank throw
modelled from main-bearing centre line to main-bearing centre line (2.1):

* torsion (3.1): both end faces coupled rigidly to a master node on the crank axis
  (surface warp suppressed), one master node held in all six dofs, the torque T at the
  other; at every node of the pin and journal fillets
  tau_equiv = max(|s1 - s2|, |s2 - s3|, |s1 - s3|) / 2 (3.1.2);
* pure bending, "4-point bending" (3.2): the same supports, the bending moment M in the
  crank plane at the free master node; von Mises sigma_equiv at every fillet node (3.2.2);
* bending with shear force, "3-point bending" (3.3): both master nodes supported
  (simply supported throw), the force F at the crankpin centre distributed over the pin
  without suppressing its warping; von Mises sigma_3P at the journal fillet nodes (3.3.3).

This module solves those cases for unit loads and returns the stress measures (their
maxima per fillet, where they occur) and the FE quantities the nominal stresses need
(support reactions, the lever from each support to its web centre); dividing by the
nominal stresses of UR M53 is the assessment's job (``fe_crank.rules.m53.scf_mode``).

Model choices (stated in docs/fe.md): the throw mesh ends at the main-bearing centre
planes (a geometry's journal length is half a main bearing, docs/geometry.md); the
rigid couplings are ``fe.core.supports.Coupling`` (RBE2 type) at the end-face centroids; the
3-point force is a uniform traction F/A over the crankpin bearing surface, a
distributing (RBE3-type) coupling: its resultant passes through the pin centre and it
does not stiffen the pin.

Mesh quality (2.3), evaluated at the node where each measure peaks:
(a) principal-stress criterion (2.3.1): the surface-normal stress should vanish,
    min|s_i| < 0.03 max|s_i|;
(b) averaged/unaveraged criterion (2.3.2): every element's unaveraged value of the
    measure at that node within 5 % of the averaged value.
The appendix asks for a refined mesh when neither holds; both are reported.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field

import numpy as np
from skfem import Basis, ElementTetP2, Mesh

from fe_crank.errors import MeshError, SolverError
from fe_crank.fe.core.assembly import assemble_surface_load
from fe_crank.fe.core.bases import facet_basis
from fe_crank.fe.core.stress import element_nodal_stress, nodal_average, principal, von_mises
from fe_crank.fe.core.supports import Coupling, boundary_facets
from fe_crank.fe.core.system import EQUILIBRIUM_TOL, System, build_system
from fe_crank.fe.throw.options import Material
from fe_crank.mesh.types import ThrowMesh

ALL6 = ("ux", "uy", "uz", "rx", "ry", "rz")
PIN_FILLETS = ("crankpin_fillet_1", "crankpin_fillet_2")
JOURNAL_FILLETS = ("journal_fillet_1", "journal_fillet_2")
PRINCIPAL_LIMIT = 0.03  # UR M53 App. III 2.3.1
AVERAGING_LIMIT = 0.05  # UR M53 App. III 2.3.2


def tau_equiv(s: np.ndarray) -> np.ndarray:
    """tau_equiv = max(|s1 - s2|, |s2 - s3|, |s1 - s3|)/2 = (s1 - s3)/2 for s1 >= s2 >= s3 (App. III 3.1.2)."""
    p = principal(s)
    out: np.ndarray = 0.5 * (p[0] - p[2])
    return out


MEASURES = {"von_mises": von_mises, "tau_equiv": tau_equiv}


@dataclass(frozen=True)
class Peak:
    """Largest value of a stress measure over one fillet and the mesh checks at that node."""

    group: str
    value: float  # Pa per unit load
    node: int
    point: tuple[float, float, float]
    principal_ratio: float  # min|s_i| / max|s_i| at the node (2.3.1: < 0.03)
    averaging: float  # max over the node's elements |s_el - s_avg| / s_avg (2.3.2: < 0.05)

    @property
    def principal_ok(self) -> bool:
        return self.principal_ratio < PRINCIPAL_LIMIT

    @property
    def averaging_ok(self) -> bool:
        return self.averaging < AVERAGING_LIMIT

    @property
    def mesh_ok(self) -> bool:
        """App. III 2.3: a refined mesh is needed when neither criterion is met."""
        return self.principal_ok or self.averaging_ok


@dataclass(frozen=True)
class ScfStresses:
    """Unit-load results of the three appendix cases (SI: N, N m, Pa, m).

    ``bending``: von Mises peaks per fillet under M = 1 N m about x (crank plane y-z);
    ``torsion``: tau_equiv peaks per fillet under T = 1 N m about z;
    ``three_point``: von Mises peaks per journal fillet under F = 1 N on the pin (-y);
    ``reaction``: |F_y| at each support of the 3-point case (end_1, end_2), N;
    ``lever``: axial distance from each support point to the centre of the web on its
    side, m (``web_centres``); ``section_moment``: reaction x lever, the web-centre
    bending moment of the statically determinate throw, N m.
    """

    bending: dict[str, Peak]
    torsion: dict[str, Peak]
    three_point: dict[str, Peak]
    reaction: dict[str, float]
    lever: dict[str, float]
    equilibrium_error: dict[str, float]
    n_dof: int
    support_points: dict[str, tuple[float, float, float]] = field(default_factory=dict)

    @property
    def section_moment(self) -> dict[str, float]:
        return {k: self.reaction[k] * self.lever[k] for k in self.reaction}


def _peaks(
    mesh: Mesh, u: np.ndarray, E: float, nu: float, groups: Iterable[str], measure: str, basis: Basis
) -> dict[str, Peak]:
    dofs = basis.dofs
    s_el, nodes = element_nodal_stress(mesh, u, E, nu, dofs=dofs)
    n = u.size // 3
    s_avg = nodal_average(s_el, nodes, n)
    f = MEASURES[measure]
    m_avg = f(s_avg)
    m_el = f(s_el)  # (10, ne)
    out = {}
    for g in groups:
        fn = np.unique(dofs.get_facet_dofs(boundary_facets(mesh, g, "the SCF mode")).all())
        i = int(fn[np.argmax(m_avg[fn])])
        p = np.abs(principal(s_avg[:, i]))
        at = nodes == i
        dev = np.abs(m_el[at] - m_avg[i]).max() / m_avg[i] if m_avg[i] > 0 else 0.0
        x = basis.doflocs[:, i]
        out[g] = Peak(
            g,
            float(m_avg[i]),
            i,
            (float(x[0]), float(x[1]), float(x[2])),
            float(p.min() / p.max()) if p.max() > 0 else 0.0,
            float(dev),
        )
    return out


def _pin_traction_load(basis: Basis, force_y: float, boundary: str = "crankpin") -> np.ndarray:
    """Uniform traction (0, F/A, 0) over the pin surface: a distributing coupling of F (App. III 3.3.1)."""
    mesh = basis.mesh
    fb = facet_basis(
        mesh, ElementTetP2(), boundary_facets(mesh, boundary, "the 3-point bending load"), 4, "the 3-point bending load"
    )
    area = float(fb.dx.sum())

    def traction(x: np.ndarray, n: np.ndarray) -> np.ndarray:
        t = np.zeros_like(x)
        t[1] = force_y / area
        return t

    return assemble_surface_load(fb, traction)


def solve_bending_torsion(
    mesh: Mesh, E: float, nu: float, *, solver: str = "auto"
) -> tuple[System, np.ndarray, list[dict[str, np.ndarray]]]:
    """App. III 3.1 and 3.2: ``end_1`` master node held in all six dofs, M_x = 1 N m (bending
    in the crank plane y-z) and M_z = 1 N m (torsion) at the ``end_2`` master node.

    Returns the ``System``, the displacements (n, 2) and the two reference-load dicts.
    """
    system = build_system(mesh, E, nu, couplings=[Coupling("end_1", fixed=ALL6), Coupling("end_2")], solver=solver)
    zero = np.zeros(3 * system.basis.N)
    loads = [{"end_2": np.array([0, 0, 0, 1.0, 0, 0])}, {"end_2": np.array([0, 0, 0, 0, 0, 1.0])}]
    return system, system.solve(np.column_stack([zero, zero]), loads), loads


def solve_three_point(
    mesh: Mesh, E: float, nu: float, *, solver: str = "auto", basis: Basis | None = None
) -> tuple[System, np.ndarray, np.ndarray]:
    """App. III 3.3: both master nodes held in ux, uy (``end_1`` also in uz and rz, against
    the rigid slide and spin), a 1 N force towards the axis (-y) distributed over the pin.

    ``basis``: the mesh's cell basis when the caller already has it (that of another
    ``System`` on the same mesh), else built here.
    Returns the ``System``, the displacement and the load vector.
    """
    system = build_system(
        mesh,
        E,
        nu,
        solver=solver,
        couplings=[Coupling("end_1", fixed=("ux", "uy", "uz", "rz")), Coupling("end_2", fixed=("ux", "uy"))],
        basis=basis,
    )
    f = _pin_traction_load(system.basis, -1.0)
    return system, system.solve(f), f


def scf_stresses(
    throw_mesh: ThrowMesh,
    material: Material,
    *,
    web_centres: tuple[float, float],
    solver: str = "auto",
    pin_fillets: tuple[str, ...] = PIN_FILLETS,
    journal_fillets: tuple[str, ...] = JOURNAL_FILLETS,
) -> ScfStresses:
    """Solve the three UR M53 App. III cases for unit loads (see module docstring).

    ``throw_mesh``: a ``ThrowMesh`` with boundaries ``end_1``, ``end_2``
    (the main-bearing centre planes), ``crankpin`` and the fillet groups;
    ``material``: ``youngs_modulus``, ``poisson_ratio``; ``web_centres``: axial (z)
    positions of the centre planes of web 1 (``end_1`` side) and web 2, m.
    """
    mesh = throw_mesh.mesh
    E, nu = material.youngs_modulus, material.poisson_ratio
    for g in (*pin_fillets, *journal_fillets, "end_1", "end_2", "crankpin"):
        boundary_facets(mesh, g, "the SCF mode")
    if len(web_centres) != 2:
        raise MeshError("web_centres must give the axial positions of web 1 and web 2")
    groups = (*pin_fillets, *journal_fillets)

    sys1, U, loads = solve_bending_torsion(mesh, E, nu, solver=solver)
    zero = np.zeros(U.shape[0])
    eq = {name: sys1.equilibrium_error(U[:, k], zero, loads[k])[0] for k, name in enumerate(("bending", "torsion"))}
    bending = _peaks(mesh, U[:, 0], E, nu, groups, "von_mises", sys1.basis)
    torsion = _peaks(mesh, U[:, 1], E, nu, groups, "tau_equiv", sys1.basis)
    n_dof = sys1.n_dof
    basis = sys1.basis  # the same cell basis serves the second system (built once)
    del sys1, U

    sys2, u3, f = solve_three_point(mesh, E, nu, solver=solver, basis=basis)
    eq["three_point"], reac = sys2.equilibrium_error(u3, f)
    if max(eq.values()) >= EQUILIBRIUM_TOL:
        raise SolverError(f"SCF mode: reactions do not balance the loads ({max(eq.values()):.2e})")
    three = _peaks(mesh, u3, E, nu, journal_fillets, "von_mises", sys2.basis)
    refs = {k: np.asarray(v, float) for k, v in sys2.ref_points.items()}
    lever = {side: abs(float(zc) - refs[side][2]) for side, zc in zip(("end_1", "end_2"), web_centres)}
    reaction = {side: abs(float(reac[side][1])) for side in ("end_1", "end_2")}
    return ScfStresses(
        bending=bending,
        torsion=torsion,
        three_point=three,
        reaction=reaction,
        lever=lever,
        equilibrium_error=eq,
        n_dof=n_dof,
        support_points={k: (float(v[0]), float(v[1]), float(v[2])) for k, v in refs.items()},
    )


def web_centres_from_mesh(
    throw_mesh: ThrowMesh, web_thickness: float, journal_fillets: tuple[str, ...] = JOURNAL_FILLETS
) -> tuple[float, float]:
    """Web centre planes estimated from the mesh: each journal fillet's web-side edge -/+ W/2.

    Exact for fillets without an undercut (the fillet ends on the web face); prefer the
    geometry's own positions (+-(L_pin/2 + W/2)) when they are known.
    """
    mesh = throw_mesh.mesh
    basis = Basis(mesh, ElementTetP2(), intorder=1)
    out = []
    for k, g in enumerate(journal_fillets):
        z = basis.doflocs[2, basis.get_dofs(boundary_facets(mesh, g, "the SCF mode")).all()]
        out.append(z.max() + web_thickness / 2 if k == 0 else z.min() - web_thickness / 2)
    return float(out[0]), float(out[1])
