"""The oil film of a dynamically loaded journal bearing: the short-bearing law and the journal's orbit.

A rigid journal (radius R) turns at omega in a rigid circular bearing (fixed) of width B and
radial clearance c, in an isoviscous film (dynamic viscosity mu).  The journal's centre is
at e = c eps (eps the eccentricity-ratio vector, bearing frame); the film thickness at the
bearing angle alpha (unit normal n(alpha)) is h = c (1 - eps . n).

**Short bearing (Ocvirk; Dubois and Ocvirk 1953).**  Reynolds' equation without the
circumferential pressure flow, p = 0 at the bearing's edges z = +-B/2:

    d/dz (h^3 dp/dz) = 12 mu (omega/2 dh/dalpha + dh/dt)
    p(alpha, z) = 6 mu (B^2/4 - z^2) c (u . n) / h^3,      u = d eps/dt - omega_bar e_z x eps,

omega_bar = (omega_journal + omega_bearing)/2 = omega/2 for a main bearing: the pressure
depends on the motion only through the *squeeze velocity* u (Booker 1965).  Cavitation
by the half-Sommerfeld (Guembel) condition: p = 0 where u . n < 0, i.e. the film carries
over the half circle centred on u's direction.  The film's force on the bearing (= the
load of the journal on the bearing, W) is then

    W = k0 K(eps, u) u,      k0 = mu R B^3 / c^2,
    K = int_{u.n > 0} n n^T / (1 - eps . n)^3 d alpha,

closed form by Sommerfeld's substitution (in the frame of the line of centres, psi from
it, gamma the Sommerfeld angle: 1 - eps cos psi = (1 - eps^2) / (1 + eps cos gamma)):

    int cos^a psi sin^b psi / (1 - eps cos psi)^(a+b+1) d psi
        = (1 - eps^2)^-(a + b/2 + 1/2) int (cos gamma + eps)^a sin^b gamma d gamma.

F is homogeneous of degree one in u and dF/du = k0 K exactly (the integrand vanishes on the
moving limits); dF/d eps = 3 k0 int (u . n) n n^T / (1 - eps . n)^4, also in closed form.

**Booker's mobility.**  For a load W the squeeze velocity is u = (|W| / k0) M(eps, W/|W|),
M the mobility vector (``mobility``), and d eps/dt = omega_bar e_z x eps + u.

**The orbit** (``periodic_orbits``) is the periodic solution of these equations under a
periodic load history: integrated from the bearing's centre cycle after cycle until the
orbit repeats (max |delta eps| at the cycle's angles below ``tol``, default 1e-4), at most
``max_cycles`` cycles (else the result says not converged).  The equations are stiff where
eps approaches 1 (the film's stiffness rises as (1 - eps^2)^-5/2), so they are integrated
implicitly: BDF2 at constant step in the journal's angle, each step's eps solved by
Newton's method on the impedance form k0 K(eps, u) u = W (the analytic Jacobian above),
kept inside the clearance circle and safeguarded (``_newton_step``, ``_step``: a BDF2 step
with no solution inside the circle is redone as backward-Euler sub-steps); the mobility form and the impedance form are the same
equations.

**Full circumferential groove**: two lands of width (B - b_g)/2, each a short bearing with
p = 0 at the groove (supply pressure neglected, conservative) and at its edge, both at the
same eccentricity: k0 = 2 mu R ((B - b_g)/2)^3 / c^2.

Peak film pressure: p at the middle of a land (z = 0 of the land, land width b),
p = 3 mu b^2 (u . n) / (2 c^2 (1 - eps . n)^3), its largest value over the angle alpha
found on a grid in the Sommerfeld angle refined by Newton's method.

**Finite bearing** (``finite_factor``).  The short bearing neglects the pressure flow
around the circumference, so it carries more than a bearing of finite width / diameter
lam = b / D (b the land's width): by a factor R(eps, lam, direction of u) that grows as
the film narrows (a finite-difference solution of Reynolds' equation with the same
half-Sommerfeld condition: R = 1.67 at lam 0.15, eps 0.97 for a tangential u, the
steady-load case).  The finite bearing is taken as the short bearing's film divided by
R_fit(eps, lam), a fit of the largest R over the direction of u (the tangential one):

    F = k0 K(eps, u) u / R_fit,   R_fit = 1 + g x / (1 + b x)^m,   x = lam^2 / (1 - eps),
    g = g0 + g1 eps + g2 eps^2   (``FINITE_FIT``),

fitted by least squares on ln R to 72 finite-difference solutions (lam 0.05-0.5, eps
0-0.99), within 2 % of them; R_fit = 1 at lam = 0 (the short bearing).  Where u is not
tangential the finite bearing carries more than this (R is smaller: 0.88 to 1 times for a
radial u, down to 0.6 times for a u turned 135 deg from the line of centres at lam 0.25):
the film's force, hence the film thickness, is then underestimated, on the safe side.
Refused beyond lam ``MAX_LAND_ASPECT``; beyond eps 0.99 the fit is extrapolated (a film
thinner than 1 % of the clearance).  The Newton iteration takes the factor on the load
side, k0 K u = R_fit W, with dR_fit/d eps in the Jacobian.  The peak film pressure is the
short bearing's at mid-land divided by R_fit (the short bearing's pressure shape scaled
to carry the load): 8-29 % above the finite-difference solution's peak (lam 0.1-0.4, eps
0.9-0.99), on the safe side.

Sources: F. W. Ocvirk, NACA TN 2808 (1952) and G. B. DuBois, F. W. Ocvirk, NACA Rep. 1157
(1953) (short bearing); J. F. Booker, "Dynamically loaded journal bearings: mobility method
of solution", J. Basic Eng. 87 (1965) 537-546, and J. Lubr. Technol. 93 (1971) 168-176;
P. K. Goenka, J. Tribology 106 (1984) 421-428 (finite-bearing mobility fits, not used
here: their coefficients could not be verified from a source; the finite-difference fit
above instead, docs/shaft.md); B. J. Hamrock, "Fundamentals of Fluid Film Lubrication"
(short-bearing and squeeze-film chapters).  Limits: rigid surfaces, isoviscous film,
half-Sommerfeld cavitation, the finite-length factor's fit (lam <= 0.5, docs/shaft.md).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fe_crank.errors import SolverError

#: mean angular speed of journal and bearing over the journal's, main bearing (bearing fixed)
MAIN_BEARING_MEAN_SPEED = 0.5
#: default cycle-to-cycle tolerance of the periodic orbit (max |delta eps| at the cycle's angles)
ORBIT_TOL = 1e-4
MAX_CYCLES = 40
NEWTON_TOL = 1e-7  # the last Newton step's size in eps (the error after it is its square)
MAX_NEWTON = 60
#: the finite-length factor R_fit's coefficients (g0, g1, g2, b, m; module doc), fitted to
#: finite-difference solutions of Reynolds' equation (tests/fe/test_fe_oil_film_finite.py checks them)
FINITE_FIT = (0.5421836, 0.3076249, 0.6811412, 89.30971, 0.1208412)
#: the largest land width / diameter the finite-length factor is fitted for
MAX_LAND_ASPECT = 0.5
#: the largest eccentricity ratio it is fitted for (beyond: extrapolated)
FIT_MAX_ECCENTRICITY = 0.99


@dataclass(frozen=True)
class JournalBearing:
    """A journal bearing's film (SI): diameter, width B, radial clearance c, dynamic
    viscosity, groove ``"none"`` or ``"full"`` (width ``groove_width``)."""

    diameter: float
    width: float
    clearance: float
    viscosity: float
    groove: str = "none"
    groove_width: float = 0.0

    @property
    def lands(self) -> int:
        return 2 if self.groove == "full" else 1

    @property
    def land_width(self) -> float:
        return (self.width - self.groove_width) / 2 if self.groove == "full" else self.width

    @property
    def k0(self) -> float:
        """N s: the short bearing's force per unit squeeze velocity scale, lands mu R b^3 / c^2."""
        return self.lands * self.viscosity * (self.diameter / 2) * self.land_width**3 / self.clearance**2

    def pressure_scale(self) -> float:
        """Pa s: p = pressure_scale * (u . n) / (1 - eps . n)^3 at a land's middle (the
        short bearing's; the finite bearing's is this over ``finite_factor``)."""
        return 1.5 * self.viscosity * self.land_width**2 / self.clearance**2

    @property
    def land_aspect(self) -> float:
        """lam = land width / diameter (of each land with a full groove)."""
        return self.land_width / self.diameter


def finite_factor(eps: np.ndarray, lam: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
    """R_fit(eps, lam) and dR_fit/d eps (module doc): the short bearing's film force over
    the finite bearing's, at eccentricity ratios ``eps`` (< 1) and land width / diameter
    ``lam`` (arrays of one shape)."""
    g0, g1, g2, b, m = FINITE_FIT
    lam2 = lam * lam
    q = 1.0 / (1.0 - eps)
    x = lam2 * q
    dx = x * q
    g = g0 + (g1 + g2 * eps) * eps
    dg = g1 + 2 * g2 * eps
    s = 1.0 + b * x
    sm = np.exp(-m * np.log(s))
    return 1.0 + g * x * sm, sm * (dg * x + g * dx * (1.0 - m * b * x / s))


def _antiderivatives(g, C, S, eps, derivatives: bool):
    """The antiderivatives in the Sommerfeld angle g (cos g = C, sin g = S; module doc)."""
    s2 = S * C / 2  # sin(2 g) / 4
    e = eps
    out = [
        g / 2 + s2 + 2 * e * S + e * e * g,  # (C + e)^2
        S * S / 2 - e * C,  # (C + e) S
        g / 2 - s2,  # S^2
    ]
    if derivatives:  # products, not powers: numpy's ** is slow on small arrays
        S3, C3, ce = S * S * S, C * C * C, C + e
        out += [
            S - S3 / 3 + 3 * e * (g / 2 + s2) + 3 * e * e * S + e * e * e * g,  # (C + e)^3
            -(ce * ce * ce) / 3,  # (C + e)^2 S
            S3 / 3 + e * (g / 2 - s2),  # (C + e) S^2
            -C + C3 / 3,  # S^3
        ]
    return out


def _sommerfeld(cpsi, spsi, eps, q):
    """The Sommerfeld angle of psi (cos, sin given) and its cosine and sine:
    cos g = (cos psi - eps) / (1 - eps cos psi), sin g = q sin psi / (1 - eps cos psi)."""
    d = 1.0 - eps * cpsi
    C, S = (cpsi - eps) / d, q * spsi / d
    return np.arctan2(S, C), C, S


def film_terms(ex, ey, ux, uy, derivatives: bool = True):
    """The short bearing's film (module doc) at eccentricity ratios (ex, ey) and squeeze
    velocities (ux, uy) (arrays of one shape, bearing frame; any unit of time): the force
    F / k0 (same unit as u), K and, with ``derivatives``, T = dF/d eps / k0, as
    ``(Fx, Fy, Kxx, Kxy, Kyy[, Txx, Txy, Tyy])``."""
    eps = np.hypot(ex, ey)
    inv = 1.0 / np.where(eps > 0, eps, 1.0)
    cp, sp = np.where(eps > 0, ex * inv, 1.0), ey * inv  # the line of centres (x at the centre)
    ur, ut = cp * ux + sp * uy, -sp * ux + cp * uy
    um = np.hypot(ur, ut)
    um_inv = 1.0 / np.where(um > 0, um, 1.0)
    cu, su = np.where(um > 0, ur * um_inv, 1.0), ut * um_inv  # u's direction psi0 from the line of centres
    q2 = 1.0 - eps * eps
    q = np.sqrt(q2)
    ga, ca, sa = _sommerfeld(su, -cu, eps, q)  # psi0 - pi/2
    gb, cb, sb = _sommerfeld(-su, cu, eps, q)  # psi0 + pi/2
    gb = ga + np.mod(gb - ga, 2 * np.pi)
    A = _antiderivatives(ga, ca, sa, eps, derivatives)
    B = _antiderivatives(gb, cb, sb, eps, derivatives)
    d = [b - a for a, b in zip(A, B)]
    q3 = q2 * q
    jcc, jcs, jss = d[0] / (q2 * q2 * q), d[1] / (q2 * q2), d[2] / q3
    fr, ft = jcc * ur + jcs * ut, jcs * ur + jss * ut
    c2, s2, cs = cp * cp, sp * sp, cp * sp
    out = [
        cp * fr - sp * ft,
        sp * fr + cp * ft,
        c2 * jcc - 2 * cs * jcs + s2 * jss,
        cs * (jcc - jss) + (c2 - s2) * jcs,
        s2 * jcc + 2 * cs * jcs + c2 * jss,
    ]
    if derivatives:
        q4 = q2 * q2
        lccc, lccs, lcss, lsss = d[3] / (q4 * q3), d[4] / (q4 * q2), d[5] / (q4 * q), d[6] / q4
        trr = 3 * (ur * lccc + ut * lccs)
        trt = 3 * (ur * lccs + ut * lcss)
        ttt = 3 * (ur * lcss + ut * lsss)
        out += [
            c2 * trr - 2 * cs * trt + s2 * ttt,
            cs * (trr - ttt) + (c2 - s2) * trt,
            s2 * trr + 2 * cs * trt + c2 * ttt,
        ]
    return tuple(out)


def film_force(eps: np.ndarray, u: np.ndarray) -> np.ndarray:
    """F / k0 (..., 2) of the film on the bearing at eccentricity ratios ``eps`` (..., 2)
    and squeeze velocities ``u`` (..., 2) (the impedance form)."""
    eps, u = np.asarray(eps, float), np.asarray(u, float)
    f = film_terms(eps[..., 0], eps[..., 1], u[..., 0], u[..., 1], derivatives=False)
    return np.stack([f[0], f[1]], axis=-1)


def mobility(eps: np.ndarray, direction: np.ndarray) -> np.ndarray:
    """Booker's mobility vector M (..., 2): the squeeze velocity per unit load,
    u = (|W| / k0) M, at eccentricity ratios ``eps`` (..., 2) under loads of unit
    ``direction`` (..., 2).  u solves K(eps, u) u = W; K depends on u's direction only and
    is positive definite, so F . u > 0: u's direction lies within 90 deg of W's, where the
    angle between F(u) and W changes sign from one end to the other; found by bisection
    (60 halvings), then |u| = |W| / |K e_u|."""
    eps = np.asarray(eps, float)
    w = np.asarray(direction, float)
    w = w / np.linalg.norm(w, axis=-1, keepdims=True)
    ex, ey = np.broadcast_arrays(eps[..., 0], eps[..., 1])
    beta = np.arctan2(w[..., 1], w[..., 0])
    lo, hi = beta - np.pi / 2, beta + np.pi / 2

    def off(psi):  # the angle from W to F(u of direction psi), in (-pi, pi]
        fx, fy = film_terms(ex, ey, np.cos(psi), np.sin(psi), derivatives=False)[:2]
        return np.angle(np.exp(1j * (np.arctan2(fy, fx) - beta)))

    for _ in range(60):
        mid = 0.5 * (lo + hi)
        neg = off(mid) < 0
        lo, hi = np.where(neg, mid, lo), np.where(neg, hi, mid)
    psi = 0.5 * (lo + hi)
    fx, fy = film_terms(ex, ey, np.cos(psi), np.sin(psi), derivatives=False)[:2]
    size = 1.0 / np.hypot(fx, fy)
    return np.stack([size * np.cos(psi), size * np.sin(psi)], axis=-1)


@dataclass(frozen=True)
class Orbits:
    """Periodic orbits of a batch of bearings (``periodic_orbits``), at the load's angles.

    ``eps`` (m, n, 2): the eccentricity-ratio vector, bearing frame; ``squeeze`` (m, n, 2):
    the squeeze velocity u per journal radian (u / omega); ``converged`` (m,): the orbit
    repeated within ``tol``; ``cycles`` (m,): cycles integrated; ``change`` (m,): max
    |delta eps| between the last two cycles."""

    eps: np.ndarray
    squeeze: np.ndarray
    converged: np.ndarray
    cycles: np.ndarray
    change: np.ndarray
    tol: float


def _squeeze(x, e1, e2, a, wb):
    a0, a1, a2 = a
    return a0 * x[0] + a1 * e1[0] + a2 * e2[0] + wb * x[1], a0 * x[1] + a1 * e1[1] + a2 * e2[1] - wb * x[0]


def _inside(x, dx, dy, t):
    """x + t (dx, dy), pulled back radially to close at most 80 % of the gap to the
    clearance circle; and whether it was pulled back."""
    r_old = np.hypot(x[0], x[1])
    nx, ny = x[0] + t * dx, x[1] + t * dy
    r_new = np.hypot(nx, ny)
    cap = 1.0 - 0.2 * (1.0 - r_old)
    k = np.where(r_new > cap, cap / np.maximum(r_new, 1e-300), 1.0)
    return np.stack([nx * k, ny * k]), k < 1.0


def _newton_step(x, e1, e2, w, a, wb, lam=None):
    """eps at the end of one BDF step (vectorised over orbits): k0 K u = W with
    u = a0 x + a1 e1 + a2 e2 - wb e_z x x (module doc).  Newton's method kept inside the
    clearance circle and safeguarded: a step that does not lower the residual is halved
    (near the clearance circle the film's force grows as (1 - eps)^-5/2, and a full
    Newton step from too far inside can land where it is orders of magnitude too large).
    ``lam`` (per orbit; None: the short bearing): the finite-length factor on the load
    side, k0 K u = R_fit W."""
    a0 = a[0]
    scale = 1.0 + np.hypot(w[0], w[1])
    base = x.copy()  # the last accepted iterate
    step = np.zeros_like(x)  # its Newton step
    t = np.ones(x.shape[1])
    r_base = np.full(x.shape[1], np.inf)
    for _ in range(MAX_NEWTON):
        ux, uy = _squeeze(x, e1, e2, a, wb)
        fx, fy, kxx, kxy, kyy, txx, txy, tyy = film_terms(x[0], x[1], ux, uy)
        if lam is None:
            rx, ry = fx - w[0], fy - w[1]
        else:
            e = np.hypot(x[0], x[1])
            f, df = finite_factor(e, lam)
            rx, ry = fx - f * w[0], fy - f * w[1]
            de = df / np.maximum(e, 1e-300)
            wxx, wxy, wyx, wyy = w[0] * de * x[0], w[0] * de * x[1], w[1] * de * x[0], w[1] * de * x[1]
        r = np.hypot(rx, ry) / scale
        worse = r > (1 - 1e-4 * t) * r_base + 1e-13
        if worse.any():  # back along the last step, for those orbits only
            t = np.where(worse, 0.5 * t, t)
            back, _ = _inside(base, step[0], step[1], t)
            x = np.where(worse, back, x)
            if (t[worse] > 1e-12).all():
                continue
            break  # no descent left for some orbit
        j11 = txx + a0 * kxx - wb * kxy
        j12 = txy + a0 * kxy + wb * kxx
        j21 = txy + a0 * kxy - wb * kyy
        j22 = tyy + a0 * kyy + wb * kxy
        if lam is not None:
            j11, j12, j21, j22 = j11 - wxx, j12 - wxy, j21 - wyx, j22 - wyy
        det = j11 * j22 - j12 * j21
        dx = -(j22 * rx - j12 * ry) / det
        dy = -(j11 * ry - j21 * rx) / det
        t = np.ones_like(dx)
        new, pulled = _inside(x, dx, dy, t)
        done = (np.hypot(dx, dy) < NEWTON_TOL) & ~pulled
        if done.all():
            # Newton's convergence is quadratic: after this step the error is of order
            # |dx|^2 (below 1e-14 in eps)
            return new, np.stack(_squeeze(new, e1, e2, a, wb)), np.zeros(x.shape[1], bool)
        base, step, r_base = x, np.stack([dx, dy]), r
        x = new
    # the orbits whose last Newton step was not small: their step is redone (``_step``)
    ux, uy = _squeeze(x, e1, e2, a, wb)
    fx, fy = film_terms(x[0], x[1], ux, uy, derivatives=False)[:2]
    factor = 1.0 if lam is None else finite_factor(np.hypot(x[0], x[1]), lam)[0]
    bad = np.hypot(fx - factor * w[0], fy - factor * w[1]) / scale > 1e-9
    return x, np.stack([ux, uy]), bad


def _step(guess, e1, e2, w, a, wb, h, lam=None):
    """One BDF2 step (``_newton_step``).  Where it has no solution inside the clearance
    circle (BDF2 carries the last steps' velocity: after a violent approach, e.g. from the
    centre under a large load, it can overshoot the circle), that orbit's step is redone
    as 1, 2, 4, ... 64 backward-Euler sub-steps under the step's end load."""
    x, u, bad = _newton_step(guess, e1, e2, w, a, wb, lam)
    if not bad.any():
        return x, u
    idx = np.flatnonzero(bad)
    for parts in (1, 2, 4, 8, 16, 32, 64):
        hh = h / parts
        y = e1[:, idx].copy()
        for _ in range(parts):
            y, uu, again = _newton_step(
                y.copy(), y, y, w[:, idx], (1.0 / hh, -1.0 / hh, 0.0), wb, None if lam is None else lam[idx]
            )
            if again.any():
                break
        else:
            x[:, idx], u[:, idx] = y, uu
            return x, u
    raise SolverError("the oil film's time step did not converge, even in backward-Euler sub-steps")


def periodic_orbits(
    load: np.ndarray,
    turns: float,
    *,
    mean_speed: float = MAIN_BEARING_MEAN_SPEED,
    tol: float = ORBIT_TOL,
    max_cycles: int = MAX_CYCLES,
    substeps: int = 1,
    start: np.ndarray | None = None,
    aspect: np.ndarray | None = None,
) -> Orbits:
    """The periodic orbits (module doc) of m bearings under loads ``load`` (m, n, 2): W /
    (k0 omega) at n equally spaced angles of one cycle (bearing frame, dimensionless),
    the journal turning ``turns`` revolutions per cycle (2 for a four-stroke cycle) at
    constant speed; ``mean_speed``: omega_bar / omega; ``substeps``: BDF steps per load
    angle (the load linear between angles); ``start`` (m, 2): eps at the first angle of
    the first cycle (default the bearing's centre); ``aspect`` (m,): each bearing's land
    width / diameter for the finite-length factor (module doc; None: the short bearing)."""
    load = np.asarray(load, float)
    m, n, _ = load.shape
    steps = n * substeps
    h = 2 * np.pi * turns / steps
    w_all = np.moveaxis(load, 2, 0)  # (2, m, n)
    frac = np.arange(1, substeps + 1) / substeps
    e1 = np.zeros((2, m)) if start is None else np.asarray(start, float).T.copy()
    e2 = e1.copy()
    e3 = None
    first = True
    prev = None
    eps = np.zeros((n, 2, m))
    squeeze = np.zeros((n, 2, m))
    converged = np.zeros(m, bool)
    cycles = np.zeros(m, int)
    change = np.full(m, np.inf)
    lam = None if aspect is None else np.broadcast_to(np.asarray(aspect, float), (m,)).copy()
    bdf1 = (1.0 / h, -1.0 / h, 0.0)
    bdf2 = (1.5 / h, -2.0 / h, 0.5 / h)
    for cyc in range(max_cycles):
        for i in range(n):
            w0, w1 = w_all[:, :, i], w_all[:, :, (i + 1) % n]
            for f in frac:
                w = w0 + f * (w1 - w0)
                guess = 2 * e1 - e2 if e3 is None else 3 * e1 - 3 * e2 + e3
                r = np.hypot(guess[0], guess[1])
                guess = guess * np.where(r > 0.999, 0.999 / np.maximum(r, 1e-300), 1.0)
                x, u = _step(guess, e1, e2, w, bdf1 if first else bdf2, mean_speed, h, lam)
                first = False
                e3, e2, e1 = e2, e1, x
            eps[(i + 1) % n], squeeze[(i + 1) % n] = e1, u
        cycles[~converged] = cyc + 1
        if prev is not None:
            change = np.max(np.hypot(*(eps - prev).transpose(1, 0, 2)), axis=0)
            converged |= change < tol
            if converged.all():
                break
        prev = eps.copy()
    return Orbits(np.moveaxis(eps, 2, 0), np.moveaxis(squeeze, 2, 0), converged, cycles, change, tol)


def peak_pressure_factor(eps: np.ndarray, u: np.ndarray, *, samples: int = 48, chunk: int = 40_000) -> np.ndarray:
    """max over the bearing angle of (u . n) / (1 - eps . n)^3 (module doc), at eccentricity
    ratios ``eps`` (..., 2) and squeeze velocities ``u`` (..., 2); times
    ``JournalBearing.pressure_scale()`` (and omega when u is per radian) it is the peak
    film pressure.  On ``samples`` points of the Sommerfeld angle gamma, where the function
    is the trigonometric polynomial [u_r (cos g + e) + u_t q sin g] (1 + e cos g)^2 / q^6,
    refined by Newton's method."""
    eps, u = np.asarray(eps, float), np.asarray(u, float)
    shape = eps.shape[:-1]
    ex, ey = eps.reshape(-1, 2).T
    ux, uy = u.reshape(-1, 2).T
    out = np.empty(ex.size)
    g0 = np.linspace(-np.pi, np.pi, samples, endpoint=False)
    for s in range(0, ex.size, chunk):
        sl = slice(s, s + chunk)
        e = np.hypot(ex[sl], ey[sl])
        phi = np.arctan2(ey[sl], ex[sl])
        cp, sp = np.cos(phi), np.sin(phi)
        ur, ut = cp * ux[sl] + sp * uy[sl], -sp * ux[sl] + cp * uy[sl]
        q = np.sqrt(1 - e * e)

        def parts(g, e=e, q=q, ur=ur, ut=ut):
            C, S = np.cos(g), np.sin(g)
            a = ur * (C + e) + ut * q * S
            a1 = -ur * S + ut * q * C
            a2 = -ur * C - ut * q * S
            b = (1 + e * C) ** 2
            b1 = -2 * e * S * (1 + e * C)
            b2 = -2 * e * C * (1 + e * C) + 2 * e * e * S * S
            return a * b, a1 * b + a * b1, a2 * b + 2 * a1 * b1 + a * b2

        vals = parts(g0[:, None] + 0 * e[None])[0]
        g = g0[np.argmax(vals, axis=0)]
        for _ in range(6):
            f, f1, f2 = parts(g)
            step = np.where(f2 < 0, -f1 / np.where(f2 < 0, f2, -1.0), 0.0)
            g = g + np.clip(step, -np.pi / samples, np.pi / samples)
        out[sl] = np.maximum(parts(g)[0], 0.0) / (1 - e * e) ** 3
    return out.reshape(shape)
