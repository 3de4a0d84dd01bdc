"""Torsional stiffness of one crank throw: Carter's empirical equivalent length and the
twist of the project's FE throw model under its unit torque.

Carter's formula (B. C. Carter, 1928, as given by Den Hartog, *Mechanical Vibrations*,
4th ed., sec. 5.2, and Ker Wilson, *Practical Solution of Torsional Vibration Problems*,
vol. 1, ch. 4): the length of plain journal-diameter shaft that twists like one throw
(journal length ``L_j`` in the throw, two webs of thickness ``h`` and width ``b``, pin
of length ``L_p`` and diameter ``D_p``, crank radius ``R``)::

    L_e = (L_j + 0.8 h) + 0.75 L_p (D_j / D_p)^4 + 1.5 R D_j^4 / (h b^3)

and ``k = G I_p / L_e`` with ``I_p = pi D_j^4 / 32``.  The three terms: the journals
(lengthened by 0.4 h into each web), the pin in torsion (shortened where the webs hold
it), the two webs in bending about their thickness (the beam value
``2 * 12 R / (E h b^3)`` times an empirical 1.5 / 0.906 for the flexible web-pin and
web-journal junctions).  The formula is empirical; it is compared with the FE value
in docs/torsion.md.

FE: the torque unit case of ``fe_crank.fe.throw.unit_cases`` applies 1 N m as the Saint-Venant
shear flow on ``end_1`` and holds ``end_2`` (rigidly coupled to the axis in rotation);
the radial journal foundation carries no torque.  The rotation of an end face is the one
work-conjugate to that shear flow: with ``f`` the consistent nodal forces of a unit torque
applied to the face as the same shear flow (``fe.core.loads.face_torque_load``),

    phi = f . u = int (x u_y - y u_x) dA / int (x^2 + y^2) dA,

the face's displacement weighted by its area (the continuum form: the shear flow of a
round shaft is t = T r e_theta / J).  It is exact for a face that turns rigidly (the
nodal forces' moment is 1 N m exactly), and on the loaded face ``T phi_1`` is the work
the torque does, so ``k = |M_z| / |phi_1 - phi_2|`` is the stiffness whose strain energy
``T^2 / (2 k)`` equals the model's (Castigliano: phi = dU/dT), whatever the face's
mesh.  A fit over the face's nodes with equal weights is not: it weighs the nodes, not
the area, and moved the throw's stiffness by 5 % with the end faces' meshing.

The chain's FE throw stiffness (``throw_stiffness = "fe"``, ``plan_throw_stiffness``):
that of the mesh plan's first throw model (``mesh.plan.throw_keys``: the engine's first
throw, or the one model that stands for every throw), for every pitch of the chain; the
check reads it from its FE stage's unit cases, the counterweight study solves the torque
case alone on the same model of the geometry each candidate writes (one assembled
stiffness, the torque a right-hand side of its own: the same displacement).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Mapping

import numpy as np

from fe_crank.cad.source import GeometrySource, mesh_source_throw
from fe_crank.errors import InputError
from fe_crank.fe.core.loads import face_torque_load
from fe_crank.fe.throw.options import FeOptions, Material
from fe_crank.fe.throw.unit_cases import UnitSolutions, solve_unit_cases
from fe_crank.mesh.plan import MeshPlan


def carter_equivalent_length(
    *,
    journal_diameter: float,
    journal_length: float,
    web_thickness: float,
    web_width: float,
    pin_diameter: float,
    pin_length: float,
    crank_radius: float,
) -> float:
    """Carter's equivalent length (m) of one throw, referred to the journal diameter."""
    dj, h, b = journal_diameter, web_thickness, web_width
    for key, v in (
        ("journal_diameter", dj),
        ("web_thickness", h),
        ("web_width", b),
        ("pin_diameter", pin_diameter),
        ("crank_radius", crank_radius),
    ):
        if not v > 0:
            raise InputError(f"must be positive for the throw stiffness (got {v} m)", key=f"geometry.{key}")
    return (
        (journal_length + 0.8 * h)
        + 0.75 * pin_length * (dj / pin_diameter) ** 4
        + 1.5 * crank_radius * dj**4 / (h * b**3)
    )


def shaft_stiffness(shear_modulus: float, diameter: float, length: float) -> float:
    """``k = G pi D^4 / (32 L)`` of a plain round shaft (N m/rad)."""
    return shear_modulus * math.pi * diameter**4 / (32.0 * length)


def carter_throw_stiffness(geometry, shear_modulus: float, journal_length: float | None = None) -> float:
    """Carter stiffness of one throw of a ``CrankGeometry`` (N m/rad).

    ``journal_length``: the journal length inside the throw (default: the geometry's two
    half-journals, ``2 * journal_length``, the span of the FE throw model).  The web
    width is the UR M53 width at the middle of the pin/journal overlap
    (``fe_crank.assess.adapters.m53_geometry_of``)."""
    from fe_crank.assess.adapters import m53_geometry_of

    m = m53_geometry_of(geometry)
    if m is None:
        raise InputError("the geometry lacks the dimensions of a crank throw", key="geometry")
    lj = 2.0 * geometry.journal_length if journal_length is None else journal_length
    le = carter_equivalent_length(
        journal_diameter=m.journal_diameter,
        journal_length=lj,
        web_thickness=m.web_thickness,
        web_width=m.web_width,
        pin_diameter=m.pin_diameter,
        pin_length=geometry.crankpin_length,
        crank_radius=m.crank_radius,
    )
    return shaft_stiffness(shear_modulus, m.journal_diameter, le)


def throw_span(geometry) -> float:
    """Axial length of the FE throw model, end_1 to end_2: ``L_p + 2 h + 2 L_j``."""
    return geometry.crankpin_length + 2 * geometry.web_thickness + 2 * geometry.journal_length


def face_rotation(basis, displacement: np.ndarray, face: str) -> float:
    """Rotation about z (rad, right-handed) of the boundary ``face``, work-conjugate to the
    Saint-Venant shear flow of a torque on it (module docstring): ``f . u`` with ``f`` the
    nodal forces of 1 N m on the face (``face_torque_load``), ``u`` the displacement vector
    of ``basis``."""
    f = face_torque_load(basis, 1.0, boundary=face)
    return float(f @ np.asarray(displacement, float))


def fe_throw_stiffness(unit_solutions: UnitSolutions, faces=("end_1", "end_2")) -> float:
    """Torsional stiffness (N m/rad) of the FE throw between its end faces from the
    ``torque`` unit case of a ``UnitSolutions`` (module docstring)."""
    if "torque" not in unit_solutions.cases:
        raise InputError("the FE unit cases lack 'torque'", key="fe.cases")
    case = unit_solutions.cases["torque"]
    basis = unit_solutions.system.basis
    rot = [face_rotation(basis, case.displacement, face) for face in faces]
    twist = rot[0] - rot[1]
    mz = float(case.applied[5])
    if not twist * mz > 0:
        raise ValueError(f"FE twist {twist:.3g} rad does not follow the applied torque {mz:.3g} N m")
    return abs(mz) / abs(twist)


def plan_throw_stiffness(
    geometry: GeometrySource,
    plan: MeshPlan,
    material: Material,
    fe: FeOptions,
    unit_solutions: Mapping[str, UnitSolutions] | None = None,
) -> float | None:
    """The FE throw stiffness (N m/rad) the chain takes with ``throw_stiffness = "fe"``
    (module docstring): ``fe_throw_stiffness`` of the torque unit case of the first
    throw model of ``plan``.  ``unit_solutions``: the FE stage's (plan key -> the unit
    cases of its model), read; without them the model is meshed with the plan's options
    (``cad.source.mesh_source_throw``, cached) and the torque case alone solved on it
    with the supports of ``fe``.  None: ``fe`` (or the solutions) hold no torque case."""
    key, throw = next(iter(plan.throws.items()))
    if unit_solutions is not None:
        solved = unit_solutions[key]
        return fe_throw_stiffness(solved) if "torque" in solved.cases else None
    if "torque" not in fe.cases:
        return None
    mesh = mesh_source_throw(
        geometry, throw, size=plan.options, cache_dir=plan.cache_dir, max_elements=plan.max_elements
    )
    solved = solve_unit_cases(mesh, material, dataclasses.replace(fe, cases=("torque",)))
    solved.system.factorisation.free()
    return fe_throw_stiffness(solved)
