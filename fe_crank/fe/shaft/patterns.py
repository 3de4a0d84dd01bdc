"""Local load patterns of the whole-shaft pieces (each in its own frame) and their moments.

Every load of the whole-shaft model is a combination of these, placed into the shaft
frame (``fe_crank.fe.shaft``):

* ``pin_<deg>``: 1 N on the crankpin as the cosine pressure of ``fe.core.loads.pin_pressure_load``
  (12 directions, a force is carried by the two that bracket it, ``fe.throw.pin_directions``);
* ``centrifugal``: rho omega^2 r_perp, omega = 1 rad/s, on every element but the
  counterweights'; ``centrifugal_cw``: the same on the counterweights alone (switched off
  for "without counterweights"); their sum is the throw's whole centrifugal load;
* ``spin_up``: the body force rho (e_z x x) of a unit angular acceleration about z
  (the d'Alembert load of an angular acceleration alpha is -alpha times it);
* on each bearing surface s (``journal_1``, ``journal_2`` of a throw, ``surface`` of an
  end journal) with consistent nodal areas a_i = int_s N_i dA, the six patterns
  ``s.P0 .. s.P2`` = a_i e_k and ``s.Q0 .. s.Q2`` = a_i (e_k x x_i): any distributing
  (RBE3) coupling on the surface is a combination of them, and they are also the
  functionals whose products with a displacement give the coupling's reference motion;
* ``torque_end_1`` / ``torque_end_2``: M_z = +1 N m on an end face as the shear flow of a
  round shaft (``fe.core.loads.face_torque_load``), where the power leaves.

``surface_moments`` gives sum a_i, sum a_i x_i and sum a_i x_i x_i^T of a bearing surface.
"""

from __future__ import annotations

import numpy as np
from skfem import ElementTetP2

from fe_crank.fe.core.assembly import assemble_body_load, assemble_surface_load
from fe_crank.fe.core.loads import COUNTERWEIGHT_BODIES as COUNTERWEIGHTS
from fe_crank.fe.core.loads import element_basis, face_torque_load, pin_pressure_load, pin_surface
from fe_crank.fe.core.supports import boundary_facets, facet_basis
from fe_crank.fe.throw.pin_directions import pin_cases, unit_force

SURFACE_INTORDER = 4


def body_loads(basis, density: float, per_web: bool = False) -> dict[str, np.ndarray]:
    """``centrifugal``, ``centrifugal_cw`` (zero without counterweights) and ``spin_up``;
    ``per_web``: also ``centrifugal_cw_1`` and ``centrifugal_cw_2``, the counterweight of
    each web alone (zero where the web has none; their sum is ``centrifugal_cw``)."""
    mesh = basis.mesh
    cw = np.unique(
        np.concatenate(
            [np.asarray(mesh.subdomains[n]) for n in COUNTERWEIGHTS if n in (mesh.subdomains or {})]
            or [np.zeros(0, int)]
        )
    )
    rest = np.setdiff1d(np.arange(mesh.nelements), cw)

    def radial(x):
        return density * np.stack([x[0], x[1], np.zeros_like(x[0])])

    def tangential(x):
        return density * np.stack([-x[1], x[0], np.zeros_like(x[0])])

    out = {"centrifugal": assemble_body_load(element_basis(basis, rest), radial)}
    out["centrifugal_cw"] = assemble_body_load(element_basis(basis, cw), radial) if cw.size else np.zeros(3 * basis.N)
    out["spin_up"] = assemble_body_load(basis, tangential)
    for name in COUNTERWEIGHTS if per_web else ():
        own = np.asarray((mesh.subdomains or {}).get(name, np.zeros(0, int)))
        out[f"centrifugal_cw_{name[-1]}"] = (
            assemble_body_load(element_basis(basis, own), radial) if own.size else np.zeros(3 * basis.N)
        )
    return out


def nodal_areas(basis, boundary: str) -> np.ndarray:
    """a_i = int_s N_i dA (N,) on the named surface."""
    fb = facet_basis(
        basis.mesh,
        ElementTetP2(),
        boundary_facets(basis.mesh, boundary, "a main-bearing coupling"),
        SURFACE_INTORDER,
        f"the bearing surface {boundary}",
    )
    f = assemble_surface_load(fb, lambda x, n: np.stack([np.ones_like(x[0]), np.zeros_like(x[0]), np.zeros_like(x[0])]))
    return f.reshape(-1, 3)[:, 0]


def surface_patterns(basis, boundary: str) -> tuple[dict[str, np.ndarray], tuple]:
    """The six patterns of a bearing surface (module doc) and its moments (m0, m1, m2)."""
    a = nodal_areas(basis, boundary)
    x = basis.doflocs
    out = {}
    for k in range(3):
        p = np.zeros((basis.N, 3))
        p[:, k] = a
        out[f"{boundary}.P{k}"] = p.ravel()
        e = np.zeros(3)
        e[k] = 1.0
        out[f"{boundary}.Q{k}"] = (a[:, None] * np.cross(e, x.T)).ravel()
    on = a != 0
    m0 = float(a.sum())
    m1 = (a[on] * x[:, on]).sum(axis=1)
    m2 = np.einsum("i,ji,ki->jk", a[on], x[:, on], x[:, on])
    return out, (m0, m1, m2)


def throw_patterns(
    basis, density: float, half_angle: float, torque_faces=(), per_web: bool = False
) -> dict[str, np.ndarray]:
    """Pin, body and torque patterns of a throw (module doc); ``per_web``: the counterweight
    of each web as a centrifugal pattern of its own (``body_loads``)."""
    out = {}
    surface = pin_surface(basis, "crankpin")
    for name in pin_cases():
        out[name], _ = pin_pressure_load(basis, unit_force(name), half_angle=half_angle, surface=surface)
    out.update(body_loads(basis, density, per_web))
    for face in torque_faces:
        out[f"torque_{face}"] = face_torque_load(basis, 1.0, boundary=face)
    return out


def end_patterns(basis, density: float, torque_faces=()) -> dict[str, np.ndarray]:
    """Body and torque patterns of an extruded end journal."""
    out = body_loads(basis, density)
    for face in torque_faces:
        out[f"torque_{face}"] = face_torque_load(basis, 1.0, boundary=face)
    return out
