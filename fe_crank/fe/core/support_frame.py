"""Displacements in the frame of the supports: the rigid motion the solve leaves in is removed.

The determinate model (``fe_crank.fe.core.determinate``) applies the six support reactions as
loads and holds six single dofs on the journals' end faces against the rigid-body modes;
its displacement therefore carries an arbitrary rigid motion, the one that makes those six
dofs zero, not the one of the support model, in which the main-bearing centres stay at rest
(radially at both, axially at one) and the torque end face does not turn.  Stresses do not
see it; a picture of the deformed shape or a VTU displacement does (35-124 % of the largest
displacement, measured against CalculiX on the determinate model).

The support displacements are the work conjugates of the reaction components: for a unit
value of component k distributed on the mesh as the nodal loads g_k (column k of
``DeterminateSupport.G``; the RBE3 distribution for a bearing-centre force, the shear flow
for the end-face torque), the displacement of the reference point in that direction is
d_k = g_k . u (the virtual work of the coupling).  A rigid motion r = B a (``B`` the six
rigid-body modes at the nodes) moves them by G^T B a = A^T a, where A is the matrix of the
resultants (force, moment about the origin) of the columns of G: the work of a load on a
translation is its force, on a rotation its moment.  So

    a = A^-T G^T u,    u_support = u - B a

is the unique rigid motion whose removal brings every support displacement to zero; the
strains, and so the stresses, are unchanged.  ``u`` may hold several fields as columns.
"""

from __future__ import annotations

import numpy as np

from fe_crank.fe.core.supports import rigid_body_modes


def support_displacements(u: np.ndarray, G, points: np.ndarray | None = None) -> np.ndarray:
    """d = G^T u: each reaction component's reference displacement (6,) or (6, k)."""
    return np.asarray(G.T @ u)


def rigid_motion_at_supports(u: np.ndarray, G, A: np.ndarray) -> np.ndarray:
    """The rigid-body coefficients a (6,) or (6, k) (translations, rotations about the
    origin) whose motion B a moves the supports as ``u`` does: a = A^-T G^T u."""
    return np.linalg.solve(np.asarray(A).T, support_displacements(u, G))


def in_support_frame(u: np.ndarray, G, A: np.ndarray, points: np.ndarray) -> np.ndarray:
    """``u`` (3 N,) or (3 N, k) with the rigid motion removed that moves the supports of
    ``G``/``A`` (``DeterminateSupport``): the main-bearing centres at rest, the torque face
    not turning.  ``points`` (3, N): the nodes of ``u``."""
    a = rigid_motion_at_supports(u, G, A)
    return u - rigid_body_modes(np.asarray(points)) @ a


def field_in_support_frame(unit_solutions, u: np.ndarray) -> np.ndarray:
    """A displacement ``u`` of the FE stage's ``UnitSolutions`` (a unit case or a superposed
    state) in the frame of its determinate supports; the foundation model has no rigid
    motion of its own to remove: ``u`` is returned as solved."""
    sup = unit_solutions.system.determinate
    if sup is None:
        return u
    return in_support_frame(u, sup.G, sup.A, sup.points)


def unit_case_in_support_frame(unit_solutions, name: str) -> np.ndarray:
    """The displacement of the unit case ``name`` in the frame of its supports
    (``field_in_support_frame``)."""
    return field_in_support_frame(unit_solutions, unit_solutions.displacement(name))


__all__ = [
    "support_displacements",
    "rigid_motion_at_supports",
    "in_support_frame",
    "field_in_support_frame",
    "unit_case_in_support_frame",
]
