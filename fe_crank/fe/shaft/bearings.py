"""The main bearings' forces at every crank angle, from the shaft's flexibility and each bearing's law.

The force method (``fe.shaft.cases``): with the two base bearings A and B held, the radial
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
bearings make it linear (one solve for every angle).

Clearance makes it a contact problem: inside its clearance circle a journal is free, so
wherever fewer than two journals touch, the shaft has rigid-body motions no bearing
resists and the system's Jacobian is singular.  It is solved as what it is, the minimum of
the total potential energy of the shaft on its bearings (convex: the shaft's strain energy
and the bearings' potentials k/2 (|d| - c)_+^2 are convex), in the unknowns
y = (delta, u_A, u_B), delta the redundant bearings' displacements relative to the base line:

    Pi(y) = 1/2 (delta - d0)^T C^-1 (delta - d0) + R0_A . u_A + R0_B . u_B + sum_j phi_j(d_j(y))

(stationarity in delta is r = C^-1 (delta - d0) = F_j, in u_A and u_B the base bearings'
statics R_AB = R0 + Q r, Q the lever rule), a rigid bearing's d_j = 0 a linear constraint
(y in its null space).  Newton's method on Pi with an exact line search along each
step (the directional derivative of a convex function rises monotonically: regula falsi)
converges from any start (the line search: regula falsi on the directional derivative); the Hessian is regularised by a vanishing multiple of its own
scale (1e-9) only to give a step in the directions no bearing yet resists, which the line
search then cuts to where a journal meets its clearance circle: the solution is the
exact one of the stated laws, no stiffness is added.  Start: the solution without
clearance; converged at a gradient (force residual) of 1e-10 of the load.  Where the
loads leave a direction without any force (e.g. every load in one plane), the journals
stay where the start put them in it, inside their clearance: the forces are unique, the
position inside the circle is not.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import scipy.linalg as sla

from fe_crank.errors import SolverError
from fe_crank.geometry.spec import BearingLaw

NEWTON_TOL = 1e-10
MAX_NEWTON = 60
#: the Hessian's regularisation, relative to its largest diagonal term (a step direction only)
REGULARISATION = 1e-9
#: most steps of the line search (regula falsi, every fourth a bisection)
LINE_SEARCH_STEPS = 80


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
    lin = [law if law.model != "clearance" else BearingLaw("spring", law.stiffness) for law in sys_.laws]
    lin_sys = BearingSystem(tuple(lin), sys_.base, sys_.redundant, sys_.C, sys_.Q, sys_.s)
    res, jac = _residual(lin_sys, D, P, np.zeros((n, nx)), d0, R0)
    x = -np.linalg.solve(jac[0], res.T).T  # linear: one Jacobian for every angle
    if any(law.model == "clearance" for law in sys_.laws):
        return _contact(sys_, x @ D.T + d0, d0, R0)
    d = x @ D.T + d0
    f = x @ P.T + R0
    return f.reshape(n, -1, 2), d.reshape(n, -1, 2)


def _kinematics(sys_: BearingSystem) -> np.ndarray:
    """(2 nb, 2m + 4): every bearing's displacement d_j = delta_j + (1 - s_j) u_A + s_j u_B
    per unknown y = (delta, u_A, u_B) (delta zero at A and B)."""
    nb, m = len(sys_.laws), len(sys_.redundant)
    G = np.zeros((2 * nb, 2 * m + 4))
    for jj, j in enumerate(sys_.redundant):
        G[2 * j : 2 * j + 2, 2 * jj : 2 * jj + 2] = np.eye(2)
    for j in range(nb):
        G[2 * j : 2 * j + 2, 2 * m : 2 * m + 2] += (1 - sys_.s[j]) * np.eye(2)
        G[2 * j : 2 * j + 2, 2 * m + 2 :] += sys_.s[j] * np.eye(2)
    return G


def _contact(sys_: BearingSystem, d_start: np.ndarray, d0: np.ndarray, R0: np.ndarray):
    """Clearance bearings: the minimum of the total potential energy (module doc) at every
    angle; ``d_start`` (n, 2 nb) the bearings' displacements to start from."""
    nb, m = len(sys_.laws), len(sys_.redundant)
    A, B = sys_.base
    n = d0.shape[0]
    G = _kinematics(sys_)
    rigid = [j for j, law in enumerate(sys_.laws) if law.model == "rigid"]
    rows = np.concatenate([np.arange(2 * j, 2 * j + 2) for j in rigid]) if rigid else np.zeros(0, int)
    N = sla.null_space(G[rows]) if rows.size else np.eye(G.shape[1])  # y = N z
    red = np.concatenate([np.arange(2 * j, 2 * j + 2) for j in sys_.redundant]) if m else np.zeros(0, int)
    delta0 = d0[:, red]
    K = np.linalg.inv(0.5 * (sys_.C + sys_.C.T)) if m else np.zeros((0, 0))
    K = 0.5 * (K + K.T)
    lin = np.concatenate([R0[:, 2 * A : 2 * A + 2], R0[:, 2 * B : 2 * B + 2]], axis=1)  # (n, 4)
    soft = [j for j, law in enumerate(sys_.laws) if law.model != "rigid"]
    GN = G @ N  # every bearing's displacement per z
    cmax = max(law.clearance for law in sys_.laws)
    scale = np.abs(lin).sum(axis=1) + np.abs(delta0 @ K).sum(axis=1) + 1e-300
    # the force a stiff contact resolves at all: k (|d| - c) with |d| known to round-off
    kc = np.array([(law.stiffness or 0.0) * law.clearance for law in sys_.laws])

    def converged(z, g):
        d = np.hypot(*(z @ N.T @ G.T).reshape(z.shape[0], nb, 2).transpose(2, 0, 1))
        k = np.array([law.stiffness or 0.0 for law in sys_.laws])
        floor = 64 * np.finfo(float).eps * (d * k + kc).sum(axis=1)
        return np.linalg.norm(g, axis=1) <= NEWTON_TOL * scale + floor

    def grad(z, k=None, hessian=False):
        y = z @ N.T
        g = np.zeros_like(y)
        g[:, : 2 * m] = (y[:, : 2 * m] - (delta0 if k is None else delta0[k])) @ K
        g[:, 2 * m :] = lin if k is None else lin[k]
        H = np.zeros((y.shape[0], y.shape[1], y.shape[1]) if hessian else (0, 0, 0))
        if hessian and m:
            H[:, : 2 * m, : 2 * m] = K
        d = y @ G.T
        for j in soft:
            sl = slice(2 * j, 2 * j + 2)
            F, dF = _law(sys_.laws[j], d[:, sl])
            g -= F @ G[sl]
            if hessian:
                H -= G[sl].T @ dF @ G[sl]
        gz = g @ N
        if not hessian:
            return gz, None
        return gz, N.T @ H @ N

    y_start = np.zeros((n, G.shape[1]))
    y_start[:, : 2 * m] = d_start[:, red]
    y_start[:, 2 * m : 2 * m + 2] = d_start[:, 2 * A : 2 * A + 2]
    y_start[:, 2 * m + 2 :] = d_start[:, 2 * B : 2 * B + 2]
    z = y_start @ N
    for _ in range(MAX_NEWTON):
        g, H = grad(z, hessian=True)
        todo = np.flatnonzero(~converged(z, g))
        if not todo.size:
            break
        Ht = H[todo]
        mu = REGULARISATION * np.abs(np.diagonal(Ht, axis1=1, axis2=2)).max(axis=1) + 1e-300
        step = -np.linalg.solve(Ht + mu[:, None, None] * np.eye(Ht.shape[1]), g[todo][..., None])[..., 0]
        # a step along a direction no bearing resists yet is as long as the load over the
        # regularisation: cut it to 10 (largest clearance + the journals' displacement),
        # so that the line search brackets the first contact within a few steps
        move = np.abs(step @ GN.T).max(axis=1)
        reach = 10.0 * (cmax + np.abs(z[todo] @ GN.T).max(axis=1))
        reach = np.where(reach > 0, reach, np.inf)
        step *= np.minimum(1.0, reach / np.maximum(move, 1e-300))[:, None]
        t = _line_search(lambda zz, k: grad(zz, k)[0], z[todo], step, todo)
        z[todo] = z[todo] + t[:, None] * step
    else:
        g, _ = grad(z)
        bad = ~converged(z, g)
        if np.any(bad):
            norm = np.linalg.norm(g, axis=1) / scale
            raise SolverError(
                f"the clearance bearings did not converge at {int(np.sum(bad))} crank angle(s) "
                f"(relative residual {norm[bad].max():.2e})"
            )
    y = z @ N.T
    d = y @ G.T
    r = (y[:, : 2 * m] - delta0) @ K
    f = np.zeros((n, 2 * nb))
    f[:, red] = r
    base = np.concatenate([R0[:, 2 * A : 2 * A + 2], R0[:, 2 * B : 2 * B + 2]], axis=1) + r @ sys_.Q.T
    f[:, 2 * A : 2 * A + 2], f[:, 2 * B : 2 * B + 2] = base[:, :2], base[:, 2:]
    return f.reshape(n, -1, 2), d.reshape(n, -1, 2)


def _line_search(grad, z: np.ndarray, step: np.ndarray, which: np.ndarray) -> np.ndarray:
    """Step lengths t in (0, 1] minimising the convex potential along ``step`` from ``z``
    (the angles ``which``; ``grad(z, angles)`` its gradient): the full step where the
    directional derivative h(t) is still not positive at t = 1, else its zero in (0, 1)
    (h rises monotonically along the step) by regula falsi with the Illinois
    modification, to |h| <= 1e-3 |h(0)| or a point short of the zero with h(0)/2 <= h <= 0
    (a Wolfe point: the potential decreases), bisecting where it stalls; where neither
    is reached, the last point with h < 0."""
    h0 = np.einsum("ni,ni->n", grad(z, which), step)
    h1 = np.einsum("ni,ni->n", grad(z + step, which), step)
    t = np.ones(z.shape[0])
    todo = np.flatnonzero(h1 > 0)
    if not todo.size:
        return t
    lo, hi = np.zeros(todo.size), np.ones(todo.size)
    hlo, hhi = h0[todo].copy(), h1[todo].copy()
    tol = 1e-3 * np.abs(h0[todo])
    out = np.full(todo.size, np.nan)
    side = np.zeros(todo.size, int)  # the end kept twice in a row: -1 lo, +1 hi
    zt, st = z[todo], step[todo]
    for it in range(LINE_SEARCH_STEPS):
        open_ = np.isnan(out)
        if not open_.any():
            break
        k = np.flatnonzero(open_)
        secant = (lo[k] * hhi[k] - hi[k] * hlo[k]) / (hhi[k] - hlo[k])
        mid = np.where(lo[k] > 0, 0.5 * (lo[k] + hi[k]), 1e-3 * hi[k])  # towards 0 by decades
        tk = np.where(it % 4 == 3, mid, secant)  # every fourth step a bisection
        tk = np.clip(tk, lo[k], hi[k])
        h = np.einsum("ni,ni->n", grad(zt[k] + tk[:, None] * st[k], which[todo[k]]), st[k])
        done = (np.abs(h) <= tol[k]) | ((h <= 0) & (-h <= 0.5 * np.abs(h0[todo[k]])))
        out[k[done]] = tk[done]
        neg = (h < 0) & ~done
        pos = (h >= 0) & ~done
        a, b = k[neg], k[pos]
        lo[a], hlo[a] = tk[neg], h[neg]
        hhi[a] = np.where(side[a] == -1, 0.5 * hhi[a], hhi[a])  # Illinois: halve the end kept
        side[a] = -1
        hi[b], hhi[b] = tk[pos], h[pos]
        hlo[b] = np.where(side[b] == 1, 0.5 * hlo[b], hlo[b])
        side[b] = 1
    out = np.where(np.isnan(out), lo, out)
    t[todo] = out
    return t
