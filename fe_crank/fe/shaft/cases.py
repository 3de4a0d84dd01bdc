"""Unit cases of the whole shaft on its statically determinate base (the force method).

Base: the first and the last main bearing held radially (x, y at their reference points),
the thrust bearing axially, the torque M_z at the power take-off's end face (the shear
flow of a round shaft).  For every unit case its six base reactions follow from statics,
R = -A^-1 (F, M) (A: the resultants of the six base reactions as distributed on the
mesh), and are applied as loads, so the case's load is self-equilibrated; the condensed
interface system S_G U = G is then solved with six single interface dofs held against the
rigid-body modes (a 3-2-1 set by pivoted QR, ``fe.core.determinate.point_constraints``), which
carry round-off only (checked).  This is the Lagrange-multiplier model of the shaft on its
determinate base (as ``fe.core.determinate`` for one throw).

Cases: ``pin_<deg>@<throw>`` (1 N on a throw's crankpin, throw frame), ``centrifugal``
(omega = 1 rad/s on everything that turns but the counterweights), ``centrifugal_cw`` (the
counterweights alone), and for every other bearing ``<bearing>.x``, ``<bearing>.y`` (1 N
on the shaft at its reference point, shaft frame).  Per case: the bearings' reference
displacements d (shaft frame), and ``d_rel``, their radial part relative to the line
through the two base bearings (the rigid motion that the base allows removed): the
flexibility of the redundant bearings is C = d_rel[redundant, unit cases].
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from fe_crank.errors import SolverError
from fe_crank.fe.core.determinate import point_constraints
from fe_crank.fe.shaft.model import ShaftModel
from fe_crank.fe.throw.pin_directions import pin_cases

#: the held interface dofs may carry at most this fraction of the load (round-off)
HELD_TOL = 1e-8


@dataclass
class ShaftCases:
    model: ShaftModel
    names: tuple[str, ...]
    coef: list[np.ndarray]  # per piece (n_pat, n_cases): local load coefficients, base reactions included
    V: list[np.ndarray]  # per piece (nb, n_cases): end-face displacements, local frame
    base: np.ndarray  # (6, n_cases): base reactions on the shaft: A.x A.y B.x B.y thrust.z torque.z
    base_bearings: tuple[int, int]
    d: np.ndarray  # (n_bearings, 3, n_cases) reference displacements, shaft frame
    d_rel: np.ndarray  # (n_bearings, 2, n_cases) radial, relative to the base line
    redundant: tuple[int, ...]  # bearing indices that are not base bearings
    held: np.ndarray  # the six interface dofs held against the rigid-body modes
    #: (n_bearings, 2, n_cases) the journal's mean slope (dx/dz, dy/dz) at each bearing,
    #: shaft frame, relative to the line through the two base bearings (the rotation of the
    #: distributing coupling's reference point, ``BearingCoupling.rotations``)
    slope: np.ndarray | None = None

    def index(self, name: str) -> int:
        return self.names.index(name)

    def recover(self, piece: int, weights: np.ndarray) -> np.ndarray:
        """Displacements (3 n_rec, k) at piece ``piece``'s recovery nodes (local frame) for
        case combinations ``weights`` (n_cases, k): sum_p a_p L_p + X v."""
        pp = self.model.pieces[piece]
        c = pp.cond
        rec = (3 * c.rec_nodes[:, None] + np.arange(3)).ravel()
        return c.L[rec] @ (self.coef[piece] @ weights) + c.X_rec @ (self.V[piece] @ weights)


def _terms(model: ShaftModel, loads: list[dict[tuple[int, str], float]]) -> list[np.ndarray]:
    out = []
    for pp in model.pieces:
        M = np.zeros((len(pp.cond.names), len(loads)))
        for j, t in enumerate(loads):
            for (k, name), v in t.items():
                if k == pp.index:
                    M[pp.cond.names.index(name), j] += v
        out.append(M)
    return out


def _resultants(model: ShaftModel, coef: list[np.ndarray]) -> np.ndarray:
    return np.sum([pp.placed_resultant(pp.cond.resultant @ a) for pp, a in zip(model.pieces, coef)], axis=0)


def applied_loads(model: ShaftModel) -> tuple[list[str], list[dict]]:
    names, loads = [], []
    for pp in model.pieces:
        if pp.kind == "throw":
            for p in pin_cases():
                names.append(f"{p}@{pp.throw}")
                loads.append({(pp.index, p): 1.0})
    names += ["centrifugal", "centrifugal_cw"]
    loads.append({(pp.index, "centrifugal"): 1.0 for pp in model.pieces})
    loads.append({(pp.index, "centrifugal_cw"): 1.0 for pp in model.pieces})
    return names, loads


def solve_cases(model: ShaftModel, extra: dict[str, dict[tuple[int, str], float]] | None = None) -> ShaftCases:
    """All unit cases on the determinate base (module doc); ``extra``: further applied
    loads by name, as {(piece, pattern): coefficient}."""
    nb = len(model.bearings)
    A, B = 0, nb - 1
    thrust = next(i for i, b in enumerate(model.mesh.layout.bearings) if b.thrust)
    names, loads = applied_loads(model)
    for name, t in (extra or {}).items():
        names.append(name)
        loads.append(dict(t))
    redundant = tuple(i for i in range(nb) if i not in (A, B))
    for i in redundant:
        b = model.bearings[i]
        names += [f"{b.name}.x", f"{b.name}.y"]
        loads += [dict(b.terms[0]), dict(b.terms[1])]
    base_loads = [
        model.bearings[A].terms[0],
        model.bearings[A].terms[1],
        model.bearings[B].terms[0],
        model.bearings[B].terms[1],
        model.bearings[thrust].terms[2],
        {model.torque_term: 1.0},
    ]
    coef = _terms(model, loads)
    base_coef = _terms(model, base_loads)
    F = _resultants(model, coef)
    Fb = _resultants(model, base_coef)
    if np.linalg.cond(Fb) > 1e12:
        raise SolverError("the base bearings cannot balance every load (coincident bearing centres?)")
    R = -np.linalg.solve(Fb, F)
    coef = [a + ab @ R for a, ab in zip(coef, base_coef)]
    n = model.n_interface
    G = np.zeros((n, len(names)))
    for pp, a in zip(model.pieces, coef):
        G[pp.dofs] += pp.to_shaft(pp.cond.g @ a)
    held = point_constraints(model.points, np.arange(model.points.shape[1]))
    S = model.S.copy()
    S[held, :] = 0.0
    S[:, held] = 0.0
    S[held, held] = 1.0
    rhs = G.copy()
    rhs[held] = 0.0
    try:
        U = sla.cho_solve(sla.cho_factor(S), rhs)
    except np.linalg.LinAlgError as exc:
        raise SolverError(f"the condensed shaft is singular on its base: {exc}") from exc
    reaction = model.S[held] @ U - G[held]
    scale = np.abs(G).sum(axis=0) + 1e-300
    if np.max(np.abs(reaction) / scale) > HELD_TOL:
        raise SolverError(
            f"the held interface dofs carry {np.max(np.abs(reaction) / scale):.2e} of the load: "
            "the base reactions do not balance it"
        )
    V = [pp.to_local(U[pp.dofs]) for pp in model.pieces]
    phi = [pp.cond.phi_L @ a + pp.cond.phi_X @ v for pp, a, v in zip(model.pieces, coef, V)]
    d = np.zeros((nb, 3, len(names)))
    for j, b in enumerate(model.bearings):
        for k in range(3):
            for (p, pat), w in b.terms[k].items():
                d[j, k] += w * phi[p][model.pieces[p].cond.phi_names.index(pat)]
    z = np.array([b.z for b in model.bearings])
    za, zb = z[A], z[B]
    s = (z - za) / (zb - za)
    d_rel = d[:, :2] - (1 - s)[:, None, None] * d[A, :2][None] - s[:, None, None] * d[B, :2][None]
    slope = None
    if all(b.rotations for b in model.bearings):
        rot = np.zeros((nb, 2, len(names)))
        for j, b in enumerate(model.bearings):
            for k in range(2):
                for (p, pat), w in b.rotations[k].items():
                    rot[j, k] += w * phi[p][model.pieces[p].cond.phi_names.index(pat)]
        line = (d[B, :2] - d[A, :2]) / (zb - za)  # the base line's slope (the held dofs' rigid motion)
        slope = np.stack([rot[:, 1] - line[0], -rot[:, 0] - line[1]], axis=1)  # u = theta x r: du/dz
    return ShaftCases(model, tuple(names), coef, V, R, (A, B), d, d_rel, redundant, held, slope)
