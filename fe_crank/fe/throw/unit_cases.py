"""Unit load cases of a crank throw on one stiffness matrix and one support model.

``solve_unit_cases(throw_mesh, material, options)`` assembles and factorises once and
solves every unit case against the same factorisation, so that any load of the cycle is
an exact linear combination:  u = omega^2 u_centrifugal + |Fx| u_pin_(+-)x + |Fy| u_pin_(+-)y
+ T u_torque.

Support model (default ``"determinate"``, ``fe_crank.fe.core.determinate``): the statically
determinate throw of IACS UR M53 2.1 -- each journal's bearing surface tied by a
distributing (RBE3) coupling to a simple support at its bearing centre (radial at both,
axial at the torque end's journal), the torque M_z reacted at the end face where the
power is taken off (``end_2``, flywheel side, unless ``torque_reaction = "end_1"``).  No
stiffness parameter enters.  ``"foundation"``: both journal surfaces on a radial Winkler
foundation whose stiffness per area the input must state (``bearing_stiffness``), the
torque end face coupled rigidly to an axis point held in u_z and r_z; statically
indeterminate, for studies of the bearing's elasticity only (docs/fe.md).
"""

from __future__ import annotations

import logging
import time
from dataclasses import dataclass, field

import numpy as np
from skfem import ElementTetP2, Mesh

from fe_crank.errors import InputError, MeshError, SolverError
from fe_crank.fe.core import stress as _stress
from fe_crank.fe.core.determinate import POINT_REACTION_TOL, DeterminateLayout
from fe_crank.fe.core.loads import PinPressure
from fe_crank.fe.core.supports import Coupling, Foundation, boundary_facets, facet_basis
from fe_crank.fe.core.system import EQUILIBRIUM_TOL, System, build_system, determinate_system
from fe_crank.fe.throw.options import (  # noqa: F401
    CASES,
    PIN_FORCES,
    SUPPORTS,
    TORQUE_ENDS,
    FeOptions,
    Material,
    axial_journal,
    check_support_options,
    support_text,
)
from fe_crank.fe.throw.pin_directions import pin_case_weights, pin_direction
from fe_crank.fe.throw.unit_loads import check_case_names, unit_loads
from fe_crank.mesh.types import ThrowMesh

log = logging.getLogger(__name__)


@dataclass(frozen=True)
class UnitCase:
    """One solved unit case: displacement (3 N,), reactions per support (Fx..Mz), equilibrium error."""

    name: str
    description: str
    displacement: np.ndarray
    applied: np.ndarray
    reactions: dict[str, np.ndarray]
    equilibrium_error: float


@dataclass(frozen=True)
class UnitSolutions:
    """All unit cases of one throw on one factorisation (see module doc)."""

    system: System
    material: Material
    options: FeOptions
    cases: dict[str, UnitCase]
    pin: dict[str, PinPressure]
    bearing_stiffness: float | None  # N/m^3, "foundation" only
    support_model: str = ""  # one-line statement of the support model (report, results.json)
    bearing_centres: dict[str, float] = field(default_factory=dict)  # journal -> z of its bearing centre, m
    timings: dict[str, float] = field(default_factory=dict)

    @property
    def mesh(self):
        return self.system.mesh

    @property
    def n_dof(self) -> int:
        return self.system.n_dof

    @property
    def solver(self) -> str:
        return self.system.factorisation.method

    @property
    def solver_description(self) -> str:
        """The solver that ran, in words, with the reason when ``auto`` fell back from PARDISO."""
        return self.system.factorisation.description

    @property
    def points(self) -> np.ndarray:
        """P2 node coordinates (3, n_nodes), the nodes of every nodal field."""
        return self.system.points

    def displacement(self, name: str) -> np.ndarray:
        return self.cases[name].displacement

    def combine(self, weights: dict[str, float]) -> np.ndarray:
        """Displacement sum_k w_k u_k (exact by linearity)."""
        u = np.zeros_like(next(iter(self.cases.values())).displacement)
        for name, w in weights.items():
            if name not in self.cases:
                raise InputError(f"unknown unit case {name!r}; solved: {', '.join(self.cases)}")
            u += w * self.cases[name].displacement
        return u

    def pin_weights(self, fx: float, fy: float) -> dict[str, float]:
        """Weights of the solved pin unit cases for a pin force (Fx, Fy), N, throw frame:
        the two directions that bracket the force (``pin_directions.pin_case_weights``)."""
        names = [c for c in self.cases if pin_direction(c) is not None]
        w = pin_case_weights(np.array([[fx, fy]]), names)[0]
        return {n: float(x) for n, x in zip(names, w) if x != 0.0}

    def stress_at_nodes(self, u: np.ndarray) -> np.ndarray:
        """Averaged nodal stress (6, n_nodes), Voigt order xx yy zz xy yz zx, Pa."""
        return _stress.stress_at_nodes(
            self.mesh, u, self.material.youngs_modulus, self.material.poisson_ratio, dofs=self.system.basis.dofs
        )

    def element_nodal_stress(self, u: np.ndarray):
        """Unaveraged stress at element nodes (6, 10, ne) and node numbers (10, ne)."""
        return _stress.element_nodal_stress(
            self.mesh, u, self.material.youngs_modulus, self.material.poisson_ratio, dofs=self.system.basis.dofs
        )

    def averaging_indicator(self, u: np.ndarray, groups) -> dict[str, float]:
        """M53 averaged-vs-unaveraged check per fillet group (see stress.averaging_indicator)."""
        return _stress.averaging_indicator(
            self.mesh, u, self.material.youngs_modulus, self.material.poisson_ratio, groups, dofs=self.system.basis.dofs
        )

    von_mises = staticmethod(_stress.von_mises)
    principal = staticmethod(_stress.principal)
    max_shear = staticmethod(_stress.max_shear)


def journal_diameter(mesh, boundary: str) -> float:
    """2 x the mean distance of the journal surface from the crank axis (area-weighted)."""
    fb = facet_basis(
        mesh, ElementTetP2(), boundary_facets(mesh, boundary, "the bearing support"), 2, "the bearing support"
    )
    x = np.asarray(fb.global_coordinates())
    return float(2.0 * np.sum(np.hypot(x[0], x[1]) * fb.dx) / fb.dx.sum())


def _tet_mesh(throw_mesh: ThrowMesh) -> Mesh:
    mesh = throw_mesh.mesh
    if mesh.t.shape[0] != 4 or mesh.p.shape[0] != 3:
        raise MeshError(f"unsupported body: FE needs a 3D tetrahedral mesh, got {type(mesh).__name__}")
    return mesh


def solve_unit_cases(throw_mesh: ThrowMesh, material: Material, options: FeOptions | None = None) -> UnitSolutions:
    """Assemble once, factorise once, solve the unit cases of ``options.cases``.

    Cases: ``centrifugal`` (omega = 1 rad/s about z; scale by omega^2), on request
    ``angular_acceleration`` (1 rad/s^2 in the sense of rotation, ``loads.BODY_CASES``), pin cases by
    direction (1 N on the crankpin in the throw frame as a cosine pressure; a force is
    built from the two directions that bracket it, see ``UnitSolutions.pin_weights``),
    ``torque`` (1 N m in the positive sense of rotation, i.e. about -z, M_z = -1 N m,
    entering at ``end_1`` and reacted at ``end_2``; a tangential pin force +Fx drives the
    shaft in the same sense, M_z = -R Fx).  Reactions are (Fx, Fy, Fz, Mx, My, Mz) about
    the origin in the throw frame (right-handed moments).
    Every case's reactions are checked against its loads: an equilibrium error above 1e-6
    raises SolverError.
    """
    options = options or FeOptions()
    check_case_names(options)
    mesh = _tet_mesh(throw_mesh)
    for attr in ("youngs_modulus", "poisson_ratio", "density"):
        if not hasattr(material, attr):
            raise InputError(f"material has no {attr!r}", key=f"material.{attr}")
    t_all = time.perf_counter()
    needed = list(options.journals) + [options.reaction_face]
    if any(c.startswith("pin") for c in options.cases):
        needed.append(options.pin_boundary)
    if "torque" in options.cases:
        needed.append(options.torque_face)
    for name in needed:
        boundary_facets(mesh, name, "the unit load cases")
    check_support_options(options)
    E, nu = material.youngs_modulus, material.poisson_ratio
    axes = tuple(throw_mesh.symmetry) if options.symmetry else ()
    if options.support == "foundation":
        k_bearing = options.bearing_stiffness
        assert k_bearing is not None  # check_support_options refuses a foundation without it
        if axes:
            log.info(
                "fe-crank: the foundation support is solved on the full model (symmetry components: "
                "determinate supports only)"
            )
        system = build_system(
            mesh,
            E,
            nu,
            foundations=[Foundation(j, k_bearing) for j in options.journals],
            couplings=[Coupling(options.reaction_face, fixed=("uz", "rz"))],
            solver=options.solver,
            intorder=options.intorder,
        )
    else:
        layout = DeterminateLayout(
            journals=(options.journals[0], options.journals[1]),
            torque_face=options.reaction_face,
            axial=axial_journal(options),
        )
        system = determinate_system(mesh, E, nu, layout, axes, solver=options.solver, intorder=options.intorder)
    basis = system.basis
    t0 = time.perf_counter()
    loads, desc, pins = unit_loads(basis, material, options)
    names = list(loads)
    t_loads = time.perf_counter() - t0
    t0 = time.perf_counter()
    U = system.solve(np.column_stack([loads[n] for n in names]))
    t_solve = time.perf_counter() - t0
    cases = {}
    for i, name in enumerate(names):
        applied = system.applied(loads[name])  # once per case: the error, the point check, the record
        err, reac = system.equilibrium_error(U[:, i], loads[name], applied=applied)
        if "point_constraints" in reac:
            _check_point_reactions(reac["point_constraints"], applied, name)
        if not err < EQUILIBRIUM_TOL:
            raise SolverError(
                f"unit case {name!r}: reactions do not balance the loads "
                f"(relative error {err:.2e} > {EQUILIBRIUM_TOL:g})"
            )
        cases[name] = UnitCase(
            name=name,
            description=desc[name],
            displacement=U[:, i],
            applied=applied[0],
            reactions=reac,
            equilibrium_error=err,
        )
    timings = dict(system.timings)
    if system.symmetric is not None:  # the components are factorised by the solve that needs them
        t_factors = system.symmetric.factors.seconds
        timings["factorisation"] = timings.get("factorisation", 0.0) + t_factors
        t_solve -= t_factors
    timings.update(
        analysis=system.factorisation.analysis_time,
        loads=t_loads,
        solve=t_solve,
        solve_per_case=t_solve / max(len(names), 1),
        total=time.perf_counter() - t_all,
    )
    sup = system.determinate
    centres = {j: float(c[2]) for j, c in sup.centres.items()} if sup is not None else {}
    return UnitSolutions(
        system=system,
        material=material,
        options=options,
        cases=cases,
        pin=pins,
        bearing_stiffness=options.bearing_stiffness,
        support_model=support_text(options, centres),
        bearing_centres=centres,
        timings=timings,
    )


def _check_point_reactions(point: np.ndarray, applied, name: str) -> None:
    """The six point constraints of the determinate model must carry nothing but round-off
    (above ``POINT_REACTION_TOL`` of the load scale it is a SolverError).  ``applied``:
    ``System.applied`` of the case's load (resultant, force scale, moment scale)."""
    _, fs, ms = applied
    pf = np.linalg.norm(point[:3]) / fs if fs > 0 else np.linalg.norm(point[:3])
    pm = np.linalg.norm(point[3:]) / ms if ms > 0 else np.linalg.norm(point[3:])
    if max(pf, pm) > POINT_REACTION_TOL:
        raise SolverError(
            f"unit case {name!r}: the point constraints carry a reaction ({max(pf, pm):.2e} of "
            f"the load): the determinate reactions do not balance the load"
        )
