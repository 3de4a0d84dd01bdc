"""Unit-load superposition over the cycle.

Linear elasticity makes the stress at crank angle theta an exact linear combination of
the unit solutions (docs/fe.md)::

    sigma(theta) = omega^2 S_c + sum_k a_k(F(theta)) S_pk + T(theta) S_t

with ``S_c`` the stress of the centrifugal case at omega = 1 rad/s (body force
rho omega^2 r scales with omega^2), ``S_pk`` the stresses of 1 N on the crankpin in
direction k of the throw frame (x tangential, y radial outward; 12 directions 30 deg
apart by default), ``a_k`` the weights of the two directions that bracket the pin force
F (``fe_crank.fe.throw.pin_directions``), ``S_t`` the stress of 1 N m through the throw, and
``F, T`` the crankpin force and the torque entering the throw at its front journal
(``torque_front``) from the dynamics stage.  With torsional vibration the throw's own
inertia torque enters as the body force of its angular acceleration ``alpha(theta)``
(unit case ``angular_acceleration``, + alpha S_a), so that the torque leaving at the rear
journal is the torsional stage's (``fe_crank.torsion.flow``).
"""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field

import numpy as np

from fe_crank.fe.core.loads import CENTRIFUGAL_PARTS
from fe_crank.fe.core.stress import stress_at_selected_nodes
from fe_crank.fe.throw.options import CASES as UNIT_CASES  # the FE stage's default unit cases
from fe_crank.fe.throw.pin_directions import patch_case, pin_case_weights, pin_direction
from fe_crank.fe.throw.pin_patches import patch_forces
from fe_crank.fe.throw.unit_cases import UnitSolutions
from fe_crank.rules.m53.calculation import RodLoads


@dataclass(frozen=True)
class UnitStresses:
    """Nodal stresses of the unit cases at the assessed nodes of one throw.

    ``stress`` (n_cases, 6, n): components ``stress.COMPONENTS``, Pa per unit load;
    ``points`` (3, n) node coordinates (throw frame, m); ``groups`` name -> indices
    into the n assessed nodes (fillets, oil bore, counterweights, junctions);
    ``node_ids`` the mesh node numbers of the assessed nodes.
    """

    stress: np.ndarray
    points: np.ndarray
    groups: dict[str, np.ndarray] = field(default_factory=dict)
    node_ids: np.ndarray | None = None
    cases: tuple[str, ...] = UNIT_CASES
    torque_mz: float = -1.0  # M_z of the unit torque case (FE stage: 1 N m in the sense of rotation)
    pin_patches: tuple[tuple[float, float], ...] = ()  # the FE stage's rod-place bands (patch cases)

    @property
    def n_nodes(self) -> int:
        n: int = self.stress.shape[-1]
        return n


def unit_nodal_stress(unit_solutions: UnitSolutions, cases: Sequence[str], node_ids: np.ndarray) -> np.ndarray:
    """Averaged nodal stresses (n_cases, 6, n) of the unit cases ``cases`` of ``unit_solutions`` (the FE
    stage's ``UnitSolutions``) at the mesh nodes ``node_ids``, Voigt xx yy zz xy yz zx, Pa.

    Equal to ``unit_solutions.stress_at_nodes(u_c)[:, node_ids]`` for each case (the average at a node
    takes every element sharing it), computed on those elements only and with one node
    basis for all cases (``fe_crank.fe.core.stress.stress_at_selected_nodes``).
    """
    mat = unit_solutions.material
    return stress_at_selected_nodes(
        unit_solutions.mesh,
        [unit_solutions.displacement(c) for c in cases],
        mat.youngs_modulus,
        mat.poisson_ratio,
        node_ids,
        dofs=unit_solutions.system.basis.dofs,
    )


def load_coefficients(
    pin_force: np.ndarray,
    torque: np.ndarray,
    omega: float,
    *,
    cases: tuple[str, ...] = UNIT_CASES,
    sense: int = 1,
    torque_mz: float = -1.0,
    angular_acceleration: np.ndarray | None = None,
    patch_forces: dict[int, np.ndarray] | None = None,
) -> np.ndarray:
    """Coefficients (n_angles, len(cases)) of the unit cases over the cycle.

    ``pin_force`` (n, 2) in the throw frame [N]; ``torque`` (n,) the torque through the
    front journal (``ThrowLoads.torque_front``) in the shaft's sense of rotation [N m];
    ``omega`` [rad/s]; ``sense`` the shaft's sense (+1 turns about -z, model.py).
    Centrifugal: omega^2.  Pin: the two pin cases whose directions bracket the force carry
    it with non-negative weights (``pin_directions.pin_case_weights``, the FE stage's
    ``UnitSolutions.pin_weights``); with two pin cases only, the signed decomposition.
    Torque: the FE case applies a moment ``torque_mz`` about +z at the front face (the FE stage's case is 1 N m in the sense of rotation of a sense +1 shaft,
    M_z = -1 N m); the torque through the front journal acts about -sense z, so its
    coefficient is -sense * torque_front / torque_mz.
    Angular acceleration (the ``angular_acceleration`` case, 1 rad/s^2 in the sense of
    rotation of a sense +1 shaft): ``angular_acceleration`` (n,) rad/s^2 in the shaft's
    sense (the throw's torsional vibration, ``fe_crank.torsion.flow``), coefficient
    sense * alpha; zero when not given.
    Patch cases ``<pin case>@<k>`` (one band per rod place, ``fe.throw.pin_patches``) carry
    ``patch_forces[k]`` (n, 2), the force of the rods bearing on band k, the same way.
    """
    pin_force = np.asarray(pin_force, float)
    torque = np.asarray(torque, float)
    n = pin_force.shape[0]
    if pin_force.shape != (n, 2) or torque.shape != (n,):
        raise ValueError(f"pin_force must be (n, 2) and torque (n,); got {pin_force.shape}, {torque.shape}")
    pins = [c for c in cases if pin_direction(c) is not None]
    patch: dict[str, np.ndarray] = {}
    by_patch: dict[int, list[str]] = {}
    for c in cases:
        pc = patch_case(c)
        if pc is not None:
            by_patch.setdefault(pc[0], []).append(c)
    # the pin's force goes to the whole-pin cases, or rod by rod to the patch cases
    wp = pin_case_weights(pin_force, pins) if pins or not by_patch else np.zeros((n, 0))
    if by_patch and patch_forces is None:
        raise ValueError("patch unit cases (one band per rod place) need each patch's force")
    for k, names in by_patch.items():
        assert patch_forces is not None
        f = np.asarray(patch_forces.get(k, np.zeros((n, 2))), float)
        w = pin_case_weights(f, [c.partition("@")[0] for c in names])
        patch.update({c: w[:, i] for i, c in enumerate(names)})
    cols = []
    for name in cases:
        if name == "centrifugal" or name in CENTRIFUGAL_PARTS:  # the parts: the drawn counterweights (k = 1)
            cols.append(np.full(n, omega**2))
        elif name == "torque":
            cols.append(-sense * torque / torque_mz)
        elif name == "angular_acceleration":
            alpha = np.zeros(n) if angular_acceleration is None else np.asarray(angular_acceleration, float)
            if alpha.shape != (n,):
                raise ValueError(f"angular_acceleration must be (n,); got {alpha.shape}")
            cols.append(sense * alpha)
        elif name in pins:
            cols.append(wp[:, pins.index(name)])
        elif name in patch:
            cols.append(patch[name])
        else:
            raise ValueError(f"unknown unit case {name!r}")
    return np.column_stack(cols)


def cycle_coefficients(
    unit: UnitStresses,
    pin_force: np.ndarray,
    torque: np.ndarray,
    omega: float,
    *,
    sense: int = 1,
    rod_loads: RodLoads | None = None,
    angular_acceleration: np.ndarray | None = None,
    vibration: bool = False,
) -> np.ndarray:
    """``load_coefficients`` of ``unit``'s cases; with patch cases, the rods' forces go to the
    bands of their places (``rod_loads``: (force (n, 2), place m) per rod, ``fe.throw.pin_patches``).
    ``angular_acceleration`` and ``vibration`` (``pin_force`` then carries the cylinders'
    vibratory inertia torque as a tangential force, ``torsion.flow.fe_loads``): the throw's
    torsional vibration; the rods' own forces do not carry that torque, so a model loaded per
    rod place is refused with it unless ``rod_loads`` are the rods' forces with their shares
    of it (then ``vibration`` False: ``assess.loads.ThrowCycle.fe_rods``)."""
    patches = None
    if any(patch_case(c) is not None for c in unit.cases):
        if rod_loads is None:
            raise ValueError("the FE model loads the pin per rod place: the rods' forces and places are needed")
        if vibration:
            raise ValueError("the FE model loads the pin per rod place, which the vibratory pin force cannot load")
        patches = patch_forces(rod_loads, unit.pin_patches)
    return load_coefficients(
        pin_force,
        torque,
        omega,
        cases=unit.cases,
        sense=sense,
        torque_mz=unit.torque_mz,
        patch_forces=patches,
        angular_acceleration=angular_acceleration,
    )


def combine(unit: np.ndarray, coefficients: np.ndarray) -> np.ndarray:
    """sum_c coefficients[t, c] unit[c, ...] for every t: shape (n_t, ...).

    Works for nodal stresses (n_cases, 6, n) and displacement vectors (n_cases, n_dof).
    """
    unit = np.asarray(unit)
    c = np.atleast_2d(np.asarray(coefficients, float))
    if c.shape[1] != unit.shape[0]:
        raise ValueError(f"{c.shape[1]} coefficients for {unit.shape[0]} unit cases")
    return np.tensordot(c, unit, axes=(1, 0))


def stress_history(unit: UnitStresses, coefficients: np.ndarray, nodes: slice | np.ndarray = slice(None)) -> np.ndarray:
    """Stress tensors (n_t, 6, n_selected) over the cycle at ``nodes``."""
    return combine(unit.stress[:, :, nodes], coefficients)


def iter_histories(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, chunk: int = 2048
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Yield (node indices, history (n_t, 6, k)) in chunks, to bound memory."""
    nodes = np.asarray(nodes)
    for start in range(0, nodes.size, chunk):
        idx = nodes[start : start + chunk]
        yield idx, stress_history(unit, coefficients, idx)


def iter_planes(
    unit: UnitStresses, coefficients: np.ndarray, nodes: np.ndarray, block: int = 128
) -> Iterator[tuple[np.ndarray, np.ndarray]]:
    """Yield (node indices, history planes (6, n_t, k)) ``block`` nodes at a time: the
    history of ``stress_history`` with the component axis first, each component's
    (n_t, k) plane contiguous (component j: coefficients (n_t, n_cases) times that
    component's unit stresses (n_cases, k), one matrix product per component).
    """
    nodes = np.asarray(nodes)
    c = np.atleast_2d(np.asarray(coefficients, float))
    if c.shape[1] != unit.stress.shape[0]:
        raise ValueError(f"{c.shape[1]} coefficients for {unit.stress.shape[0]} unit cases")
    for start in range(0, nodes.size, block):
        idx = nodes[start : start + block]
        u = unit.stress[:, :, idx]
        planes = np.empty((6, c.shape[0], idx.size))
        for j in range(6):
            np.dot(c, u[:, j, :], out=planes[j])
        yield idx, planes
