"""The main bearings' forces at every crank angle, from the shaft's flexibility and each bearing's law.

The force method (``fe.shaft_cases``): with the two base bearings A and B held, the radial
displacement of bearing j relative to the line through A and B is

    d_rel,j = d0_j(theta) + sum_i C_ji r_i          (r: forces of the other bearings on the shaft)

and the base bearings' forces follow from statics, R_AB = R0(theta) + Q r.  The bearings
themselves may move: with u_A, u_B the radial displacements of A and B, bearing j is at
d_j = d_rel,j + (1 - s_j) u_A + s_j u_B (s_j = (z_j - z_A) / (z_B - z_A); a rigid motion
of the shaft changes no force).  Each bearing's law (``geometry.spec.BearingLaw``) closes
the system, per angle, in the unknowns x = (r, u_A, u_B):

* ``rigid``: d_j = 0;
* ``spring``: F_j = -k d_j;
* ``clearance``: F_j = -k (|d_j| - c)_+ d_j / |d_j| (no force inside the clearance circle,
  the contact stiffness k beyond it);

F_j being r_j for the redundant bearings and R_AB for the base ones.  Rigid and spring
bearings make it linear (one solve for every angle); clearance makes it piecewise linear,
solved by Newton's method with a backtracking line search from the solution without
clearance, per angle, to a relative residual of 1e-10 of the load.  Thousands of angles
on a few dozen unknowns take milliseconds per Newton step.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import SolverError
from fe_crank.geometry.spec import BearingLaw

NEWTON_TOL = 1e-10
MAX_NEWTON = 60


@dataclass(frozen=True)
class BearingSystem:
    """The per-angle problem's constant parts (module doc), shaft frame."""

    laws: tuple[BearingLaw, ...]  # per bearing, front to rear
    base: tuple[int, int]  # indices of A and B
    redundant: tuple[int, ...]
    C: np.ndarray  # (2m, 2m) flexibility of the redundant bearings, m/N
    Q: np.ndarray  # (4, 2m) base forces (A.x A.y B.x B.y) per unit redundant force
    s: np.ndarray  # (n_bearings,) position between A (0) and B (1)


def _shape(sys_: BearingSystem):
    nb, m = len(sys_.laws), len(sys_.redundant)
    nx = 2 * m + 4
    # D: (2 nb, nx) displacement of every bearing per unit x, without d0
    D = np.zeros((2 * nb, nx))
    A, B = sys_.base
    for jj, j in enumerate(sys_.redundant):
        D[2 * j : 2 * j + 2, : 2 * m] = sys_.C[2 * jj : 2 * jj + 2]
    for j in range(nb):
        D[2 * j : 2 * j + 2, 2 * m : 2 * m + 2] += (1 - sys_.s[j]) * np.eye(2)
        D[2 * j : 2 * j + 2, 2 * m + 2 :] += sys_.s[j] * np.eye(2)
    # P: (2 nb, nx) force of every bearing on the shaft per unit x, without R0
    P = np.zeros((2 * nb, nx))
    for jj, j in enumerate(sys_.redundant):
        P[2 * j : 2 * j + 2, 2 * jj : 2 * jj + 2] = np.eye(2)
    P[2 * A : 2 * A + 2, : 2 * m] = sys_.Q[:2]
    P[2 * B : 2 * B + 2, : 2 * m] = sys_.Q[2:]
    return D, P


def _law(law: BearingLaw, d: np.ndarray):
    """Force on the shaft (n, 2) and its derivative (n, 2, 2) at displacements d (n, 2)."""
    n = d.shape[0]
    if law.stiffness is None:
        raise ValueError(f"a {law.model} bearing law needs its stiffness")
    k = law.stiffness
    if law.model == "spring":
        return -k * d, np.broadcast_to(-k * np.eye(2), (n, 2, 2))
    r = np.hypot(d[:, 0], d[:, 1])
    c = law.clearance
    on = r > c
    e = np.where(on[:, None], d / np.where(r > 0, r, 1.0)[:, None], 0.0)
    F = -k * np.where(on, r - c, 0.0)[:, None] * e
    ratio = np.where(on, c / np.where(r > 0, r, 1.0), 0.0)
    J = -k * (
        (1 - ratio)[:, None, None] * np.eye(2) * on[:, None, None]
        + ratio[:, None, None] * np.einsum("ni,nj->nij", e, e)
    )
    return F, J


def _stiffness_scale(sys_: BearingSystem) -> float:
    """N/m that turns a rigid bearing's displacement residual into a force (the shaft's
    own stiffness at the redundant bearings; 1 without them)."""
    diag = np.abs(np.diag(sys_.C))
    return 1.0 / diag.mean() if diag.size and diag.mean() > 0 else 1.0


def _residual(sys_, D, P, x, d0, R0):
    """Residual (n, 2 nb) and Jacobian (n, 2 nb, nx) at x (n, nx); a rigid bearing's
    rows are its displacement times ``_stiffness_scale`` (force units, like the others)."""
    kref = _stiffness_scale(sys_)
    n, nx = x.shape
    d = x @ D.T + d0
    f = x @ P.T + R0
    res = np.empty_like(d)
    jac = np.empty((n, d.shape[1], nx))
    for j, law in enumerate(sys_.laws):
        sl = slice(2 * j, 2 * j + 2)
        if law.model == "rigid":
            res[:, sl] = kref * d[:, sl]
            jac[:, sl] = kref * D[sl]
            continue
        F, dF = _law(law, d[:, sl])
        res[:, sl] = f[:, sl] - F
        jac[:, sl] = P[sl][None] - np.einsum("nij,jk->nik", dF, D[sl])
    return res, jac


def bearing_forces(sys_: BearingSystem, d0: np.ndarray, R0: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Forces of every bearing on the shaft (n, n_bearings, 2) and the bearings' radial
    displacements (n, n_bearings, 2), shaft frame, at n angles.

    ``d0`` (n, 2 n_bearings): the bearings' displacements relative to the base line under
    the applied loads alone (zero at A and B); ``R0`` (n, 2 n_bearings): the base bearings'
    forces under the applied loads alone (zero elsewhere)."""
    D, P = _shape(sys_)
    n = d0.shape[0]
    nx = D.shape[1]
    scale = np.maximum(np.abs(R0).sum(axis=1), 1e-300)
    lin = [law if law.model != "clearance" else BearingLaw("spring", law.stiffness) for law in sys_.laws]
    lin_sys = BearingSystem(tuple(lin), sys_.base, sys_.redundant, sys_.C, sys_.Q, sys_.s)
    res, jac = _residual(lin_sys, D, P, np.zeros((n, nx)), d0, R0)
    x = -np.linalg.solve(jac[0], res.T).T  # linear: one Jacobian for every angle
    if any(law.model == "clearance" for law in sys_.laws):
        x = _newton(sys_, D, P, x, d0, R0, scale)
    d = x @ D.T + d0
    f = x @ P.T + R0
    return f.reshape(n, -1, 2), d.reshape(n, -1, 2)


def _newton(sys_, D, P, x, d0, R0, scale):
    res, jac = _residual(sys_, D, P, x, d0, R0)
    norm = np.linalg.norm(res, axis=1) / scale
    for _ in range(MAX_NEWTON):
        todo = norm > NEWTON_TOL
        if not np.any(todo):
            return x
        step = -np.linalg.solve(jac[todo], res[todo][..., None])[..., 0]
        t = np.ones(step.shape[0])
        xi = x[todo]
        best = norm[todo]
        for _ in range(30):
            trial = xi + t[:, None] * step
            r2, _ = _residual(sys_, D, P, trial, d0[todo], R0[todo])
            n2 = np.linalg.norm(r2, axis=1) / scale[todo]
            ok = n2 < best * (1 - 1e-4 * t) + 1e-300
            if np.all(ok):
                break
            t = np.where(ok, t, 0.5 * t)
        x[todo] = xi + t[:, None] * step
        res, jac = _residual(sys_, D, P, x, d0, R0)
        norm = np.linalg.norm(res, axis=1) / scale
    raise SolverError(
        f"the clearance bearings did not converge at {int(np.sum(norm > NEWTON_TOL))} crank angle(s) "
        f"(relative residual {norm.max():.2e})"
    )
